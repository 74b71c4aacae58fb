"""The output folder stays the user's: refused targets (the root, system folders, home, the
working folder and its ancestors) before any work; a symlinked folder stays a symlink; the set is
committed inside the folder, so its inode, mode, extended attributes, a user's file and a process
working in it stay; a full disk leaves the old set; a kill at every step of a commit, settled by the
next run, leaves the old or the new complete set; a forged manifest cannot make a run delete a
user's file; a FIFO or a huge file as the manifest is not read (files in tmp_path, read back)."""

from __future__ import annotations

import contextlib
import errno
import hashlib
import json
import os
import stat
import subprocess
import sys
import time
from collections.abc import Callable, Iterator, Mapping
from pathlib import Path
from typing import Any

import pytest

import corrugate.core.fileio as fileio
from corrugate.core.errors import OutputError
from corrugate.core.fileio import (
    JOURNAL,
    MANIFEST,
    MAX_MANIFEST_BYTES,
    read_manifest,
    recover,
    write_set,
)

ROOT = Path(__file__).resolve().parents[2]


@pytest.mark.parametrize("target", ["/", "/etc", "/usr/lib", "/proc/self", "/sys", "/dev/shm"])
def test_system_targets_are_refused(target: str, tmp_path: Path) -> None:
    with pytest.raises(OutputError, match=r"--out = .*system"):
        write_set(target, {"a.txt": "x"})
    assert not list(tmp_path.iterdir())


def test_the_working_folder_its_ancestors_and_home_are_refused(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    work = tmp_path / "work"
    work.mkdir()
    (work / "mine.txt").write_text("mine")
    monkeypatch.chdir(work)
    for target in (".", str(work), "..", str(tmp_path)):
        with pytest.raises(OutputError, match="working folder"):
            write_set(target, {"a.txt": "x"})
    monkeypatch.setenv("HOME", str(tmp_path / "home"))
    (tmp_path / "home").mkdir()
    with pytest.raises(OutputError, match="home folder"):
        write_set(tmp_path / "home", {"a.txt": "x"})
    assert sorted(p.name for p in work.iterdir()) == ["mine.txt"]
    write_set("out", {"a.txt": "x"})  # a folder inside the working folder is fine
    assert (work / "out" / "a.txt").read_text() == "x"


@pytest.mark.parametrize("target", ["/", ".", ""])
def test_the_cli_refuses_before_solving_with_one_line(target: str, tmp_path: Path) -> None:
    run = subprocess.run(
        [
            sys.executable,
            "-m",
            "corrugate",
            "design",
            str(ROOT / "examples" / "infeasible.toml"),
            "--out",
            target,
        ],
        capture_output=True,
        text=True,
        cwd=tmp_path,
        env={**os.environ, "PYTHONPATH": str(ROOT / "src")},
        timeout=120,
    )
    assert run.returncode == 2
    (line,) = run.stderr.splitlines()
    assert line.startswith("corrugate: error: --out = ") and "folder" in line
    assert run.stdout == "" and not list(tmp_path.iterdir())  # refused before any answer


def test_a_symlinked_folder_stays_a_symlink_and_keeps_its_mode(tmp_path: Path) -> None:
    target = tmp_path / "real"
    target.mkdir(mode=0o700)
    os.chmod(target, 0o700)
    (target / "mine.txt").write_text("mine")
    link = tmp_path / "out"
    link.symlink_to(target)
    for k in range(2):
        write_set(link, {"a.txt": f"run {k}"}, kind="design")
        assert link.is_symlink() and os.readlink(link) == str(target)
        assert (target / "a.txt").read_text() == f"run {k}"
        assert stat.S_IMODE(os.stat(target).st_mode) == 0o700
        assert (target / "mine.txt").read_text() == "mine"
    assert sorted(p.name for p in tmp_path.iterdir()) == ["out", "real"]  # nothing left aside


def test_a_forged_manifest_cannot_delete_a_users_file(tmp_path: Path) -> None:
    out = tmp_path / "out"
    write_set(out, {"a.txt": "set"}, kind="design")
    (out / "thesis.tex").write_text("years of work")
    forged = {"sets": {"design": {"run": "x", "files": {"thesis.tex": "0" * 64, "a.txt": "0"}}}}
    (out / MANIFEST).write_text(json.dumps(forged))
    write_set(out, {"b.txt": "new"}, kind="design")
    assert (out / "thesis.tex").read_text() == "years of work"
    assert (out / "b.txt").read_text() == "new"
    # a.txt no longer matches what the forged manifest says the set wrote: it stays too
    assert (out / "a.txt").read_text() == "set"
    # while a file the set wrote, unchanged, is replaced by the next set of its kind
    write_set(out, {"c.txt": "newer"}, kind="design")
    assert not (out / "b.txt").exists() and (out / "c.txt").read_text() == "newer"


def test_a_fifo_or_a_huge_manifest_is_not_read(tmp_path: Path) -> None:
    out = tmp_path / "out"
    out.mkdir()
    os.mkfifo(out / MANIFEST)  # reading it would block for ever
    assert read_manifest(out) == {}
    write_set(out, {"a.txt": "x"}, kind="design")  # returns: the FIFO is not opened to read
    assert read_manifest(out)["design"]["files"].keys() == {"a.txt"}
    (out / MANIFEST).unlink()
    (out / MANIFEST).symlink_to("/dev/zero")
    assert read_manifest(out) == {}
    (out / MANIFEST).unlink()
    (out / MANIFEST).write_bytes(b" " * (MAX_MANIFEST_BYTES + 1))
    assert read_manifest(out) == {}


# -- the set is committed inside the folder -------------------------------------------------------


def _sha(data: str) -> str:
    return hashlib.sha256(data.encode()).hexdigest()


def _xattr_ok(path: Path) -> bool:
    try:
        os.setxattr(path, "user.corrugate-test", b"mine")
    except OSError:
        return False
    return True


def test_the_commit_keeps_the_folder_its_inode_mode_xattr_files_and_a_process_in_it(
    tmp_path: Path,
) -> None:
    real = tmp_path / "real"
    real.mkdir()
    os.chmod(real, 0o700)
    if not _xattr_ok(real):
        pytest.skip(f"the file system of {tmp_path} takes no user.* extended attributes")
    (real / "mine.txt").write_text("mine")
    link = tmp_path / "out"
    link.symlink_to(real)
    write_set(link, {"a.txt": "old", "gone.txt": "old"}, kind="design")
    inode = os.stat(real).st_ino
    sleeper = subprocess.Popen(["sleep", "60"], cwd=link)
    try:
        deadline = time.monotonic() + 10
        while os.readlink(f"/proc/{sleeper.pid}/cwd") != str(real):
            assert time.monotonic() < deadline, "sleep did not start in the folder"
            time.sleep(0.01)
        for k in range(3):
            write_set(link, {"a.txt": f"new {k}", "b.txt": f"new {k}"}, kind="design")
            cwd = os.readlink(f"/proc/{sleeper.pid}/cwd")
            assert cwd == str(real), cwd  # not "... (deleted)": the folder was not replaced
            assert os.stat(real).st_ino == inode
            assert link.is_symlink() and os.readlink(link) == str(real)
            assert stat.S_IMODE(os.stat(real).st_mode) == 0o700
            assert os.getxattr(real, "user.corrugate-test") == b"mine"
            assert (real / "mine.txt").read_text() == "mine"
            assert (real / "a.txt").read_text() == f"new {k}"
            names = sorted(p.name for p in real.iterdir())
            assert names == [MANIFEST, "a.txt", "b.txt", "mine.txt"]  # gone.txt dropped
    finally:
        sleeper.kill()
        sleeper.wait()
    assert sorted(p.name for p in tmp_path.iterdir()) == ["out", "real"]


def _leftovers(folder: Path) -> list[str]:
    return sorted(
        p.name
        for p in folder.iterdir()
        if p.name == JOURNAL or (p.name.startswith(".") and p.name != MANIFEST)
    )


@contextlib.contextmanager
def _small_disk(where: Path, size: str) -> Iterator[Path]:
    """A tmpfs of ``size`` mounted at ``where`` (skips where mounting is not allowed)."""
    where.mkdir()
    run = subprocess.run(
        ["mount", "-t", "tmpfs", "-o", f"size={size}", "tmpfs", str(where)],
        capture_output=True,
        text=True,
        check=False,
    )
    if run.returncode != 0:
        pytest.skip(f"cannot mount a small tmpfs here: {run.stderr.strip()}")
    try:
        yield where
    finally:
        subprocess.run(["umount", "-l", str(where)], check=False)


def test_a_full_disk_leaves_the_old_set_no_staged_file_and_one_line(tmp_path: Path) -> None:
    """A real full disk (a 512 kB tmpfs; as root) while the new set is staged."""
    with _small_disk(tmp_path / "small", "512k") as disk:
        out = disk / "out"
        old = {f"f{i}.bin": os.urandom(60_000) for i in range(4)}  # 240 kB
        write_set(out, old, kind="design")
        (out / "mine.txt").write_text("mine")
        before = {p.name: p.read_bytes() for p in out.iterdir()}
        new = {f"f{i}.bin": os.urandom(90_000) for i in range(4)}  # 360 kB: does not fit beside
        with pytest.raises(OutputError) as info:
            write_set(out, new, kind="design")
        text = str(info.value)
        assert "\n" not in text and "No space left on device" in text and str(out) in text
        assert {p.name: p.read_bytes() for p in out.iterdir()} == before  # old set, no temp
        assert sorted(p.name for p in disk.iterdir()) == ["out"]
        fresh = disk / "fresh"  # a folder made for the set is removed with it
        with pytest.raises(OutputError, match="No space left"):
            write_set(fresh, new, kind="design")
        assert sorted(p.name for p in disk.iterdir()) == ["out"]


@pytest.mark.parametrize("failing", [1, 2, 3, 4])
def test_a_simulated_full_disk_while_staging_leaves_the_old_set(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch, failing: int
) -> None:
    """ENOSPC from the ``failing``-th fsync of a file (where a tmpfs cannot be mounted): of a staged
    file (1, 2), of the staged manifest (3), of the journal (4)."""
    out = tmp_path / "out"
    write_set(out, {"a.txt": "old", "b.txt": "old"}, kind="design")
    before = {p.name: p.read_bytes() for p in out.iterdir()}
    real_fsync = os.fsync
    calls = [0]

    def full(fd: int) -> None:
        if stat.S_ISREG(os.fstat(fd).st_mode):  # a folder's fsync is not counted
            calls[0] += 1
            if calls[0] == failing:
                raise OSError(errno.ENOSPC, os.strerror(errno.ENOSPC))
        real_fsync(fd)

    monkeypatch.setattr(os, "fsync", full)
    with pytest.raises(OutputError, match=r"No space left on device\)"):
        write_set(out, {"a.txt": "new", "c.txt": "new"}, kind="design")
    assert calls[0] == failing
    assert {p.name: p.read_bytes() for p in out.iterdir()} == before


def _complete_set(folder: Path, expected: Mapping[str, str]) -> bool:
    """Whether ``folder``'s design set is ``expected`` (name -> text) whole: the manifest lists
    exactly those files with their SHA-256, each present with it, nothing else but the user's file,
    the other kind's set and the manifest."""
    sets = read_manifest(folder)
    if sets.get("design", {}).get("files") != {n: _sha(t) for n, t in expected.items()}:
        return False
    if sets.get("pareto", {}).get("files") != {"p.csv": _sha("pareto")}:
        return False
    names = {p.name for p in folder.iterdir()}
    if names != {*expected, "mine.txt", "p.csv", MANIFEST}:
        return False
    return all((folder / n).read_text() == t for n, t in expected.items())


def _killed_at(step: int, action: Callable[[], object]) -> bool:
    """Run ``action`` in a forked child that dies (``os._exit``, no cleanup: a SIGKILL) just
    before its ``step``-th call of os.replace, os.rename, os.link or os.unlink; True if it got
    there, False if the action finished first."""
    pid = os.fork()
    if pid == 0:  # pragma: no cover - the child
        try:
            calls = [0]

            def counted(fn: Callable[..., Any]) -> Callable[..., Any]:
                def call(*args: Any, **kwargs: Any) -> Any:
                    if calls[0] == step:
                        os._exit(9)
                    calls[0] += 1
                    return fn(*args, **kwargs)

                return call

            for name in ("replace", "rename", "link", "unlink"):
                setattr(os, name, counted(getattr(os, name)))
            action()
        finally:
            os._exit(0)
    _, status = os.waitpid(pid, 0)
    return os.waitstatus_to_exitcode(status) == 9


@pytest.mark.slow
def test_a_kill_at_every_step_of_a_commit_settles_to_the_old_or_the_new_set(
    tmp_path: Path,
) -> None:
    """For every k, a run dies before its k-th rename, link or unlink; the next run's recovery
    (:func:`recover`, itself killed at every step once) leaves the old or the new complete set, as
    the manifest says: the old one before the manifest's rename, the new one after; then no
    staged file, backup or journal is left, and the folder's inode, mode and user's file stay."""
    old = {"a.txt": "old a", "b.txt": "same", "c.txt": "old c"}
    new = {"a.txt": "new a", "b.txt": "same", "d.txt": "new d"}
    outcomes: list[str] = []
    k = 0
    while True:
        out = tmp_path / f"k{k}"
        out.mkdir()
        os.chmod(out, 0o700)
        (out / "mine.txt").write_text("mine")
        write_set(out, {"p.csv": "pareto"}, kind="pareto")
        write_set(out, old, kind="design")
        inode = os.stat(out).st_ino
        if not _killed_at(k, lambda out=out: write_set(out, new, kind="design")):
            break  # the commit has fewer steps: it finished
        in_window = (out / JOURNAL).exists()
        j = 0
        while in_window and _killed_at(j, lambda out=out: recover(out)):
            j += 1  # the recovery killed at its j-th step, recovered again by the next one
        recover(out)
        if _complete_set(out, old):
            outcomes.append("old")
        elif _complete_set(out, new):
            outcomes.append("new")
        else:
            pytest.fail(f"kill before step {k}: {sorted(p.name for p in out.iterdir())}")
        assert _leftovers(out) == [], k
        assert os.stat(out).st_ino == inode and stat.S_IMODE(os.stat(out).st_mode) == 0o700
        assert (out / "mine.txt").read_text() == "mine"
        k += 1
    assert _complete_set(tmp_path / f"k{k}", new)  # the run that was not killed
    # the old set up to the manifest's rename, the new one from it on, each at least once
    assert "old" in outcomes and "new" in outcomes
    switch = outcomes.index("new")
    assert outcomes == ["old"] * switch + ["new"] * (len(outcomes) - switch), outcomes
    assert k >= 8  # journal, 2 backups, 3 renames, manifest, drop, backups, journal


def test_a_failed_rename_mid_commit_is_rolled_back_by_the_run_itself(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    out = tmp_path / "out"
    old = {f"f{i}.txt": "old" for i in range(6)}
    write_set(out, old, kind="design")
    before = {p.name: p.read_bytes() for p in out.iterdir()}
    real_replace = os.replace
    calls = [0]

    def failing(src: Any, dst: Any) -> None:
        calls[0] += 1
        if calls[0] == 4:  # the journal, two files renamed, then this one fails
            raise OSError(errno.EIO, "Input/output error", str(dst))
        real_replace(src, dst)

    monkeypatch.setattr(fileio.os, "replace", failing)
    with pytest.raises(OutputError) as info:
        write_set(out, {f"f{i}.txt": "new" for i in range(8)}, kind="design")
    assert "\n" not in str(info.value) and "Input/output error" in str(info.value)
    monkeypatch.setattr(fileio.os, "replace", real_replace)
    assert {p.name: p.read_bytes() for p in out.iterdir()} == before  # rolled back whole


def test_two_runs_at_once_each_commit_a_whole_set(tmp_path: Path) -> None:
    """Commits into one folder are serialized by its lock: the last one wins, whole."""
    import threading

    out = tmp_path / "out"
    write_set(out, {"a.txt": "first"}, kind="design")
    errors: list[BaseException] = []

    def run(k: int) -> None:
        try:
            for r in range(10):
                write_set(out, {f"x{k}.txt": str(r), "a.txt": f"{k}-{r}"}, kind="design")
        except BaseException as exc:  # pragma: no cover - reported below
            errors.append(exc)

    threads = [threading.Thread(target=run, args=(k,)) for k in range(3)]
    for t in threads:
        t.start()
    for t in threads:
        t.join()
    assert errors == []
    files = read_manifest(out)["design"]["files"]
    assert isinstance(files, dict) and set(files) == {p.name for p in out.iterdir()} - {MANIFEST}
    assert all(_sha((out / n).read_text()) == d for n, d in files.items())


def test_a_forged_or_broken_journal_reaches_nothing_outside_the_folder(tmp_path: Path) -> None:
    out = tmp_path / "out"
    write_set(out, {"a.txt": "set"}, kind="design")
    victim = tmp_path / "victim.txt"
    victim.write_text("outside")
    staged = ".corrugate-999999999-0123456789ab.new.x"
    forged = {
        "files": {"../victim.txt": {"staged": staged, "sha256": _sha("outside"), "backup": None}},
        "drop": {"../victim.txt": _sha("outside")},
        "manifest": {"staged": staged, "sha256": "0" * 64},
    }
    for text in (json.dumps(forged), "{not json", ""):
        (out / JOURNAL).write_text(text)
        assert recover(out) == "unreadable journal removed"
        assert victim.read_text() == "outside" and not (out / JOURNAL).exists()
    assert (out / "a.txt").read_text() == "set"
    os.mkfifo(out / JOURNAL)  # not opened to read: removed
    assert recover(out) == "unreadable journal removed"
    write_set(out, {"b.txt": "new"}, kind="design")
    assert sorted(p.name for p in out.iterdir()) == [MANIFEST, "b.txt"]


def test_without_a_lock_a_live_runs_journal_is_left_to_it(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    """Where flock is missing, a journal of a run still alive is not settled by another run (one
    line, EBUSY); once that run is gone, the next run rolls it back."""
    out = tmp_path / "out"
    write_set(out, {"a.txt": "old"}, kind="design")
    monkeypatch.setattr(fileio, "fcntl", None)
    sleeper = subprocess.Popen(["sleep", "60"])
    gen = f"corrugate-{sleeper.pid}-0123456789ab"
    staged = f".{gen}.new.a.txt"
    (out / staged).write_text("new")
    backup = f".{gen}.bak.a.txt"
    os.link(out / "a.txt", out / backup)
    os.replace(out / staged, out / "a.txt")  # killed after its first rename
    journal = {
        "generation": gen,
        "files": {"a.txt": {"staged": staged, "sha256": _sha("new"), "backup": backup}},
        "drop": {},
        "manifest": {"staged": f".{gen}.new.{MANIFEST}", "sha256": "0" * 64},
    }
    (out / JOURNAL).write_text(json.dumps(journal))
    try:
        with pytest.raises(OutputError, match="another run is committing"):
            write_set(out, {"a.txt": "mine"}, kind="design")
        assert (out / "a.txt").read_text() == "new" and (out / JOURNAL).exists()
    finally:
        sleeper.kill()
        sleeper.wait()
    assert recover(out) == "rolled back"
    assert (out / "a.txt").read_text() == "old" and _leftovers(out) == []
