"""The result store: opaque ids, plain names, no path lookups, eviction; the ASGI body limit."""

from __future__ import annotations

import asyncio
import json
from pathlib import Path
from typing import Any

import pytest

from corrugate import Assembly, Layer, analyze, get_material
from corrugate.export.writers import WRITERS
from corrugate.web.guards import BodySizeLimit
from corrugate.web.store import UNKNOWN_MEDIA_TYPE, ResultStore, file_response
from corrugate.workflow import output_options, write_design_files


class Clock:
    def __init__(self) -> None:
        self.now = 0.0

    def __call__(self) -> float:
        return self.now


@pytest.fixture
def store(tmp_path: Path) -> ResultStore:
    return ResultStore(tmp_path, max_results=3, ttl_s=100.0, clock=Clock())


def make(store: ResultStore, text: str = "x") -> str:
    rid, folder = store.create()
    (folder / "assembly.glb").write_text(text)
    (folder / "sheet-1.svg").write_text(text)
    store.publish(rid, [folder / "assembly.glb", folder / "sheet-1.svg"])
    return rid


def test_publish_and_get(store: ResultStore, tmp_path: Path) -> None:
    rid = make(store, "hello")
    assert len(rid) == 32 and int(rid, 16) >= 0
    f = store.get(rid, "assembly.glb")
    assert f is not None and f.path.read_text() == "hello" and f.media_type == "model/gltf-binary"
    assert f.url == f"/api/results/{rid}/assembly.glb"
    svg = store.get(rid, "sheet-1.svg")
    assert svg is not None and svg.media_type == "image/svg+xml"
    assert f.path.parent.parent == store.root and store.root.parent == tmp_path
    assert (f.path.parent.stat().st_mode & 0o777) == 0o700


def test_every_file_of_a_design_gets_its_registry_media_type(tmp_path: Path) -> None:
    """The files ``write_design_files`` writes (a laser: SVG and DXF cut files; A4 tiles; a
    report), published: each has the media type of the one registry entry it is a file of, and is
    served with it; every entry has a file among them."""
    store = ResultStore(tmp_path)
    a = Assembly.identical(Layer(8.0, 8, 84.0, get_material("dura-lar")))
    analysis = analyze(a, "paper", [0.0, 90.0])
    options = output_options("laser:600x400", paper="a4")
    files = store.make(
        lambda folder: write_design_files(analysis, folder, options, report="<!doctype html>")
    )
    kinds = set()
    for f in files:
        (entry,) = [w for w in WRITERS if w.matches(f.name)]
        kinds.add(entry.name)
        assert f.media_type == entry.media_type, f.name
        response = file_response(store, f.result_id, f.name)
        assert response is not None and response.headers["content-type"] == entry.media_type
    assert kinds == {w.name for w in WRITERS}
    rid, folder = store.create()
    (folder / "notes.txt").write_text("x")
    (other,) = store.publish(rid, [folder / "notes.txt"])
    assert other.media_type == UNKNOWN_MEDIA_TYPE == "application/octet-stream"


@pytest.mark.parametrize(
    "name",
    [
        "../assembly.glb",
        "./assembly.glb",
        "ASSEMBLY.GLB",
        "assembly.glb/",
        "",
        "..",
        "/etc/passwd",
        "assembly.glb\x00",
        "c.txt",
    ],
)
def test_only_published_names_are_found(store: ResultStore, name: str) -> None:
    rid = make(store)
    (store.root / rid / "c.txt").write_text("not published")
    assert store.get(rid, name) is None
    assert store.get(f"../{rid}", "assembly.glb") is None
    assert store.get(str(store.root / rid), "assembly.glb") is None


def test_publish_refuses_files_from_elsewhere(store: ResultStore, tmp_path: Path) -> None:
    rid, _ = store.create()
    outside = tmp_path / "outside.txt"
    outside.write_text("x")
    with pytest.raises(ValueError, match="not a file of result"):
        store.publish(rid, [outside])


def test_eviction_by_count_and_age(store: ResultStore) -> None:
    clock = store._clock
    assert isinstance(clock, Clock)
    ids = [make(store) for _ in range(4)]
    assert store.get(ids[0], "assembly.glb") is None and not (store.root / ids[0]).exists()
    assert all(store.get(i, "assembly.glb") is not None for i in ids[1:])
    clock.now = 101.0
    assert store.get(ids[3], "assembly.glb") is None
    assert len(store) == 0 and list(store.root.iterdir()) == []


def test_make_publishes_what_the_writer_wrote_or_nothing(store: ResultStore) -> None:
    def good(folder: Path) -> list[Path]:
        (folder / "report.html").write_text("<p>hi</p>")
        return [folder / "report.html"]

    (f,) = store.make(good)
    assert store.get(f.result_id, "report.html") == f and f.media_type.startswith("text/html")

    def bad(folder: Path) -> list[Path]:
        (folder / "half.dxf").write_text("0\nSECTION")
        raise RuntimeError("writer failed")

    with pytest.raises(RuntimeError, match="writer failed"):
        store.make(bad)
    assert [p.name for p in store.root.iterdir()] == [f.result_id]


def test_discard_and_close(store: ResultStore) -> None:
    rid, folder = store.create()
    (folder / "assembly.glb").write_text("x")
    store.discard(rid)
    assert not folder.exists()
    make(store)
    root = store.root
    store.close()
    assert not root.exists()


def test_the_root_is_made_on_first_use(tmp_path: Path) -> None:
    store = ResultStore(tmp_path / "results")
    assert not (tmp_path / "results").exists()
    store.close()  # nothing to remove
    make(store)
    assert [p.name.startswith("corrugate-web-") for p in (tmp_path / "results").iterdir()] == [True]
    store.close()
    assert list((tmp_path / "results").iterdir()) == []


def run_limited(max_bytes: int, chunks: list[bytes], headers: list[tuple[bytes, bytes]]) -> Any:
    """Drive BodySizeLimit around an app that echoes the body length; returns (status, body)."""
    seen: dict[str, Any] = {}

    async def app(scope: Any, receive: Any, send: Any) -> None:
        message = await receive()
        seen["body"] = message["body"]
        await send({"type": "http.response.start", "status": 200, "headers": []})
        await send({"type": "http.response.body", "body": b"ok"})

    async def main() -> tuple[int, bytes]:
        queue = [
            {"type": "http.request", "body": c, "more_body": i < len(chunks) - 1}
            for i, c in enumerate(chunks)
        ]
        sent: list[dict[str, Any]] = []

        async def receive() -> dict[str, Any]:
            return queue.pop(0)

        async def send(message: dict[str, Any]) -> None:
            sent.append(message)

        scope = {"type": "http", "headers": headers}
        await BodySizeLimit(app, max_bytes)(scope, receive, send)
        return sent[0]["status"], b"".join(m.get("body", b"") for m in sent[1:])

    status, body = asyncio.run(main())
    return status, body, seen.get("body")


def test_body_limit_counts_chunks_and_replays_the_body() -> None:
    status, _, seen = run_limited(10, [b"12345", b"67890"], [])
    assert status == 200 and seen == b"1234567890"
    status, body, seen = run_limited(10, [b"12345", b"67890", b"1"], [])
    assert status == 413 and seen is None and json.loads(body)["field"] == "body"
    status, _, seen = run_limited(10, [b"1"], [(b"content-length", b"11")])
    assert status == 413 and seen is None
    status, _, _ = run_limited(10, [b"1"], [(b"content-length", b"ten")])
    assert status == 400


def test_a_design_id_is_a_keyed_hash_of_its_parts() -> None:
    """The same parts give the same id in one cache and another id in a cache with another
    secret (so ids cannot be guessed); another part, or the same bytes split differently, give
    another id."""
    from corrugate.web.store import DesignCache

    a, b = DesignCache(), DesignCache()
    assert a.key(b"spec", b"design") == a.key(b"spec", b"design")
    assert len(a.key(b"spec", b"design")) == 32
    assert a.key(b"spec", b"design") != b.key(b"spec", b"design")
    assert a.key(b"spec", b"design") != a.key(b"spec", b"design2")
    assert a.key(b"spe", b"cdesign") != a.key(b"spec", b"design")


def test_the_design_cache_is_bounded_and_expires() -> None:
    from corrugate.web.store import DesignCache

    clock = Clock()
    cache = DesignCache(max_designs=2, ttl_s=10.0, clock=clock)
    for name in ("a", "b", "c"):
        cache.add(name, name.encode())
    assert len(cache) == 2 and cache.recipe("a") is None  # the oldest went
    assert cache.recipe("c") == b"c" and cache.result_id("c") is None
    cache.made("c", "r1")
    assert cache.result_id("c") == "r1" and cache.files_made == 1
    cache.add("c", b"other")  # kept already: its recipe and files stay
    assert cache.recipe("c") == b"c" and cache.result_id("c") == "r1"
    clock.now = 11.0
    assert cache.recipe("c") is None and cache.recipe("b") is None


def test_the_zip_of_a_result_is_made_once(store: ResultStore) -> None:
    import io
    import zipfile

    rid = make(store, "abc")
    first = store.zipped(rid)
    assert first is not None and store.zipped(rid) is first  # the same bytes, not made again
    archive = zipfile.ZipFile(io.BytesIO(first))
    assert sorted(archive.namelist()) == ["assembly.glb", "sheet-1.svg"]
    assert archive.read("sheet-1.svg") == b"abc"
    assert store.zipped("0" * 32) is None
    store.discard(rid)
    assert store.zipped(rid) is None
