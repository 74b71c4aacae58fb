"""Messages of hostile input, issue 37 item 5: each case of the independent fuzz as a test.

* a ``[robust]`` target no design reaches prints what happened and the tightened bounds, never
  ``P(spec holds) = None``;
* a 4000-digit laser bed is named by the key the user wrote (``fabrication.machine``) and their
  value, cut short, never rewritten (``laser:infx300``) under another key (``cutter``);
* control characters in a name (spec, design.json, an error's value) never reach the terminal;
* a direction beyond one turn (``eta = 1e300 deg``) is refused (docs/spec.md, "Directions");
* a load of 1e-300 N prints no number of hundreds of digits;
* ``safety_factor = 100``, the top of the reference's 1-100, is accepted;
* digits other than 0-9 (full-width ``４``) are refused in ``--mesh`` and every number read from
  text.

Each CLI case runs in-process through :func:`corrugate.cli.main`: exit 2 and one line on stderr
naming the key, or the answer's words.
"""

from __future__ import annotations

import contextlib
import copy
import io
import json
import re
import tomllib
from pathlib import Path
from typing import Any

import pytest

from corrugate.cli import main
from corrugate.core.errors import InputError
from corrugate.core.text import clipped, foreign_digits, printable
from corrugate.spec.schema import SpecError, parse_spec

ROOT = Path(__file__).resolve().parents[2]
SPEC = ROOT / "examples" / "blimp_gripper.toml"
ROBUST = ROOT / "examples" / "blimp_gripper_robust.toml"
CANTILEVER = ROOT / "examples" / "blimp_gripper_cantilever.toml"
BASE: dict[str, Any] = tomllib.loads(SPEC.read_text())

#: Every control character class a terminal acts on: ESC (CSI colour, OSC title), BEL, BS, CR,
#: DEL, a C1 CSI and a right-to-left override.
CONTROLS = "\x1b[31m\x1b]0;pwned\x07\x08\r\x7f\x9b2J\u202e"


def run_cli(args: list[str]) -> tuple[int, str, str]:
    """Exit code, stdout and stderr of ``corrugate ARGS`` run in-process."""
    out, err = io.StringIO(), io.StringIO()
    code: Any = 0
    with contextlib.redirect_stdout(out), contextlib.redirect_stderr(err):
        try:
            main(args)
        except SystemExit as exc:
            code = exc.code
    return (0 if code is None else int(code)), out.getvalue(), err.getvalue()


def one_error_line(code: int, err: str, field: str) -> str:
    """Exit 2 and one line on stderr naming ``field``; returns the line."""
    assert code == 2, (code, err[-400:])
    line = err.strip()
    assert "\n" not in line, err
    assert line.startswith(f"corrugate: error: {field} = "), line
    return line


def spec_file(tmp: Path, text: str) -> Path:
    p = tmp / "spec.toml"
    p.write_text(text)
    return p


# -- [robust] with a target no design reaches ---------------------------------------------------


def test_an_unreached_robust_target_prints_the_tightened_bounds(tmp_path: Path) -> None:
    """probability = 0.999999: the tightened spec turns infeasible; the answer says so and lists
    each tightened bound (it printed "P(spec holds) = None ... bounds above are the tightened
    ones" with no bound). Each listed bound is stricter than the spec's, by the factor shown
    (tightened = bound x f for a min bound, bound / f for a max bound: the definition of
    corrugate.solver.robust, module docstring step 1)."""
    text = ROBUST.read_text().replace("probability = 0.9", "probability = 0.999999")
    code, out, err = run_cli(["design", str(spec_file(tmp_path, text))])
    assert code == 1, err
    assert "None" not in out
    assert "P(spec holds) is not estimated" in out
    rows = re.findall(r"^  (\S+): (>=|<=) (\S+) -> (\S+) \S* ?\(x(\S+)\)$", out, re.M)
    assert rows, out
    spec = tomllib.loads(text)
    for name, op, old, new, factor in rows:
        assert name.startswith("constraints."), name
        key = name.removeprefix("constraints.").split(".")[0].split("[")[0]
        assert key in spec["constraints"], name  # a bound the spec has
        o, n, f = float(old), float(new), float(factor)
        assert f > 1
        if op == ">=":
            assert n > o and n == pytest.approx(o * f, rel=2e-3)
        else:
            assert n < o and n == pytest.approx(o / f, rel=2e-3)


# -- a laser bed of 4000 digits ----------------------------------------------------------------


def test_a_4000_digit_laser_bed_is_named_by_its_key_and_value(tmp_path: Path) -> None:
    """It was reported as ``cutter = 'laser:infx300'``: another key and a rewritten value."""
    digits = "9" * 4000
    text = SPEC.read_text() + f'\n[fabrication]\nmachine = "laser:{digits}x300"\n'
    code, _, err = run_cli(["design", str(spec_file(tmp_path, text))])
    line = one_error_line(code, err, "fabrication.machine")
    assert "'laser:999" in line and "inf" not in line
    assert f"({len('laser:') + 4000 + len('x300') + 2} characters)" in line  # the repr's length
    assert len(line) < 300


def test_a_laser_bed_on_the_command_line_is_refused_as_written() -> None:
    code, _, err = run_cli(["design", str(SPEC), "--machine", "laser:1" + "0" * 400 + "x300"])
    line = one_error_line(code, err, "--machine")
    assert "'laser:1000" in line and "inf" not in line


# -- control characters --------------------------------------------------------------------------


def test_printable_removes_every_control_character() -> None:
    """Against the Unicode categories: nothing of category Cc (C0, DEL, C1) and no bidi control
    survives; letters, digits, spaces, 'é', 'µ' and '·' do."""
    import unicodedata

    kept = "W 8 mm é µm N·m ok"
    text = printable(kept + CONTROLS)
    assert text.startswith(kept)
    assert all(unicodedata.category(ch) != "Cc" for ch in text)
    assert "\u202e" not in text
    assert printable(kept) == kept


def test_a_spec_name_with_escapes_never_reaches_the_terminal(tmp_path: Path) -> None:
    name = "gripper" + CONTROLS.replace("\\", "")
    escaped = json.dumps(name)  # a TOML basic string takes JSON's \u escapes
    text = SPEC.read_text().replace('name = "blimp-gripper"', f"name = {escaped}")
    assert tomllib.loads(text)["name"] == name  # the spec really holds them
    code, out, err = run_cli(["design", str(spec_file(tmp_path, text)), "--json"])
    assert code == 0, err
    payload = json.loads(out)
    assert payload["name"].startswith("gripper") and printable(payload["name"]) == payload["name"]
    code, out, err = run_cli(["design", str(spec_file(tmp_path, text))])
    assert code == 0
    assert not re.search(r"[\x00-\x08\x0b-\x1f\x7f-\x9f\u202e]", out + err)
    assert out.startswith("gripper[31m]0;pwned2J: optimal")  # the text stays, the controls go


def test_a_constraint_name_with_escapes_in_design_json_is_read_clean(tmp_path: Path) -> None:
    from corrugate.export.record import read_design

    folder = tmp_path / "out"
    code, _, err = run_cli(["design", str(SPEC), "--out", str(folder)])
    assert code == 0, err
    record = json.loads((folder / "design.json").read_text())
    for c in record["constraints"]:
        c["name"] = CONTROLS + c["name"]
    (folder / "design.json").write_text(json.dumps(record))
    _, constraints, _ = read_design(folder)
    assert constraints and all(printable(c["name"]) == c["name"] for c in constraints)
    assert all("\x1b" not in json.dumps(c) for c in constraints)


def test_an_error_shows_its_value_without_control_characters_and_cut_short() -> None:
    exc = InputError("DIR" + CONTROLS, "out" + CONTROLS + "x" * 500, "a folder")
    text = str(exc)
    assert not re.search(r"[\x00-\x1f\x7f-\x9f\u202e]", text)
    assert "(5" in text and "characters)" in text and len(text) < 250
    assert exc.value.startswith("out\x1b")  # the value itself is kept for the caller
    assert clipped("x" * 100) == "x" * 100  # short values whole


# -- directions ----------------------------------------------------------------------------------


@pytest.mark.parametrize("eta", ["1e300 deg", "360.5 deg", "-361", "7 rad"])
def test_a_direction_beyond_one_turn_is_refused(eta: str) -> None:
    """docs/spec.md, "Directions": -360 to 360 deg; 7 rad is 401 deg."""
    data = copy.deepcopy(BASE)
    data["constraints"]["flexural_rigidity"][0]["eta"] = eta
    with pytest.raises(SpecError) as exc:
        parse_spec(data)
    assert exc.value.field == "constraints.flexural_rigidity[0].eta"
    assert repr(eta) in str(exc.value) and "360" in exc.value.allowed


@pytest.mark.parametrize("eta", ["360 deg", "-360", "6.28 rad", 45])
def test_a_direction_within_one_turn_is_accepted(eta: object) -> None:
    data = copy.deepcopy(BASE)
    data["constraints"]["flexural_rigidity"][0]["eta"] = eta
    parse_spec(data)


def test_analyze_refuses_a_direction_beyond_one_turn() -> None:
    code, _, err = run_cli(["analyze", "--W", "8", "--n", "9", "--alpha", "78", "--eta", "1e300"])
    one_error_line(code, err, "eta")


# -- a load of 1e-300 N ----------------------------------------------------------------------


def test_a_tiny_load_prints_no_number_of_hundreds_of_digits(tmp_path: Path) -> None:
    """Every number the answer prints has at most 17 significant digits and no 300 zeros."""
    text = CANTILEVER.read_text().replace('load = "0.5 N"', 'load = "1e-300 N"')
    text = text.replace(
        "[objective]",
        '[[constraints.strength]]\ntest = "cantilever"\nload = "1e-300 N"\n\n[objective]',
    )
    code, out, err = run_cli(["design", str(spec_file(tmp_path, text))])
    assert code == 0, err
    assert "1e-300" in out  # the load is printed, in exponent form
    longest = max((len(m) for m in re.findall(r"\d[\d.]*", out)), default=0)
    assert longest <= 20, longest


# -- safety_factor -------------------------------------------------------------------------------


def test_the_safety_factor_range_is_the_references() -> None:
    """The reference (docs/spec.md) says 1 to 100, both included; 100 was refused as '< 100'."""
    from corrugate.spec.reference import KEYS

    assert "1 to 100, both included" in KEYS["safety_factor"].text
    for sf in (1, 100, 100.0):
        assert parse_spec(BASE | {"safety_factor": sf}).safety_factor == sf
    for sf in (0.99, 100.01):
        with pytest.raises(SpecError) as exc:
            parse_spec(BASE | {"safety_factor": sf})
        assert exc.value.field == "safety_factor" and "<= 100" in exc.value.allowed


# -- digits other than 0-9 -----------------------------------------------------------------------


def test_foreign_digits_are_found() -> None:
    """Against Python's own reading: ``int`` reads each of these as a digit."""
    for text in ("４", "١٢", "२", "8８"):
        assert int(text) >= 0 and foreign_digits(text)
    for text in ("48", "4.8e3 mm", "µm", "N·m", ""):
        assert not foreign_digits(text)


@pytest.mark.parametrize(
    ("args", "field"),
    [
        (["analyze", "--W", "８", "--n", "9", "--alpha", "78"], "W"),
        (["analyze", "--W", "8", "--n", "９", "--alpha", "78"], "n"),
        (["analyze", "--W", "8", "--n", "9", "--alpha", "７８deg"], "alpha"),
    ],
)
def test_full_width_digits_in_a_table_option_are_one_error_line(
    args: list[str], field: str
) -> None:
    code, _, err = run_cli(args)
    assert "digits other than 0-9" in one_error_line(code, err, field)


def test_full_width_digits_in_mesh_are_refused(tmp_path: Path) -> None:
    """``verify --mesh ２,４`` ran as 2,4 (int() reads full-width digits)."""
    folder = tmp_path / "design"
    folder.mkdir()
    code, _, err = run_cli(["verify", str(folder), "--mesh", "２,４,８"])
    assert "digits other than 0-9" in one_error_line(code, err, "mesh")
    for args in (
        ["validate", "--W", "8", "--n", "9", "--alpha", "78", "--mesh", "４"],
        ["verify", str(folder), "--max-mesh", "１６"],
        ["design", str(SPEC), "--budget", "５"],
    ):
        code, out, err = run_cli(args)
        assert code == 2, (args, code, out[-300:], err[-300:])
        assert "Invalid value for '--" in err, err


def test_full_width_digits_in_a_spec_quantity_are_refused() -> None:
    data = copy.deepcopy(BASE)
    data["constraints"]["side"]["min"] = "４８ mm"
    with pytest.raises(SpecError) as exc:
        parse_spec(data)
    assert exc.value.field == "constraints.side.min"
    assert "digits other than 0-9" in str(exc.value)


@pytest.mark.parametrize(
    ("value", "shown"),
    [
        ("1" + "0" * 5000, "an integer of 5001 digits is too long: at most 30"),
        ("x\x1b[31m\x1b]0;pwned\x07", "x[31m]0;pwned is not an integer written in 0-9"),
        ("\u202e1e9", "1e9 is not an integer written in 0-9"),
    ],
)
def test_a_bad_integer_option_is_shown_short_and_without_control_characters(
    value: str, shown: str
) -> None:
    """click echoed a ValueError's value whole: ``tolerance --samples`` of 5000 digits (beyond
    int()) was a 5 kB line, an escape sequence reached the terminal as written; now the value
    is its length, or shown without its control characters (exit 2, click's usage error)."""
    code, out, err = run_cli(["tolerance", str(SPEC), "--samples", value])
    assert code == 2 and out == "", (code, err[-300:])
    assert f"Invalid value for '--samples': {shown}" in err, err[-300:]
    assert len(err) < 400, len(err)
    assert not any(ord(c) < 32 and c != "\n" for c in err), repr(err)
    assert "\u202e" not in err
