"""Files the web app made, addressed by opaque ids: nothing from a request reaches the file system.

Each result (one mesh, later one design with its SVG, DXF, PDF, FOLD, GLB and report) gets its own
folder under a private temporary root, named by a fresh random UUID. Writers put files there; the
store then *publishes* them under their plain names, each with the media type of its entry in the
writers registry (:mod:`corrugate.export.writers`). A download looks the pair (id, name) up in an
in-memory table: an id or a name that was not published, whatever it contains (``..``, ``/``,
an absolute path, percent escapes), is simply not found. Old results are evicted (oldest first past
``max_results``, and after ``ttl_s`` seconds); the root is made on first use and goes when the
store is closed.

A design answered first (``POST /api/design``) has its files made later, on demand, once:
:class:`DesignCache` keeps, by a design id (a keyed hash of the request's spec and output options
and of the design), what the worker needs to write them (an opaque recipe) and, once made, the id
of the stored result that holds them (docs/web.md).
"""

from __future__ import annotations

import hashlib
import hmac
import secrets
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
    "DesignCache",
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


@dataclass
class _Design:
    recipe: bytes
    created: float
    result_id: str | None = None


class DesignCache:
    """The designs whose files are made on demand: design id -> the recipe of its files (opaque
    bytes a worker made, :func:`corrugate.web.app.design_files_job` reads them) and, once they
    are made, the id of the stored result holding them.

    A design id is :meth:`key` of the request's spec and output options and of the design: an
    HMAC-SHA256 under a secret of this cache (random per server), so the same request and design
    get the same id, and an id cannot be guessed without the request. At most ``max_designs``
    are kept (the oldest go first), each for ``ttl_s`` seconds. ``files_made`` counts the file
    sets made (:meth:`made`). Thread-safe."""

    def __init__(
        self,
        *,
        max_designs: int = 200,
        ttl_s: float = 3600.0,
        clock: Callable[[], float] = time.monotonic,
    ) -> None:
        self.max_designs = max_designs
        self.ttl_s = ttl_s
        self._clock = clock
        self._secret = secrets.token_bytes(32)
        self._lock = threading.Lock()
        self._designs: dict[str, _Design] = {}
        self.files_made = 0

    def key(self, *parts: bytes) -> str:
        """The design id of ``parts`` (the request's canonical JSON, the design's): 32 hex
        digits of their HMAC-SHA256 (each part length-prefixed, so no two splits collide)."""
        mac = hmac.new(self._secret, digestmod=hashlib.sha256)
        for part in parts:
            mac.update(len(part).to_bytes(8, "big"))
            mac.update(part)
        return mac.hexdigest()[:32]

    def add(self, design_id: str, recipe: bytes) -> None:
        """Keep ``recipe`` under ``design_id`` (a design already kept keeps its files)."""
        with self._lock:
            self._evict_locked()
            if design_id in self._designs:
                self._designs[design_id].created = self._clock()
                return
            self._designs[design_id] = _Design(recipe, self._clock())
            excess = len(self._designs) - self.max_designs
            for old in list(self._designs)[: max(0, excess)]:
                del self._designs[old]

    def recipe(self, design_id: str) -> bytes | None:
        """The recipe of a kept design, or None."""
        with self._lock:
            self._evict_locked()
            found = self._designs.get(design_id)
            return None if found is None else found.recipe

    def result_id(self, design_id: str) -> str | None:
        """The stored result holding the design's files, once made (None before, or when the
        design is not kept)."""
        with self._lock:
            found = self._designs.get(design_id)
            return None if found is None else found.result_id

    def made(self, design_id: str, result_id: str) -> None:
        """The design's files were made into the stored result ``result_id``."""
        with self._lock:
            self.files_made += 1
            found = self._designs.get(design_id)
            if found is not None:
                found.result_id = result_id

    def __len__(self) -> int:
        with self._lock:
            return len(self._designs)

    def _evict_locked(self) -> None:
        now = self._clock()
        for k in [k for k, d in self._designs.items() if now - d.created > self.ttl_s]:
            del self._designs[k]


class ResultStore:
    """Per-result folders under one private temporary root, with an id -> files table, and the
    designs whose files are made on demand (``designs``, a :class:`DesignCache` with the same
    bounds).

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
        self.designs = DesignCache(max_designs=max_results, ttl_s=ttl_s, clock=clock)
        self._zips: dict[str, bytes] = {}
        self._zipping = threading.Lock()

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
            self._zips.pop(result_id, None)
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

    def zipped(self, result_id: str) -> bytes | None:
        """Every published file of a result in one zip archive (deflated, the files at its top
        level, in publishing order), or None when there is no such result: made on the first
        request, once, and kept with the result (the same bytes after)."""
        import io
        import zipfile

        with self._zipping:
            with self._lock:
                cached = self._zips.get(result_id)
            if cached is not None:
                return cached
            got = self.read_all(result_id)
            if got is None:
                return None
            buffer = io.BytesIO()
            with zipfile.ZipFile(buffer, "w", zipfile.ZIP_DEFLATED) as archive:
                for found, data in got:
                    archive.writestr(found.name, data)
            made = buffer.getvalue()
            with self._lock:
                if result_id in self._entries:
                    self._zips[result_id] = made
            return made

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
            self._zips.clear()
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
        for k in gone:
            self._zips.pop(k, None)
        return [self._entries.pop(k).folder for k in gone]


#: The name under which a result's files download together (never the name of a file it holds).
ZIP_NAME = "all.zip"


def zip_response(store: ResultStore, result_id: str) -> Response | None:
    """Every file of a result in one zip archive (:meth:`ResultStore.zipped`: made once), or
    None when there is no such result."""
    made = store.zipped(result_id)
    if made is None:
        return None
    return Response(
        made,
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
