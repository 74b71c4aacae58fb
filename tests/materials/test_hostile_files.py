"""Hostile materials files (``corrugate-materials.toml`` beside a spec, ``materials.toml`` in the
config folder) and measurements files: every bad value is one line naming the file, the table and
the key, exit 2 (never exit 3 with an internal error, never a value accepted unchecked), and no
name read from a file reaches the terminal with its control characters."""

from __future__ import annotations

import json
from pathlib import Path
from typing import TYPE_CHECKING

import pytest

from corrugate.materials.user import SPEC_FILE
from corrugate.spec.examples import example_text

if TYPE_CHECKING:
    from conftest import CliRun

LONG_INT = "1" + "0" * 400  # overflows float(): OverflowError before the fix
HUGE_INT = "1" + "0" * 5000  # beyond Python's int conversion (4300 digits): ValueError
DEEP = "[" * 5000 + "]" * 5000  # tomllib recurses into it: RecursionError

#: (a line of the table [mine], the field the error names, a word of what is allowed)
BAD_ENTRIES = [
    ('nu = "abc"', "[mine].nu", "number"),
    ("nu = [1]", "[mine].nu", "number"),
    (f"nu = {LONG_INT}", "[mine].nu", "digits"),
    (f"E = {LONG_INT}", "[mine].E", "digits"),
    ('thicknesses = "0.125 mm"', "[mine].thicknesses", "array"),
    ("thicknesses = 5", "[mine].thicknesses", "array"),
    ('thicknesses = ["1e300 km"]', "[mine].thicknesses", "thickness <= 100 mm"),
    ('default_thickness = "-1 mm"', "[mine].default_thickness", "1e-05 <= thickness"),
    ("aliases = 5", "[mine].aliases", "array"),
    ("aliases = [5]", "[mine].aliases", "string"),
    ("name = 5", "[mine].name", "string"),
    ('name = "' + "a" * 300 + '"', "[mine].name", "200 characters"),
    ("creep = 5", "[mine].creep", "moduli"),
    ("creep = {}", "[mine].creep", "moduli"),
    (f"x = {HUGE_INT}", "materials file", "4300 digits"),
    (f"x = {DEEP}", "materials file", "16 levels"),
]


def _spec(folder: Path, material: str) -> Path:
    text = example_text("blimp_gripper").replace('name = "dura-lar"', f'name = "{material}"', 1)
    path = folder / "gripper.toml"
    path.write_text(text)
    return path


@pytest.mark.parametrize(("line", "field", "allowed"), BAD_ENTRIES)
def test_a_bad_value_of_a_materials_file_is_one_line_naming_its_key(
    line: str, field: str, allowed: str, tmp_path: Path, cli: CliRun
) -> None:
    (tmp_path / SPEC_FILE).write_text(f'[mine]\nextends = "dura-lar"\n{line}\n')
    code, out, err = cli(["design", str(_spec(tmp_path, "mine")), "-q"])
    assert code == 2, (code, err)
    assert err.count("\n") == 1 and "internal error" not in err, err
    assert err.startswith("corrugate: error: "), err
    assert field in err and allowed in err, err
    assert len(err) < 400, err  # the 300-character name or 5000 digits are not repeated
    assert out == ""


def test_the_config_folders_file_is_checked_as_the_one_beside_the_spec(
    tmp_path: Path, cli: CliRun, monkeypatch: pytest.MonkeyPatch
) -> None:
    config = tmp_path / "config"
    config.mkdir()
    (config / "materials.toml").write_text('[mine]\nextends = "dura-lar"\nnu = "abc"\n')
    monkeypatch.setenv("CORRUGATE_CONFIG_DIR", str(config))
    code, _, err = cli(["design", str(_spec(tmp_path, "mine")), "-q"])
    assert (code, err.count("\n")) == (2, 1), err
    assert "materials.toml [mine].nu = 'abc'" in err, err


def test_a_materials_file_within_the_limits_still_designs(tmp_path: Path, cli: CliRun) -> None:
    """The checks refuse only what is outside the limits: nu as a string, a creep table, a list
    of thicknesses and aliases within range design as before."""
    (tmp_path / SPEC_FILE).write_text(
        '[mine]\nextends = "polypropylene"\nnu = "0.42"\nthicknesses = ["0.5 mm", 0.8]\n'
        'aliases = ["my-pp"]\nname = "my PP"\n'
    )
    code, out, err = cli(["design", str(_spec(tmp_path, "my-pp")), "--json"])
    assert code == 0, err
    answer = json.loads(out)
    assert answer["status"] == "optimal", answer["status"]
    assert '"material": "mine"' in out  # found by its alias


def test_a_material_id_with_escapes_never_reaches_the_terminal(tmp_path: Path, cli: CliRun) -> None:
    """An unknown material lists the known ids, those of the materials file too: an id holding
    an escape sequence (a colour, an OSC that retitles the terminal) is listed without its
    control characters."""
    (tmp_path / SPEC_FILE).write_text(
        '["x\\u001b[31mred\\u001b]0;pwned\\u0007"]\nextends = "dura-lar"\n'
    )
    code, _, err = cli(["design", str(_spec(tmp_path, "nope")), "-q"])
    assert (code, err.count("\n")) == (2, 1), err
    assert "material.name = 'nope' is unknown" in err, err
    assert "x[31mred]0;pwned" in err, err  # listed, its control characters removed
    assert not any(ord(c) < 32 and c != "\n" for c in err), repr(err)


@pytest.mark.parametrize(
    ("text", "allowed"), [(f"x = {HUGE_INT}\n", "4300 digits"), (f"x = {DEEP}\n", "16 levels")]
)
def test_a_hostile_measurements_file_is_one_line(
    text: str, allowed: str, tmp_path: Path, cli: CliRun
) -> None:
    path = tmp_path / "m.toml"
    path.write_text(text)
    code, _, err = cli(["calibrate", "fit", str(path)])
    assert (code, err.count("\n")) == (2, 1), err
    assert f"MEASUREMENTS = {path}" in err and allowed in err, err


def test_an_unknown_material_lists_at_most_50_names(tmp_path: Path, cli: CliRun) -> None:
    """A materials file of 30 000 tables (1 MiB) made the unknown-name error one line of 300 kB
    listing every id; it lists the first 50 (sorted) and how many more."""
    text = "".join(f'[m{i:05d}]\nextends = "dura-lar"\n' for i in range(30_000))
    assert len(text.encode()) < 1 << 20  # within the file's cap: read, not refused for size
    (tmp_path / SPEC_FILE).write_text(text)
    code, _, err = cli(["design", str(_spec(tmp_path, "nope")), "-q"])
    assert (code, err.count("\n")) == (2, 1), err[:300]
    assert err.rstrip().endswith(" and 29962 more"), err[-200:]  # 12 library ids + 30 000
    assert len(err) < 1000
    # the 6 library ids before "m", then m00000 to m00043: 50
    assert "acetate, aluminium-shim" in err and "m00043" in err and "m00044" not in err
