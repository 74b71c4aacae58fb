"""All-or-nothing file output: write to temporary names beside the targets, then move into place.

Every file of one output step is written to a hidden temporary file in its target's directory
(``.NAME.XXXX.tmp``); only when all of them are complete are they renamed onto their final names
with :func:`os.replace` (atomic on one file system). If anything fails, every temporary file is
removed and no target is touched, so an error never leaves a partial file behind. (Should a
rename itself fail half-way through a commit, the files already renamed are complete files.)
"""

from __future__ import annotations

import os
import secrets
from collections.abc import Iterator
from contextlib import contextmanager
from pathlib import Path

__all__ = ["Staging", "atomic_write", "staged"]


class Staging:
    """The temporary files of one output step (see :func:`staged`)."""

    def __init__(self) -> None:
        self._files: list[tuple[Path, Path]] = []

    def path(self, target: str | os.PathLike[str]) -> Path:
        """A new temporary path in ``target``'s directory; it becomes ``target`` on commit."""
        final = Path(target)
        while True:  # a fresh name, created here (mode 0o666 less the umask, like any new file)
            tmp = final.parent / f".{final.name}.{secrets.token_hex(6)}.tmp"
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
        """Move every temporary file onto its target."""
        for tmp, final in self._files:
            os.replace(tmp, final)
        self._files.clear()

    def discard(self) -> None:
        """Remove every temporary file that is still there."""
        for tmp, _ in self._files:
            tmp.unlink(missing_ok=True)
        self._files.clear()


@contextmanager
def staged() -> Iterator[Staging]:
    """Collect temporary files; commit them all when the block ends normally, else remove them.

    Example::

        with staged() as st:
            Path(st.path(out / "a.svg")).write_text(svg)
            doc.saveas(st.path(out / "a.dxf"))
    """
    st = Staging()
    try:
        yield st
    except BaseException:
        st.discard()
        raise
    try:
        st.commit()
    finally:
        st.discard()


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
