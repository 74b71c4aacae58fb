"""Fault tests (issue 12): kills during ``design --out``, failed commits, downloads racing
evictions, dead sweep workers, SIGTERM during a sweep."""

from __future__ import annotations

import json
import os
import signal
import subprocess
import sys
import threading
import time
from pathlib import Path
from typing import Any

import pytest

from corrugate.core.errors import OutputError
from corrugate.core.fileio import MANIFEST, read_manifest, recover, staged, write_set
from corrugate.geometry.layer import Assembly, Layer
from corrugate.materials.library import get_material

ROOT = Path(__file__).resolve().parents[2]
SRC = ROOT / "src"


def _env() -> dict[str, str]:
    return {**os.environ, "PYTHONPATH": str(SRC) + os.pathsep + os.environ.get("PYTHONPATH", "")}


# -- sets of files -----------------------------------------------------------------------------


def _write(out: Path, names: dict[str, str], kind: str = "design") -> None:
    with staged(out, kind=kind) as st:
        for name, text in names.items():
            st.path(out / name).write_text(text)


def test_a_set_replaces_the_old_set_whole_and_keeps_foreign_files(tmp_path: Path) -> None:
    out = tmp_path / "o"
    _write(out, {"a.txt": "1", "b.txt": "1", "c.txt": "1"})
    (out / "mine.txt").write_text("the user's")
    _write(out, {"a.txt": "2", "d.txt": "2"})
    names = sorted(p.name for p in out.iterdir())
    assert names == [MANIFEST, "a.txt", "d.txt", "mine.txt"]
    assert (out / "a.txt").read_text() == "2"
    _write(out, {"p.csv": "x"}, kind="pareto")  # another kind joins, the design set stays
    assert set(read_manifest(out)) == {"design", "pareto"}
    assert (out / "d.txt").exists()
    assert sorted(p.name for p in tmp_path.iterdir()) == ["o"]  # no leftovers beside it


def test_a_failed_commit_leaves_the_old_set_and_one_line(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    """A hard link refused while backing up the files a set replaces (here EACCES, which no
    copy can fall back from): the run rolls back before any rename, one line."""
    out = tmp_path / "o"
    _write(out, {f"f{i}.txt": "old" for i in range(10)})

    def broken(a: Path, b: Path, **kwargs: object) -> None:
        raise OSError(13, "Permission denied", str(b))

    monkeypatch.setattr(os, "link", broken)
    with pytest.raises(OutputError) as info:
        _write(out, {f"f{i}.txt": "new" for i in range(10)})
    assert "\n" not in str(info.value) and "Permission denied" in str(info.value)
    assert {p.read_text() for p in out.glob("f*.txt")} == {"old"}
    assert sorted(p.name for p in out.iterdir()) == sorted(
        [MANIFEST, *(f"f{i}.txt" for i in range(10))]
    )
    assert sorted(p.name for p in tmp_path.iterdir()) == ["o"]


def test_a_kill_between_the_two_renames_is_undone_by_the_next_run(tmp_path: Path) -> None:
    """An earlier version's commit (a sibling folder swapped in by two renames where renameat2 was
    missing): the old folder set aside, the new one not yet in place, the process died. The next
    run puts the old folder back."""
    out = tmp_path / "o"
    _write(out, {"a.txt": "old"})
    aside = tmp_path / ".o.corrugate-999999999-0123456789ab.old"
    staging = tmp_path / ".o.corrugate-999999999-ba9876543210.new"
    staging.mkdir()
    (staging / "a.txt").write_text("half")
    os.rename(out, aside)
    recover(out)
    assert (out / "a.txt").read_text() == "old"
    assert sorted(p.name for p in tmp_path.iterdir()) == ["o"]


@pytest.mark.parametrize(
    ("where", "words"),
    [
        ("file", "it is a file"),
        ("under-file", "cannot be written"),
        ("/proc/corrugate-test", "cannot be written"),
        ("long", "too long"),
    ],
)
def test_output_folder_os_errors_are_one_line(tmp_path: Path, where: str, words: str) -> None:
    (tmp_path / "f").write_text("x")
    out = {
        "file": tmp_path / "f",
        "under-file": tmp_path / "f" / "sub",
        "long": tmp_path / ("x" * 300),
    }.get(where, Path(where))
    with pytest.raises(OutputError) as info:
        write_set(out, {"a.txt": "1"})
    text = str(info.value)
    assert "\n" not in text and words in text and text.startswith("--out = ")


def _kill_driver(tmp_path: Path, trials: int, seed: int, *mode: str) -> dict[str, Any]:
    """The JSON summary of tests/system/kill_driver.py run on the case study into tmp_path/out."""
    r = subprocess.run(
        [
            sys.executable,
            str(ROOT / "tests" / "system" / "kill_driver.py"),
            str(ROOT / "examples" / "blimp_gripper.toml"),
            str(tmp_path / "out"),
            str(trials),
            str(seed),
            *mode,
        ],
        capture_output=True,
        text=True,
        env=_env(),
        timeout=1200,
        check=False,
    )
    assert r.returncode == 0, r.stderr[-3000:]
    summary: dict[str, Any] = json.loads(r.stdout.strip().splitlines()[-1])
    return summary


@pytest.mark.slow
def test_kill_during_design_out_leaves_one_complete_set(tmp_path: Path) -> None:
    """SIGKILL at random moments while ``design --out`` writes into a folder holding an earlier
    set (tests/system/kill_driver.py): every time, once settled as the next run does, the folder
    holds one complete set (every file parses and matches its run's manifest), keeps its inode, and
    the next run leaves no leftovers."""
    trials = 20
    summary = _kill_driver(tmp_path, trials, 12)
    print(f"kill test: {summary}")
    assert summary["trials"] >= 20
    assert summary["mixed"] == [] and summary["folder_changed"] == []
    assert summary["leftovers_after_next_run"] == []
    assert summary["old_set_kept"] + summary["new_set_complete"] == trials


@pytest.mark.slow
def test_kill_during_design_out_keeps_a_symlinked_0700_folder_and_a_users_file(
    tmp_path: Path,
) -> None:
    """60 SIGKILLs at random moments of ``design --out LINK``, LINK a symlink to a 0700 folder
    that holds a user's file, a third of them aimed at the commit itself (after its journal
    appears): each time, once settled as the next run does (:func:`recover`), one complete set;
    the symlink, the folder's inode and mode, the user's file and the working folder of a process
    in it as they were (tests/system/kill_driver.py, ``user-folder``)."""
    trials = 60
    summary = _kill_driver(tmp_path, trials, 22, "user-folder")
    print(f"kill test, user's folder: {summary}")
    assert summary["mixed"] == [] and summary["folder_changed"] == []
    assert summary["leftovers_after_next_run"] == []
    assert summary["old_set_kept"] + summary["new_set_complete"] == trials
    assert summary["new_set_complete"] > 0  # some kills came after a commit
    assert summary["killed_in_commit_window"] > 0  # and some inside one, settled by recover
    assert sum(summary["settled_by_recover"].values()) == summary["killed_in_commit_window"]


# -- downloads across evictions ------------------------------------------------------------------


@pytest.mark.slow
def test_downloads_across_evictions_never_fail() -> None:
    """1000+ downloads while results are published and evicted (3 kept): each answer is the whole
    file of the right result (200) or 404, never a 500 or a broken connection."""
    from fastapi.testclient import TestClient

    from corrugate.web import WebSettings, create_app

    app = create_app(WebSettings(max_results=3))
    store = app.state.store
    published: list[str] = []
    stop = threading.Event()

    def writer(folder: Path) -> list[Path]:
        rid = folder.name
        p = folder / "design.json"
        p.write_text(json.dumps({"id": rid, "pad": "x" * 20_000}))
        return [p]

    def publisher() -> None:
        while not stop.is_set():
            files = store.make(writer)
            published.append(files[0].result_id)

    counts = {"ok": 0, "gone": 0, "errors": 0}
    with TestClient(app, raise_server_exceptions=False) as client:
        for _ in range(4):
            published.append(store.make(writer)[0].result_id)
        threads = [threading.Thread(target=publisher)]
        for t in threads:
            t.start()
        try:
            i = 0
            while counts["ok"] + counts["gone"] + counts["errors"] < 1200:
                rid = published[-1 - (i % 4)]
                i += 1
                try:
                    r = client.get(f"/api/results/{rid}/design.json")
                except Exception:  # a broken connection
                    counts["errors"] += 1
                    continue
                if r.status_code == 200 and json.loads(r.content)["id"] == rid:
                    counts["ok"] += 1
                elif r.status_code == 404:
                    counts["gone"] += 1
                else:
                    counts["errors"] += 1
        finally:
            stop.set()
            for t in threads:
                t.join()
    print(f"downloads across evictions: {counts}, results published {len(published)}")
    assert counts["errors"] == 0
    assert counts["ok"] > 100 and counts["gone"] > 0


# -- FE sweeps with dying workers ----------------------------------------------------------------


def _cases(labels: list[str]) -> list[Any]:
    from corrugate.fea.validation import Case

    layer = Layer(5.0, 3, 120.0, get_material("dura-lar"), 0.1)
    return [Case(label, Assembly.identical(layer)) for label in labels]


def fake_run(case: Any) -> Any:
    """A worker's job: ``die-once:MARKER`` dies by SIGKILL the first time (creating MARKER),
    ``die-always`` every time, ``slow`` sleeps; each leaves a work folder under case.folder."""
    from corrugate.fea.validation import CaseResult

    work = Path(case.folder) / f"w-{os.getpid()}-{time.monotonic_ns()}"
    work.mkdir(parents=True)
    label: str = case.label
    if label.startswith("die-once:"):
        marker = Path(label.split(":", 1)[1])
        if not marker.exists():
            marker.write_text("died")
            time.sleep(0.2)
            os.kill(os.getpid(), signal.SIGKILL)
    elif label == "die-always":
        time.sleep(0.2)
        os.kill(os.getpid(), signal.SIGKILL)
    elif label == "slow":
        time.sleep(60)
    time.sleep(0.05)
    return CaseResult(case, {"K_N_per_mm@0": 1.0}, {}, {}, (), False, None)


@pytest.mark.slow
def test_a_dead_worker_restarts_the_pool_and_its_case_is_retried(tmp_path: Path) -> None:
    from corrugate.fea.series import run_sweep

    labels = [f"case {i}" for i in range(11)] + [f"die-once:{tmp_path / 'marker'}"]
    work = tmp_path / "work"
    results = list(run_sweep(_cases(labels), jobs=2, folder=work, run=fake_run))
    assert len(results) == 12
    assert sorted(r.case.label for r in results) == sorted(labels)
    assert [r.error for r in results if r.error] == []
    assert list(work.iterdir()) == []  # work folders removed

    labels = [f"case {i}" for i in range(11)] + ["die-always"]
    results = list(run_sweep(_cases(labels), jobs=2, folder=work, run=fake_run))
    assert len(results) == 12
    failed = [r for r in results if r.error]
    assert [r.case.label for r in failed] == ["die-always"]
    assert failed[0].error is not None and "\n" not in failed[0].error
    assert list(work.iterdir()) == []


SIGTERM_SCRIPT = """
import sys
from pathlib import Path
sys.path.insert(0, {tests!r})
from test_faults import _cases, fake_run
from corrugate.fea.series import run_sweep
for r in run_sweep(_cases(["slow", "slow"]), jobs=2, folder=Path({work!r}), run=fake_run):
    pass
"""


def _default_sigint() -> None:
    signal.signal(signal.SIGINT, signal.SIG_DFL)


@pytest.mark.parametrize("sig", [signal.SIGTERM, signal.SIGINT])
def test_work_folders_are_removed_on_sigterm_and_sigint(tmp_path: Path, sig: int) -> None:
    work = tmp_path / "work"
    code = SIGTERM_SCRIPT.format(tests=str(ROOT / "tests" / "system"), work=str(work))
    # SIGINT back to its default in the child: a background job (`cmd &` in a script, nohup)
    # starts pytest with SIGINT ignored, the child would inherit that and never see the signal
    proc = subprocess.Popen(
        [sys.executable, "-c", code],
        env=_env(),
        start_new_session=True,
        preexec_fn=_default_sigint,
    )
    deadline = time.monotonic() + 60
    while time.monotonic() < deadline:  # both workers made their work folders
        if work.is_dir() and len(list(work.glob("*/w-*"))) >= 2:
            break
        time.sleep(0.05)
    else:
        proc.kill()
        pytest.fail("the sweep did not start")
    os.killpg(proc.pid, sig) if sig == signal.SIGINT else proc.send_signal(sig)
    assert proc.wait(timeout=30) != 0
    time.sleep(0.2)
    assert list(work.iterdir()) == []
