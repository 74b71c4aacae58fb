"""Files the web app made, addressed by opaque ids: nothing from a request reaches the file system.

Each result (one mesh, later one design with its SVG, DXF, PDF, FOLD, GLB and report) gets its own
folder under a private temporary root, named by a fresh random UUID. Writers put files there; the
store then *publishes* them under their plain names, each with the media type of its entry in the
writers registry (:mod:`corrugate.export.writers`). A download looks the pair (id, name) up in an
in-memory table: an id or a name that was not published, whatever it contains (``..``, ``/``,
an absolute path, percent escapes), is simply not found. Old results are evicted (oldest first past
``max_results``, and after ``ttl_s`` seconds); the root is made on first use and goes when the
store is closed.
"""

from __future__ import annotations

import shutil
import tempfile
import threading
import time
import uuid
from collections.abc import Callable, Iterable, Iterator
from contextlib import contextmanager
from dataclasses import dataclass
from pathlib import Path
from urllib.parse import quote

from starlette.responses import Response

from corrugate.export.writers import writer_for

__all__ = [
    "UNKNOWN_MEDIA_TYPE",
    "ZIP_NAME",
    "ResultStore",
    "StoredFile",
    "file_response",
    "zip_response",
]

#: The media type of a file that is no entry of the writers registry.
UNKNOWN_MEDIA_TYPE = "application/octet-stream"


@dataclass(frozen=True, slots=True)
class StoredFile:
    """One published file: its result id, plain name, path on disk and media type."""

    result_id: str
    name: str
    path: Path
    media_type: str

    @property
    def url(self) -> str:
        """Where the app serves it."""
        return f"/api/results/{self.result_id}/{self.name}"


@dataclass(frozen=True, slots=True)
class _Entry:
    folder: Path
    created: float
    files: dict[str, StoredFile]


class ResultStore:
    """Per-result folders under one private temporary root, with an id -> files table.

    Thread-safe: several requests may create, publish and read results at once.
    """

    def __init__(
        self,
        root: Path | None = None,
        *,
        max_results: int = 200,
        ttl_s: float = 3600.0,
        clock: Callable[[], float] = time.monotonic,
    ) -> None:
        self._parent = root
        self._root: Path | None = None
        self.max_results = max_results
        self.ttl_s = ttl_s
        self._clock = clock
        self._lock = threading.Lock()
        self._pending: dict[str, Path] = {}
        self._entries: dict[str, _Entry] = {}

    @property
    def root(self) -> Path:
        """The private root folder (mode 0700), made on first use."""
        with self._lock:
            if self._root is None:
                if self._parent is not None:
                    self._parent.mkdir(parents=True, exist_ok=True)
                parent = None if self._parent is None else str(self._parent)
                self._root = Path(tempfile.mkdtemp(prefix="corrugate-web-", dir=parent))
            return self._root

    def create(self) -> tuple[str, Path]:
        """A new result id and its empty private folder, for a writer to fill."""
        result_id = uuid.uuid4().hex
        folder = self.root / result_id
        folder.mkdir(mode=0o700)
        with self._lock:
            self._pending[result_id] = folder
        return result_id, folder

    def publish(self, result_id: str, paths: Iterable[Path]) -> list[StoredFile]:
        """Make the files ``paths`` (written into the result's folder) downloadable by name."""
        with self._lock:
            folder = self._pending.pop(result_id)
        files: dict[str, StoredFile] = {}
        for path in paths:
            if path.parent != folder or not path.is_file():
                raise ValueError(f"{path} is not a file of result {result_id}")
            writer = writer_for(path.name)
            media = UNKNOWN_MEDIA_TYPE if writer is None else writer.media_type
            files[path.name] = StoredFile(result_id, path.name, path, media)
        expired: list[Path] = []
        with self._lock:
            self._entries[result_id] = _Entry(folder, self._clock(), files)
            expired = self._evict_locked()
        for old in expired:
            shutil.rmtree(old, ignore_errors=True)
        return list(files.values())

    @contextmanager
    def reserved(self) -> Iterator[tuple[str, Path]]:
        """A new result id and its private folder (:meth:`create`) for the block to fill and
        publish; if the block fails (or is cancelled), the result and its folder go."""
        result_id, folder = self.create()
        try:
            yield result_id, folder
        except BaseException:
            self.discard(result_id)
            raise

    def make(self, write: Callable[[Path], Iterable[Path]]) -> list[StoredFile]:
        """Run ``write(folder)`` on a new result's private folder and publish the files it returns;
        if it fails, the folder and everything in it go."""
        with self.reserved() as (result_id, folder):
            return self.publish(result_id, list(write(folder)))

    def discard(self, result_id: str) -> None:
        """Forget a result that failed before it was published and remove its folder."""
        with self._lock:
            folder = self._pending.pop(result_id, None)
            entry = self._entries.pop(result_id, None)
        for path in (folder, entry.folder if entry else None):
            if path is not None:
                shutil.rmtree(path, ignore_errors=True)

    def get(self, result_id: str, name: str) -> StoredFile | None:
        """The published file ``name`` of result ``result_id``, or None (never a path lookup)."""
        with self._lock:
            expired = self._evict_locked()
            entry = self._entries.get(result_id)
            found = None if entry is None else entry.files.get(name)
        for old in expired:
            shutil.rmtree(old, ignore_errors=True)
        return found

    def read(self, result_id: str, name: str) -> tuple[StoredFile, bytes] | None:
        """The published file and its bytes, or None. The file is opened under the lock, so an
        eviction cannot remove it in between (see the module's note)."""
        with self._lock:
            expired = self._evict_locked()
            entry = self._entries.get(result_id)
            found = None if entry is None else entry.files.get(name)
            fh = None
            if found is not None:
                try:
                    fh = found.path.open("rb")
                except OSError:
                    found = None
        for old in expired:
            shutil.rmtree(old, ignore_errors=True)
        if found is None or fh is None:
            return None
        with fh:
            return found, fh.read()

    def read_all(self, result_id: str) -> list[tuple[StoredFile, bytes]] | None:
        """Every published file of a result with its bytes (in publishing order), or None; the
        files are opened under the lock, as :meth:`read` does."""
        with self._lock:
            expired = self._evict_locked()
            entry = self._entries.get(result_id)
            handles = []
            if entry is not None:
                try:
                    handles = [(f, f.path.open("rb")) for f in entry.files.values()]
                except OSError:
                    for _, fh in handles:
                        fh.close()
                    entry = None
        for old in expired:
            shutil.rmtree(old, ignore_errors=True)
        if entry is None:
            return None
        out = []
        for f, fh in handles:
            with fh:
                out.append((f, fh.read()))
        return out

    def files(self, result_id: str) -> list[StoredFile]:
        """Every published file of a result (empty if unknown or expired)."""
        with self._lock:
            entry = self._entries.get(result_id)
            return [] if entry is None else list(entry.files.values())

    def __len__(self) -> int:
        with self._lock:
            return len(self._entries)

    def close(self) -> None:
        """Remove every result and the root folder."""
        with self._lock:
            self._entries.clear()
            self._pending.clear()
            root, self._root = self._root, None
        if root is not None:
            shutil.rmtree(root, ignore_errors=True)

    def _evict_locked(self) -> list[Path]:
        now = self._clock()
        gone = [k for k, e in self._entries.items() if now - e.created > self.ttl_s]
        excess = len(self._entries) - len(gone) - self.max_results
        if excess > 0:
            alive = [k for k in self._entries if k not in gone]  # insertion order: oldest first
            gone.extend(alive[:excess])
        return [self._entries.pop(k).folder for k in gone]


#: The name under which a result's files download together (never the name of a file it holds).
ZIP_NAME = "all.zip"


def zip_response(store: ResultStore, result_id: str) -> Response | None:
    """Every file of a result in one zip archive (deflated, the files at its top level), or None
    when there is no such result."""
    import io
    import zipfile

    got = store.read_all(result_id)
    if got is None:
        return None
    buffer = io.BytesIO()
    with zipfile.ZipFile(buffer, "w", zipfile.ZIP_DEFLATED) as archive:
        for found, data in got:
            archive.writestr(found.name, data)
    return Response(
        buffer.getvalue(),
        media_type="application/zip",
        headers={
            "content-disposition": f'attachment; filename="corrugate-{result_id[:8]}.zip"',
            "content-security-policy": "sandbox",
        },
    )


def file_response(store: ResultStore, result_id: str, name: str) -> Response | None:
    """The HTTP response of a download (the bytes read by :meth:`ResultStore.read`), or None when
    there is no such file. The report (``.html``) opens in the browser (sandboxed: no script runs,
    no same-origin access); every other file is an attachment."""
    got = store.read(result_id, name)
    if got is None:
        return None
    found, data = got
    kind = "inline" if found.name.endswith(".html") else "attachment"
    return Response(
        data,
        media_type=found.media_type,
        headers={
            "content-disposition": f'{kind}; filename="{quote(found.name)}"',
            "content-security-policy": "sandbox",
        },
    )
