"""Inner cut-outs (holes): geometry, the facet-sum model, mass, every file read back, bad input.

Numbers are checked against hand derivations: the area of an inscribed regular polygon
(k/2) r^2 sin(2 pi / k), the chord 2 sqrt(r^2 - d^2), and the spring sums of docs/theory.md 3.2 with the
facets a hole touches left out of the parallel sums and shortened in the series sums.
"""

from __future__ import annotations

import json
import math
import xml.etree.ElementTree as ET
from pathlib import Path
from typing import TYPE_CHECKING

import numpy as np
import pytest

from corrugate.analysis.evaluate import analyze
from corrugate.core.errors import InputError
from corrugate.fabrication.build import build_pattern
from corrugate.fabrication.model import polygon_area
from corrugate.geometry.holes import HOLE_SEGMENTS, Hole, check_holes
from corrugate.geometry.layer import Assembly, Layer
from corrugate.geometry.layouts import layer_inverse_sums, make_layout
from corrugate.materials.library import get_material
from corrugate.mechanics.mass import assembly_mass
from corrugate.mechanics.moduli import moduli
from corrugate.spec.inputs import assembly_from_options
from corrugate.workflow import write_design_files
from plan_readers import svg_mm_per_unit

if TYPE_CHECKING:
    from conftest import CliRun

SVG = "{http://www.w3.org/2000/svg}"
AXLE = Hole("circle", (0.0, 0.0), diameter=6.0)
DURALAR = get_material("dura-lar")


def shoelace(points: list[tuple[float, float]]) -> float:
    """Independent polygon area (mm^2) for the files read back."""
    p = np.asarray(points, dtype=float)
    return float(abs(0.5 * np.sum(p[:, 0] * np.roll(p[:, 1], -1) - np.roll(p[:, 0], -1) * p[:, 1])))


def wheel(holes: tuple[Hole, ...] = (AXLE,), n: int = 12, W: float = 8.0) -> Assembly:
    """A circle layout, W 8 mm, n 12, alpha 90 deg, Dura-Lar: L = 13 x 8 sin 45 = 73.5 mm."""
    return Assembly.identical(Layer(W, n, 90.0, DURALAR), make_layout("circle", holes=holes))


# -- geometry --------------------------------------------------------------------------------------


def test_circle_hole_is_cut_as_the_inscribed_polygon() -> None:
    k, r = HOLE_SEGMENTS, 3.0
    assert AXLE.area == pytest.approx(k / 2 * r * r * math.sin(2 * math.pi / k), rel=1e-12)
    assert 1 - AXLE.area / (math.pi * r * r) == pytest.approx((2 * math.pi / k) ** 2 / 6, rel=1e-3)
    ring = AXLE.ring()
    assert np.allclose(np.hypot(ring[:, 0], ring[:, 1]), r)


def test_polygon_hole_area_and_blocked_lengths() -> None:
    tri = Hole(
        "polygon", (10.0, 0.0), vertices=((-2.0, -2.0), (0.0, 3.0), (2.0, -2.0))
    )  # clockwise
    assert tri.area == pytest.approx(0.5 * 4 * 5)  # base 4, height 5, made counter-clockwise
    # slab 11 <= x <= 11.5: bottom edge y = -2, right edge x = 12 - 0.4 (y + 2) -> y = 0.5 at x = 11
    assert float(tri.blocked("x", 11.0, 11.5)) == pytest.approx(2.5)
    assert float(tri.blocked("x", 12.5, 13.0)) == 0.0
    # the circle: 2 r across a slab holding the centre, 2 sqrt(r^2 - d^2) at distance d
    assert float(AXLE.blocked("x", -1.0, 1.0)) == pytest.approx(6.0)
    assert float(AXLE.blocked("y", 1.0, 2.0)) == pytest.approx(2 * math.sqrt(9 - 1))
    assert float(AXLE.blocked("x", 3.0, 4.0)) == 0.0


def test_hole_must_clear_the_outline_and_other_holes() -> None:
    square = np.array([[0.0, 0.0], [50.0, 0.0], [50.0, 50.0], [0.0, 50.0]])
    check_holes((AXLE,), square, 50.0, 50.0)
    with pytest.raises(InputError, match=r"holes\[0\] .* cuts the outline"):
        check_holes((Hole("circle", (24.0, 0.0), 6.0),), square, 50.0, 50.0)
    with pytest.raises(InputError, match=r"holes\[0\] .* ligament of 0\.2"):
        check_holes((Hole("circle", (21.8, 0.0), 6.0),), square, 50.0, 50.0)
    with pytest.raises(InputError, match=r"holes\[1\] .* cuts holes\[0\]"):
        check_holes((AXLE, Hole("circle", (4.0, 0.0), 6.0)), square, 50.0, 50.0)


def test_two_holes_are_refused_exactly_when_their_true_gap_is_under_the_ligament() -> None:
    """Pairs of holes placed at random distances, near the ligament: check_holes (which skips
    pairs whose enclosing circles are a ligament apart) refuses a pair exactly when the true
    boundaries (two circles: centre distance minus radii; a circle and a square: by hand, centre to
    the square's nearest point) are closer than MIN_LIGAMENT or overlap."""
    from corrugate.geometry.holes import MIN_LIGAMENT

    square = np.array([[0.0, 0.0], [80.0, 0.0], [80.0, 80.0], [0.0, 80.0]])
    rng = np.random.default_rng(7)
    box = ((-2.0, -2.0), (2.0, -2.0), (2.0, 2.0), (-2.0, 2.0))
    refused = kept = 0
    for _ in range(300):
        d = float(rng.uniform(4.0, 12.0))
        ang = float(rng.uniform(0.0, 2 * math.pi))
        c2 = (d * math.cos(ang), d * math.sin(ang))
        if rng.random() < 0.5:  # two circles of diameters 6 and 4
            holes = (Hole("circle", (0.0, 0.0), 6.0), Hole("circle", c2, 4.0))
            true_gap = d - 3.0 - 2.0
        else:  # a circle of diameter 6 and a 4 mm square
            holes = (Hole("circle", (0.0, 0.0), 6.0), Hole("polygon", c2, vertices=box))
            nx = max(abs(c2[0]) - 2.0, 0.0)
            ny = max(abs(c2[1]) - 2.0, 0.0)
            true_gap = math.hypot(nx, ny) - 3.0
        if abs(true_gap - MIN_LIGAMENT) < 0.05:  # the cut polygon's own tolerance
            continue
        try:
            check_holes(holes, square, 80.0, 80.0)
            ok = True
        except InputError:
            ok = False
        assert ok == (true_gap >= MIN_LIGAMENT), (holes, true_gap)
        refused += not ok
        kept += ok
    assert refused > 20 and kept > 20  # both sides of the ligament were drawn


@pytest.mark.slow
def test_a_hole_near_the_outline_is_refused_exactly_when_its_true_ligament_is_too_small() -> None:
    """Circular and square holes at random places in a square and in a circle outline, many
    near the edge: check_holes (whose shortcut passes a hole whose enclosing circle is a ligament
    inside, without the vertex-by-vertex test) refuses a hole exactly when its true ligament,
    by hand (the square: the distance to the nearest side; the circle outline: its radius less
    the centre distance and the hole's reach), is under MIN_LIGAMENT; and the full test (the
    shortcut disabled) agrees with it on every draw."""
    from corrugate.geometry import holes as hmod
    from corrugate.geometry.layouts import make_layout

    square = np.array([[0.0, 0.0], [60.0, 0.0], [60.0, 60.0], [0.0, 60.0]])
    disc = make_layout("circle").plan_outline(60.0, 60.0)
    rng = np.random.default_rng(11)
    box = ((-2.0, -2.0), (2.0, -2.0), (2.0, 2.0), (-2.0, 2.0))
    seen = {True: 0, False: 0}
    for _ in range(200):
        in_disc = rng.random() < 0.5
        r_c = float(rng.uniform(22.0, 29.0))  # centre distance from the middle: near an edge
        ang = float(rng.uniform(0.0, 2 * math.pi))
        c = (r_c * math.cos(ang), r_c * math.sin(ang))
        if rng.random() < 0.5:
            hole, corners = Hole("circle", c, 4.0), None
        else:
            hole, corners = Hole("polygon", c, vertices=box), np.array(box) + np.array(c)
        if in_disc:  # the outline is a 720-gon inscribed in the radius-30 circle
            far = 2.0 if corners is None else float(np.max(np.hypot(*corners.T)) - r_c)
            true_gap = 30.0 * math.cos(math.pi / 720) - r_c - far
        else:
            pts = (
                np.array(
                    [
                        [c[0] + 2 * math.cos(t), c[1] + 2 * math.sin(t)]
                        for t in np.linspace(0, 2 * math.pi, 721)
                    ]
                )
                if corners is None
                else corners
            ) + 30.0
            true_gap = float(min(pts.min(), (60.0 - pts).min()))
        if abs(true_gap - hmod.MIN_LIGAMENT) < 0.05:  # the cut polygons' own tolerance
            continue
        outline = disc if in_disc else square
        verdicts = []
        for shortcut in (True, False):
            clear = hmod._clear
            if not shortcut:
                hmod._clear = lambda *a: False  # type: ignore[assignment]
            try:
                check_holes((hole,), outline, 60.0, 60.0)
                verdicts.append(True)
            except InputError:
                verdicts.append(False)
            finally:
                hmod._clear = clear  # type: ignore[assignment]
        assert verdicts == [true_gap >= hmod.MIN_LIGAMENT] * 2, (hole, in_disc, true_gap)
        seen[verdicts[0]] += 1
    assert seen[True] > 20 and seen[False] > 20  # both sides of the ligament were drawn


# -- model -----------------------------------------------------------------------------------------


@pytest.mark.parametrize(
    "hole",
    [
        Hole("circle", (0.0, 0.0), 6.0),
        Hole("polygon", (0.0, 0.0), vertices=((-2, -2), (2, -2), (2, 2), (-2, 2))),
    ],
)
def test_square_facet_sums_by_hand(hole: Hole) -> None:
    """Square, n = 9 (10 facets of length L), the hole at the centre, which is crease 5: it
    touches facets 4 and 5 of each layer and blocks b = 6 (circle) or 4 mm (square) of each."""
    layer = Layer(8.0, 9, 90.0, DURALAR)
    a = Assembly.identical(layer, make_layout("square", holes=(hole,)))
    L, p, t = a.Lx, layer.pitch, layer.t
    b = 6.0 if hole.shape == "circle" else 4.0
    q_par, q_ser = 8 / L, 8 / L + 2 / (L - b)
    par, ser = layer_inverse_sums(a.layout, 9, p, L, "x")
    assert float(par) == pytest.approx(q_par, rel=1e-12)
    assert float(ser) == pytest.approx(q_ser, rel=1e-12)
    m = moduli(DURALAR.E, DURALAR.nu, t, 8.0, 90.0, "refined")
    K0 = m.Ecy * p * t * q_par + m.Ecx * t / (p * q_ser)  # K_S1 + K_C2, docs/theory.md 3.3
    D0 = m.Eby * t**3 * p * q_par / 12 + m.Ebx * t**3 / (12 * p * q_ser)
    res = analyze(a, "refined", (0.0,))
    assert res.to_dict()["stiffness"][0]["K_N_per_mm"] == pytest.approx(float(K0), rel=1e-10)
    assert res.to_dict()["stiffness"][0]["D_Nmm"] == pytest.approx(float(D0), rel=1e-10)


@pytest.mark.slow
def test_a_hole_never_stiffens_and_mass_drops_by_rho_t_area_over_s() -> None:
    rng = np.random.default_rng(3)
    plain = analyze(wheel(()), "refined", (0.0, 30.0, 90.0))
    for _ in range(20):
        d = rng.uniform(2.0, 12.0)
        c = rng.uniform(-20.0, 20.0, 2)
        holed = analyze(wheel((Hole("circle", (c[0], c[1]), d),)), "refined", (0.0, 30.0, 90.0))
        for s0, s1 in zip(plain.to_dict()["stiffness"], holed.to_dict()["stiffness"], strict=True):
            assert s1["K_N_per_mm"] <= s0["K_N_per_mm"] and s1["D_Nmm"] <= s0["D_Nmm"]
    m0, m1 = assembly_mass(wheel(())), assembly_mass(wheel())
    s = math.sin(math.radians(45.0))
    removed = DURALAR.density * DURALAR.default_thickness * AXLE.area / s  # type: ignore[operator]
    assert m0.layer1 - m1.layer1 == pytest.approx(removed, rel=1e-9)
    assert m0.layer2 - m1.layer2 == pytest.approx(removed, rel=1e-9)
    assert m1.connectors == m0.connectors


def test_solver_bounds_hold_with_holes() -> None:
    """Box bounds of mass, K and D contain the exact values at points sampled in each box."""
    from corrugate.solver.points import DesignPoints, LayerPoints
    from corrugate.solver.problem import Problem
    from corrugate.solver.quantities import Tables, box_bounds, point_values
    from corrugate.solver.quantity import Quantity
    from corrugate.solver.solve import _pairs
    from corrugate.spec.schema import parse_spec

    spec = parse_spec(
        {
            "tolerances": "none",  # nominal: the test checks the model, not the tolerances (docs/tolerances.md)
            "material": {"name": "dura-lar"},
            "layout": {
                "shape": "circle",
                "holes": [
                    {"diameter": "6 mm"},
                    {
                        "shape": "polygon",
                        "center": ["12 mm", "-4 mm"],
                        "vertices": [[0, 0], [4, 0], [0, 3]],
                    },
                ],
            },
            "variables": {"W": {"min": 2, "max": 12}, "alpha": {"min": 40, "max": 140}},
            "constraints": {
                "diameter": {"min": "60 mm"},
                "inplane_stiffness": [{"min": "1 N/mm", "eta": 0}, {"min": "1 N/mm", "eta": 30}],
                "bending_stiffness": [{"min": "1 N*mm", "eta": 90}],
            },
        }
    )
    prob = Problem.from_spec(spec)
    tables = Tables(prob)
    c1, c2 = _pairs(prob)[0]
    keys = {Quantity.parse(k) for k in ("mass", "K@0", "K@30", "D@90")}
    rng = np.random.default_rng(7)
    for _ in range(60):
        nl = int(rng.integers(8, 30))
        nh = nl + int(rng.integers(0, 2))
        Wl, al = rng.uniform(3, 10), rng.uniform(50, 130)
        Wh, ah = Wl + rng.choice([1e-3, 0.3]), al + rng.choice([1e-3, 3.0])
        lo = DesignPoints.of(LayerPoints(*(np.array([v], dtype=float) for v in (nl, Wl, al))))
        hi = DesignPoints.of(LayerPoints(*(np.array([v], dtype=float) for v in (nh, Wh, ah))))
        b = box_bounds(prob, c1, c2, lo, hi, tables, keys)
        n = rng.integers(nl, nh + 1, 50).astype(float)
        W, a = rng.uniform(Wl, Wh, 50), rng.uniform(al, ah, 50)
        v = point_values(prob, c1, c2, DesignPoints.of(LayerPoints(n, W, a)), tables)
        for k in keys:
            assert np.all(v[k] >= b[k][0][0] * (1 - 1e-12)), k
            assert np.all(v[k] <= b[k][1][0] * (1 + 1e-12)), k
        if nl == nh and Wh - Wl < 0.01 and ah - al < 0.01:  # narrow boxes: tight bounds
            for k in (Quantity.parse("K@0"), Quantity.parse("D@90")):
                assert b[k][0][0] >= 0.9 * b[k][1][0], k


# -- files -----------------------------------------------------------------------------------------


def svg_rings(
    path: Path,
) -> tuple[list[list[tuple[float, float]]], list[list[tuple[float, float]]]]:
    """Outline and hole rings of a fold map, in mm."""
    root = ET.parse(path).getroot()
    u = svg_mm_per_unit(root)
    outlines, holes = [], []
    for poly in root.iter(f"{SVG}polygon"):
        pts = [tuple(u * float(c) for c in p.split(",")) for p in poly.attrib["points"].split()]
        (holes if "hole" in poly.attrib["class"] else outlines).append(pts)
    return outlines, holes  # type: ignore[return-value]


@pytest.mark.slow
def test_axle_hole_in_every_file_and_mass_equals_the_cut_area(tmp_path: Path) -> None:
    import trimesh
    from ezdxf.filemanagement import readfile

    a = wheel()
    res = analyze(a, "refined", (0.0, 90.0))
    paths = write_design_files(res, tmp_path)
    names = {p.name for p in paths}
    assert {"sheet-1.svg", "cut-1.dxf", "pattern.pdf", "layer1.fold", "assembly.stl"} <= names
    t, rho = a.layer1.t, DURALAR.density
    s = a.layer1.s
    flat_hole = AXLE.area / s  # the plan hole stretched by 1/s across the creases

    # SVG: every part's outline less its holes; one hole ring per layer, of area A_h / s
    outlines, holes = svg_rings(tmp_path / "sheet-1.svg")
    assert len(holes) == 2
    assert [shoelace(h) for h in holes] == pytest.approx([flat_hole] * 2, rel=1e-5)  # SVG rounding
    svg_area = sum(shoelace(o) for o in outlines) - sum(shoelace(h) for h in holes)
    mass = res.mass.total
    assert rho * t * svg_area == pytest.approx(mass, rel=0.005)
    assert rho * t * svg_area == pytest.approx(mass, rel=1e-4)  # in fact much closer
    # the hole ring is an ellipse of half-axes r / s and r, centred in its blank
    for h in holes:
        q = np.asarray(h)
        c = q.mean(axis=0)
        assert np.ptp(q[:, 0]) == pytest.approx(6.0 / s, rel=1e-3)
        assert np.ptp(q[:, 1]) == pytest.approx(6.0, rel=1e-3)
        assert any(
            shoelace(o) > 1000 and np.allclose(c, np.mean(np.asarray(o), axis=0), atol=0.05)
            for o in outlines
        )

    # cut DXF (the Silhouette's file): closed CUT polylines; holes are those inside another
    doc = readfile(tmp_path / "cut-1.dxf")
    rings = [
        [(float(x), float(y)) for x, y, *_ in e.get_points()]
        for e in doc.modelspace().query('LWPOLYLINE[layer=="CUT"]')
    ]
    areas = sorted(shoelace(r) for r in rings)
    assert areas[:2] == pytest.approx([flat_hole] * 2, rel=1e-6)
    dxf_area = sum(areas[2:]) - sum(areas[:2])
    assert rho * t * dxf_area == pytest.approx(mass, rel=1e-4)

    # FOLD: faces cover the blank less the hole; the hole's ring is boundary; no face covers it
    part = build_pattern(a).parts[0]
    for i in (1, 2):
        fold = json.loads((tmp_path / f"layer{i}.fold").read_text())
        V = np.asarray(fold["vertices_coords"])
        faces = [[tuple(V[k]) for k in f] for f in fold["faces_vertices"]]
        assert sum(polygon_area(f) for f in faces) == pytest.approx(part.area, rel=1e-9)
        # a valid FOLD mesh: every face a simple polygon (no vertex visited twice), no edge from
        # a vertex to itself (there were 14 and 20 such edges: one point's v computed twice,
        # up to 1.4e-14 mm apart, kept twice by the pass that removes T-junctions)
        assert all(len(set(f)) == len(f) >= 3 for f in fold["faces_vertices"])
        assert all(u != w for u, w in fold["edges_vertices"])
        hole = np.asarray(part.holes[0])
        c = hole.mean(axis=0)
        for f in faces:
            assert not _contains(np.asarray(f), c)
        on_ring = {
            k
            for k, (x, y) in enumerate(V)
            if abs(((x - c[0]) * s / 3.0) ** 2 + ((y - c[1]) / 3.0) ** 2 - 1) < 1e-3
        }
        ring_edges = [
            (u, w)
            for (u, w), kind in zip(fold["edges_vertices"], fold["edges_assignment"], strict=True)
            if u in on_ring and w in on_ring
        ]
        assert len(ring_edges) >= HOLE_SEGMENTS
        kinds = {
            kind
            for (u, w), kind in zip(fold["edges_vertices"], fold["edges_assignment"], strict=True)
            if (u, w) in ring_edges
        }
        assert kinds == {"B"}
        perimeter = sum(float(np.linalg.norm(V[u] - V[w])) for u, w in ring_edges)
        flat_ring = np.vstack([hole, hole[:1]])
        assert perimeter == pytest.approx(
            np.sum(np.linalg.norm(np.diff(flat_ring, axis=0), axis=1)), rel=1e-6
        )

    # STL and GLB: no triangle of the folded assembly crosses the axle's line (x, y) = centre
    for name in ("assembly.stl", "assembly.glb"):
        mesh = trimesh.load(tmp_path / name, force="mesh")
        tri = np.asarray(mesh.triangles)
        centre = np.array([a.Lx / 2, a.Ly / 2])
        hits = [k for k, tr in enumerate(tri) if _contains(tr[:, :2], centre)]
        assert hits == []
        radial = np.hypot(tri[..., 0] - centre[0], tri[..., 1] - centre[1])
        assert radial.min() == pytest.approx(3.0 * math.cos(math.pi / HOLE_SEGMENTS), abs=1e-4)

    # PDF (1:1, drawn as separate segments): around each hole of the fold map, in page mm (y up
    # from the bottom edge), a ring of segments whose ends lie on the hole's ellipse
    pytest.importorskip("pypdf")
    from pypdf import PdfReader

    from pdf_readers import PT, page_paths

    reader = PdfReader(tmp_path / "pattern.pdf")
    page = reader.pages[0]
    height = float(page.mediabox.height) / PT
    ends = np.array([pt for sp in page_paths(reader, page) for pt in sp.points])
    for h in holes:
        cx, cy = np.asarray(h).mean(axis=0)
        u = (ends[:, 0] - cx) * s / 3.0
        v = (ends[:, 1] - (height - cy)) / 3.0
        on = np.abs(u**2 + v**2 - 1) < 0.02
        assert on.sum() >= 2 * HOLE_SEGMENTS, (h[:2], on.sum())

    design = json.loads((tmp_path / "design.json").read_text())
    assert design["layout"]["holes"][0]["diameter_mm"] == 6.0


def _contains(poly: np.ndarray, point: np.ndarray) -> bool:
    """Even-odd test, strictly inside (a point on an edge counts as outside)."""
    x, y = point
    inside = False
    for (x0, y0), (x1, y1) in zip(poly, np.roll(poly, -1, axis=0), strict=True):
        if (y0 > y) != (y1 > y) and x < x0 + (y - y0) * (x1 - x0) / (y1 - y0) - 1e-9:
            inside = not inside
    return inside


# -- input -----------------------------------------------------------------------------------------

SPEC = """
name = "holed-wheel"
tolerances = "none"  # nominal: the test checks the model, not the tolerances (docs/tolerances.md)
[material]
name = "dura-lar"
[layout]
shape = "circle"
holes = [HOLES]
[variables]
W = { min = "6 mm", max = "9 mm", step = "0.5 mm" }
n = { min = 8, max = 12 }
alpha = { min = "80 deg", max = "100 deg", step = "1 deg" }
[constraints]
diameter = { min = "60 mm", max = "80 mm" }
inplane_stiffness = [{ min = "600 N/mm", eta = "0 deg" }]
"""


@pytest.mark.slow
def test_design_with_an_axle_hole_writes_it_into_the_report(tmp_path: Path, cli: CliRun) -> None:
    spec = tmp_path / "wheel.toml"
    spec.write_text(SPEC.replace("HOLES", '{ diameter = "6 mm", center = ["0 mm", "0 mm"] }'))
    code, _, err = cli(["design", str(spec), "--out", str(tmp_path / "out")])
    assert code == 0, err
    report = (tmp_path / "out" / "report.html").read_text()
    assert "holes: circle d 6 mm at (0, 0) mm" in report
    design = json.loads((tmp_path / "out" / "design.json").read_text())
    outlines, holes = svg_rings(tmp_path / "out" / "sheet-1.svg")
    assert len(holes) == 2
    area = sum(shoelace(o) for o in outlines) - sum(shoelace(h) for h in holes)
    rho, t = DURALAR.density, DURALAR.default_thickness
    assert rho * t * area == pytest.approx(design["mass_g"], rel=1e-4)  # type: ignore[operator]
    # the certified optimum is the lightest feasible point of the grid, by brute force
    assert design["certified"] is True
    best = math.inf
    for n in range(8, 13):
        for W in np.arange(6.0, 9.0001, 0.5):
            for alpha in np.arange(80.0, 100.0001, 1.0):
                layer = Layer(float(W), n, float(alpha), DURALAR)
                if not 60.0 <= layer.chord_extent <= 80.0:
                    continue
                a = Assembly.identical(layer, make_layout("circle", holes=(AXLE,)))
                r = analyze(a, "refined", (0.0,))
                if r.to_dict()["stiffness"][0]["K_N_per_mm"] >= 600.0:
                    best = min(best, r.mass.total)
    assert design["mass_g"] == pytest.approx(best, rel=1e-9)
    # the hole binds: without it the optimum would be n 9, W 8, alpha 98 deg (K 633 N/mm), which
    # with the hole has K 543 N/mm < 600; the holed optimum is n 12, W 7, alpha 83 deg
    assert [design["design"]["layers"][0][k] for k in ("n", "W_mm", "alpha_deg")] == [12, 7.0, 83.0]


@pytest.mark.parametrize(
    ("holes", "field", "why"),
    [
        (
            '{ diameter = "6 mm", center = ["28 mm", "0 mm"] }',
            "layout.holes[0]",
            "cuts the outline",
        ),
        (
            '{ diameter = "6 mm" }, { diameter = "4 mm", center = ["4 mm", "0 mm"] }',
            "layout.holes[1]",
            "cuts layout.holes[0]",
        ),
        ('{ diameter = "-6 mm" }', "layout.holes[0].diameter", "out of range"),
        (
            '{ shape = "polygon", vertices = [[0, 0], [1, 1]] }',
            "layout.holes[0].vertices",
            "not a polygon",
        ),
        ('{ diameter = "6 mm", centre = [0, 0] }', "layout.holes[0].centre", "not a known key"),
    ],
)
def test_bad_hole_is_one_line_naming_the_field_exit_2_no_file(
    tmp_path: Path, cli: CliRun, holes: str, field: str, why: str
) -> None:
    spec = tmp_path / "bad.toml"
    spec.write_text(SPEC.replace("HOLES", holes))
    out = tmp_path / "out"
    code, _, err = cli(["design", str(spec), "--out", str(out)])
    assert code == 2
    lines = err.strip().splitlines()
    assert len(lines) == 1 and field in lines[0] and why in lines[0], err
    assert not out.exists()


def test_hole_needs_a_minimum_size_in_a_spec(tmp_path: Path, cli: CliRun) -> None:
    spec = tmp_path / "bad.toml"
    spec.write_text(SPEC.replace("HOLES", '{ diameter = "6 mm" }').replace('min = "60 mm", ', ""))
    code, _, err = cli(["design", str(spec), "--out", str(tmp_path / "o")])
    assert code == 2 and "constraints.diameter.min" in err and "is missing" in err
    assert not (tmp_path / "o").exists()


@pytest.mark.slow
def test_options_and_web_api_take_holes() -> None:
    from fastapi.testclient import TestClient

    from corrugate.web import create_app

    a = assembly_from_options(
        W=8, n=12, alpha=90, layout="circle", holes='[{"shape": "circle", "diameter": "6 mm"}]'
    )
    assert a.layout.holes == (AXLE,)
    with pytest.raises(InputError, match=r"holes\[0\]\.diameter"):
        assembly_from_options(W=8, n=12, alpha=90, layout="circle", holes=[{"diameter": "x"}])
    body = {"W": 8, "n": 12, "alpha": 90, "layout": "circle", "holes": [{"diameter": "6 mm"}]}
    with TestClient(create_app()) as client:
        r = client.post("/api/analyze", json=body)
        assert r.status_code == 200, r.text
        d = r.json()
        assert d["layout"]["holes"][0]["diameter_mm"] == 6.0
        assert d["mass_g"] == pytest.approx(assembly_mass(wheel()).total, rel=1e-12)
        bad = client.post(
            "/api/analyze", json={**body, "holes": [{"diameter": 6, "center": [36, 0]}]}
        )
        assert bad.status_code == 422
        assert bad.json()["field"] == "holes[0]"


# -- finite elements -------------------------------------------------------------------------------


@pytest.mark.fea
def test_assembly_fe_with_a_central_hole_lies_between_the_model_and_no_hole(ccx: str) -> None:
    """Square, W 8, n 8, alpha 84 deg (the case study), in-plane compression at eta = 0: the FE
    (CalculiX, staircase hole) K with a 6 mm central hole is below the FE K without it and above
    the model's (which drops the 3 facets the hole touches from the parallel sum: conservative)."""
    from corrugate.fea.assembly import AssemblyMesh, assembly_deck, solve_assembly

    layer = Layer(8.0, 8, 84.0, DURALAR)
    plain = Assembly.identical(layer, make_layout("square"))
    holed = Assembly.identical(layer, make_layout("square", holes=(AXLE,)))
    _, info0 = assembly_deck(plain, "platens", AssemblyMesh(4))
    _, info1 = assembly_deck(holed, "platens", AssemblyMesh(4))
    assert info1.elements < info0.elements and info1.nodes < info0.nodes
    model = [
        analyze(x, "refined", (0.0,)).to_dict()["stiffness"][0]["K_N_per_mm"]
        for x in (plain, holed)
    ]
    fe = [solve_assembly(x, "platens", AssemblyMesh(4)).K for x in (plain, holed)]
    assert fe[0] == pytest.approx(model[0], rel=0.01)
    assert model[1] < fe[1] < fe[0]  # type: ignore[operator]


@pytest.mark.slow
def test_validate_reads_the_holes_of_a_design_json(tmp_path: Path) -> None:
    """``corrugate validate --design`` must not drop the holes: design.json round trip."""
    from corrugate.export.record import read_record

    layer = Layer(8.0, 8, 84.0, DURALAR)
    tri = Hole("polygon", (10.0, 5.0), vertices=((0.0, 0.0), (4.0, 0.0), (0.0, 3.0)))
    a = Assembly.identical(layer, make_layout("square", holes=(AXLE, tri)))
    write_design_files(analyze(a, "refined", (0.0,)), tmp_path)
    back = read_record(tmp_path / "design.json").assembly()
    assert back.layout.holes == (AXLE, tri)
    assert assembly_mass(back).total == pytest.approx(assembly_mass(a).total, rel=1e-12)


def test_facet_sums_and_polygon_spans_in_slices_equal_one_pass(
    monkeypatch: pytest.MonkeyPatch,
) -> None:
    """touched_sums and a polygon outline's span and cumulative area take their points in slices
    to bound memory (issue 22): the values are those of one pass over every point (to the last
    bits of a sum: numpy may add a row's terms in another order when the array's shape differs)."""
    import corrugate.geometry.holes as holes_mod
    import corrugate.geometry.layouts as layouts_mod

    rng = np.random.default_rng(7)
    ring = [(40 * math.cos(t), 30 * math.sin(t)) for t in np.linspace(0, 2 * math.pi, 40)[:-1]]
    polygon = make_layout("polygon", ring)
    disc = make_layout("circle", holes=(Hole("circle", (0.0, 0.0), diameter=60.0),))
    n = rng.integers(2, 60, size=500)
    p = rng.uniform(1.2, 1.5, size=500)
    side = rng.uniform(70.0, 80.0, size=500)
    u = rng.uniform(0.0, 1.0, size=(50, 7))
    eta = rng.uniform(0.0, 180.0, size=500)

    def values() -> list[np.ndarray]:
        par, ser = layer_inverse_sums(disc, n, p, side, "x")
        return [
            par,
            ser,
            polygon.span(side, side * 0.8, eta),
            polygon.cumulative_area(u, "x"),
            polygon.cumulative_area(u, "y"),
        ]

    whole = values()
    monkeypatch.setattr(holes_mod, "TOUCHED_SLICE", 97)
    monkeypatch.setattr(layouts_mod, "SLICE_ELEMENTS", 101)
    sliced = values()
    for a, b in zip(whole, sliced, strict=True):
        assert a.shape == b.shape
        assert np.array_equal(np.isinf(a), np.isinf(b))  # a facet the hole cuts through
        f = np.isfinite(a)
        scale = float(np.max(np.abs(a[f])))
        assert np.allclose(a[f], b[f], rtol=1e-13, atol=1e-15 * scale)
    assert np.all(np.isfinite(whole[0])) and np.any(whole[1] > whole[0])  # the hole counts
