"""``corrugate verify DIR --nonlinear`` (issue 34 item 4): the ramp's block in verify.json and
nonlinear.png in the folder, read back; its mesh option's bad input. CalculiX is stood in for
(the FE runs are replaced by stated results), so this runs without it; the ramp itself is
checked in tests/fea/test_nonlinear.py."""

from __future__ import annotations

import json
from pathlib import Path
from typing import TYPE_CHECKING, Any

import pytest

if TYPE_CHECKING:
    from conftest import CliRun

#: a design solved and written (about 10 s on 2 loaded cores), matplotlib drawn
pytestmark = pytest.mark.slow


#: Issue 34's stubby panel, its variables fixed (a solve of one point): a three-point deflection
#: under a load, so a load capacity. Its alpha 40 deg and t/W 0.00625 lie outside the models'
#: validated ranges (docs/validation/ranges.md), so the design is extrapolated, not certified.
SPEC = """
name = "stubby"
trust = "extrapolate"
tolerances = "none"  # one fixed design checked in FE: the nominal part (docs/tolerances.md)

[material]
name = "dura-lar"
thickness = "0.075 mm"

[layout]
shape = "square"

[variables]
W = { min = "12 mm", max = "12 mm" }
n = { min = 10, max = 10 }
alpha = { min = "40 deg", max = "40 deg" }

[[constraints.deflection]]
test = "three-point"
load = "0.05 N"
max = "5 mm"
eta = "0 deg"

[objective]
minimize = "mass"
"""


@pytest.fixture(scope="module")
def square(tmp_path_factory: pytest.TempPathFactory) -> Path:
    from corrugate.cli import main

    folder = tmp_path_factory.mktemp("verify-nonlinear")
    spec = folder / "stubby.toml"
    spec.write_text(SPEC)
    with pytest.raises(SystemExit) as info:
        main(["design", str(spec), "--out", str(folder / "d"), "-q"])
    assert info.value.code in (0, None)
    return folder / "d"


def _stand_ins(monkeypatch: pytest.MonkeyPatch, tmp_path: Path) -> list[Any]:
    """A ccx that is never run, no constraint rows, and a ramp with a knee at 0.6 N (model 0.5
    N, safety factor 2): returns the list the ramp's calls are recorded in."""
    import corrugate.fea.nonlinear as nl
    import corrugate.fea.verify as fv
    from corrugate.fea.assembly import AssemblyMesh

    stub = tmp_path / "ccx"
    stub.write_text("#!/bin/sh\nexit 1\n")
    stub.chmod(0o755)
    monkeypatch.setenv("CORRUGATE_CCX", str(stub))
    monkeypatch.setattr(fv, "verify_design", lambda *a, **k: fv.Verification((), (2,)))
    calls: list[Any] = []

    def ramp(assembly: Any, constraints: Any, joint: str, mesh: AssemblyMesh, **kw: Any) -> Any:
        calls.append(mesh)
        case = nl.NonlinearCase("three-point", 0.0, None, ("cap",), 0.5, 2.0)
        return nl.NonlinearResult(
            case,
            mesh,
            0.8,
            100.0,
            0.04,
            "layer 1",
            1.2,
            (0.2, 0.4, 0.6, 0.7),
            (0.002, 0.004, 0.006, 0.016),
            (0.0, 0.001, 0.002, 0.02),
            "target",
            seconds=12.0,
        )

    monkeypatch.setattr(nl, "run_for_design", ramp)
    return calls


def test_nonlinear_writes_its_block_and_figure(
    cli: CliRun, square: Path, tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    import shutil

    from matplotlib.image import imread

    from corrugate.fea.assembly import AssemblyMesh

    calls = _stand_ins(monkeypatch, tmp_path)
    folder = tmp_path / "d"
    shutil.copytree(square, folder)
    args = ["verify", str(folder), "--mesh", "2", "--no-first-failure"]
    code, out, _ = cli([*args, "--nonlinear", "--nonlinear-mesh", "2", "--json"])
    assert code == 0
    assert calls == [AssemblyMesh(2)]
    printed = json.loads(out)["nonlinear"]
    written = json.loads((folder / "verify.json").read_text())["nonlinear"]
    assert written == printed
    assert written["knee_N"] == 0.6 and written["compared_with"] == "knee"
    assert written["model_first_failure_N"] == 0.5 and written["model_holds"] is True
    assert written["mesh"] == "2/facet" and written["imperfection_mm"] == 0.04
    assert [p["load_N"] for p in written["curve"]] == [0.2, 0.4, 0.6, 0.7]
    png = folder / "nonlinear.png"
    image = imread(png)  # a PNG matplotlib reads back, wider than high (two panels)
    assert image.shape[1] > image.shape[0] > 100
    # the console names the files; without --nonlinear the block and the figure are gone
    code, out, _ = cli([*args, "--nonlinear"])
    assert code == 0 and "nonlinear.png" in out and "knee" in out
    code, _, _ = cli(args)
    assert code == 0
    assert "nonlinear" not in json.loads((folder / "verify.json").read_text())
    assert not png.exists()


def test_a_bad_nonlinear_mesh_is_one_line(
    cli: CliRun, square: Path, tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    calls = _stand_ins(monkeypatch, tmp_path)
    code, _, err = cli(["verify", str(square), "--nonlinear", "--nonlinear-mesh", "3"])
    assert code == 2
    lines = err.strip().splitlines()
    assert len(lines) == 1 and "--nonlinear-mesh = 3" in lines[0], err
    assert calls == []
