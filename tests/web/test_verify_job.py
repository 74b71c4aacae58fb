"""The web app's FE verification (``POST /api/jobs/verify``, :func:`corrugate.web.app.verify_job`)
under issue 35's rule: a series not shown asymptotic is refined up to the server's
``fe_max_mesh`` (default 16) as ``corrugate verify --max-mesh`` does, its rows, verdict, exit
code and statement are the CLI's, and an extending run the memory does not allow is not made:
the row is "not converged (memory)". CalculiX is a stand-in here (the job function runs in this
process); the real run is tests/web/test_browser_jobs.py's (marked fea)."""

from __future__ import annotations

import json
import shutil
from pathlib import Path
from types import SimpleNamespace
from typing import TYPE_CHECKING, Any

import pytest
from fastapi.testclient import TestClient

from corrugate.spec.examples import example_text
from corrugate.web import WebSettings, create_app

if TYPE_CHECKING:
    from conftest import CliRun


@pytest.fixture(scope="module")
def design(tmp_path_factory: pytest.TempPathFactory) -> Path:
    """The blimp gripper's design folder, its constraint replaced by one EI(0) bound."""
    from corrugate.cli import main

    folder = tmp_path_factory.mktemp("web-verify")
    spec = folder / "blimp_gripper.toml"
    spec.write_text(example_text("blimp_gripper"))
    with pytest.raises(SystemExit) as info:
        main(["design", str(spec), "--out", str(folder / "d"), "-q"])
    assert info.value.code in (0, None)
    return folder / "d"


def _with_bound(design: Path, tmp_path: Path, bound: float) -> Path:
    folder = tmp_path / "d"
    shutil.copytree(design, folder)
    record = json.loads((folder / "design.json").read_text())
    record["constraints"] = [
        {
            "name": "ei0",
            "quantity": "EI@0",
            "sense": "min",
            "unit": "N*mm^2",
            "value": 2e5,
            "bound": bound,
        }
    ]
    (folder / "design.json").write_text(json.dumps(record))
    return folder


def _stand_in(
    monkeypatch: pytest.MonkeyPatch, tmp_path: Path, series: dict[int, float], nodes: int
) -> list[int]:
    """CalculiX replaced: EI(0) of the 4-point gauge is ``series[mesh]`` (N mm^2), every run
    ``nodes`` nodes; returns the meshes run."""
    from corrugate.fea import verify

    stub = tmp_path / "ccx"
    stub.write_text("#!/bin/sh\nexit 1\n")
    stub.chmod(0o755)
    monkeypatch.setenv("CORRUGATE_CCX", str(stub))
    alongs: list[int] = []

    def fake(assembly: Any, test: Any, mesh: Any, eta: float, **kw: Any) -> Any:
        alongs.append(mesh.along)
        return SimpleNamespace(EI=series[mesh.along], nodes=nodes)

    monkeypatch.setattr(verify, "solve_assembly", fake)
    return alongs


#: The K(15) series of docs/fea.md 2.9 (scaled to N mm^2): extrapolations 82.676 from 2 / 4 /
#: 8 and 78.590 from 4 / 8 / 16, 4.09 apart; against a bound of 62 (16.6 below 78.59, more
#: than four disagreements) it holds, but only with the 16-per-facet run.
K15 = {2: 126.23668e3, 4: 93.202237e3, 8: 85.219855e3, 16: 81.597965e3}


def test_the_web_verify_refines_to_its_cap_and_says_what_the_cli_says(
    cli: CliRun, design: Path, tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    """On 2 / 4 / 8 the K(15)-like series is one extrapolation short: the job refines it to 16
    (the server's default cap), where it holds against 62e3, and its rows, verdict, exit code
    and statement equal ``corrugate verify --json`` on the same design.json; capped at 8 (the
    old web cap) the same series is "not converged", exit code 5, not holds."""
    from corrugate.web import app as web

    assert WebSettings().fe_max_mesh == 16
    folder = _with_bound(design, tmp_path, 62e3)
    alongs = _stand_in(monkeypatch, tmp_path, K15, nodes=1000)
    got = web.verify_job(folder, (2, 4, 8), 60.0, None, max_mesh=WebSettings().fe_max_mesh)
    assert alongs == [2, 4, 8, 16]
    code, out, _ = cli(["verify", str(folder), "--no-first-failure", "--json"])
    expected = json.loads(out)
    assert code == expected["exit_code"] == got["exit_code"] == 0
    assert got["verdict"] == expected["verdict"] == "holds" and got["holds"] is True
    assert got["statement"] == expected["statement"] == "every constraint holds in FE"
    assert got["constraints"] == expected["constraints"]
    assert got["constraints"][0]["fe"] == pytest.approx(78.590e3, rel=1e-4)
    assert got["constraints"][0]["fe_series"].keys() == {"2", "4", "8", "16"}

    capped = web.verify_job(folder, (2, 4, 8), 60.0, None, max_mesh=8)
    code, out, _ = cli(["verify", str(folder), "--no-first-failure", "--json", "--max-mesh", "8"])
    assert capped["verdict"] == json.loads(out)["verdict"] == "not converged"
    assert capped["holds"] is False and capped["exit_code"] == code == 5
    assert capped["statement"] == (
        "no constraint fails, but not every FE series converged: not shown to hold (exit 5)"
    )


def test_an_extension_the_memory_does_not_allow_is_not_run(
    design: Path, tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    """Runs of 60 000 nodes: the 16-per-facet run is estimated at 4 x 60 000 x 48 kB = 11.5 GB
    (corrugate.fea.verify.BYTES_PER_NODE), above the job's 8 GiB cap: it is not run, and the row
    is not converged (memory), exit code 5. With 1 000 nodes (0.19 GB) it runs; with the cap
    lifted but only 4 GB available on the machine, it is not run either."""
    from corrugate.fea.verify import BYTES_PER_NODE
    from corrugate.web import app as web

    assert BYTES_PER_NODE == 48_000
    folder = _with_bound(design, tmp_path, 62e3)
    monkeypatch.setattr(web, "available_memory", lambda: 20 * 1024**3)
    alongs = _stand_in(monkeypatch, tmp_path, K15, nodes=60_000)
    got = web.verify_job(folder, (2, 4, 8), 60.0, 8 * 1024**3, max_mesh=16)
    assert alongs == [2, 4, 8]
    row = got["constraints"][0]
    assert row["verdict"] == "not converged" and got["exit_code"] == 5
    assert "not extended to 16 per facet: its run would take about 11.5 GB" in row["note"]
    assert "not converged (memory) at 8 per facet" in row["note"]
    alongs = _stand_in(monkeypatch, tmp_path, K15, nodes=1000)
    assert web.verify_job(folder, (2, 4, 8), 60.0, 8 * 1024**3, max_mesh=16)["verdict"] == "holds"
    assert alongs == [2, 4, 8, 16]
    monkeypatch.setattr(web, "available_memory", lambda: 4 * 10**9)
    alongs = _stand_in(monkeypatch, tmp_path, K15, nodes=30_000)  # 5.8 GB at 16
    got = web.verify_job(folder, (2, 4, 8), 60.0, None, max_mesh=16)
    assert alongs == [2, 4, 8] and "(memory)" in got["constraints"][0]["note"]


def test_the_cli_does_not_make_a_run_the_machines_memory_does_not_allow(
    cli: CliRun, design: Path, tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    """``corrugate verify`` reads the memory available as the web job does: runs of 30 000
    nodes, the 16-per-facet run estimated at 4 x 30 000 x 48 kB = 5.8 GB, with 4 GB available:
    not run, the row not converged (memory), exit code 5 (before, the command started it and
    CalculiX failed or the kernel killed it); with 20 GiB available it runs and the row holds."""
    from corrugate.core import memory

    folder = _with_bound(design, tmp_path, 62e3)
    monkeypatch.setattr(memory, "available_memory", lambda: 4 * 10**9)
    alongs = _stand_in(monkeypatch, tmp_path, K15, nodes=30_000)
    code, out, _ = cli(["verify", str(folder), "--no-first-failure", "--json"])
    row = json.loads(out)["constraints"][0]
    assert code == 5 and alongs == [2, 4, 8]
    assert "not extended to 16 per facet: its run would take about 5.8 GB" in row["note"]
    assert "(memory)" in row["note"]
    monkeypatch.setattr(memory, "available_memory", lambda: 20 * 1024**3)
    alongs = _stand_in(monkeypatch, tmp_path, K15, nodes=30_000)
    code, out, _ = cli(["verify", str(folder), "--no-first-failure", "--json"])
    assert code == 0 and alongs == [2, 4, 8, 16]
    assert json.loads(out)["constraints"][0]["verdict"] == "holds"


@pytest.mark.slow
def test_the_app_offers_16_per_facet_and_refuses_finer(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    """``GET /api/fea`` says the cap (16); a series asking for 2 / 16 is accepted as far as its
    meshes go (the unknown result is what is refused), 2 / 32 is refused naming the mesh and the
    cap, 422 before any job."""
    stub = tmp_path / "ccx"
    stub.write_text("#!/bin/sh\nexit 1\n")
    stub.chmod(0o755)
    monkeypatch.setenv("CORRUGATE_CCX", str(stub))
    with TestClient(create_app(WebSettings(processes=1))) as client:
        info = client.get("/api/fea").json()
        assert info["available"] is True and info["max_mesh"] == 16
        r = client.post("/api/jobs/verify", json={"result": "nope", "mesh": "2,16"})
        assert r.status_code == 422 and r.json()["field"] == "result"
        r = client.post("/api/jobs/verify", json={"result": "nope", "mesh": "2,32"})
        assert r.status_code == 422 and r.json()["field"] == "mesh"
        assert "at most 16 elements per facet" in r.json()["detail"]
