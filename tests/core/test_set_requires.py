"""Sets made of other files of their folder (``requires``, :mod:`corrugate.core.fileio`): a
verification of one design.json is refused when that file changed under it, dropped by the commit
that changes it, never listed by :func:`read_manifest` once it is stale, and removed by
:func:`recover` (files in tmp_path; every digest computed here with hashlib)."""

from __future__ import annotations

import hashlib
import json
import os
import signal
import subprocess
import sys
from pathlib import Path

import pytest

import corrugate
from corrugate.core.errors import StaleSetError
from corrugate.core.fileio import JOURNAL, MANIFEST, read_manifest, recover, write_set

SRC = Path(corrugate.__file__).resolve().parents[1]


def _sha(text: str) -> str:
    return hashlib.sha256(text.encode()).hexdigest()


def _sets(out: Path) -> dict[str, object]:
    sets = json.loads((out / MANIFEST).read_text())["sets"]
    assert isinstance(sets, dict)
    return sets


def test_a_set_requiring_a_changed_file_is_refused_and_nothing_is_written(tmp_path: Path) -> None:
    out = tmp_path / "out"
    write_set(out, {"design.json": "A"}, kind="design")
    with pytest.raises(StaleSetError, match=r"design.json changed .* not written"):
        write_set(out, {"verify.json": "of B"}, kind="verify", requires={"design.json": _sha("B")})
    assert not (out / "verify.json").exists()
    assert set(_sets(out)) == {"design"}
    assert sorted(p.name for p in out.iterdir()) == [MANIFEST, "design.json"]


def test_the_commit_that_changes_a_required_file_drops_the_set_with_it(tmp_path: Path) -> None:
    out = tmp_path / "out"
    write_set(out, {"design.json": "A", "report.html": "r"}, kind="design")
    write_set(out, {"verify.json": "of A"}, kind="verify", requires={"design.json": _sha("A")})
    assert read_manifest(out)["verify"]["requires"] == {"design.json": _sha("A")}
    write_set(out, {"design.json": "A", "report.html": "r2"}, kind="design")  # same design.json
    assert (out / "verify.json").read_text() == "of A"
    write_set(out, {"design.json": "B", "report.html": "r"}, kind="design")
    assert not (out / "verify.json").exists()
    assert set(_sets(out)) == {"design"}
    assert not (out / JOURNAL).exists()


def test_a_verify_json_edited_by_the_user_is_not_deleted(tmp_path: Path) -> None:
    """The dropped set's files go only when they are still what the set wrote."""
    out = tmp_path / "out"
    write_set(out, {"design.json": "A"}, kind="design")
    write_set(out, {"verify.json": "of A"}, kind="verify", requires={"design.json": _sha("A")})
    (out / "verify.json").write_text("my notes")
    write_set(out, {"design.json": "B"}, kind="design")
    assert (out / "verify.json").read_text() == "my notes"
    assert set(_sets(out)) == {"design"}


def test_readers_and_recover_drop_a_set_whose_required_file_changed(tmp_path: Path) -> None:
    out = tmp_path / "out"
    write_set(out, {"design.json": "A"}, kind="design")
    write_set(out, {"verify.json": "of A"}, kind="verify", requires={"design.json": _sha("A")})
    (out / "design.json").write_text("edited")
    assert set(read_manifest(out)) == {"design"}
    assert "verify" in _sets(out)
    assert recover(out) == "dropped verify (made of files that changed)"
    assert not (out / "verify.json").exists()
    assert set(_sets(out)) == {"design"}
    assert recover(out) is None
    (out / "design.json").unlink()  # a required file that is gone: refused too
    with pytest.raises(StaleSetError):
        write_set(
            out, {"verify.json": "x"}, kind="verify", requires={"design.json": _sha("edited")}
        )
    assert not (out / "verify.json").exists()


def test_a_malformed_requires_entry_counts_as_stale(tmp_path: Path) -> None:
    out = tmp_path / "out"
    write_set(out, {"design.json": "A"}, kind="design")
    write_set(out, {"verify.json": "v"}, kind="verify", requires={"design.json": _sha("A")})
    sets = _sets(out)
    sets["verify"]["requires"] = {"../etc/passwd": "0" * 64}  # type: ignore[index]
    (out / MANIFEST).write_text(json.dumps({"sets": sets}))
    assert set(read_manifest(out)) == {"design"}
    recover(out)
    assert not (out / "verify.json").exists()


_KILLED_COMMIT = """
import os, signal, sys
from pathlib import Path
import corrugate.core.fileio as f
out = Path(sys.argv[1])
def die(folder, j):
    os.kill(os.getpid(), signal.SIGKILL)
f._finish = die
f.write_set(out, {"design.json": "B"}, kind="design")
"""


def test_a_design_commit_killed_after_its_commit_point_drops_the_verdict_on_recovery(
    tmp_path: Path,
) -> None:
    """Killed between the manifest (the commit point) and step 5: the next recover() completes
    the commit, verify.json of A goes with it."""
    out = tmp_path / "out"
    write_set(out, {"design.json": "A"}, kind="design")
    write_set(out, {"verify.json": "of A"}, kind="verify", requires={"design.json": _sha("A")})
    done = subprocess.run(
        [sys.executable, "-c", _KILLED_COMMIT, str(out)],
        env={**os.environ, "PYTHONPATH": str(SRC)},
        timeout=120,
        preexec_fn=lambda: signal.signal(signal.SIGINT, signal.SIG_DFL),
    )
    assert done.returncode == -signal.SIGKILL
    assert (out / JOURNAL).exists()
    assert recover(out) == "completed"
    assert (out / "design.json").read_text() == "B"
    assert not (out / "verify.json").exists()
    assert set(_sets(out)) == {"design"}


def test_a_verdict_that_names_no_design_json_is_superseded_by_the_next_design(
    tmp_path: Path,
) -> None:
    """A verify set written by an earlier version (no ``requires``) leaves with the next design
    set that supersedes its kind, even when design.json is byte for byte the same; a kind not
    superseded stays."""
    out = tmp_path / "out"
    write_set(out, {"design.json": "A"}, kind="design")
    write_set(out, {"verify.json": "old"}, kind="verify")
    write_set(out, {"pareto.csv": "p"}, kind="pareto")
    write_set(out, {"design.json": "A"}, kind="design", supersedes=("verify",))
    assert not (out / "verify.json").exists()
    assert (out / "pareto.csv").read_text() == "p"
    assert set(_sets(out)) == {"design", "pareto"}
