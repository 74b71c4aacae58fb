"""``corrugate verify DIR`` against ``corrugate validate`` (issue 23, item 1): a small design's
FE twins at a coarse mesh series are the numbers validate gives for the same fixtures; verify.json
is the folder's ``verify`` set; the exit code follows the verdict (issue 35: a two-mesh series is
never shown converged); a design of an inline material verifies end to end."""

from __future__ import annotations

import json
from pathlib import Path
from typing import TYPE_CHECKING, Any

import pytest

from corrugate.core.fileio import read_manifest
from data_files import VERIFY_SMALL

if TYPE_CHECKING:
    from conftest import CliRun

#: The small design (tests/data/verify_small.toml says why each of its numbers).
SPEC = VERIFY_SMALL.read_text()


def _strict(text: str) -> Any:
    def refuse(name: str) -> None:
        raise ValueError(f"not strict JSON: {name}")

    return json.loads(text, parse_constant=refuse)


@pytest.fixture(scope="module")
def designed(tmp_path_factory: pytest.TempPathFactory) -> Path:
    from corrugate.cli import main

    folder = tmp_path_factory.mktemp("verify")
    spec = folder / "small.toml"
    spec.write_text(SPEC)
    out = folder / "design"
    with pytest.raises(SystemExit) as info:
        main(["design", str(spec), "--out", str(out), "-q"])
    assert info.value.code in (0, None)
    return out


@pytest.mark.fea
def test_verify_json_matches_validate_at_the_same_meshes(
    ccx: str, cli: CliRun, designed: Path
) -> None:
    code, out, _ = cli(["verify", str(designed), "--mesh", "2,4", "--max-mesh", "4", "--json"])
    result = _strict(out)
    rows = {r["quantity"]: r for r in result["constraints"]}
    assert set(rows) == {"EI@0", "k3pt@0", "Pmax3pt@0"}  # the load held at the safety factor
    for r in rows.values():
        assert set(r) >= {"name", "bound", "model", "fe_series", "fe", "holds", "verdict"}
        assert list(r["fe_series"]) == ["2", "4"]
        assert r["fe"] == r["fe_series"]["4"]  # two meshes: no order, the finest value
        assert r["order"] is None
        # two meshes show no asymptote: never "holds" (docs/fea.md 6)
        assert r["verdict"] == "not converged" and r["holds"] is False
    assert result["verdict"] == "not converged" and code == 5

    record = json.loads((designed / "design.json").read_text())
    L = record["L_mm"]  # the square's side: the span of both fixtures along eta = 0
    load = next(c["load_N"] for c in record["constraints"] if c["quantity"] == "k3pt@0")
    for along in (2, 4):
        code, vout, _ = cli(
            [
                "validate",
                "--design",
                str(designed),
                "--mesh",
                str(along),
                "--no-unit-cell",
                "--json",
            ]
        )
        assert code == 0
        fe = json.loads(vout)["fe"]
        # pure bending: validate's 4-point gauge D4 times the span is verify's EI
        assert rows["EI@0"]["fe_series"][str(along)] == pytest.approx(fe["D4_Nmm@0"] * L, rel=1e-9)
        # three-point: validate's D = P L^2 / (48 delta), so delta = load L^2 / (48 D)
        assert rows["k3pt@0"]["fe_series"][str(along)] == pytest.approx(
            load * L**2 / (48 * fe["D_Nmm@0"]), rel=1e-9
        )

    written = _strict((designed / "verify.json").read_text())
    assert written["holds"] == result["holds"]
    assert written["constraints"] == result["constraints"]
    manifest = read_manifest(designed)
    assert "verify.json" in manifest["verify"]["files"]  # type: ignore[operator]
    assert "design.json" in manifest["design"]["files"]  # type: ignore[operator]


@pytest.mark.fea
def test_a_bound_the_fe_misses_exits_1(
    ccx: str, cli: CliRun, designed: Path, tmp_path: Path
) -> None:
    """The same design with its deflection bound made tighter than the FE's deflection (edited
    in design.json, the deflection its only constraint, to keep the runs few): on 2 / 4 / 8 the
    deflection is past its maximum and grows as the mesh refines, so that row fails from three
    meshes, without running on, and the design does, exit 1; the table names it."""
    import shutil

    folder = tmp_path / "tight"
    shutil.copytree(designed, folder)
    record = json.loads((folder / "design.json").read_text())
    record["constraints"] = [c for c in record["constraints"] if c["quantity"] == "k3pt@0"]
    record["constraints"][0]["bound"] = 1e-4
    (folder / "design.json").write_text(json.dumps(record))
    args = ["verify", str(folder), "--mesh", "2,4,8", "--no-first-failure"]
    code, out, _ = cli([*args, "--json"])
    result = _strict(out)
    assert code == 1 and result["holds"] is False and result["verdict"] == "fails"
    rows = {r["quantity"]: r for r in result["constraints"]}
    k = rows["k3pt@0"]
    assert k["verdict"] == "fails" and "moves away" in k["estimate"]
    series = [k["fe_series"][m] for m in ("2", "4", "8")]
    assert series == sorted(series) and series[-1] > 1e-4  # past the bound, growing
    assert list(k["fe_series"]) == ["2", "4", "8"]  # failed early: not run on to 16
    code, out, _ = cli(args)
    assert code == 1
    assert "not every constraint holds" in out


@pytest.mark.fea
def test_ctrl_c_mid_run_exits_130_with_one_line_and_writes_nothing(
    ccx: str, designed: Path, tmp_path: Path
) -> None:
    """SIGINT while CalculiX runs (after the first progress line): exit 130, the CLI's one
    interrupted line, no verify.json and the folder's manifest as it was."""
    import os
    import shutil
    import signal
    import subprocess
    import sys
    import time

    from corrugate.cli import INTERRUPTED

    folder = tmp_path / "int"
    shutil.copytree(designed, folder)
    (folder / "verify.json").unlink(missing_ok=True)
    manifest = (folder / ".corrugate-set.json").read_bytes()
    root = Path(__file__).resolve().parents[2]
    run = subprocess.Popen(
        [sys.executable, "-m", "corrugate", "verify", str(folder), "--mesh", "8,16"],
        stdout=subprocess.PIPE,
        stderr=subprocess.PIPE,
        text=True,
        env={**os.environ, "PYTHONPATH": str(root / "src")},
        preexec_fn=lambda: signal.signal(signal.SIGINT, signal.SIG_DFL),
    )
    assert run.stderr is not None
    first = run.stderr.readline()
    assert first.startswith("CalculiX run 1"), first
    time.sleep(0.5)
    run.send_signal(signal.SIGINT)
    _, stderr = run.communicate(timeout=120)
    assert run.returncode == 130, stderr
    assert stderr.splitlines() == [INTERRUPTED]
    assert not (folder / "verify.json").exists()
    assert (folder / ".corrugate-set.json").read_bytes() == manifest


@pytest.mark.fea
@pytest.mark.slow
def test_three_point_over_a_shorter_span_lies_between_the_beam_limits(ccx: str) -> None:
    """3-point bending over a span s inside a panel of length L (the ends overhang, carrying no
    moment) against the same panel supported at its ends: shorter is stiffer, and P / delta
    grows by at most (L / s)^3 (all bending, Euler-Bernoulli) and at least L / s (all shear)."""
    from corrugate import Assembly, Layer, get_material
    from corrugate.fea.assembly import AssemblyMesh, solve_assembly

    a = Assembly.identical(
        Layer(W=5.0, n=5, alpha_deg=84.0, material=get_material("dura-lar"), t=0.125)
    )
    L, s = a.Ly, 15.0
    full = solve_assembly(a, "three-point", AssemblyMesh(2), 0.0, mesher="gmsh")
    short = solve_assembly(a, "three-point", AssemblyMesh(2), 0.0, span=s)
    assert short.span == s and full.span == pytest.approx(L)
    ratio = (short.force / short.displacement) / (full.force / full.displacement)
    assert L / s < ratio < (L / s) ** 3, ratio


#: The spec above on an inline material (issue 35's arm link's PET), with its flexural rigidity
#: bound only: one twin, the 4-point fixture's pure-bending gauge.
INLINE = (
    SPEC.replace(
        """[material]
name = "dura-lar"
thickness = "0.125 mm"
""",
        """[material]
name = "PET (generic)"
E = "4 GPa"
nu = 0.38
density = "1.38 g/cm^3"
thickness = "0.25 mm"
""",
    ).split("[[constraints.deflection]]")[0]
    + '[objective]\nminimize = "mass"\n'
)


@pytest.mark.fea
def test_a_design_of_an_inline_material_verifies_end_to_end(
    ccx: str, cli: CliRun, tmp_path: Path
) -> None:
    """Issue 35: ``corrugate verify`` of a design of an inline material (E 4 GPa, nu 0.38, not in
    the library) runs its FE twin instead of refusing it: design.json stores the material, and
    verify's FE at each mesh is the 4-point gauge's EI of the same layers built here from the
    spec's own numbers (a second path, not through design.json); the exit code is the verdict's."""
    from corrugate import Assembly, Layer
    from corrugate.fea.assembly import AssemblyMesh, solve_assembly
    from corrugate.fea.verify import EXIT_CODES
    from corrugate.materials.library import inline_material

    spec = tmp_path / "inline.toml"
    spec.write_text(INLINE)
    out = tmp_path / "design"
    code, _, _ = cli(["design", str(spec), "--out", str(out), "-q"])
    assert code == 0
    record = json.loads((out / "design.json").read_text())
    [lay, _] = record["layers"]
    assert lay["material_properties"]["E_MPa"] == 4000.0
    code, text, _ = cli(
        ["verify", str(out), "--mesh", "2,4", "--max-mesh", "4", "--no-first-failure", "--json"]
    )
    result = _strict(text)
    assert code == EXIT_CODES[result["verdict"]] != 2
    [row] = result["constraints"]
    assert row["quantity"] == "EI@0" and "material" not in (row["note"] or "")
    pet = inline_material("4 GPa", 0.38, "1.38 g/cm^3", name="PET (generic)")
    layer = Layer(lay["W_mm"], lay["n"], lay["alpha_deg"], pet, t=0.25)
    direct = solve_assembly(Assembly.identical(layer), "four-point", AssemblyMesh(4), 0.0)
    assert direct.EI is not None
    assert row["fe_series"]["4"] == pytest.approx(direct.EI, rel=1e-9)
