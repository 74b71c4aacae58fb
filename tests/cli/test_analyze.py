"""The command line: output contents, units at the boundary, and bad input (exit 2, one line)."""

from __future__ import annotations

import json
import math
import subprocess
import sys
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
