"""The output folder stays the user's: refused targets (the root, system folders, home, the
working folder and its ancestors) before any work; a symlinked folder stays a symlink; the folder's
mode stays; a forged manifest cannot make a run delete a user's file; a FIFO or a huge file as the
manifest is not read (files in tmp_path, read back)."""

from __future__ import annotations

import json
import os
import stat
import subprocess
import sys
from pathlib import Path

import pytest

from corrugate.core.errors import OutputError
from corrugate.core.fileio import MANIFEST, MAX_MANIFEST_BYTES, read_manifest, write_set

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
