"""The command line: output contents, units at the boundary, and bad input (exit 2, one line)."""

from __future__ import annotations

import json
import math
import subprocess
import sys
from pathlib import Path
from typing import TYPE_CHECKING

import pytest

if TYPE_CHECKING:
    from conftest import CliRun


BASE = ["analyze", "--W", "8", "--n", "8", "--alpha", "84", "--material", "dura-lar"]


def test_analyze_json_has_the_documented_fields(cli: CliRun) -> None:
    code, out, _ = cli([*BASE, "--model", "paper", "--eta", "0", "--eta", "90", "--json"])
    assert code == 0
    d = json.loads(out)
    assert d["model"] == "paper"
    assert len(d["layers"]) == 2
    for layer in d["layers"]:
        assert (layer["W_mm"], layer["n"], layer["alpha_deg"]) == (8, 8, 84)
        assert layer["material"] == "dura-lar" and layer["t_mm"] == 0.125
        assert set(layer["moduli_MPa"]) == {"Ecx", "Ecy", "Ebx", "Eby"}
    assert d["L_mm"] == pytest.approx(48.18, abs=0.01)
    assert d["thickness_mm"] == pytest.approx(11.89, abs=0.01)
    assert [s["eta_deg"] for s in d["stiffness"]] == [0, 90]
    assert d["stiffness"][0]["EI_Nmm2"] == pytest.approx(87800, rel=5e-4)  # Table 1, case 1
    for key in ("K_N_per_mm", "D_Nmm", "EI_Nmm2"):
        assert d["stiffness"][0][key] > 0
    assert d["mass_g"] > 0
    assert any(w["code"] == "paper-model" for w in d["warnings"])


def test_units_at_the_boundary(cli: CliRun) -> None:
    """'0.3 in' is 7.62 mm; '2.7GPa' is 2700 MPa; '1.466 rad' is 84 deg (to 4 digits)."""
    code, out, _ = cli(
        [
            "analyze",
            "--W",
            "0.3 in",
            "--n",
            "8",
            "--alpha",
            "1.4661 rad",
            "--E",
            "2.7GPa",
            "--nu",
            "0.43",
            "--density",
            "1390 kg/m^3",
            "--thickness",
            "0.125",
            "--json",
        ],
    )
    assert code == 0
    d = json.loads(out)
    assert d["layers"][0]["W_mm"] == pytest.approx(7.62)
    assert d["layers"][0]["alpha_deg"] == pytest.approx(math.degrees(1.4661))
    # same design in plain internal units must give the same stiffness
    code, out2, _ = cli(
        [
            "analyze",
            "--W",
            "7.62",
            "--n",
            "8",
            "--alpha",
            str(math.degrees(1.4661)),
            "--E",
            "2700",
            "--nu",
            "0.43",
            "--density",
            "1.39",
            "--thickness",
            "0.125",
            "--json",
        ],
    )
    d2 = json.loads(out2)
    assert d["stiffness"][0]["K_N_per_mm"] == pytest.approx(d2["stiffness"][0]["K_N_per_mm"])
    assert d["mass_g"] == pytest.approx(d2["mass_g"])


def test_compare_models(cli: CliRun) -> None:
    code, out, _ = cli([*BASE, "--compare-models", "--json"])
    assert code == 0
    d = json.loads(out)["models"]
    assert set(d) == {"paper", "xia", "refined"}
    # refined differs from xia only in Eby, which is smaller by the factor (1 - nu^2) on its big term
    assert (
        d["refined"]["layers"][0]["moduli_MPa"]["Eby"] < d["xia"]["layers"][0]["moduli_MPa"]["Eby"]
    )
    assert (
        d["refined"]["layers"][0]["moduli_MPa"]["Ecx"] == d["xia"]["layers"][0]["moduli_MPa"]["Ecx"]
    )
    code, out, _ = cli([*BASE, "--compare-models"])
    assert code == 0 and "refined" in out and "xia" in out and "paper" in out


def test_table_output_and_independent_layers(cli: CliRun) -> None:
    code, out, _ = cli([*BASE, "--layout", "rectangle", "--n2", "12", "--W2", "6"])
    assert code == 0
    assert "Lx = 48.18 mm" in out and "stiffness" in out


def test_the_buckling_lines_are_the_directions_asked_for(cli: CliRun) -> None:
    """`--eta 0` states compression along 0 deg only (issue 36: it also printed 90 deg); without
    --eta both crease directions."""
    code, out, _ = cli([*BASE, "--eta", "0"])
    assert code == 0
    assert "compression along 0 deg" in out and "compression along 90 deg" not in out
    code, out, _ = cli([*BASE, "--eta", "90"])
    assert "compression along 90 deg" in out and "compression along 0 deg" not in out
    code, out, _ = cli(BASE)
    assert "compression along 0 deg" in out and "compression along 90 deg" in out


@pytest.mark.parametrize(
    ("extra", "field", "allowed"),
    [
        (["--alpha", "190"], "alpha", "0 < alpha < 180"),
        (["--alpha", "0"], "alpha", "0 < alpha < 180"),
        (["--W", "-1"], "W", "0.01 <= W <= 10000 mm"),
        (["--W", "0"], "W", "0.01 <= W <= 10000 mm"),
        (["--thickness", "0"], "thickness", "1e-05 <= thickness <= 100 mm"),
        (["--n", "8.5"], "n", "integer"),
        (["--n", "0"], "n", "1 <= n <= 5000"),
        (["--n", "eight"], "n", "integer"),
        (["--material", "unobtainium"], "material", "dura-lar"),
        (["--model", "exact"], "model", "refined"),
        (["--layout", "hexagon"], "layout", "polygon"),
        (["--W", "3 GPa"], "W", "mm"),
        (["--W2", "9", "--layout", "square"], "layout", "rectangle"),
        # JSON beyond int() (4300 digits: ValueError, exit 3 before) and nested 20 000 deep
        # (RecursionError: a line not naming --holes before)
        (["--holes", "[1" + "0" * 5000 + "]"], "holes", "a JSON list"),
        (["--holes", "[" * 20_000 + "]" * 20_000], "holes", "nested at most 16 deep"),
        (["--holes", '[{"shape": "circle", "diameter": 1' + "0" * 400 + "}]"], "holes[0]", "30"),
        # float() reads full-width digits: "１" was taken as 1
        (["--layout", "polygon", "--vertices", "0,0 \uff11,0 0,1"], "vertices", "0-9"),
        (["--holes", json.dumps([{"center": [0, 0], "diameter": 1}] * 17)], "holes", "16 holes"),
    ],
)
def test_bad_input_one_line_exit_2(extra: list[str], field: str, allowed: str, cli: CliRun) -> None:
    args = [*BASE, *extra]
    code, out, err = cli(args)
    assert code == 2
    assert out == ""
    lines = err.strip().splitlines()
    assert len(lines) == 1, err
    assert lines[0].startswith(f"corrugate: error: {field}")
    assert allowed in lines[0]
    assert "Traceback" not in err


@pytest.mark.parametrize(
    ("inline", "field", "allowed"),
    [
        (["--E", "3 mm", "--nu", "0.4", "--density", "1.2"], "E", "MPa"),
        (["--E", "2700", "--nu", "0.5", "--density", "1.2"], "nu", "-1 < nu < 0.5"),
        (["--E", "2700", "--nu", "-1.2", "--density", "1.2"], "nu", "-1 < nu < 0.5"),
        (["--E", "-5", "--nu", "0.3", "--density", "1.2"], "E", "0.001 <= E"),
        (["--E", "2700", "--nu", "0.3", "--density", "0"], "density", "0.001 <= density"),
        (["--E", "2700", "--nu", "0.3"], "density", "--density"),
    ],
)
def test_bad_inline_material(inline: list[str], field: str, allowed: str, cli: CliRun) -> None:
    args = ["analyze", "--W", "8", "--n", "8", "--alpha", "84", "--thickness", "0.1", *inline]
    code, _, err = cli(args)
    assert code == 2
    assert err.startswith(f"corrugate: error: {field}")
    assert allowed in err and len(err.strip().splitlines()) == 1


def test_real_process_exit_code_and_no_traceback() -> None:
    proc = subprocess.run(
        [sys.executable, "-m", "corrugate", *BASE, "--alpha", "200"],
        capture_output=True,
        text=True,
        check=False,
    )
    assert proc.returncode == 2
    assert proc.stderr.strip() == (
        "corrugate: error: alpha = 200 deg is out of range: allowed 0 < alpha < 180 deg"
    )
    assert proc.stdout == ""


def test_materials_command(cli: CliRun) -> None:
    code, out, _ = cli(["materials", "--json"])
    assert code == 0
    ids = {m["id"] for m in json.loads(out)}
    assert {"dura-lar", "kapton", "fr4"} <= ids
    code, out, _ = cli(["materials"])
    assert code == 0 and "dura-lar" in out


# ---- load cases: --test, --load, --span (docs/load_cases.md) --------------------------------

#: delta / P = a Ls^3 / EI + (b Ls + c h_l) / S of each bending test (docs/load_cases.md,
#: sections 1-2: the Timoshenko beam's a and b; the local term c h_l, h_l = h sqrt(0.01 W / t):
#: c = 2 on line supports, 1.5 with a clamped root).
TESTS_AB = {
    "three-point": (1 / 48, 1 / 4, 2.0),
    "four-point": (1 / 96, 1 / 8, 2.0),
    "cantilever": (1 / 3, 1, 1.5),
}


def _hand_deflection(d: dict[str, object], test: str, load: float, span: float | None) -> float:
    """The test's deflection (mm) of the identical square 8/8/84 Dura-Lar panel at eta = 0 by
    hand: EI = D L over the panel's length L, S = (5/6) G t W c^2 (n + 1) (the n + 1 facets as
    webs with a parabolic shear flow, zero at each crease; c = cos(alpha/2)), h = W c and the
    local term's length h sqrt(0.01 W / t) (docs/load_cases.md, sections 1-2)."""
    from corrugate import get_material

    m = get_material("dura-lar")
    st = d["stiffness"][0]  # type: ignore[index]
    D, L = st["D_Nmm"], st["span_mm"]
    W, n, t, c = 8.0, 8, 0.125, math.cos(math.radians(84 / 2))
    S = 5 / 6 * m.E / (2 * (1 + m.nu)) * t * W * c**2 * (n + 1)
    h_l = W * c * math.sqrt(0.01 * W / t)
    Ls = L if span is None else span
    a, b, local = TESTS_AB[test]
    return load * (a * Ls**3 / (D * L) + (b * Ls + local * h_l) / S)


@pytest.mark.parametrize("test", sorted(TESTS_AB))
@pytest.mark.parametrize("span", [None, 30.0])
def test_load_case_deflection_is_the_documented_formula(
    cli: CliRun, test: str, span: float | None
) -> None:
    extra = [] if span is None else ["--span", f"{span} mm"]
    code, out, _ = cli([*BASE, "--eta", "0", "--test", test, "--load", "10 N", *extra, "--json"])
    assert code == 0
    d = json.loads(out)
    case = d["load_case"]
    assert (case["test"], case["load_N"], case["span_mm"]) == (test, 10.0, span)
    (row,) = case["directions"]
    length = d["stiffness"][0]["span_mm"]
    assert math.isclose(length, 9 * 8 * math.sin(math.radians(42)))  # (n + 1) W sin(alpha/2)
    assert row["eta_deg"] == 0
    assert row["span_mm"] == pytest.approx(length if span is None else span)
    assert row["deflection_mm"] == pytest.approx(_hand_deflection(d, test, 10.0, span), rel=1e-9)
    assert row["deflection_mm"] * row["stiffness_N_per_mm"] == pytest.approx(10.0)


def test_load_case_between_platens_is_the_load_over_K(cli: CliRun) -> None:
    code, out, _ = cli([*BASE, "--test", "platens", "--load", "2 lbf", "--json"])
    assert code == 0
    d = json.loads(out)
    assert d["load_case"]["load_N"] == pytest.approx(2 * 4.4482216152605)  # 1 lbf in N
    for st, row in zip(d["stiffness"], d["load_case"]["directions"], strict=True):
        assert row["eta_deg"] == st["eta_deg"]
        assert row["stiffness_N_per_mm"] == pytest.approx(st["K_N_per_mm"])
        assert row["deflection_mm"] == pytest.approx(2 * 4.4482216152605 / st["K_N_per_mm"])


def test_load_case_is_linear_in_the_load_and_shortens_with_the_span(cli: CliRun) -> None:
    def deflection(*extra: str) -> float:
        code, out, _ = cli([*BASE, "--eta", "0", "--test", "three-point", *extra, "--json"])
        assert code == 0
        value: float = json.loads(out)["load_case"]["directions"][0]["deflection_mm"]
        return value

    assert deflection("--load", "20") == pytest.approx(2 * deflection("--load", "10"))
    short, long = deflection("--load", "10", "--span", "20"), deflection("--load", "10")
    assert 0 < short < long


def test_load_case_text_and_compare_models(cli: CliRun) -> None:
    code, out, _ = cli([*BASE, "--test", "four-point", "--load", "5", "--span", "40"])
    assert code == 0
    assert "load case: four-point, 5 N over 40 mm" in out and "deflection mm" in out
    code, out, _ = cli([*BASE, "--test", "cantilever", "--load", "1", "--compare-models", "--json"])
    assert code == 0
    models = json.loads(out)["models"]
    assert set(models) == {"paper", "xia", "refined"}
    for d in models.values():
        rows = d["load_case"]["directions"]
        assert [r["eta_deg"] for r in rows] == [0, 90]
        assert rows[0]["deflection_mm"] == pytest.approx(1 / rows[0]["stiffness_N_per_mm"])
    code, out, _ = cli([*BASE, "--test", "cantilever", "--load", "1", "--compare-models"])
    assert code == 0 and "cantilever delta(0) mm at 1 N" in out


@pytest.mark.parametrize(
    ("extra", "option", "words"),
    [
        (["--load", "10"], "--load", "without --test"),
        (["--span", "30"], "--span", "without --test"),
        (["--test", "three-point"], "--load", "required with --test"),
        (["--test", "five-point", "--load", "1"], "--test", "cantilever, four-point"),
        (["--test", "three-point", "--load", "0"], "--load", "> 0 N"),
        (["--test", "three-point", "--load", "-2 N"], "--load", "> 0 N"),
        (["--test", "three-point", "--load", "2 mm"], "--load", "N"),
        (["--test", "three-point", "--load", "1", "--span", "0"], "--span", "> 0 mm"),
        (["--test", "platens", "--load", "1", "--span", "30"], "--span", "no span for platens"),
        (["--test", "three-point", "--load", "1", "--span", "60"], "--span", "48.1774 mm"),
        (
            ["--test", "cantilever", "--load", "1", "--layout", "circle"],
            "--test",
            "a square or rectangle layout",
        ),
    ],
)
def test_bad_load_case_one_line_exit_2(
    cli: CliRun, extra: list[str], option: str, words: str
) -> None:
    code, out, err = cli([*BASE, *extra])
    assert code == 2 and out == ""
    lines = err.strip().splitlines()
    assert len(lines) == 1, err
    assert lines[0].startswith(f"corrugate: error: {option} "), lines[0]
    assert words in lines[0], lines[0]


def test_analyze_states_the_capacity_in_the_design_answers_words(
    cli: CliRun, tmp_path: Path
) -> None:
    """`analyze --test --load --joint` on the chassis example's nominal certified design
    (`tolerances = "none"`: analyze evaluates one part) states the capacity and first failure in
    the same words as `design`'s certificate, and its --json the same capacity as design.json's
    row (two paths: the Analysis's springs, the solver's points; docs/load_cases.md 10)."""
    root = Path(__file__).resolve().parents[2]
    spec = tmp_path / "nominal.toml"
    spec.write_text(
        'tolerances = "none"\n' + (root / "examples" / "chassis_plate.toml").read_text()
    )
    code, out, _ = cli(["design", str(spec), "--json"])
    assert code == 0
    answer = json.loads(out)
    [row] = [c for c in answer["constraints"] if c["name"] == "constraints.deflection[0].max"]
    l1, l2 = answer["design"]["layers"]
    args = [
        "analyze",
        *("--W", str(l1["W_mm"]), "--n", str(l1["n"]), "--alpha", str(l1["alpha_deg"])),
        *("--W2", str(l2["W_mm"]), "--n2", str(l2["n"]), "--alpha2", str(l2["alpha_deg"])),
        *("--material", "polypropylene", "--thickness", f"{l1['t_mm']}mm"),
        *("--layout", "rectangle"),
        *("--eta", "0", "--test", "three-point", "--load", "10N", "--span", "120mm"),
        *("--joint", "band-edges"),
    ]
    code, text, _ = cli(args)
    assert code == 0
    said = next(line for line in text.splitlines() if line.startswith("at 0 deg: holds"))
    assert said.removeprefix("at 0 deg: ") in answer["certificate"]
    code, out, _ = cli([*args, "--json"])
    [direction] = json.loads(out)["load_case"]["directions"]
    assert direction["load_capacity_N"] == pytest.approx(row["load_capacity_N"], rel=1e-9)
    assert direction["first_failure"] == row["first_failure"]
    # with the edges free (the default joint) the outermost facet fails first, far lower
    code, out, _ = cli([*args[:-2], "--json"])
    [free] = json.loads(out)["load_case"]["directions"]
    assert free["first_failure_mode"] == "edge-facet-buckling"
    assert free["load_capacity_N"] < 0.1 * row["load_capacity_N"]


def test_a_warning_s_spec_table_is_printed_not_read_as_markup(cli: CliRun) -> None:
    """The short-panel warning names `[[constraints.deflection]]`; rich read it as a style tag and
    printed "or a []" (found running issue 34's stubby panel)."""
    stubby = ["--W", "12", "--n", "10", "--alpha", "40", "--material", "dura-lar"]
    case = ["--thickness", "0.075", "--eta", "0", "--test", "three-point", "--load", "1N"]
    code, out, _ = cli(["analyze", *stubby, *case])
    assert code == 0
    assert "short-panel-shear" in out and "[[constraints.deflection]]" in " ".join(out.split())
