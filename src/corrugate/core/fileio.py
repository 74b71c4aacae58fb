"""All-or-nothing file output: single files and whole sets of files.

Single files (:func:`atomic_write`, :func:`staged` without a folder): each file of one output step
is written to a hidden temporary file beside its target (``.NAME.corrugate-PID-XXXX.tmp``), fsynced,
and renamed onto its final name only when all of them are complete.

Sets of files (:func:`staged` with a folder, :func:`write_set`): the files that belong together
(a design's cut files, PDF, report and ``design.json``; a sweep's table, CSV and plot) are written
into a hidden sibling folder ``.NAME.corrugate-PID-XXXX.new``, together with a manifest
(:data:`MANIFEST`: the run's id and every file's SHA-256); everything is fsynced; files of the old
folder that are not part of its set (the user's own) are linked into the new one; then the two
folders are swapped in one step (Linux ``renameat2(RENAME_EXCHANGE)``; elsewhere two renames, the
old folder kept as ``.NAME.corrugate-PID-XXXX.old`` until the new one is in place). A failure or a
kill at any moment thus leaves either the old complete set or the new complete set under the
folder's name, never a mix. Leftovers of a killed run (its staging folder, the swapped-out old
folder, temporary files) are removed by the next run that writes there (:func:`recover`); an old
folder left aside between the two renames is put back.

Every OS error becomes one :class:`~corrugate.core.errors.OutputError` line naming the path.
"""

from __future__ import annotations

import contextlib
import ctypes
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

from corrugate.core.errors import CorrugateError, OutputError
from corrugate.core.limits import MAX_PATH_CHARS

__all__ = [
    "MANIFEST",
    "MAX_MANIFEST_BYTES",
    "SYSTEM_FOLDERS",
    "SYSTEM_TREES",
    "FolderStaging",
    "Staging",
    "atomic_write",
    "check_output_folder",
    "read_manifest",
    "recover",
    "staged",
    "write_set",
]

#: The manifest of the sets committed in a folder, inside it: ``{"sets": {kind: {"run": id,
#: "files": {name: sha256}}}}``; one set per kind (``design``, ``pareto``, ``sweep``), so that a
#: design and a Pareto front may share a folder while a new design replaces the old one whole.
MANIFEST = ".corrugate-set.json"

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

_LEFTOVER = re.compile(
    r"^\.(?P<name>.+)\.corrugate-(?P<pid>\d+)-[0-9a-f]{12}\.(?P<kind>new|old|tmp)$"
)


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
    naming ``field``) when it is empty, the root or a system folder (:data:`SYSTEM_FOLDERS`),
    inside a pseudo file system (:data:`SYSTEM_TREES`), the user's home folder itself, or the
    working folder or one of its ancestors (a set replaces the folder it is written to: a run
    must not take the folder it runs in, nor the user's files around it); returns the path with
    symlinks resolved. Called before any computation, and again by :class:`FolderStaging`."""
    text = os.fspath(folder)
    if not str(text).strip():
        raise OutputError(field, repr(text), "an empty path: name a folder, e.g. out/my-part")
    real = Path(os.path.realpath(text))
    shown = _short(text)
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


def recover(folder: str | os.PathLike[str]) -> None:
    """Clean up after killed runs that wrote ``folder``: remove their staging folders, the old
    folders they swapped out and their temporary files; if a run was killed between its two renames
    (``folder`` missing, its old folder aside), put the old folder back. Runs still alive are left
    alone."""
    target = Path(folder)
    parent = target.parent
    places: list[tuple[Path, str | None]] = [(parent, target.name)]
    if target.is_dir():
        places.append((target, None))
    for where, name in places:
        try:
            entries = list(os.scandir(where))
        except OSError:
            continue
        for entry in entries:
            m = _LEFTOVER.match(entry.name)
            if m is None or (name is not None and m["kind"] != "tmp" and m["name"] != name):
                continue
            if _pid_alive(int(m["pid"])):
                continue
            path = Path(entry.path)
            if m["kind"] == "old" and name is not None and not os.path.lexists(target):
                with contextlib.suppress(OSError):
                    os.rename(path, target)
                    continue
            _remove(path)


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


def _exchange(a: Path, b: Path) -> bool:
    """Swap the paths ``a`` and ``b`` atomically (Linux renameat2 with RENAME_EXCHANGE); False if
    the system or the file system cannot."""
    try:
        libc = ctypes.CDLL(None, use_errno=True)
        fn = libc.renameat2
    except (OSError, AttributeError):
        return False
    fn.argtypes = [ctypes.c_int, ctypes.c_char_p, ctypes.c_int, ctypes.c_char_p, ctypes.c_uint]
    fn.restype = ctypes.c_int
    at_fdcwd, rename_exchange = -100, 2
    if fn(at_fdcwd, os.fsencode(a), at_fdcwd, os.fsencode(b), rename_exchange) == 0:
        return True
    err = ctypes.get_errno()
    if err in (errno.ENOSYS, errno.EINVAL, errno.ENOTSUP, errno.EOPNOTSUPP):
        return False
    raise OSError(err, os.strerror(err), str(b))


def read_manifest(folder: str | os.PathLike[str]) -> dict[str, dict[str, object]]:
    """The sets committed in ``folder`` (kind -> ``{"run": id, "files": {name: sha256}}``)."""
    try:
        data = json.loads(_read_regular(Path(folder) / MANIFEST, MAX_MANIFEST_BYTES))
        sets = data["sets"]
    except (OSError, ValueError, KeyError, TypeError):
        return {}
    if not isinstance(sets, dict):
        return {}
    return {
        k: v for k, v in sets.items() if isinstance(v, dict) and isinstance(v.get("files"), dict)
    }


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


def _link_into(src: Path, dst: Path) -> None:
    if src.is_symlink():
        os.symlink(os.readlink(src), dst)
    elif src.is_dir():
        shutil.copytree(src, dst, symlinks=True, copy_function=_link_or_copy)
    else:
        _link_or_copy(src, dst)


def _link_or_copy(src: str | os.PathLike[str], dst: str | os.PathLike[str]) -> None:
    try:
        os.link(src, dst)
    except OSError:
        shutil.copy2(src, dst)


class FolderStaging(Staging):
    """The files of one set, staged in a hidden sibling of ``folder`` and swapped in on commit.

    :meth:`path` of a file directly in ``folder`` gives its place in the staging folder; any other
    target is staged as a single file (:class:`Staging`)."""

    def __init__(
        self, folder: str | os.PathLike[str], field: str = "--out", kind: str = "files"
    ) -> None:
        super().__init__()
        check_output_folder(folder, field)
        given = Path(folder)
        # a symlinked folder stays a symlink: the set is swapped in at its target
        self.folder = Path(os.path.realpath(given)) if given.is_symlink() else given
        self.field = field
        self.kind = kind
        self._abs = os.path.abspath(given)
        if len(self._abs) > MAX_PATH_CHARS or any(
            len(part) > 200 for part in Path(self._abs).parts
        ):
            raise OutputError(field, _short(self.folder), "the path is too long")
        if self.folder.exists() and not self.folder.is_dir():
            raise OutputError(field, _short(self.folder), "it is a file, not a folder")
        self.folder.parent.mkdir(parents=True, exist_ok=True)
        recover(self.folder)
        self.stage = self.folder.parent / f".{self.folder.name}.{_tag()}.new"
        self.stage.mkdir()
        self._names: list[str] = []

    def path(self, target: str | os.PathLike[str]) -> Path:
        final = Path(target)
        if os.path.abspath(final.parent) != self._abs:
            return super().path(target)
        if final.name == MANIFEST or final.name in self._names:
            raise ValueError(f"{final.name} is staged twice")
        self._names.append(final.name)
        p = self.stage / final.name
        p.touch()
        return p

    @property
    def targets(self) -> tuple[Path, ...]:
        return tuple(self.folder / n for n in self._names) + super().targets

    def commit(self) -> None:
        """Write the manifest, carry over the folder's foreign files, fsync, swap."""
        files = {name: _sha256(self.stage / name) for name in self._names}
        sets = read_manifest(self.folder) if self.folder.is_dir() else {}
        listed = sets.pop(self.kind, {}).get("files", {})
        old_files: dict[object, object] = listed if isinstance(listed, dict) else {}
        old_set = {
            name
            for name, digest in old_files.items()
            if isinstance(name, str) and _written_by_set(self.folder / name, digest)
        }  # a listed file is dropped only if it is still what the set wrote
        for other in sets.values():  # files of other kinds that this set overwrites leave them
            other["files"] = {
                k: v
                for k, v in other["files"].items()  # type: ignore[attr-defined]
                if k not in files
            }
        sets[self.kind] = {"run": self.stage.name.split(".")[-2], "files": files}
        text = json.dumps({"sets": sets}, indent=1)
        (self.stage / MANIFEST).write_text(text, encoding="utf-8")
        if self.folder.is_dir():
            for entry in os.scandir(self.folder):
                name = entry.name
                if name in old_set or name in files or name == MANIFEST or _LEFTOVER.match(name):
                    continue
                _link_into(Path(entry.path), self.stage / name)
        for name in [*self._names, MANIFEST]:
            _fsync_file(self.stage / name)
        if self.folder.is_dir():  # the folder's mode, times and extended attributes stay
            with contextlib.suppress(OSError):
                shutil.copystat(self.folder, self.stage, follow_symlinks=False)
        _fsync_dir(self.stage)
        if not os.path.lexists(self.folder):
            os.rename(self.stage, self.folder)
        elif _exchange(self.stage, self.folder):
            _remove(self.stage)  # now the old set
        else:
            aside = self.folder.parent / f".{self.folder.name}.{_tag()}.old"
            os.rename(self.folder, aside)
            os.rename(self.stage, self.folder)
            _remove(aside)
        _fsync_dir(self.folder.parent)
        self._names.clear()
        super().commit()

    def discard(self) -> None:
        _remove(self.stage)
        self._names.clear()
        super().discard()


def _short(path: object) -> str:
    text = str(path)
    return text if len(text) <= 120 else text[:60] + "..." + text[-40:]


@contextmanager
def staged(
    folder: str | os.PathLike[str] | None = None, field: str = "--out", kind: str = "files"
) -> Iterator[Staging]:
    """Collect temporary files; commit them all when the block ends normally, else remove them.

    With ``folder``, the files put in that folder form one set (:class:`FolderStaging`), and every
    OS error is one :class:`~corrugate.core.errors.OutputError` naming ``field`` and the folder; the
    set replaces the folder's earlier set of the same ``kind`` whole (other files stay).

    Example::

        with staged(out) as st:
            Path(st.path(out / "a.svg")).write_text(svg)
            doc.saveas(st.path(out / "a.dxf"))
    """
    try:
        st: Staging = Staging() if folder is None else FolderStaging(folder, field, kind)
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
) -> list[Path]:
    """Write ``files`` (name -> text or bytes) into ``folder`` as one set (see :func:`staged`)."""
    out = Path(folder)
    with staged(out, field, kind) as st:
        for name, data in files.items():
            tmp = st.path(out / name)
            if isinstance(data, bytes):
                tmp.write_bytes(data)
            else:
                tmp.write_text(data, encoding="utf-8")
    return [out / name for name in files]


def atomic_write(path: str | os.PathLike[str], data: str | bytes) -> Path:
    """Write ``data`` (text as UTF-8) to ``path`` all or nothing; returns the path.

    The parent folder is created if missing."""
    Path(path).parent.mkdir(parents=True, exist_ok=True)
    with staged() as st:
        tmp = st.path(path)
        if isinstance(data, bytes):
            tmp.write_bytes(data)
        else:
            tmp.write_text(data, encoding="utf-8")
    return Path(path)
