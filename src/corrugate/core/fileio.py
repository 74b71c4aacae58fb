"""All-or-nothing file output: single files and whole sets of files.

Single files (:func:`atomic_write`, :func:`staged` without a folder): each file of one output step
is written to a hidden temporary file beside its target (``.NAME.corrugate-PID-XXXX.tmp``), fsynced,
and renamed onto its final name only when all of them are complete.

Sets of files (:func:`staged` with a folder, :func:`write_set`): the files that belong together
(a design's cut files, PDF, report and ``design.json``; a sweep's table, CSV and plot) are
committed inside the existing folder, file by file. The folder itself is never replaced: its
inode, a symlink to it, its mode, owner and extended attributes, the user's own files in it and
processes whose working folder it is stay as they were. A commit (:class:`FolderStaging`):

1. stages each file beside its target as a hidden file ``.corrugate-PID-XXXX.new.NAME`` (same
   folder, same suffix) and fsyncs it; a failure here (a full disk) removes the staged files and
   leaves the folder as it was;
2. under an exclusive ``flock`` of the folder, reads the manifest (:data:`MANIFEST`: per kind of
   set, the run's id and every file's SHA-256), stages the new one and reads it back, and writes
   the journal :data:`JOURNAL`, the generation marker: the new generation, each file's staged
   name, SHA-256 and backup name, the old files to drop and the new manifest's SHA-256 (fsynced);
3. hard-links every file it replaces to a backup ``.corrugate-PID-XXXX.bak.NAME`` (a copy where
   the file system has no hard links), then renames the staged files onto their names one by one;
4. renames the staged manifest onto :data:`MANIFEST`: **the commit point**;
5. removes the old set's files that the new set has not (only a file whose SHA-256 is still what
   the old manifest says the set wrote: a user's file is never deleted), the backups, and last
   the journal; the folder is fsynced between the steps.

A set may be made of other files of the folder (``requires``: their names and SHA-256, kept in
its manifest entry): ``verify.json`` is the verdict of one ``design.json``. Its commit is refused
(:class:`~corrugate.core.errors.StaleSetError`) when they changed since the run read them
(checked under the lock, before step 2); a later commit that changes them (a new design) drops
the set in its own journal (step 5), as does a commit that ``supersedes`` the set's kind when the
set names no required files (one an earlier version wrote), :func:`read_manifest` does not list a set whose files are no
longer those, and :func:`recover` drops it (a design.json edited by hand). So a folder never pairs
one design with another design's verdict.

A journal whose new manifest is not in place is rolled back (the backups renamed back, the set's
new files removed), one whose manifest is in place is rolled forward (step 5 finished): by the
failing run itself, and after a kill by the next run that writes there or by :func:`recover`.
After that the folder holds the old complete set or the new complete set, as its manifest lists
them, never a mix. What a reader sees before: while a live run is in steps 3-5 (milliseconds), or
after a kill in them until the next run, the folder's files may be a mix of the two sets (some
renamed, some not; the old set's extra files not yet dropped) while :data:`MANIFEST` still lists
the old set (until step 4) and :data:`JOURNAL` is present. A reader that must see one whole set
calls :func:`recover` first: it waits for a live commit's lock, settles a killed one and removes
what killed runs left behind. A file of the user's that has the name of one of the set's files is
replaced by it (as it always was); the journal, like the manifest, is read only as a regular file
of bounded size, and only plain names in the folder are taken from it. A missing folder is
created (its mode from the umask) and removed again if the set fails before its commit.

Every OS error becomes one :class:`~corrugate.core.errors.OutputError` line naming the path.

Input files (:func:`read_input`, :func:`read_input_text`): every file a command reads (a spec, a
design.json, a verify.json) is read as untrusted: a regular file only (opened non-blocking and
checked by ``fstat`` before a byte is read: a FIFO, a device, a folder is one line at once), at
most :data:`MAX_INPUT_BYTES` (8 MiB), decoded strictly as UTF-8; text taken from a file is
printed through :func:`printable` (no control characters reach the terminal).
"""

from __future__ import annotations

import contextlib
import errno
import hashlib
import json
import os
import re
import secrets
import shutil
import stat
from collections.abc import Iterator, Mapping
from contextlib import contextmanager
from pathlib import Path
from typing import Any

from corrugate.core.errors import CorrugateError, InputError, OutputError, StaleSetError
from corrugate.core.limits import MAX_DEPTH, MAX_PATH_CHARS, bracket_depth
from corrugate.core.text import printable

try:
    import fcntl
except ImportError:  # pragma: no cover - not a POSIX system: commits are not locked
    fcntl = None  # type: ignore[assignment]

__all__ = [
    "JOURNAL",
    "MANIFEST",
    "MAX_INPUT_BYTES",
    "MAX_MANIFEST_BYTES",
    "SYSTEM_FOLDERS",
    "SYSTEM_TREES",
    "FolderStaging",
    "Staging",
    "atomic_write",
    "check_output_folder",
    "decode_input",
    "parse_toml_input",
    "read_input",
    "read_input_text",
    "read_manifest",
    "recover",
    "staged",
    "write_set",
]

#: The manifest of the sets committed in a folder, inside it: ``{"sets": {kind: {"run": id,
#: "files": {name: sha256}}}}``; one set per kind (``design``, ``pareto``, ``sweep``), so that a
#: design and a Pareto front may share a folder while a new design replaces the old one whole.
MANIFEST = ".corrugate-set.json"

#: The journal of a set's commit in progress, inside the folder: its presence marks a
#: half-committed generation, which the next run completes or rolls back (see the module's text).
JOURNAL = ".corrugate-set.journal"

#: The largest manifest read (bytes): a real one lists a few dozen files.
MAX_MANIFEST_BYTES = 1 << 20

#: Folders that are never an output folder (after resolving symlinks and ``..``): the root, the
#: system's own folders and everything under the pseudo file systems.
SYSTEM_FOLDERS = ("/", "/bin", "/boot", "/dev", "/etc", "/lib", "/lib32", "/lib64", "/libx32",
                  "/proc", "/root", "/run", "/sbin", "/sys", "/usr", "/var", "/tmp", "/home",
                  "/opt", "/srv", "/mnt", "/media", "/snap")  # fmt: skip
#: Folders under which nothing is written (pseudo file systems, the system's programs and settings).
SYSTEM_TREES = ("/proc", "/sys", "/dev", "/run", "/etc", "/usr", "/bin", "/sbin", "/boot", "/lib",
                "/lib32", "/lib64", "/libx32")  # fmt: skip

#: A single file's temporary file, and (in a folder of an earlier version) a set's staging folder
#: or old folder beside it.
_LEFTOVER = re.compile(
    r"^\.(?P<name>.+)\.corrugate-(?P<pid>\d+)-[0-9a-f]{12}\.(?P<kind>new|old|tmp)$"
)
#: A set's staged file (``new``) or the backup of the file it replaces (``bak``), in the folder.
_STAGED = re.compile(r"^\.corrugate-(?P<pid>\d+)-[0-9a-f]{12}\.(?P<kind>new|bak)\.(?P<name>.+)$")
_SHA256 = re.compile(r"^[0-9a-f]{64}$")


def _tag() -> str:
    return f"corrugate-{os.getpid()}-{secrets.token_hex(6)}"


def _pid_alive(pid: int) -> bool:
    if pid == os.getpid():
        return True
    try:
        os.kill(pid, 0)
    except ProcessLookupError:
        return False
    except OSError:
        return True
    return True


def _fsync_file(path: Path) -> None:
    fd = os.open(path, os.O_RDONLY)
    try:
        os.fsync(fd)
    finally:
        os.close(fd)


def _fsync_dir(path: Path) -> None:
    with contextlib.suppress(OSError):  # not every file system syncs directories
        fd = os.open(path, os.O_RDONLY | os.O_DIRECTORY)
        try:
            os.fsync(fd)
        finally:
            os.close(fd)


def _remove(path: Path) -> None:
    if path.is_dir() and not path.is_symlink():
        shutil.rmtree(path, ignore_errors=True)
    else:
        with contextlib.suppress(OSError):
            path.unlink()


def check_output_folder(folder: str | os.PathLike[str], field: str = "--out") -> Path:
    """``folder`` as an output folder, refused (:class:`~corrugate.core.errors.OutputError`
    naming ``field``) when it is empty, longer than :data:`~corrugate.core.limits.MAX_PATH_CHARS`
    or with a folder name longer than 200 characters, the root or a system folder (:data:`SYSTEM_FOLDERS`),
    inside a pseudo file system (:data:`SYSTEM_TREES`), the user's home folder itself, or the
    working folder or one of its ancestors (a set's files would land among the user's own, and a
    later set of the same kind removes the earlier one's files there); returns the path with
    symlinks resolved. Called before any computation, and again by :class:`FolderStaging`."""
    text = os.fspath(folder)
    if not str(text).strip():
        raise OutputError(field, repr(text), "an empty path: name a folder, e.g. out/my-part")
    shown = _short(text)
    absolute = os.path.abspath(text)  # before the OS sees it: ENAMETOOLONG names no option
    if len(absolute) > MAX_PATH_CHARS or any(len(part) > 200 for part in Path(absolute).parts):
        raise OutputError(
            field,
            shown,
            f"the path is too long: at most {MAX_PATH_CHARS} characters, 200 a folder name",
        )
    real = Path(os.path.realpath(text))
    if str(real) in SYSTEM_FOLDERS:
        raise OutputError(field, shown, f"{real} is a system folder: name a folder of your own")
    for tree in SYSTEM_TREES:
        if real.is_relative_to(tree):
            raise OutputError(field, shown, f"{real} is inside {tree}, a system folder")
    home = os.path.realpath(os.path.expanduser("~"))
    if str(real) == home:
        raise OutputError(field, shown, "it is your home folder: name a folder inside it")
    cwd = Path(os.path.realpath(os.getcwd()))
    if cwd == real or cwd.is_relative_to(real):
        raise OutputError(
            field,
            shown,
            "it is the working folder or holds it: name a folder inside it, e.g. out",
        )
    return real


def recover(folder: str | os.PathLike[str]) -> str | None:
    """Settle what killed runs left in ``folder`` and around it; returns what was done with a
    half-committed set (``"rolled back"``, ``"completed"``, ``"unreadable journal removed"``),
    else with sets made of files that changed (``"dropped verify (...)"``), or None when there
    was nothing to do.

    Waits while a live run commits a set there (the folder's lock); a journal (:data:`JOURNAL`)
    left by a killed run is rolled back when its new manifest is not in place and completed when
    it is, so the folder then holds one complete set (see the module's text). Then the staged
    files, backups and temporary files of runs no longer alive are removed, and leftovers of an
    earlier version beside the folder (its staging folder, the old folder it swapped out) too, an
    old folder left aside between two renames being put back. A set whose required files
    (``requires``) changed is dropped, its files with it (module text). Runs still alive are left alone
    (where the file system has no ``flock``, a journal of one: OSError EBUSY)."""
    target = Path(folder)
    _recover_beside(target)
    if not target.is_dir():
        return None
    with _locked(target) as held:
        done = _settle(target, held=held)
        if held:
            dropped = _drop_stale(target)
            if dropped and done is None:
                done = "dropped " + ", ".join(dropped) + " (made of files that changed)"
        _sweep(target)
    return done


def _recover_beside(target: Path) -> None:
    """Leftovers of an earlier version's commit beside ``target``: a staging folder
    (``.NAME.corrugate-PID-XXXX.new``) removed, an old folder (``.old``) put back if ``target`` is
    missing, else removed."""
    try:
        entries = list(os.scandir(target.parent))
    except OSError:
        return
    for entry in entries:
        m = _LEFTOVER.match(entry.name)
        if m is None or m["name"] != target.name or _pid_alive(int(m["pid"])):
            continue
        path = Path(entry.path)
        if m["kind"] == "old" and not os.path.lexists(target):
            with contextlib.suppress(OSError):
                os.rename(path, target)
                continue
        _remove(path)


def _sweep(folder: Path) -> None:
    """Remove the staged files, backups and temporary files of runs no longer alive in
    ``folder`` (after :func:`_settle`: no journal names them any more)."""
    try:
        entries = list(os.scandir(folder))
    except OSError:
        return
    for entry in entries:
        m = _STAGED.match(entry.name) or _LEFTOVER.match(entry.name)
        if m is None or m["kind"] == "old" or _pid_alive(int(m["pid"])):
            continue
        _remove(Path(entry.path))


@contextmanager
def _locked(folder: Path) -> Iterator[bool]:
    """Hold the folder's exclusive lock (``flock`` on the folder itself): one set is committed or
    settled at a time. Where the system or file system has no such lock, go on without (yields
    False): a journal of a run still alive is then left to it (see :func:`_settle`), but two runs
    that begin their commits into one folder at the same moment are not kept apart."""
    fd = os.open(folder, os.O_RDONLY | os.O_DIRECTORY)
    held = False
    try:
        if fcntl is not None:
            with contextlib.suppress(OSError):
                fcntl.flock(fd, fcntl.LOCK_EX)
                held = True
        yield held
    finally:
        os.close(fd)  # releases the lock; so does a kill


class Staging:
    """The temporary files of one output step (see :func:`staged`)."""

    def __init__(self) -> None:
        self._files: list[tuple[Path, Path]] = []

    def path(self, target: str | os.PathLike[str]) -> Path:
        """A new temporary path in ``target``'s directory; it becomes ``target`` on commit."""
        final = Path(target)
        while True:  # a fresh name, created here (mode 0o666 less the umask, like any new file)
            tmp = final.parent / f".{final.name}.{_tag()}.tmp"
            try:
                tmp.open("x").close()
            except FileExistsError:
                continue
            break
        self._files.append((tmp, final))
        return tmp

    @property
    def targets(self) -> tuple[Path, ...]:
        """The final paths, in the order they were asked for."""
        return tuple(final for _, final in self._files)

    def commit(self) -> None:
        """fsync every temporary file, then move each onto its target."""
        for tmp, _ in self._files:
            _fsync_file(tmp)
        for tmp, final in self._files:
            os.replace(tmp, final)
        for parent in {final.parent for _, final in self._files}:
            _fsync_dir(parent)
        self._files.clear()

    def discard(self) -> None:
        """Remove every temporary file that is still there."""
        for tmp, _ in self._files:
            tmp.unlink(missing_ok=True)
        self._files.clear()


def read_manifest(folder: str | os.PathLike[str]) -> dict[str, dict[str, object]]:
    """The sets committed in ``folder`` (kind -> ``{"run": id, "files": {name: sha256}}``, and
    ``"requires": {name: sha256}`` for a set made of other files of the folder, a design's
    verification of its ``design.json``). A set whose required files are no longer those (a
    verification of another design) is not listed: it is dropped by the next commit or by
    :func:`recover`."""
    sets = _read_sets(Path(folder))
    return {k: v for k, v in sets.items() if not _stale(Path(folder), v)}


def _read_sets(folder: Path) -> dict[str, dict[str, object]]:
    """The manifest's sets as written (a set with malformed ``requires`` counts as stale)."""
    try:
        data = json.loads(_read_regular(folder / MANIFEST, MAX_MANIFEST_BYTES))
        sets = data["sets"]
    except (OSError, ValueError, KeyError, TypeError):
        return {}
    if not isinstance(sets, dict):
        return {}
    return {
        k: v for k, v in sets.items() if isinstance(v, dict) and isinstance(v.get("files"), dict)
    }


def _stale(folder: Path, entry: Mapping[str, object], new: Mapping[str, str] | None = None) -> bool:
    """Whether the set ``entry`` requires files of ``folder`` that are not (or, after a commit of
    the files ``new``, name -> SHA-256, will not be) the ones it was made of."""
    requires = entry.get("requires")
    if requires is None:
        return False
    if not isinstance(requires, dict) or not requires:
        return True
    for name, digest in requires.items():
        if not _plain(name) or not isinstance(digest, str) or _SHA256.match(digest) is None:
            return True
        if new is not None and name in new:
            if new[name] != digest:
                return True
        elif not _written_by_set(folder / name, digest):
            return True
    return False


def _read_regular(path: Path, limit: int) -> str:
    """The text of ``path`` if it is a regular file (not a symlink, FIFO or device: opened with
    ``O_NOFOLLOW | O_NONBLOCK``, checked by ``fstat``) of at most ``limit`` bytes; else OSError."""
    fd = os.open(path, os.O_RDONLY | os.O_NOFOLLOW | os.O_NONBLOCK)
    try:
        info = os.fstat(fd)
        if not stat.S_ISREG(info.st_mode) or info.st_size > limit:
            raise OSError(errno.EINVAL, "not a regular file of bounded size", str(path))
        with os.fdopen(fd, "rb", closefd=False) as fh:
            data = fh.read(limit + 1)
    finally:
        os.close(fd)
    if len(data) > limit:
        raise OSError(errno.EFBIG, "too large", str(path))
    return data.decode("utf-8")


def _written_by_set(path: Path, digest: object) -> bool:
    """Whether ``path`` is a regular file (not a symlink) whose SHA-256 is ``digest``: a file a
    manifest lists is replaced or removed only if it is still the one the set wrote."""
    try:
        return path.is_file() and not path.is_symlink() and _sha256(path) == digest
    except OSError:
        return False


def _sha256(path: Path) -> str:
    h = hashlib.sha256()
    with path.open("rb") as fh:
        for block in iter(lambda: fh.read(1 << 20), b""):
            h.update(block)
    return h.hexdigest()


def _unlink(path: Path) -> None:
    with contextlib.suppress(FileNotFoundError):
        os.unlink(path)


def _write_synced(path: Path, data: bytes) -> None:
    """Create ``path`` (it must not exist) with ``data`` and fsync it."""
    with path.open("xb") as fh:
        fh.write(data)
        fh.flush()
        os.fsync(fh.fileno())


def _plain(name: object) -> bool:
    """Whether ``name`` is a plain file name of a set (no folder part, not ours)."""
    return (
        isinstance(name, str)
        and name not in ("", ".", "..", MANIFEST, JOURNAL)
        and "/" not in name
        and "\0" not in name
        and _STAGED.match(name) is None
    )


def _read_journal(folder: Path) -> dict[str, Any] | None:
    """The journal in ``folder``: None if there is none, ``{}`` if it cannot be read or is not
    one a commit wrote (its names are checked: a forged journal cannot reach outside the
    folder nor name a file as staged or as a backup that is not)."""
    path = folder / JOURNAL
    if not os.path.lexists(path):
        return None
    try:
        j = json.loads(_read_regular(path, MAX_MANIFEST_BYTES))
        files, drop, manifest = j["files"], j["drop"], j["manifest"]
        ok = (
            isinstance(files, dict)
            and isinstance(drop, dict)
            and all(_plain(n) and isinstance(d, str) for n, d in drop.items())
            and _staged_name(manifest["staged"])
            and _SHA256.match(manifest["sha256"]) is not None
            and all(
                _plain(n)
                and _staged_name(f["staged"])
                and _SHA256.match(f["sha256"]) is not None
                and (f["backup"] is None or _staged_name(f["backup"]))
                for n, f in files.items()
            )
        )
    except (OSError, ValueError, KeyError, TypeError):
        return {}
    return j if ok and isinstance(j, dict) else {}


def _staged_name(name: object) -> bool:
    return isinstance(name, str) and "/" not in name and _STAGED.match(name) is not None


def _settle(folder: Path, journal: dict[str, Any] | None = None, held: bool = True) -> str | None:
    """Complete or roll back the half-committed set of ``journal`` (default: the folder's
    journal), under the folder's lock: completed when the manifest in place is the journal's new
    one (the commit point passed), else rolled back. Without the lock (``held`` False) the journal
    of another run still alive is not touched: OSError (EBUSY)."""
    j = _read_journal(folder) if journal is None else journal
    if j is None:
        return None
    if not held and journal is None and j:
        m = re.match(r"^corrugate-(\d+)-", str(j.get("generation", "")))
        if m is not None and int(m[1]) != os.getpid() and _pid_alive(int(m[1])):
            raise OSError(errno.EBUSY, "another run is committing a set in this folder")
    if not j:
        if not (folder / JOURNAL).is_dir():
            _unlink(folder / JOURNAL)
        return "unreadable journal removed"
    if _written_by_set(folder / MANIFEST, j["manifest"]["sha256"]):
        _finish(folder, j)
        return "completed"
    _roll_back(folder, j)
    return "rolled back"


def _roll_back(folder: Path, j: dict[str, Any]) -> None:
    """Undo steps 3 and 4 of a commit: each replaced file's backup renamed back (if the file
    there is still the one the set wrote, or missing), each new file the set added removed (if it
    is still the one the set wrote); then the staged files and the journal removed."""
    for name, f in j["files"].items():
        target = folder / name
        _unlink(folder / f["staged"])
        ours = not os.path.lexists(target) or _written_by_set(target, f["sha256"])
        if f["backup"] is not None:
            backup = folder / f["backup"]
            if os.path.lexists(backup):
                if ours:
                    os.replace(backup, target)
                else:  # someone else's file came since: it stays
                    _unlink(backup)
        elif ours:
            _unlink(target)
    _unlink(folder / j["manifest"]["staged"])
    _fsync_dir(folder)
    _unlink(folder / JOURNAL)
    _fsync_dir(folder)


def _finish(folder: Path, j: dict[str, Any]) -> None:
    """Step 5 of a commit: the old set's files that the new set has not removed (only if still
    what the old set wrote), the backups, the staged leftovers and then the journal."""
    for f in j["files"].values():
        _unlink(folder / f["staged"])
        if f["backup"] is not None:
            _unlink(folder / f["backup"])
    for name, digest in j["drop"].items():
        if _written_by_set(folder / name, digest):
            _unlink(folder / name)
    _unlink(folder / j["manifest"]["staged"])
    _fsync_dir(folder)
    _unlink(folder / JOURNAL)
    _fsync_dir(folder)


def _begin(
    folder: Path,
    generation: str,
    kind: str,
    files: Mapping[str, str],
    requires: Mapping[str, str],
    temps: list[Path],
    supersedes: tuple[str, ...] = (),
) -> dict[str, Any]:
    """Step 2 of a commit of ``files`` (name -> SHA-256, staged as ``.GENERATION.new.NAME``) as
    the set ``kind``: the old manifest read, the new one staged and read back, the journal
    written. The journal drops the kind's old files the new set has not, and every other set
    made of files (its ``requires``) that this commit changes or that changed since: a design's
    verification leaves with the design it checked, in the same commit; so does a set of a kind
    in ``supersedes`` that names no required files (a verification written by an earlier
    version, which did not record its design.json). Staged names are added to ``temps``."""
    sets = _read_sets(folder)
    listed = sets.pop(kind, {}).get("files", {})
    old_files: dict[object, object] = listed if isinstance(listed, dict) else {}
    drop = {
        str(name): str(digest)
        for name, digest in old_files.items()
        if _plain(name) and name not in files and _written_by_set(folder / str(name), digest)
    }  # a listed file is dropped only if it is still what the set wrote
    stale = [
        k
        for k, v in sets.items()
        if _stale(folder, v, files) or (k in supersedes and v.get("requires") is None)
    ]
    for other_kind in stale:
        gone = sets.pop(other_kind)["files"]
        assert isinstance(gone, dict)
        for name, digest in gone.items():
            if _plain(name) and name not in files and _written_by_set(folder / name, digest):
                drop[name] = digest
    for other in sets.values():  # files of other kinds that this set overwrites leave them
        other["files"] = {
            k: v
            for k, v in other["files"].items()  # type: ignore[attr-defined]
            if k not in files
        }
    if kind:
        entry: dict[str, object] = {"run": generation, "files": dict(files)}
        if requires:
            entry["requires"] = dict(requires)
        sets[kind] = entry
    staged_manifest = folder / f".{generation}.new.{MANIFEST}"
    temps.append(staged_manifest)
    _write_synced(staged_manifest, json.dumps({"sets": sets}, indent=1).encode("utf-8"))
    if json.loads(_read_regular(staged_manifest, MAX_MANIFEST_BYTES)) != {"sets": sets}:
        raise OSError(errno.EIO, "the manifest did not read back", str(staged_manifest))
    journal = {
        "format": 1,
        "generation": generation,
        "kind": kind,
        "files": {
            name: {
                "staged": f".{generation}.new.{name}",
                "sha256": digest,
                "backup": f".{generation}.bak.{name}" if os.path.lexists(folder / name) else None,
            }
            for name, digest in files.items()
        },
        "drop": drop,
        "manifest": {"staged": staged_manifest.name, "sha256": _sha256(staged_manifest)},
    }
    staged_journal = folder / f".{generation}.new.{JOURNAL}"
    temps.append(staged_journal)
    _write_synced(staged_journal, json.dumps(journal, indent=1).encode("utf-8"))
    os.replace(staged_journal, folder / JOURNAL)
    _fsync_dir(folder)
    return journal


def _drop_stale(folder: Path) -> list[str]:
    """Under the folder's lock, after :func:`_settle`: the sets whose required files changed
    since they were made (a verification whose ``design.json`` was edited or replaced by a run
    of an earlier version) dropped from the manifest and their files removed (only those still
    what the set wrote), as one journalled commit of no files; returns their kinds."""
    stale = [k for k, v in _read_sets(folder).items() if _stale(folder, v)]
    if not stale:
        return []
    temps: list[Path] = []
    journal = _begin(folder, _tag(), "", {}, {}, temps)
    try:
        _forward(folder, journal)
        _finish(folder, journal)
    except BaseException:
        with contextlib.suppress(OSError):
            _settle(folder, journal)
        raise
    finally:
        for p in temps:
            _unlink(p)
    return stale


def _backup(target: Path, backup: Path) -> None:
    """``backup``: a hard link to ``target`` (the file itself if it is a symlink), or a copy where
    the file system has no hard links."""
    try:
        os.link(target, backup, follow_symlinks=False)
    except OSError as exc:
        if exc.errno not in (
            errno.EPERM,
            errno.ENOTSUP,
            errno.EOPNOTSUPP,
            errno.EMLINK,
            errno.EXDEV,
        ):
            raise
        if target.is_symlink():
            os.symlink(os.readlink(target), backup)
        else:
            shutil.copy2(target, backup)


def _forward(folder: Path, j: dict[str, Any]) -> None:
    """Steps 3 and 4 of a commit: the backups, the staged files renamed onto their names one by
    one, then the manifest (the commit point), read back."""
    for name, f in j["files"].items():
        if f["backup"] is not None:
            _backup(folder / name, folder / f["backup"])
    _fsync_dir(folder)
    for name, f in j["files"].items():
        os.replace(folder / f["staged"], folder / name)
    _fsync_dir(folder)
    os.replace(folder / j["manifest"]["staged"], folder / MANIFEST)
    _fsync_dir(folder)
    if not _written_by_set(folder / MANIFEST, j["manifest"]["sha256"]):
        raise OSError(errno.EIO, "the manifest did not read back", str(folder / MANIFEST))


class FolderStaging(Staging):
    """The files of one set, staged beside their targets in ``folder`` and committed there file by
    file (see the module's text); the folder is created if missing.

    :meth:`path` of a file directly in ``folder`` gives its staged file; any other target is
    staged as a single file (:class:`Staging`)."""

    def __init__(
        self,
        folder: str | os.PathLike[str],
        field: str = "--out",
        kind: str = "files",
        requires: Mapping[str, str] | None = None,
        supersedes: tuple[str, ...] = (),
    ) -> None:
        super().__init__()
        check_output_folder(folder, field)
        #: Files of the folder (name -> SHA-256) this set is made of: the commit is refused when
        #: they changed, and a later commit that changes them drops the set (module text).
        self.requires = dict(requires or {})
        #: Kinds of sets this one replaces when they name no required files (module text).
        self.supersedes = tuple(supersedes)
        given = Path(folder)
        # a symlinked folder stays a symlink: the set is written into its target
        self.folder = Path(os.path.realpath(given)) if given.is_symlink() else given
        self.field = field
        self.kind = kind
        self._abs = os.path.abspath(given)  # its length checked by check_output_folder
        if self.folder.exists() and not self.folder.is_dir():
            raise OutputError(field, _short(self.folder), "it is a file, not a folder")
        self._created = not self.folder.is_dir()
        self.folder.mkdir(parents=True, exist_ok=True)
        recover(self.folder)
        self.generation = _tag()
        self._names: list[str] = []
        self._temps: list[Path] = []

    def _temp(self, kind: str, name: str) -> Path:
        return self.folder / f".{self.generation}.{kind}.{name}"

    def path(self, target: str | os.PathLike[str]) -> Path:
        final = Path(target)
        if os.path.abspath(final.parent) != self._abs:
            return super().path(target)
        if not _plain(final.name) or final.name in self._names:
            raise ValueError(f"{final.name} is staged twice or is not a plain file name")
        p = self._temp("new", final.name)
        p.open("x").close()
        self._names.append(final.name)
        self._temps.append(p)
        return p

    @property
    def targets(self) -> tuple[Path, ...]:
        return tuple(self.folder / n for n in self._names) + super().targets

    def commit(self) -> None:
        """fsync the staged files, then commit them under the folder's lock: the journal, the
        renames, the manifest, the old set's files dropped (see the module's text). A set made
        of other files (``requires``) whose files changed since is refused here, before anything
        is renamed (:class:`~corrugate.core.errors.StaleSetError`)."""
        files: dict[str, str] = {}
        for name in self._names:
            _fsync_file(self._temp("new", name))
            files[name] = _sha256(self._temp("new", name))
        with _locked(self.folder) as held:
            _settle(self.folder, held=held)  # a run killed since this one began
            for name, digest in self.requires.items():
                if not _written_by_set(self.folder / name, digest):
                    raise StaleSetError(self.field, _short(self.folder), name)
            self._check_targets(files)
            journal = _begin(
                self.folder,
                self.generation,
                self.kind,
                files,
                self.requires,
                self._temps,
                self.supersedes,
            )
            try:
                _forward(self.folder, journal)
                _finish(self.folder, journal)
            except BaseException:  # an OS error, Ctrl-C: rolled back or completed here
                with contextlib.suppress(OSError):  # else by the next run
                    _settle(self.folder, journal)
                raise
        self._names.clear()
        self._created = False
        super().commit()

    def _check_targets(self, files: Mapping[str, str]) -> None:
        """A file the set writes that is a folder is refused, before anything is renamed."""
        for name in files:
            path = self.folder / name
            if path.is_dir() and not path.is_symlink():
                raise OutputError(self.field, _short(path), "it is a folder, not a file")

    def discard(self) -> None:
        for p in self._temps:
            with contextlib.suppress(OSError):
                _unlink(p)
        self._temps.clear()
        self._names.clear()
        if self._created:  # a folder made for a set that never came
            with contextlib.suppress(OSError):
                self.folder.rmdir()
            self._created = False
        super().discard()


def _short(path: object) -> str:
    text = str(path)
    return text if len(text) <= 120 else text[:60] + "..." + text[-40:]


@contextmanager
def staged(
    folder: str | os.PathLike[str] | None = None,
    field: str = "--out",
    kind: str = "files",
    requires: Mapping[str, str] | None = None,
    supersedes: tuple[str, ...] = (),
) -> Iterator[Staging]:
    """Collect temporary files; commit them all when the block ends normally, else remove them.

    With ``folder``, the files put in that folder form one set (:class:`FolderStaging`), and every
    OS error is one :class:`~corrugate.core.errors.OutputError` naming ``field`` and the folder; the
    set replaces the folder's earlier set of the same ``kind`` whole (other files stay).
    ``requires`` (name -> SHA-256): files of the folder the set is made of (a verification of
    ``design.json``): checked under the lock at the commit
    (:class:`~corrugate.core.errors.StaleSetError` when they changed) and kept in the manifest,
    so that a later commit that changes them drops this set with them. ``supersedes``: kinds of
    sets the commit drops when they name no required files (a design's set drops a verification
    written by an earlier version, which did not record the design.json it checked).

    Example::

        with staged(out) as st:
            Path(st.path(out / "a.svg")).write_text(svg)
            doc.saveas(st.path(out / "a.dxf"))
    """
    try:
        st: Staging = (
            Staging()
            if folder is None
            else FolderStaging(folder, field, kind, requires, supersedes)
        )
    except OSError as exc:
        if isinstance(exc, CorrugateError) or folder is None:
            raise
        raise OutputError(field, _short(folder), exc.strerror or type(exc).__name__) from None
    try:
        yield st
    except BaseException as exc:
        st.discard()
        if folder is not None and isinstance(exc, OSError) and not isinstance(exc, CorrugateError):
            raise OutputError(field, _short(folder), exc.strerror or type(exc).__name__) from None
        raise
    try:
        st.commit()
    except OSError as exc:
        if folder is None or isinstance(exc, CorrugateError):
            raise
        raise OutputError(field, _short(folder), exc.strerror or type(exc).__name__) from None
    finally:
        st.discard()


def write_set(
    folder: str | os.PathLike[str],
    files: Mapping[str, str | bytes],
    field: str = "--out",
    kind: str = "files",
    requires: Mapping[str, str] | None = None,
    supersedes: tuple[str, ...] = (),
) -> list[Path]:
    """Write ``files`` (name -> text or bytes) into ``folder`` as one set (see :func:`staged`;
    ``requires``: the folder's files it is made of; ``supersedes``: kinds it replaces)."""
    out = Path(folder)
    with staged(out, field, kind, requires, supersedes) as st:
        for name, data in files.items():
            tmp = st.path(out / name)
            if isinstance(data, bytes):
                tmp.write_bytes(data)
            else:
                tmp.write_text(data, encoding="utf-8")
    return [out / name for name in files]


def atomic_write(path: str | os.PathLike[str], data: str | bytes, field: str | None = None) -> Path:
    """Write ``data`` (text as UTF-8) to ``path`` all or nothing; returns the path.

    The parent folder is created if missing. With ``field`` (the option that named ``path``),
    an OS error is one :class:`~corrugate.core.errors.OutputError` line naming it and ``path``
    (not the staged file beside it, which the OS names)."""
    try:
        Path(path).parent.mkdir(parents=True, exist_ok=True)
        if Path(path).is_dir():
            raise IsADirectoryError(errno.EISDIR, "Is a directory", os.fspath(path))
        with staged() as st:
            tmp = st.path(path)
            if isinstance(data, bytes):
                tmp.write_bytes(data)
            else:
                tmp.write_text(data, encoding="utf-8")
    except OSError as exc:
        if field is None or isinstance(exc, CorrugateError):
            raise
        reason = exc.strerror or type(exc).__name__
        raise OutputError(field, _short(os.fspath(path)), reason) from None
    return Path(path)


#: The largest file a command reads as input (bytes): a design.json (about 20 kB; a few hundred
#: kB with a 256-vertex outline and its runner-ups), a verify.json, a spec (which has its own,
#: smaller cap, :data:`~corrugate.core.limits.MAX_SPEC_BYTES`).
MAX_INPUT_BYTES = 8 << 20


def read_input(path: str | os.PathLike[str], field: str, limit: int = MAX_INPUT_BYTES) -> bytes:
    """The bytes of the input file ``path``, read as untrusted: opened non-blocking (a FIFO
    never blocks) and checked by ``fstat`` before any byte is read: a folder, a FIFO, a device
    (a symlink to ``/dev/zero``) or a socket is refused, so is a file above ``limit`` bytes (also
    one that grows while it is read). Each refusal is one
    :class:`~corrugate.core.errors.InputError` line naming ``field`` and the path."""
    shown = printable(_short(os.fspath(path)))
    allowed = f"a regular file of at most {limit} bytes"
    try:
        fd = os.open(path, os.O_RDONLY | os.O_NONBLOCK | getattr(os, "O_NOCTTY", 0))
    except OSError as exc:
        reason = exc.strerror or type(exc).__name__
        raise InputError(field, shown, allowed, reason=f"cannot be read ({reason})") from None
    try:
        info = os.fstat(fd)
        if stat.S_ISDIR(info.st_mode):
            raise InputError(field, shown, allowed, reason="is a folder")
        if not stat.S_ISREG(info.st_mode):
            what = (
                "a FIFO"
                if stat.S_ISFIFO(info.st_mode)
                else "a device"
                if stat.S_ISCHR(info.st_mode) or stat.S_ISBLK(info.st_mode)
                else "a socket"
                if stat.S_ISSOCK(info.st_mode)
                else "not a regular file"
            )
            raise InputError(field, shown, allowed, reason=f"is {what}, not a regular file")
        if info.st_size > limit:
            raise InputError(field, shown, allowed, reason=f"is too large ({info.st_size} bytes)")
        os.set_blocking(fd, True)
        chunks: list[bytes] = []
        size = 0
        while size <= limit:
            chunk = os.read(fd, min(1 << 20, limit + 1 - size))
            if not chunk:
                break
            chunks.append(chunk)
            size += len(chunk)
    except OSError as exc:
        if isinstance(exc, CorrugateError):
            raise
        reason = exc.strerror or type(exc).__name__
        raise InputError(field, shown, allowed, reason=f"cannot be read ({reason})") from None
    finally:
        os.close(fd)
    if size > limit:
        raise InputError(field, shown, allowed, reason="is too large (it grew while read)")
    return b"".join(chunks)


def read_input_text(path: str | os.PathLike[str], field: str, limit: int = MAX_INPUT_BYTES) -> str:
    """The text of the input file ``path`` (:func:`read_input`), decoded strictly as UTF-8; a file
    of another encoding (UTF-16 with its byte-order mark, Latin-1) is one
    :class:`~corrugate.core.errors.InputError` line naming ``field`` and the path."""
    return decode_input(read_input(path, field, limit), field, printable(_short(os.fspath(path))))


#: The UTF-8 byte-order mark some editors put at the start of a UTF-8 file (Windows Notepad did).
UTF8_BOM = b"\xef\xbb\xbf"


def decode_input(raw: bytes, field: str, shown: str) -> str:
    """``raw`` decoded strictly as UTF-8, without the byte-order mark it may start with (a UTF-8
    file so saved is the same text: tomllib and json would refuse the mark "at line 1, column
    1", a file that looks right in the editor), else one
    :class:`~corrugate.core.errors.InputError` line naming ``field`` and ``shown``."""

    if raw[:2] in (b"\xff\xfe", b"\xfe\xff"):
        raise InputError(
            field, shown, "a UTF-8 text file", reason="is UTF-16 text: save it as UTF-8"
        )
    raw = raw.removeprefix(UTF8_BOM)
    try:
        return raw.decode("utf-8")
    except UnicodeDecodeError as exc:
        raise InputError(
            field, shown, "a UTF-8 text file", reason=f"is not UTF-8 text (byte {exc.start})"
        ) from None


def parse_toml_input(text: str, field: str, shown: str) -> dict[str, Any]:
    """The tables of the TOML ``text`` of an input file (a materials file, a measurements file),
    read as untrusted: nesting deeper than :data:`~corrugate.core.limits.MAX_DEPTH` is refused
    before tomllib recurses into it, an integer longer than Python converts (4300 digits) is named
    by its line, a syntax error by tomllib's words; each refusal one
    :class:`~corrugate.core.errors.InputError` line naming ``field`` and ``shown``."""
    import sys
    import tomllib

    if bracket_depth(text) > MAX_DEPTH:
        raise InputError(
            field,
            shown,
            f"at most {MAX_DEPTH} levels of arrays and tables",
            reason="is nested too deeply",
        )
    try:
        return tomllib.loads(text)
    except tomllib.TOMLDecodeError as exc:
        msg = str(exc).splitlines()[0] if str(exc) else "syntax error"
        raise InputError(field, shown, "valid TOML", reason=f"is not valid TOML ({msg})") from None
    except ValueError:  # an integer too long to convert (not a TOMLDecodeError)
        digits = sys.get_int_max_str_digits() or 4300
        found = re.search("[0-9_]{" + str(digits + 1) + ",}", text)  # one pass, no backtracking
        line = "" if found is None else f" (line {text.count(chr(10), 0, found.start()) + 1})"
        raise InputError(
            field,
            shown,
            f"integers of at most {digits} digits",
            reason=f"has a longer integer{line}",
        ) from None
    except RecursionError:  # nesting the bracket count missed (table headers)
        raise InputError(
            field,
            shown,
            f"at most {MAX_DEPTH} levels of arrays and tables",
            reason="is nested too deeply",
        ) from None
