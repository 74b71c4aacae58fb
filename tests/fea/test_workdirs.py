"""CalculiX work folders name their owner's pid, and the sweep removes only those whose owner has
ended (:mod:`corrugate.fea.workdirs`); ``corrugate verify`` killed with SIGKILL leaves its work
folder, and the next ``verify`` in that ``--workdir`` removes it (issue 37, item 2).

Which processes run is read from the system (a child started and waited for has ended; this test
process and a sleeping child run), never from the module under test."""

from __future__ import annotations

import os
import signal
import subprocess
import sys
import time
from pathlib import Path

import pytest

from corrugate.fea.ccx import work_dir
from corrugate.fea.workdirs import owner, owner_running, sweep_owned, sweep_stale
from corrugate.spec.examples import example_text

ROOT = Path(__file__).resolve().parents[2]


def _ended_pid() -> int:
    """The pid of a process that has run and ended (reaped)."""
    child = subprocess.Popen([sys.executable, "-c", "pass"])
    child.wait()
    return child.pid


def _folder(parent: Path, name: str, age_s: float = 0.0) -> Path:
    path = parent / name
    path.mkdir()
    (path / "job.inp").write_text("*NODE\n")
    if age_s:
        then = time.time() - age_s
        os.utime(path, (then, then))
    return path


def test_a_work_folder_names_its_owner_and_goes_after_the_run(tmp_path: Path) -> None:
    with work_dir(tmp_path) as wd:
        assert wd.parent == tmp_path and owner(wd) == os.getpid()
        assert wd.name.startswith(f"corrugate-ccx-{os.getpid()}-")
    assert not wd.exists()
    with work_dir(tmp_path, keep=True) as kept:  # a folder to keep names no owner
        assert owner(kept) is None and kept.name.startswith("corrugate-ccx-")
    assert kept.exists()
    assert sweep_stale(tmp_path) == [] and kept.exists()  # never swept


def test_the_sweep_removes_only_the_folders_of_ended_owners(tmp_path: Path) -> None:
    dead = _ended_pid()
    sleeper = subprocess.Popen(["sleep", "30"])
    try:
        time.sleep(0.05)
        stale = _folder(tmp_path, f"corrugate-ccx-{dead}-abc_123", age_s=60)
        live = _folder(tmp_path, f"corrugate-ccx-{sleeper.pid}-abc", age_s=0)
        mine = _folder(tmp_path, f"corrugate-ccx-{os.getpid()}-abc", age_s=60)
        legacy = _folder(tmp_path, "corrugate-ccx-q1w2e3r4", age_s=3600)
        other = _folder(tmp_path, f"something-{dead}-abc", age_s=3600)
        # the sleeper's pid on a folder changed before it started: a reused pid, not its owner
        reused = _folder(tmp_path, f"corrugate-ccx-{sleeper.pid}-old", age_s=3600)
        target = _folder(tmp_path, "target", age_s=3600)
        link = tmp_path / f"corrugate-ccx-{dead}-link"
        link.symlink_to(target, target_is_directory=True)
        file = tmp_path / f"corrugate-ccx-{dead}-file"
        file.write_text("x")
        assert owner_running(sleeper.pid, time.time()) and not owner_running(dead, time.time())
        assert not owner_running(sleeper.pid, time.time() - 3600)
        # a folder changed after the start of the sweeper is left, whoever made it
        assert sweep_stale(tmp_path, before=time.time() - 7200) == []
        removed = sweep_stale(tmp_path)
        assert sorted(removed) == sorted([stale, reused])
        for kept in (live, mine, legacy, other, target, link, file):
            assert kept.exists() or kept.is_symlink(), kept
        assert (target / "job.inp").exists()
        # once its owner is known to have ended, its folders go (the web app's worker pool)
        assert sweep_owned(sleeper.pid, tmp_path) == [live]
    finally:
        sleeper.kill()
        sleeper.wait()


@pytest.mark.slow  # a design (seconds) and two verify processes
def test_a_verify_killed_with_sigkill_leaves_nothing_after_the_next_run(tmp_path: Path) -> None:
    """CalculiX stubbed by a program that sleeps: ``verify --workdir W`` killed with SIGKILL
    during its first run leaves its work folder in W (nothing of it runs to remove it); the next
    ``verify --workdir W`` removes it before its own runs."""
    from corrugate.cli import main

    spec = tmp_path / "blimp_gripper.toml"
    spec.write_text(example_text("blimp_gripper"))
    with pytest.raises(SystemExit) as info:
        main(["design", str(spec), "--out", str(tmp_path / "d"), "-q"])
    assert info.value.code in (0, None)
    stub = tmp_path / "ccx"
    stub.write_text("#!/bin/sh\nexec sleep 60\n")
    stub.chmod(0o755)
    work = tmp_path / "work"
    env = dict(os.environ, CORRUGATE_CCX=str(stub), PYTHONPATH=str(ROOT / "src"))
    command = [sys.executable, "-m", "corrugate", "verify", str(tmp_path / "d"), "--mesh", "2"]
    command += ["--workdir", str(work), "--no-first-failure", "-q"]

    def killed_in_its_run() -> Path:
        """Start verify, wait for its work folder, SIGKILL it; its folder."""
        run = subprocess.Popen(command, env=env, stderr=subprocess.PIPE)
        try:
            deadline = time.monotonic() + 120
            while time.monotonic() < deadline:
                mine = [p for p in work.glob("corrugate-ccx-*") if owner(p) == run.pid]
                if mine and any(mine[0].iterdir()):  # its deck written, CalculiX running
                    break
                assert run.poll() is None, run.communicate()[1]
                time.sleep(0.05)
            else:
                pytest.fail("verify made no work folder")
        finally:
            run.send_signal(signal.SIGKILL)
            run.wait(30)
        return mine[0]

    first = killed_in_its_run()
    time.sleep(0.2)
    assert first.exists()  # the defect: nothing of a SIGKILLed process runs to remove it
    second = killed_in_its_run()
    assert not first.exists()  # the next run swept it before its own
    assert second.exists() and [p.name for p in work.iterdir()] == [second.name]
