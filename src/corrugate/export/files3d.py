"""Writers for the folded geometry: FOLD 1.2 (JSON) per layer, GLB and STL of the assembly.

GLB and STL are written with numpy and :mod:`struct` from their published layouts: trimesh (and
the scipy it imports) cost over a second of start-up for two simple binary formats.
"""

from __future__ import annotations

import contextlib
import json
import struct
from collections.abc import Sequence
from pathlib import Path
from typing import Any

import numpy as np
from numpy.typing import NDArray

from corrugate.core.fileio import Staging, staged
from corrugate.fabrication.folded import fold_document, folded_mesh_groups
from corrugate.fabrication.model import Pattern
from corrugate.fabrication.palette import PARTS, rgba
from corrugate.geometry.layer import Assembly

__all__ = ["PART_COLOURS", "glb_bytes", "stl_bytes", "write_fold", "write_mesh"]

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


#: Colours of the GLB's parts (linear RGBA, glTF's baseColorFactor): layer 1 blue, layer 2
#: orange, the connector band grey.
#: Each mesh's colour (glTF baseColorFactor): the palette's part colours
#: (:data:`corrugate.fabrication.palette.PARTS`), as in the assembly figure.
PART_COLOURS: dict[str, tuple[float, float, float, float]] = {
    "layer 1": rgba(PARTS["L1"].hex),
    "layer 2": rgba(PARTS["L2"].hex),
    "band": rgba(PARTS["band"].hex),
}
_DEFAULT_COLOUR = rgba(PARTS["L1"].hex)


def glb_bytes(
    vertices: FloatArray,
    faces: NDArray[np.int64],
    groups: Sequence[tuple[str, int, int]] | None = None,
) -> bytes:
    """Binary glTF 2.0 (GLB) of a triangle mesh (positions in mm as written; glTF reads metres,
    viewers here scale to the model), one glTF mesh per part.

    ``groups`` lists the parts in order as ``(name, vertex count, triangle count)``: each part's
    vertices and triangles follow the previous part's, and its triangles use only its own
    vertices (:func:`~corrugate.fabrication.folded.folded_mesh_groups`); None is one part named
    ``assembly``. Each part is a node and a mesh of its own with its own material (colour from
    :data:`PART_COLOURS`, double-sided), so a viewer can colour and move the layers apart.

    The container (glTF 2.0 specification, section "GLB File Format Specification"): a 12-byte
    header (magic ``glTF``, version 2, total length), a JSON chunk padded with spaces and a BIN
    chunk padded with zeros to 4 bytes. The BIN chunk holds, part after part, the uint32 triangle
    indices (relative to the part's first vertex), then the float32 positions; each POSITION
    carries the min/max the specification requires.
    """
    v_all = np.ascontiguousarray(vertices, dtype="<f4")
    f_all = np.asarray(faces, dtype=np.int64)
    parts = list(groups) if groups is not None else [("assembly", len(v_all), len(f_all))]
    if sum(p[1] for p in parts) != len(v_all) or sum(p[2] for p in parts) != len(f_all):
        raise ValueError("glb_bytes: the groups do not add up to the vertices and faces")
    chunks: list[bytes] = []
    offset = 0
    doc: dict[str, Any] = {
        "asset": {"version": "2.0", "generator": "corrugate"},
        "scene": 0,
        "scenes": [{"nodes": list(range(len(parts)))}],
        "nodes": [],
        "meshes": [],
        "materials": [],
        "accessors": [],
        "bufferViews": [],
    }
    first_vertex = first_face = 0
    for i, (name, n_vertices, n_faces) in enumerate(parts):
        v = v_all[first_vertex : first_vertex + n_vertices]
        idx = np.ascontiguousarray(
            f_all[first_face : first_face + n_faces] - first_vertex, dtype="<u4"
        ).ravel()
        first_vertex += n_vertices
        first_face += n_faces
        index_bytes, position_bytes = idx.tobytes(), v.tobytes()  # both multiples of 4 bytes
        doc["bufferViews"] += [
            {"buffer": 0, "byteOffset": offset, "byteLength": len(index_bytes), "target": 34963},
            {
                "buffer": 0,
                "byteOffset": offset + len(index_bytes),
                "byteLength": len(position_bytes),
                "target": 34962,
            },
        ]
        offset += len(index_bytes) + len(position_bytes)
        chunks += [index_bytes, position_bytes]
        doc["accessors"] += [
            {
                "bufferView": 2 * i,
                "componentType": 5125,  # UNSIGNED_INT
                "count": int(idx.size),
                "type": "SCALAR",
                "max": [int(idx.max())] if idx.size else [0],
                "min": [int(idx.min())] if idx.size else [0],
            },
            {
                "bufferView": 2 * i + 1,
                "componentType": 5126,  # FLOAT
                "count": len(v),
                "type": "VEC3",
                "max": v.max(axis=0).tolist() if len(v) else [0.0, 0.0, 0.0],
                "min": v.min(axis=0).tolist() if len(v) else [0.0, 0.0, 0.0],
            },
        ]
        doc["materials"].append(
            {
                "name": name,
                "pbrMetallicRoughness": {
                    "baseColorFactor": list(PART_COLOURS.get(name, _DEFAULT_COLOUR)),
                    "metallicFactor": 0.0,
                    "roughnessFactor": 0.65,
                },
                "doubleSided": True,
            }
        )
        doc["meshes"].append(
            {
                "name": name,
                "primitives": [
                    {
                        "attributes": {"POSITION": 2 * i + 1},
                        "indices": 2 * i,
                        "material": i,
                        "mode": 4,
                    }
                ],
            }
        )
        doc["nodes"].append({"name": name, "mesh": i})
    doc["buffers"] = [{"byteLength": offset}]
    json_chunk = _pad(json.dumps(doc, separators=(",", ":")).encode("utf-8"), b" ")
    bin_chunk = _pad(b"".join(chunks), b"\x00")
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
    """Write the folded assembly as ``assembly.glb`` (one coloured mesh per layer and one for the
    band) and ``assembly.stl`` (every triangle, one solid) in mm: numpy and the documented binary
    layouts (:func:`glb_bytes`, :func:`stl_bytes`), no mesh library."""
    vertices, faces, groups = folded_mesh_groups(a, pattern.parts)
    data = {
        "assembly.glb": glb_bytes(vertices, faces, groups),
        "assembly.stl": stl_bytes(vertices, faces),
    }
    out_dir.mkdir(parents=True, exist_ok=True)
    with contextlib.nullcontext(staging) if staging is not None else staged() as st:
        paths = []
        for name, content in data.items():
            target = out_dir / name
            st.path(target).write_bytes(content)
            paths.append(target)
    return paths
