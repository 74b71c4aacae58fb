"""Flat patterns and folded geometry: parsed back and checked by geometry, not by snapshots."""

from __future__ import annotations

import json
import math
from pathlib import Path

import numpy as np
import pytest

from corrugate import Assembly, Layer, analyze, get_material, make_layout
from corrugate.export.files3d import write_fold, write_mesh
from corrugate.fabrication.build import build_pattern
from corrugate.fabrication.model import Role, polygon_area
from corrugate.geometry.layouts import Layout

DURALAR = get_material("dura-lar")

LAYOUTS: list[tuple[str, Layout, Layer, Layer]] = [
    ("square", make_layout("square"), Layer(8, 8, 84, DURALAR), Layer(8, 8, 84, DURALAR)),
    ("rectangle", make_layout("rectangle"), Layer(8, 8, 84, DURALAR), Layer(6, 13, 100, DURALAR)),
    ("circle", make_layout("circle"), Layer(10, 11, 90, DURALAR), Layer(10, 11, 90, DURALAR)),
    (
        "trapezoid",
        make_layout("polygon", [(0, 0), (1, 0), (0.75, 1), (0.25, 1)]),
        Layer(6, 12, 100, DURALAR),
        Layer(7, 9, 80, get_material("kapton"), 0.05),
    ),
    (
        "concave",
        make_layout("polygon", [(0, 0), (3, 0), (3, 1), (1, 1), (1, 3), (0, 3)]),
        Layer(6, 12, 100, DURALAR),
        Layer(6, 12, 100, DURALAR),
    ),
]


@pytest.mark.parametrize(("name", "layout", "l1", "l2"), LAYOUTS, ids=[x[0] for x in LAYOUTS])
def test_mass_equals_rho_t_area_of_cut_polygons(
    name: str, layout: Layout, l1: Layer, l2: Layer
) -> None:
    a = Assembly(l1, l2, layout)
    pattern = build_pattern(a)
    mass = analyze(a).mass
    by_kind: dict[str, float] = {"layer": 0.0, "connector": 0.0}
    for part in pattern.parts:
        t = part.t or pattern.t
        rho = part.density or pattern.density
        by_kind[part.kind] += rho * t * polygon_area(part.outline)  # independent shoelace
    assert by_kind["layer"] == pytest.approx(mass.layer1 + mass.layer2, rel=5e-3)
    assert by_kind["connector"] == pytest.approx(mass.connectors, rel=5e-3)
    assert sum(by_kind.values()) == pytest.approx(mass.total, rel=5e-3)


@pytest.mark.parametrize(("name", "layout", "l1", "l2"), LAYOUTS, ids=[x[0] for x in LAYOUTS])
def test_every_crease_once_alternating(name: str, layout: Layout, l1: Layer, l2: Layer) -> None:
    a = Assembly(l1, l2, layout)
    parts = {p.name: p for p in build_pattern(a).parts}
    for index, layer in ((1, l1), (2, l2)):
        creases = parts[f"L{index}"].creases()
        us = sorted({round(c.a[0], 9) for c in creases})
        assert us == pytest.approx([k * layer.W for k in range(1, layer.n + 1)])
        for c in creases:
            k = round(c.a[0] / layer.W)
            assert c.role is (Role.MOUNTAIN if k % 2 else Role.VALLEY)
            assert c.fold_angle_deg == pytest.approx(180 - layer.alpha_deg)
            assert c.a[0] == c.b[0]  # straight across the blank


def test_square_blank_is_the_papers() -> None:
    """Flat blank of one layer: (n + 1) W by L (docs/theory.md section 2)."""
    a = Assembly.identical(Layer(8, 8, 84, DURALAR))
    blank = build_pattern(a).parts[0]
    assert blank.size == pytest.approx((72.0, a.Lx))
    assert len(blank.creases()) == 8
    assert all(c.length == pytest.approx(a.Lx) for c in blank.creases())


def test_band_marks_match_crease_ends() -> None:
    """Each crease of each layer meets the perimeter twice on a square: 2 n1 + 2 n2 marks, and each
    mark sits at k p from its segment's start."""
    l1, l2 = Layer(8, 8, 84, DURALAR), Layer(6, 13, 100, DURALAR)
    a = Assembly(l1, l2, make_layout("rectangle"))
    bands = [p for p in build_pattern(a).parts if p.kind == "connector"]
    assert len(bands) == 4
    marks = [ln for b in bands for ln in b.lines if ln.role is Role.MARK]
    assert len(marks) == 2 * l1.n + 2 * l2.n
    first = sorted(ln.a[0] for ln in bands[0].lines if ln.role is Role.MARK)
    assert first == pytest.approx([k * l1.pitch for k in range(1, l1.n + 1)])
    for b in bands:  # band height is t_d and corners fold by 90 deg
        assert max(y for _, y in b.outline) - 4.0 == pytest.approx(a.thickness)
        corner = [ln for ln in b.lines if ln.role is Role.VALLEY and ln.fold_angle_deg == 90.0]
        assert corner


def _fold(tmp_path: Path, a: Assembly, index: int) -> dict:  # type: ignore[type-arg]
    write_fold(a, build_pattern(a), tmp_path)
    return json.loads((tmp_path / f"layer{index}.fold").read_text())


@pytest.mark.parametrize("alpha", [40.0, 84.0, 115.0])
def test_fold_is_isometric_planar_and_spans_the_square(tmp_path: Path, alpha: float) -> None:
    layer = Layer(8, 9, alpha, DURALAR)
    a = Assembly.identical(layer)
    doc = _fold(tmp_path, a, 1)
    assert doc["file_spec"] == 1.2
    assert doc["frame_unit"] == "mm"
    flat = np.array(doc["vertices_coords"], dtype=float)
    folded = np.array(doc["file_frames"][0]["vertices_coords"], dtype=float)
    assert folded.shape == (len(flat), 3)
    for i, j in doc["edges_vertices"]:
        assert np.linalg.norm(folded[i] - folded[j]) == pytest.approx(
            np.linalg.norm(flat[i] - flat[j]), abs=1e-6
        )
    for face in doc["faces_vertices"]:
        p = folded[face]
        # planar: every vertex lies on the plane of the first three (to 1e-9 mm)
        n = np.cross(p[1] - p[0], p[2] - p[0])
        n /= np.linalg.norm(n)
        assert np.abs((p - p[0]) @ n).max() < 1e-9
        # and the folded face keeps its flat area (isometry, second check)
        flat_area = polygon_area([tuple(q) for q in flat[face]])
        tri = sum(
            np.linalg.norm(np.cross(p[k] - p[0], p[k + 1] - p[0])) / 2 for k in range(1, len(p) - 1)
        )
        assert tri == pytest.approx(flat_area, rel=1e-9)
    span = folded.max(axis=0) - folded.min(axis=0)
    assert span[0] == pytest.approx(a.Lx, abs=1e-9)
    assert span[1] == pytest.approx(a.Lx, abs=1e-9)
    assert span[2] == pytest.approx(8 * math.cos(math.radians(alpha) / 2), abs=1e-9)


def test_fold_angle_signs_agree_with_geometry(tmp_path: Path) -> None:
    """Mountain (negative angle): the crease is higher than the neighbouring facets seen from the
    face that was up when flat; valley (positive): lower. Checked on the folded coordinates."""
    layer = Layer(8, 8, 84, DURALAR)
    doc = _fold(tmp_path, Assembly.identical(layer), 1)
    folded = np.array(doc["file_frames"][0]["vertices_coords"], dtype=float)
    centroid_z = {}
    for f, face in enumerate(doc["faces_vertices"]):
        centroid_z[f] = folded[face][:, 2].mean()
    creases = 0
    for e, (i, j) in enumerate(doc["edges_vertices"]):
        assignment, angle = doc["edges_assignment"][e], doc["edges_foldAngle"][e]
        if assignment == "B":
            assert angle == 0
            continue
        creases += 1
        faces = [f for f, face in enumerate(doc["faces_vertices"]) if i in face and j in face]
        assert len(faces) == 2
        crease_z = (folded[i, 2] + folded[j, 2]) / 2
        around = np.mean([centroid_z[f] for f in faces])
        if assignment == "M":
            assert angle == pytest.approx(-(180 - 84))
            assert crease_z > around
        else:
            assert assignment == "V"
            assert angle == pytest.approx(180 - 84)
            assert crease_z < around
    assert creases == 8


def test_mesh_files_load_and_span_the_assembly(tmp_path: Path) -> None:
    import trimesh

    a = Assembly.identical(Layer(8, 8, 84, DURALAR))
    write_mesh(a, build_pattern(a), tmp_path)
    for name in ("assembly.glb", "assembly.stl"):
        mesh = trimesh.load(tmp_path / name, force="mesh")
        lo, hi = mesh.bounds
        assert hi - lo == pytest.approx([a.Lx, a.Ly, a.thickness], abs=1e-4)
        assert len(mesh.faces) > 0


def test_assembly_instructions(tmp_path: Path) -> None:
    from corrugate.fabrication.instructions import write_instructions

    a = Assembly.identical(Layer(8, 8, 84, DURALAR), make_layout("circle"))
    pattern = build_pattern(a)
    write_instructions(a, pattern, tmp_path)
    text = (tmp_path / "ASSEMBLY.md").read_text()
    numbered = [line for line in text.splitlines() if line[:1].isdigit()]
    assert [int(line.split(".")[0]) for line in numbered] == list(range(1, len(numbered) + 1))
    assert len(numbered) >= 6
    for part in pattern.parts:
        assert part.name in text
    assert "96 deg" in text  # the fold angle 180 - 84
    png = (tmp_path / "assembly.png").read_bytes()
    assert png[:8] == b"\x89PNG\r\n\x1a\n"
    width, height = int.from_bytes(png[16:20], "big"), int.from_bytes(png[20:24], "big")
    assert width > 600
    assert height > 400


def test_mesh_files_are_the_folded_triangles_as_trimesh_reads_them(tmp_path: Path) -> None:
    """GLB and STL are written without a mesh library: trimesh (an independent reader) gets back
    every triangle of :func:`folded_mesh` (float32; in order from the STL, the GLB's per-part
    meshes in any order), the STL normals are trimesh's own of
    the float64 triangles,
    and a GLB container whose chunks are aligned and whose declared lengths are the file's."""
    import json
    import struct

    import trimesh

    from corrugate.fabrication.folded import folded_mesh

    a = Assembly.identical(Layer(8, 8, 84, DURALAR), make_layout("circle"))
    pattern = build_pattern(a)
    write_mesh(a, pattern, tmp_path)
    vertices, faces = folded_mesh(a, pattern.parts)
    expected = vertices.astype(np.float32)[faces]

    def rows(tris: np.ndarray) -> np.ndarray:  # the GLB's parts may be joined in any order
        flat = np.round(np.asarray(tris, dtype=np.float64).reshape(len(tris), 9), 4)
        return flat[np.lexsort(flat.T[::-1])]

    for name in ("assembly.glb", "assembly.stl"):
        mesh = trimesh.load(tmp_path / name, force="mesh", process=False)
        got = np.asarray(mesh.triangles)
        if name.endswith(".stl"):  # one solid: every triangle in order
            assert got == pytest.approx(expected, abs=1e-6), name
        assert rows(got) == pytest.approx(rows(expected), abs=2e-4), name
    stored = np.frombuffer((tmp_path / "assembly.stl").read_bytes()[84:], dtype=np.uint8)
    records = stored.reshape(len(faces), 50)
    normals = records[:, :12].copy().view("<f4").reshape(-1, 3)
    reference, valid = trimesh.triangles.normals(vertices[faces])
    assert valid.all()
    assert normals == pytest.approx(reference, abs=1e-6)
    glb = (tmp_path / "assembly.glb").read_bytes()
    magic, version, total = struct.unpack("<4sII", glb[:12])
    assert (magic, version, total) == (b"glTF", 2, len(glb))
    json_len, json_type = struct.unpack("<I4s", glb[12:20])
    assert json_type == b"JSON" and json_len % 4 == 0
    doc = json.loads(glb[20 : 20 + json_len])
    bin_len, bin_type = struct.unpack("<I4s", glb[20 + json_len : 28 + json_len])
    assert bin_type == b"BIN\x00" and 28 + json_len + bin_len == len(glb)
    positions = [
        doc["accessors"][mesh["primitives"][0]["attributes"]["POSITION"]] for mesh in doc["meshes"]
    ]
    low = np.min([p["min"] for p in positions], axis=0)
    high = np.max([p["max"] for p in positions], axis=0)
    assert low == pytest.approx(vertices.min(axis=0).tolist(), rel=1e-6)
    assert high == pytest.approx(vertices.max(axis=0).tolist(), rel=1e-6)


def test_glb_has_one_coloured_mesh_per_layer_and_the_stl_is_one_solid(tmp_path: Path) -> None:
    """The GLB holds layer 1, layer 2 and the band as separate nodes, meshes and materials (each
    its own colour), which trimesh reads as three geometries whose triangles are, in order, those
    of the folded mesh; the STL stays every triangle in one solid, byte for byte
    :func:`stl_bytes` of :func:`folded_mesh`."""
    import json
    import struct

    import trimesh

    from corrugate.export.files3d import PART_COLOURS, stl_bytes
    from corrugate.fabrication.folded import folded_mesh, folded_mesh_groups

    a = Assembly(Layer(8, 8, 84, DURALAR), Layer(10, 6, 90, DURALAR), make_layout("rectangle"))
    pattern = build_pattern(a)
    write_mesh(a, pattern, tmp_path)
    vertices, faces = folded_mesh(a, pattern.parts)
    assert (tmp_path / "assembly.stl").read_bytes() == stl_bytes(vertices, faces)

    glb = (tmp_path / "assembly.glb").read_bytes()
    json_len = struct.unpack("<I", glb[12:16])[0]
    doc = json.loads(glb[20 : 20 + json_len])
    names = ["layer 1", "layer 2", "band"]
    assert [n["name"] for n in doc["nodes"]] == names
    assert [m["name"] for m in doc["materials"]] == names
    colours = [tuple(m["pbrMetallicRoughness"]["baseColorFactor"]) for m in doc["materials"]]
    assert colours == [PART_COLOURS[n] for n in names] and len(set(colours)) == 3
    assert [m["primitives"][0]["material"] for m in doc["meshes"]] == [0, 1, 2]

    scene = trimesh.load(tmp_path / "assembly.glb", process=False)
    assert isinstance(scene, trimesh.Scene)
    assert len(scene.geometry) == 3
    _, _, groups = folded_mesh_groups(a, pattern.parts)
    first = 0
    expected = vertices.astype(np.float32)[faces]
    for (name, _, count), node in zip(groups, names, strict=True):
        geometry = scene.geometry[scene.graph[node][1]]
        assert len(geometry.faces) == count > 0
        tris = np.asarray(geometry.triangles)
        assert tris == pytest.approx(expected[first : first + count], abs=1e-6), name
        first += count
    assert first == len(faces)
