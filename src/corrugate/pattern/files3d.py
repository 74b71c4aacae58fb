"""Writers for the folded geometry: FOLD 1.2 (JSON) per layer, GLB and STL of the assembly.

GLB and STL are written with numpy and :mod:`struct` from their published layouts: trimesh (and
the scipy it imports) cost over a second of start-up for two simple binary formats.
"""

from __future__ import annotations

import contextlib
import json
import struct
from pathlib import Path

import numpy as np
from numpy.typing import NDArray

from ..fileio import Staging, staged
from ..geometry import Assembly
from .folded import fold_document, folded_mesh
from .model import Pattern

__all__ = ["glb_bytes", "stl_bytes", "write_fold", "write_mesh"]

FloatArray = NDArray[np.float64]
#: One binary STL triangle: normal, three vertices (float32) and the attribute byte count.
_STL_RECORD = np.dtype([("normal", "<f4", (3,)), ("vertices", "<f4", (3, 3)), ("attr", "<u2")])


def write_fold(
    a: Assembly, pattern: Pattern, out_dir: Path, staging: Staging | None = None
) -> list[Path]:
    """Write ``layer1.fold`` and ``layer2.fold`` (FOLD 1.2, mm) into ``out_dir``.

    With ``staging`` the files join that output step; otherwise they are written all or nothing.
    """
    by_name = {p.name: p for p in pattern.parts}
    docs = [
        (index, fold_document(by_name[f"L{index}"], layer))
        for index, layer in ((1, a.layer1), (2, a.layer2))
    ]
    out_dir.mkdir(parents=True, exist_ok=True)
    with contextlib.nullcontext(staging) if staging is not None else staged() as st:
        paths = []
        for index, doc in docs:
            target = out_dir / f"layer{index}.fold"
            st.path(target).write_text(json.dumps(doc, indent=1), encoding="utf-8")
            paths.append(target)
    return paths


def stl_bytes(vertices: FloatArray, faces: NDArray[np.int64]) -> bytes:
    """Binary STL of the triangles ``faces`` over ``vertices`` (mm, as written; STL has no unit).

    Layout (little endian): an 80-byte header, the triangle count (uint32), then per triangle its
    unit normal (right-hand rule over the vertex order; zero for a degenerate triangle), its three
    vertices (12 float32) and a zero attribute count (uint16): 50 bytes each.
    """
    tri = np.asarray(vertices, dtype=np.float64)[np.asarray(faces)]
    normal = np.cross(tri[:, 1] - tri[:, 0], tri[:, 2] - tri[:, 0])
    length = np.linalg.norm(normal, axis=1)
    normal = np.divide(
        normal, length[:, None], out=np.zeros_like(normal), where=length[:, None] > 0
    )
    record = np.zeros(len(tri), dtype=_STL_RECORD)
    record["normal"] = normal
    record["vertices"] = tri
    header = b"corrugate: folded assembly, mm".ljust(80, b" ")
    return header + struct.pack("<I", len(tri)) + record.tobytes()


def _pad(data: bytes, fill: bytes) -> bytes:
    return data + fill * (-len(data) % 4)


def glb_bytes(vertices: FloatArray, faces: NDArray[np.int64]) -> bytes:
    """Binary glTF 2.0 (GLB) of one triangle mesh (positions in mm as written; glTF reads metres,
    viewers here scale to the model).

    The container (glTF 2.0 specification, section "GLB File Format Specification"): a 12-byte
    header (magic ``glTF``, version 2, total length), a JSON chunk padded with spaces and a BIN
    chunk padded with zeros to 4 bytes. The BIN chunk holds the uint32 triangle indices, then the
    float32 positions; POSITION carries the min/max the specification requires.
    """
    v = np.ascontiguousarray(vertices, dtype="<f4")
    idx = np.ascontiguousarray(faces, dtype="<u4").ravel()
    index_bytes = _pad(idx.tobytes(), b"\x00")
    position_bytes = v.tobytes()
    doc = {
        "asset": {"version": "2.0", "generator": "corrugate"},
        "scene": 0,
        "scenes": [{"nodes": [0]}],
        "nodes": [{"name": "assembly", "mesh": 0}],
        "meshes": [
            {
                "name": "assembly",
                "primitives": [{"attributes": {"POSITION": 1}, "indices": 0, "mode": 4}],
            }
        ],
        "accessors": [
            {
                "bufferView": 0,
                "componentType": 5125,  # UNSIGNED_INT
                "count": int(idx.size),
                "type": "SCALAR",
                "max": [int(idx.max())] if idx.size else [0],
                "min": [int(idx.min())] if idx.size else [0],
            },
            {
                "bufferView": 1,
                "componentType": 5126,  # FLOAT
                "count": len(v),
                "type": "VEC3",
                "max": v.max(axis=0).tolist() if len(v) else [0.0, 0.0, 0.0],
                "min": v.min(axis=0).tolist() if len(v) else [0.0, 0.0, 0.0],
            },
        ],
        "bufferViews": [
            {"buffer": 0, "byteOffset": 0, "byteLength": idx.size * 4, "target": 34963},
            {
                "buffer": 0,
                "byteOffset": len(index_bytes),
                "byteLength": len(position_bytes),
                "target": 34962,
            },
        ],
        "buffers": [{"byteLength": len(index_bytes) + len(position_bytes)}],
    }
    json_chunk = _pad(json.dumps(doc, separators=(",", ":")).encode("utf-8"), b" ")
    bin_chunk = _pad(index_bytes + position_bytes, b"\x00")
    total = 12 + 8 + len(json_chunk) + 8 + len(bin_chunk)
    return b"".join(
        [
            struct.pack("<4sII", b"glTF", 2, total),
            struct.pack("<I4s", len(json_chunk), b"JSON"),
            json_chunk,
            struct.pack("<I4s", len(bin_chunk), b"BIN\x00"),
            bin_chunk,
        ]
    )


def write_mesh(
    a: Assembly, pattern: Pattern, out_dir: Path, staging: Staging | None = None
) -> list[Path]:
    """Write the folded assembly as ``assembly.glb`` and ``assembly.stl`` (mm): numpy and the
    documented binary layouts (:func:`glb_bytes`, :func:`stl_bytes`), no mesh library."""
    vertices, faces = folded_mesh(a, pattern.parts)
    data = {"assembly.glb": glb_bytes(vertices, faces), "assembly.stl": stl_bytes(vertices, faces)}
    out_dir.mkdir(parents=True, exist_ok=True)
    with contextlib.nullcontext(staging) if staging is not None else staged() as st:
        paths = []
        for name, content in data.items():
            target = out_dir / name
            st.path(target).write_bytes(content)
            paths.append(target)
    return paths
