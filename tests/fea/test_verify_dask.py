"""``corrugate verify DIR`` scaled out (issue 39, item 5): the FE runs of its constraint rows and
first-failure rows as tasks on a dask cluster of two worker processes, or in a local pool of two,
give the verify.json of the run in one process, number for number, its mesh series refined in
rounds (ccx is deterministic: the same
decks give the same results wherever they run); a run whose worker is killed is reported in its
row and the verification goes on."""

from __future__ import annotations

import json
import os
import shutil
import subprocess
import sys
from pathlib import Path
from typing import TYPE_CHECKING, Any

import pytest

from data_files import VERIFY_SMALL

if TYPE_CHECKING:
    from conftest import CliRun

#: A 20 mm square of Dura-Lar with an EI bound (the four-point gauge), a three-point deflection
#: under 0.3 N and the load capacity it brings (a buckling run): three constraint rows and two
#: first-failure rows (three-point buckling and yield), a few seconds of CalculiX per mesh
#: (the design of tests/fea/test_verify.py).
SPEC = VERIFY_SMALL.read_text()


@pytest.fixture(scope="module")
def designed(tmp_path_factory: pytest.TempPathFactory) -> Path:
    from corrugate.cli import main

    folder = tmp_path_factory.mktemp("verify-dask")
    spec = folder / "small.toml"
    spec.write_text(SPEC)
    out = folder / "design"
    with pytest.raises(SystemExit) as info:
        main(["design", str(spec), "--out", str(out), "-q"])
    assert info.value.code in (0, None)
    return out


def _copy(designed: Path, to: Path) -> Path:
    shutil.copytree(designed, to)
    return to


@pytest.mark.fea
def test_verify_on_a_dask_cluster_and_a_pool_equals_the_single_process_run(
    ccx: str, cli: CliRun, designed: Path, dask_cluster: str, tmp_path: Path
) -> None:
    # one requested mesh, refined to 4 per facet: the runs at 2 in one round, then each open
    # row's extending run at 4 in the next (the rounds of fea.tasks.Tasks)
    args = ["--mesh", "2", "--max-mesh", "4", "--json"]
    code, out, _ = cli(["verify", str(_copy(designed, tmp_path / "one")), *args])
    single: dict[str, Any] = json.loads(out)
    rows = single["constraints"]
    assert {r["quantity"] for r in rows} == {"EI@0", "k3pt@0", "Pmax3pt@0"}
    for r in rows:
        assert list(r["fe_series"]) == ["2", "4"] and None not in r["fe_series"].values()
        assert r["extended"].startswith("extended to 4 per facet")
    assert {r["mode"] for r in single["first_failure"]} == {"buckling", "yield"}
    for how, name in ((["--scheduler", dask_cluster], "dask"), (["--jobs", "2"], "pool")):
        code_there, out, _ = cli(["verify", str(_copy(designed, tmp_path / name)), *args, *how])
        assert code_there == code
        assert json.loads(out) == single  # every number, note and verdict
        written = json.loads((tmp_path / name / "verify.json").read_text())
        assert written["constraints"] == rows


#: A verification whose runs at 4 elements per facet kill their worker (SIGKILL, as the
#: out-of-memory killer does), in a process of its own: the pool's workers are forked from it,
#: not from pytest (which holds the session's dask cluster).
KILLING_SCRIPT = """
import json, os, signal, sys
from pathlib import Path
from corrugate.export.record import read_design_file
from corrugate.fea import verify

real = verify._solve_caught

def killed_at_4(run):
    if run.along == 4:
        os.kill(os.getpid(), signal.SIGKILL)
    return real(run)

verify._solve_caught = killed_at_4
d = read_design_file(Path(sys.argv[1]))
lines = []
v = verify.verify_design(
    d.assembly, d.constraints, d.joint, (2, 4), max_mesh=4, jobs=2, progress=lines.append
)
print(json.dumps({"rows": [r.as_json() for r in v.rows], "exit": v.exit_code, "lines": lines}))
"""


@pytest.mark.fea
def test_a_run_whose_worker_is_killed_is_reported_in_its_row(ccx: str, designed: Path) -> None:
    root = Path(__file__).resolve().parents[2]
    env = {**os.environ, "PYTHONPATH": str(root / "src")}
    done = subprocess.run(
        [sys.executable, "-c", KILLING_SCRIPT, str(designed)],
        capture_output=True,
        text=True,
        env=env,
        timeout=600,
        check=False,
    )
    assert done.returncode == 0, done.stderr
    found = json.loads(done.stdout)
    assert len(found["rows"]) == 3
    for r in found["rows"]:
        assert r["fe_series"]["4"] is None  # its worker died, twice (the pool's one retry, alone)
        assert "4/facet not run: worker failed" in r["note"]
        # the runs at 2, lost with the pool, ran again alone
        assert r["fe_series"]["2"] is not None and r["fe_series"]["2"] > 0
        assert r["verdict"] == "not converged"  # a run that failed never lets a row hold
    assert found["exit"] == 5
    assert any(": failed (" in line for line in found["lines"])  # said as it finished
