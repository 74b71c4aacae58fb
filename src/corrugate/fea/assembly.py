"""The whole OADLC assembly as shells in CalculiX: in-plane compression and 3-point bending.

Model (every choice stated; DESIGN.md section 6):

* **Geometry** (eta = 0 or 90 deg). Both layers of a rectangular layout (``square`` or
  ``rectangle``; the layers may differ), each as the
  zig-zag mid-surface of its n + 1 facets, L_j equal to the other layer's extent. Layer 1's creases
  run along y, its zig-zag spans x in [0, Lx] between z = 0 and z = h1 (it starts and ends on a
  bottom crease line); layer 2's creases run along x, it spans y in [0, Ly] between z = h1 and
  z = h1 + h2, resting on layer 1.
* **Connectors** (``connectors=True``, off by default). The band of :mod:`corrugate.pattern.
  connectors` as four flat walls standing on the rectangle's outline from z = 0 to t_d = h1 + h2
  (as :func:`corrugate.pattern.folded.band_walls`), S8R shells of layer 1's material and
  thickness. Each wall is meshed to conform to the layer edges it meets: the wall at y = 0 (and
  Ly) is cut by layer 1's zig-zag edge into two triangles per facet (each meshed as three
  quadrilateral patches meeting at its centroid, ``along`` elements on every side), with a plain
  strip from h1 to t_d above; the walls at x = 0 and Lx likewise carry layer 2's zig-zag above a
  strip from 0 to h1. The layers are meshed with along x (n_other + 1) elements along their
  creases so that their edge nodes fall on the band's nodes. **Tie: shared nodes.** Every layer
  node on the outline *is* a band node (checked: a SolverError otherwise), so the crease ends and
  the end creases are glued to the band along their whole length; CalculiX makes these nodes knots
  (rigid through-thickness links), i.e. a rigid, fully bonded joint that also transmits moments.
  Where layer 1's ridges meet layer 2's end valleys on the band, the two layers' nodes are merged
  into one; inside the panel the layers stay unconnected, as without the band. Walls meet at the
  corners on shared nodes (the overlap tabs are taken as fully bonded). That is ``bond="edges"``
  (the default), a perfect bond without the glue flanges. ``bond="flanges"`` models the band as
  cut instead: the walls plus their glue flanges (horizontal strips about 4 mm deep at the foot
  and the top of each wall, on the layers' node stations, slit into the cut file's tabs), and the
  layers tied only where they rest on a flange (layer nodes on z = 0 or t_d: layer 1's valleys on
  the foot flanges, layer 2's ridges under the top ones); elsewhere the layer edges only touch the
  walls (no contact is modelled). The fixtures act on the band as on the layers: in compression
  every band node on a platen plane is on the platen (the walls at the loaded edges lie entirely
  on it); in bending every band node on an end line is supported and every band node on a load
  line moves with the rigid load line. The rigid-body constraints are applied to layer 1 only
  (the parts form one body). In 4-point bending the band joins the parts into one body, so D4
  comes from one deflection: the mean over the nodes of the band and of the layer bent along its
  creases on the mid-span and gauge lines (the other layer, bent across its creases, sags between
  the walls and would measure the distortion of the section rather than its bending).
* **Elements.** 8-node shells with reduced integration (S8R, ``*SHELL SECTION`` of thickness t),
  ``mesh.along`` elements across each facet (even) and elements of about the same size along the
  creases (an even number). Facets share their nodes on the creases; CalculiX turns these nodes
  into knots (rigid links through the thickness), i.e. stiff creases, as in the closed forms.
* **How the layers interact.** In the panel the layers touch along crease lines and are tied by
  connectors at the edges. Here they are **not connected to each other at all**: each layer is
  loaded by the same rigid fixture (same prescribed displacement), and the assembly's force is the
  sum of the two layers' reactions. That is the parallel-spring assumption of the closed forms
  (DESIGN.md 3.3), checked without contact or connector models, which would add stiffness the
  closed forms neglect (the paper saw its experiments slightly stiffer for that reason).
* **Compression along eta** (eta = 0: along y, layer 1's creases; eta = 90: along x). Both loaded
  edges of each layer lie on rigid, frictionless, non-rotating platens: the displacement along the
  load axis is 0 on one edge and -delta on the other, the rotations about the two in-plane axes of
  each platen are held (a plane of symmetry, which makes the end facets of the chordwise layer
  behave as the interior, periodic ones); the other translations are free except for three
  rigid-body constraints per layer. K = (sum of reactions on the moving platen) / delta, N/mm.
* **3-point bending about eta** (span along the load axis, equal to the panel's extent, as in
  ``analyze``: EI = D x span). Line supports at both ends (u_z = 0 on every node of each layer's end
  edge: an end diaphragm, free to rotate and slide), and a rigid line load at mid-span: every node
  of each layer on the mid-span line moves by u_z = -delta, with u along the span held there
  (symmetry). EI = P span^3 / (48 delta) (Euler-Bernoulli 3-point bending), D = EI / span, in
  N mm^2 and N mm. This is the apparent stiffness a bench test would measure: it includes the
  shear deformation of stubby panels, which the closed forms neglect, but not local crushing
  under the rollers (the fixtures act on whole node lines).
* **Buckling** (``buckling``): the compression fixture with the moving platens of all parts
  tied (``*EQUATION``) to one reference node loaded by 1 N, and a ``*BUCKLE`` step (linear
  eigenvalue buckling about the unloaded state, 3 modes, relative accuracy 1e-6; ccx's default
  is 1e-2): the first buckling factor is the
  platen force (N) of the first mode. Bounds from plate theory: :mod:`corrugate.buckling`.
* **Frame** (``frame``, the kinematics of the paper's spring rule): compression along eta = 0 or
  90 as above with the two side edges of each layer on platens too, held in place (normal
  displacement and the rotations about their in-plane axes zero); the side platen's reaction
  gives the coupling term. :mod:`corrugate.fea.frame` combines two such runs into the 2 x 2
  platen stiffness of the panel in a rigid frame and K_frame(eta) from it.
* **4-point bending about eta** (``bending4``, a diagnostic the paper did not run): the same
  supports, rigid line loads u_z = -delta at a quarter and three quarters of the span, symmetry at
  mid-span. Between the load lines the moment M = P L / 8 is constant and the shear zero, so the
  deflection of mid-span relative to gauge lines at 3/8 and 5/8 of the span, Delta (means over
  each layer's nodes on those lines; away from the local deformation at the load lines), gives
  the pure bending stiffness of each layer, EI_i = P_i span^3 / (1024 Delta_i), free of shear
  deformation: the quantity the closed forms model. Needs node lines at 1/4 and 3/8 of the span
  (``along`` x (n + 1) divisible by 8).

**Any other eta** (``specimen``, ``_oblique_shells``): the specimen is a square coupon of the
layout's side cut from the same two layers with its edges along and across eta (the layers'
zig-zags continue periodically past the layout's extent, centred on it), in a test frame with y
along eta. Its plan is meshed by gmsh (:mod:`corrugate.fea.planmesh`) with the creases and the
fixture lines as element edges and the nodes lifted onto the zig-zags: S8R quadrilaterals and a
few S6 triangles. Fixtures as above, on the coupon's edges; no band. ``mesher="gmsh"`` meshes
eta = 0 and 90 this way too (a second discretisation of the same model, which the tests compare
with the structured mesh). Circles and polygons are refused: no straight edges for the fixtures.
"""

from __future__ import annotations

import itertools
import math
from dataclasses import dataclass, field
from pathlib import Path
from typing import Literal

import numpy as np
from numpy.typing import NDArray

from ..errors import InputError
from ..geometry import Assembly, Layer
from ..pattern.connectors import slit_count
from ..pattern.options import DEFAULT_FABRICATION, FabricationOptions
from .ccx import SolverError, run_ccx, work_dir

__all__ = [
    "TESTS",
    "AssemblyMesh",
    "AssemblyResult",
    "Bond",
    "DeckInfo",
    "LoadTest",
    "assembly_deck",
    "principal_axis",
    "solve_assembly",
    "specimen",
]

LoadTest = Literal["compression", "bending", "bending4", "frame", "buckling"]
Mesher = Literal["auto", "structured", "gmsh"]
TESTS: tuple[LoadTest, ...] = ("compression", "bending", "bending4", "frame", "buckling")
FloatArray = NDArray[np.float64]


@dataclass(frozen=True, slots=True)
class AssemblyMesh:
    """Shell mesh: ``along`` S8R elements across each facet (even, >= 2); along the creases the
    element length is about the facet element width, rounded to an even number of elements."""

    along: int = 4

    def __post_init__(self) -> None:
        v = self.along
        if isinstance(v, bool) or not isinstance(v, int) or v < 2 or v % 2:
            raise InputError("mesh.along", v, "an even integer >= 2")

    def refined(self, factor: float = 2.0) -> AssemblyMesh:
        """The mesh with ``along`` scaled by ``factor`` (kept even)."""
        return AssemblyMesh(max(2, 2 * round(self.along * factor / 2)))

    def label(self) -> str:
        return f"{self.along}/facet"


@dataclass(frozen=True, slots=True)
class AssemblyResult:
    """One FE load case of the assembly: K (N/mm) for compression and the frame test, D (N mm)
    and EI (N mm^2) for bending (the other entries None); for the frame test, ``side_force`` (N,
    compressive) on the far side platen, held in place; for ``buckling``, ``buckling_load`` (N,
    the platen force of the first buckling mode; force and displacement are then NaN); ``force`` (N) at the prescribed ``displacement`` (mm), the
    share of the force carried by each layer, and each layer's part of K or D (``layer_values``).
    With ``connectors`` the band's own nodes carry ``band_value``; nodes shared by a layer and the
    band count for the layer, so the split between the parts is bookkeeping, the total is not."""

    test: LoadTest
    eta_deg: float
    mesh: AssemblyMesh
    span: float
    force: float
    displacement: float
    layer_forces: tuple[float, float]
    K: float | None
    D: float | None
    EI: float | None
    nodes: int
    elements: int
    layer_values: tuple[float, float] = (math.nan, math.nan)
    band_value: float | None = None
    connectors: bool = False
    side_force: float | None = None
    buckling_load: float | None = None

    def value(self) -> float:
        """K (N/mm) for compression and the frame, D (N mm) for bending (what ``analyze``
        reports), the first buckling load (N) for ``buckling``."""
        if self.test == "buckling":
            v = self.buckling_load
        else:
            v = self.K if self.test in ("compression", "frame") else self.D
        assert v is not None
        return v


@dataclass(frozen=True, slots=True)
class _Shell:
    """Nodes (global ids, coordinates) and connectivity of one part: S8R ``elements`` and, from
    the gmsh mesher, S6 triangles ``triangles``."""

    ids: NDArray[np.int64]
    xyz: FloatArray
    elements: list[list[int]]
    t: float
    E: float
    nu: float
    triangles: list[list[int]] = field(default_factory=list)


def _layer_shell(
    layer: Layer,
    span: float,
    along: int,
    first_id: int,
    chord_axis: int,
    z0: float,
    multiple: int = 2,
    nel_s: int | None = None,
) -> _Shell:
    """S8R mesh of a layer whose chord runs along ``chord_axis`` (0 = x, 1 = y); the number of
    elements along the creases is ``nel_s`` if given, else a multiple of ``multiple`` giving
    elements about as long as they are wide."""
    nf = layer.n + 1
    p, h = layer.pitch, layer.height
    nel_c = along * nf
    if nel_s is None:
        nel_s = multiple * max(1, math.ceil(span / (layer.W / along) / multiple))
    ni, nj = 2 * nel_c + 1, 2 * nel_s + 1
    chord = np.linspace(0.0, nf * p, ni)
    crease_c = np.arange(nf + 1) * p
    crease_z = np.where(np.arange(nf + 1) % 2 == 0, 0.0, h) + z0
    z_of = np.interp(chord, crease_c, crease_z)
    spanw = np.linspace(0.0, span, nj)
    ids = np.zeros((ni, nj), dtype=np.int64)
    coords: list[tuple[float, float, float]] = []
    order: list[int] = []
    nid = first_id
    for j in range(nj):
        for i in range(ni):
            if i % 2 and j % 2:
                continue  # S8R has no centre node
            ids[i, j] = nid
            order.append(nid)
            nid += 1
            c, s_ = float(chord[i]), float(spanw[j])
            xy = (c, s_) if chord_axis == 0 else (s_, c)
            coords.append((xy[0], xy[1], float(z_of[i])))
    elements: list[list[int]] = []
    for ej in range(nel_s):
        for ei in range(nel_c):
            i0, j0 = 2 * ei, 2 * ej
            quad = [
                (i0, j0),
                (i0 + 2, j0),
                (i0 + 2, j0 + 2),
                (i0, j0 + 2),
                (i0 + 1, j0),
                (i0 + 2, j0 + 1),
                (i0 + 1, j0 + 2),
                (i0, j0 + 1),
            ]
            elements.append([int(ids[a, b]) for a, b in quad])
    m = layer.material
    return _Shell(
        np.asarray(order, dtype=np.int64), np.asarray(coords), elements, layer.t, m.E, m.nu
    )


Point2 = tuple[float, float]


def _patch(corners: tuple[FloatArray, ...], nu: int, nv: int) -> list[list[Point2]]:
    """S8R elements (8 points each, in the wall's (s, z) plane) of the bilinear patch ``corners``
    (P0, P1, P2, P3), ``nu`` x ``nv`` elements, counter-clockwise in (s, z)."""
    P0, P1, P2, P3 = corners

    def at(u: float, v: float) -> Point2:
        q = (1 - u) * (1 - v) * P0 + u * (1 - v) * P1 + u * v * P2 + (1 - u) * v * P3
        return (float(q[0]), float(q[1]))

    out: list[list[Point2]] = []
    for i in range(nu):
        u0, u1 = i / nu, (i + 1) / nu
        um = (u0 + u1) / 2
        for j in range(nv):
            v0, v1 = j / nv, (j + 1) / nv
            vm = (v0 + v1) / 2
            corner = [at(u0, v0), at(u1, v0), at(u1, v1), at(u0, v1)]
            mids = [at(um, v0), at(u1, vm), at(um, v1), at(u0, vm)]
            area2 = sum(
                corner[k][0] * corner[(k + 1) % 4][1] - corner[(k + 1) % 4][0] * corner[k][1]
                for k in range(4)
            )
            if area2 < 0:  # keep every normal along e_s x e_z
                corner = [corner[0], corner[3], corner[2], corner[1]]
                mids = [mids[3], mids[2], mids[1], mids[0]]
            out.append(corner + mids)
    return out


def _triangle(A: Point2, B: Point2, C: Point2, along: int) -> list[list[Point2]]:
    """A triangle as three quadrilateral patches meeting at its centroid, ``along`` / 2 x
    ``along`` / 2 elements each: every side gets ``along`` elements, evenly spaced."""
    a, b, c = (np.asarray(v, dtype=np.float64) for v in (A, B, C))
    g = (a + b + c) / 3
    ab, bc, ca = (a + b) / 2, (b + c) / 2, (c + a) / 2
    k = along // 2
    out: list[list[Point2]] = []
    for quad in ((a, ab, g, ca), (b, bc, g, ab), (c, ca, g, bc)):
        out += _patch(quad, k, k)
    return out


def _wall(layer: Layer, along: int, z_zig: float, strip: tuple[float, float]) -> list[list[Point2]]:
    """S8R elements of one band wall in its (s, z) plane: the strip of height ``layer.height``
    from ``z_zig`` up, cut by the layer's zig-zag edge (valleys at z_zig, at s = 0 and every
    second crease) into two triangles per facet, and the plain strip ``strip`` = (z0, z1) above or
    below it, ``along`` elements per facet along s and ``along`` elements through each strip."""
    nf, p, h = layer.n + 1, layer.pitch, layer.height
    out: list[list[Point2]] = []
    lo, hi = z_zig, z_zig + h
    for k in range(nf):
        x0, x1 = k * p, (k + 1) * p
        if k % 2 == 0:  # rising facet: valley at x0, ridge at x1
            out += _triangle((x0, lo), (x1, lo), (x1, hi), along)
            out += _triangle((x0, lo), (x1, hi), (x0, hi), along)
        else:
            out += _triangle((x0, lo), (x1, lo), (x0, hi), along)
            out += _triangle((x0, hi), (x1, lo), (x1, hi), along)
    z0, z1 = strip
    corners = tuple(
        np.asarray(v, dtype=np.float64) for v in ((0.0, z0), (nf * p, z0), (nf * p, z1), (0.0, z1))
    )
    out += _patch(corners, along * nf, along)
    return out


Bond = Literal["edges", "flanges"]
Point3 = tuple[float, float, float]


def _flanges(
    a: Assembly, along: int, opts: FabricationOptions = DEFAULT_FABRICATION
) -> list[tuple[int, list[list[Point3]]]]:
    """S8R elements (8 points each, global x, y, z) of the band's glue flanges: a horizontal strip
    of about ``depth`` inwards at the foot (z = 0) and at the top (z = t_d) of each wall, on the
    layers' own node stations (the layers meshed with ``along`` x (n_other + 1) elements along
    their creases), ``opts.tab_depth`` deep (rounded to whole elements), cut by slits into as many
    equal tabs as the cut file has along that edge (:func:`corrugate.pattern.connectors.
    slit_count`; tab ends rounded to element boundaries).
    Returns (tab number, elements) per tab; tabs share nodes only through the wall and the layers.
    The flanges of the walls y = 0 and Ly run the full length; those of x = 0 and Lx stop where
    they meet them (no overlap at the corners; the cut file chamfers them instead)."""
    l1, l2 = a.layer1, a.layer2
    td, Lx, Ly = a.thickness, a.Lx, a.Ly
    out: list[tuple[int, list[list[Point3]]]] = []
    # half-element spacings: along x, layer 1's chordwise stations; along y, layer 2's
    hx = l1.pitch / (2 * along)
    hy = l2.pitch / (2 * along)
    mx = max(1, round(opts.tab_depth / (2 * hx)))  # flange elements inwards from an x wall
    my = max(1, round(opts.tab_depth / (2 * hy)))
    tab = 0
    # (wall-normal axis, wall coordinate, inward sign, along-wall stations, inward spacing, count)
    nx_stations = 2 * along * (l1.n + 1)
    ny_stations = 2 * along * (l2.n + 1)
    walls = [
        (1, 0.0, 1.0, (0, nx_stations), hx, hy, my, Lx),
        (1, Ly, -1.0, (0, nx_stations), hx, hy, my, Lx),
        (0, 0.0, 1.0, (2 * my, ny_stations - 2 * my), hy, hx, mx, Ly),
        (0, Lx, -1.0, (2 * my, ny_stations - 2 * my), hy, hx, mx, Ly),
    ]
    for normal, c, sign, (i_lo, i_hi), h_along, h_in, m, edge in walls:
        n_tabs = slit_count(edge, opts) + 1
        bounds = [i_lo + 2 * round((i_hi - i_lo) / 2 * k / n_tabs) for k in range(n_tabs + 1)]
        for z in (0.0, td):
            for i0, i1 in itertools.pairwise(bounds):
                tab += 1
                elems: list[list[Point3]] = []
                for ei in range(i0, i1, 2):
                    for ej in range(m):
                        j0 = 2 * ej
                        quad = [(ei, j0), (ei + 2, j0), (ei + 2, j0 + 2), (ei, j0 + 2)]
                        mids = [(ei + 1, j0), (ei + 2, j0 + 1), (ei + 1, j0 + 2), (ei, j0 + 1)]
                        pts: list[Point3] = []
                        for i, j in quad + mids:
                            s_, w_ = i * h_along, c + sign * j * h_in
                            pts.append((s_, w_, z) if normal == 1 else (w_, s_, z))
                        elems.append(pts)
                out.append((tab, elems))
    return out


def _band_shell(
    a: Assembly, along: int, shells: list[_Shell], tol: float, bond: Bond = "edges"
) -> _Shell:
    """The connector band: four walls standing on the rectangle's outline from z = 0 to t_d, as
    S8R shells of layer 1's material and thickness; the layer meshes must run ``along`` x
    (n_other + 1) elements along their creases.

    ``bond="edges"``: band nodes at the position of a layer node are that node (shared nodes: the
    layer edges are tied to the band along their whole length, a perfect bond); where layer 1's
    ridges meet layer 2's end valleys on the band, layer 2's node is merged into layer 1's
    (``shells`` is updated in place). ``bond="flanges"``: the band as cut, with its glue flanges
    (:func:`_flanges`), and the layers tied to it only where they rest on a flange (the planes
    z = 0 and z = t_d: layer 1's valleys on the foot flanges, layer 2's ridges under the top
    ones); elsewhere a layer edge merely touches the wall, unconnected."""
    l1, l2 = a.layer1, a.layer2
    h1, td = l1.height, a.thickness
    Lx, Ly = a.Lx, a.Ly
    walls: list[tuple[list[list[Point2]], int, float]] = [
        (_wall(l1, along, 0.0, (h1, td)), 1, 0.0),  # y = 0: layer 1's zig-zag below h1
        (_wall(l1, along, 0.0, (h1, td)), 1, Ly),
        (_wall(l2, along, h1, (0.0, h1)), 0, 0.0),  # x = 0: layer 2's zig-zag above h1
        (_wall(l2, along, h1, (0.0, h1)), 0, Lx),
    ]

    def key(x: float, y: float, z: float) -> tuple[int, int, int]:
        return (round(x / tol), round(y / tol), round(z / tol))

    def glued(z: float) -> bool:
        return bond == "edges" or abs(z) < tol or abs(z - td) < tol

    layer_nodes: dict[tuple[int, int, int], int] = {}
    alias: dict[int, int] = {}  # a layer node at the place of another layer's node
    for sh in shells:
        for nid, (x, y, z) in zip(sh.ids, sh.xyz, strict=True):
            k = key(float(x), float(y), float(z))
            if k in layer_nodes:
                alias[int(nid)] = layer_nodes[k]
            else:
                layer_nodes[k] = int(nid)
    next_id = max(int(sh.ids.max()) for sh in shells) + 1
    band_nodes: dict[tuple[object, ...], int] = {}
    ids: list[int] = []
    coords: list[Point3] = []
    elements: list[list[int]] = []

    def node(xyz: Point3, tab: int = 0) -> int:
        """The node at ``xyz``: a layer node where the band is glued to it, else a band node
        (per flange tab off the wall line, so that the slits separate the tabs)."""
        nonlocal next_id
        k = key(*xyz)
        if k in layer_nodes and glued(xyz[2]):
            return layer_nodes[k]
        bk: tuple[object, ...] = (*k, tab)
        if bk not in band_nodes:
            band_nodes[bk] = next_id
            ids.append(next_id)
            coords.append(xyz)
            next_id += 1
        return band_nodes[bk]

    on_wall: set[tuple[int, int, int]] = set()
    for elems, normal_axis, c in walls:
        for pts in elems:
            conn = []
            for s_, z in pts:
                xyz = (c, s_, z) if normal_axis == 0 else (s_, c, z)
                on_wall.add(key(*xyz))
                conn.append(node(xyz))
            elements.append(conn)
    if bond == "flanges":
        for tab, elems3 in _flanges(a, along):
            for pts3 in elems3:
                elements.append([node(p, 0 if key(*p) in on_wall else tab) for p in pts3])
    used = {n for e in elements for n in e}
    # merge coincident layer nodes on the band only: inside, where layer 1's ridges cross layer
    # 2's valleys, the layers stay unconnected as without the band
    alias = {d: n for d, n in alias.items() if n in used}
    for i, sh in enumerate(shells):
        off = [int(n) for n in sh.ids if int(n) in alias]
        if off:
            keep = ~np.isin(sh.ids, off)
            merged = [[alias.get(n, n) for n in e] for e in sh.elements]
            shells[i] = _Shell(sh.ids[keep], sh.xyz[keep], merged, sh.t, sh.E, sh.nu)
    if bond == "edges":
        for sh in shells:  # every layer node on the outline must be a band node
            on = (
                (np.abs(sh.xyz[:, 0]) < tol)
                | (np.abs(sh.xyz[:, 0] - Lx) < tol)
                | (np.abs(sh.xyz[:, 1]) < tol)
                | (np.abs(sh.xyz[:, 1] - Ly) < tol)
            )
            missing = [int(n) for n in sh.ids[on] if int(n) not in used]
            if missing:
                raise SolverError(f"{len(missing)} layer edge nodes do not meet the band's mesh")
    m = l1.material
    return _Shell(np.asarray(ids, dtype=np.int64), np.asarray(coords), elements, l1.t, m.E, m.nu)


def principal_axis(eta_deg: float) -> int | None:
    """The load axis (0 = x, 1 = y) of a principal direction eta, None for any other eta."""
    if math.isclose(eta_deg % 180, 0.0, abs_tol=1e-9) or math.isclose(
        eta_deg % 180, 180.0, abs_tol=1e-9
    ):
        return 1  # eta = 0: along layer 1's creases, the y axis
    if math.isclose(eta_deg % 180, 90.0, abs_tol=1e-9):
        return 0
    return None


def specimen(assembly: Assembly, eta_deg: float) -> tuple[float, float]:
    """Width A (across eta) and length B (along eta) of the FE specimen, mm: the rectangle
    Lx x Ly itself at eta = 0 or 90 deg; at any other eta a square of the layout's side whose
    edges run along and across eta (a coupon cut from the same two layers), which needs a square
    layout (Lx = Ly). Circles and polygons are refused (:class:`InputError`): they have no
    straight edges for platens and supports."""
    a = assembly
    if a.layout.name not in ("square", "rectangle"):
        raise InputError(
            "layout",
            a.layout.name,
            "square or rectangle for the FE assembly",
            reason="has no straight loaded edges for the paper's tests (docs/fea.md)",
        )
    axis = principal_axis(eta_deg)
    if axis == 1:
        return a.Lx, a.Ly
    if axis == 0:
        return a.Ly, a.Lx
    if not math.isclose(a.Lx, a.Ly, rel_tol=1e-9):
        raise InputError(
            "eta",
            f"{eta_deg:g} deg",
            "0 or 90 deg for a rectangle (other angles need a square layout, Lx = Ly)",
        )
    return a.Lx, a.Ly


def _oblique_shells(
    assembly: Assembly, eta_deg: float, along: int, fixture_y: tuple[float, ...]
) -> list[_Shell]:
    """Both layers over the specimen of :func:`specimen`, in the test frame (y along eta, x
    across), meshed by :mod:`corrugate.fea.planmesh`. The specimen's centre is the layout's
    centre; beyond the layout's extent the zig-zags continue periodically (the specimen is cut
    from the panel's material)."""
    from .planmesh import Corrugation, plan_mesh

    a = assembly
    A, B = specimen(a, eta_deg)
    e = math.radians(eta_deg)
    ce, se = math.cos(e), math.sin(e)
    # chordwise unit vectors of the layers in the test frame: layer 1 across its creases
    # (crease-frame x), layer 2 across its own (crease-frame y); origin: centre on centre
    chords = ((ce, se), (-se, ce))
    centres = (a.Lx / 2, a.Ly / 2)
    shells: list[_Shell] = []
    first = 1
    for layer, chord, centre, z0 in zip(
        a.layers, chords, centres, (0.0, a.layer1.height), strict=True
    ):
        offset = centre - (chord[0] * A / 2 + chord[1] * B / 2)
        corr = Corrugation(chord, offset, layer.pitch, layer.height, z0)
        pm = plan_mesh(corr, A, B, along, fixture_y)
        ids = np.arange(first, first + len(pm.xyz), dtype=np.int64)
        m = layer.material
        shells.append(
            _Shell(
                ids,
                pm.xyz,
                [[int(ids[i]) for i in r] for r in pm.elements["S8R"]],
                layer.t,
                m.E,
                m.nu,
                [[int(ids[i]) for i in r] for r in pm.elements["S6"]],
            )
        )
        first = int(ids[-1]) + 1
    return shells


def _fmt_set(name: str, nodes: list[int]) -> list[str]:
    out = [f"*NSET,NSET={name}"]
    for k in range(0, len(nodes), 12):
        out.append(",".join(map(str, nodes[k : k + 12])))
    return out


@dataclass(frozen=True, slots=True)
class DeckInfo:
    """Bookkeeping of an assembly deck: node sets whose reactions make the load (one per layer),
    span along the load axis (mm), prescribed displacement (mm), load axis (0 = x, 1 = y)."""

    sets: tuple[str, ...]  # one per part: layer 1, layer 2 (and the band)
    mid_sets: tuple[tuple[str, str], ...] | None  # (MIDk, GAUGEk) per part (4-point only)
    span: float
    delta: float
    axis: int
    nodes: int
    elements: int
    side_sets: tuple[str, ...] = ()  # far side platen of each part ("frame" only)


def assembly_deck(
    assembly: Assembly,
    test: LoadTest,
    mesh: AssemblyMesh | None = None,
    eta_deg: float = 0.0,
    delta: float | None = None,
    *,
    connectors: bool = False,
    match_layers: bool | None = None,
    mesher: Mesher = "auto",
    bond: Bond = "edges",
) -> tuple[str, DeckInfo]:
    """CalculiX deck of one load case of the assembly, and its bookkeeping (sets, span, delta).

    ``connectors`` adds the band (see the module docstring); ``match_layers`` (default: as
    ``connectors``) meshes each layer with along x (n_other + 1) elements along its creases, the
    mesh the band needs, so that a run without the band can be compared on the same layer mesh."""
    if test not in TESTS:
        raise InputError("test", test, " or ".join(TESTS))
    specimen(assembly, eta_deg)  # the layout and eta must fit the FE tests
    if mesher not in ("auto", "structured", "gmsh"):
        raise InputError("mesher", mesher, "auto, structured or gmsh")
    if bond not in ("edges", "flanges"):
        raise InputError("bond", bond, "edges or flanges")
    mesh = mesh or AssemblyMesh()
    a = assembly
    Lx, Ly = a.Lx, a.Ly
    tol = 1e-7 * max(Lx, Ly)
    principal = principal_axis(eta_deg)
    use_gmsh = mesher == "gmsh" or (mesher == "auto" and principal is None)
    if use_gmsh and test == "frame":
        raise InputError(
            "eta", f"{eta_deg:g} deg", "0 or 90 deg for the frame test (the layout's own edges)"
        )
    if use_gmsh:
        if connectors:
            raise InputError(
                "eta",
                f"{eta_deg:g} deg",
                "0 or 90 deg with connectors (the band is modelled on the structured mesh only)",
            )
        B = specimen(a, eta_deg)[1]
        fixture: tuple[float, ...] = {
            "compression": (),
            "bending": (B / 2,),
            "bending4": (B / 4, 3 * B / 8, B / 2, 5 * B / 8, 3 * B / 4),
        }[test]
        shells = _oblique_shells(a, eta_deg, mesh.along, fixture)
        axis, L_load = 1, B
    else:
        if principal is None:
            raise InputError("eta", f"{eta_deg:g} deg", "0 or 90 deg for the structured mesh")
        axis = principal
        mult = 8 if test == "bending4" else 2
        match = connectors if match_layers is None else match_layers
        ns1 = mesh.along * (a.layer2.n + 1) if match else None
        ns2 = mesh.along * (a.layer1.n + 1) if match else None
        shells = [_layer_shell(a.layer1, Ly, mesh.along, 1, 0, 0.0, mult, ns1)]
        shells.append(
            _layer_shell(
                a.layer2,
                Lx,
                mesh.along,
                int(shells[0].ids.max()) + 1,
                1,
                a.layer1.height,
                mult,
                ns2,
            )
        )
        L_load = (Lx, Ly)[axis]
        if connectors:
            shells.append(_band_shell(a, mesh.along, shells, tol, bond))
    other = 1 - axis
    if delta is None:
        delta = 1e-3 * L_load
    lines = [
        "*HEADING",
        f"corrugate OADLC assembly, {test} at eta = {eta_deg:g} deg (S8R shells)",
        "*NODE",
    ]
    for sh in shells:
        for n, (x, y, z) in zip(sh.ids, sh.xyz, strict=True):
            lines.append(f"{n},{x:.10g},{y:.10g},{z:.10g}")
    e_no = 1
    for k, sh in enumerate(shells, start=1):
        for etype, elems in (("S8R", sh.elements), ("S6", sh.triangles)):
            if not elems:
                continue
            lines.append(f"*ELEMENT,TYPE={etype},ELSET=L{k}")
            for e in elems:
                lines.append(f"{e_no}," + ",".join(map(str, e)))
                e_no += 1
    for k, sh in enumerate(shells, start=1):
        lines += [
            f"*MATERIAL,NAME=M{k}",
            "*ELASTIC",
            f"{sh.E:.10g},{sh.nu:.10g}",
            f"*SHELL SECTION,ELSET=L{k},MATERIAL=M{k}",
            f"{sh.t:.10g}",
        ]
    bc: list[str] = []
    load_sets: list[str] = []
    mid_sets: list[str] = []
    side_sets: list[str] = []
    platen: list[int] = []
    ua, ub = axis + 1, other + 1
    for k, sh in enumerate(shells, start=1):
        c_load = sh.xyz[:, axis]
        c_other = sh.xyz[:, other]
        lo = [int(n) for n in sh.ids[np.abs(c_load) < tol]]
        hi = [int(n) for n in sh.ids[np.abs(c_load - L_load) < tol]]
        mid = [int(n) for n in sh.ids[np.abs(c_load - L_load / 2) < tol]]
        if not (lo and hi and (mid or test == "compression")):
            raise SolverError("assembly mesh has no node line at an end or at mid-span")
        lo_other = c_other[np.isin(sh.ids, lo)]
        a_node, b_node = lo[int(np.argmin(lo_other))], lo[int(np.argmax(lo_other))]
        # with the band, the parts form one body: rigid-body constraints on layer 1 only
        rigid = k == 1 or not connectors
        if test in ("compression", "frame", "buckling"):
            lines += _fmt_set(f"LO{k}", lo) + _fmt_set(f"HI{k}", hi)
            rot_b = 4 + other  # rotation about the platen's in-plane axis
            if test == "buckling":  # the moving platen: one reference node, loaded by 1 N
                platen += hi
            else:
                bc.append(f"HI{k},{ua},{ua},{-delta:.12g}")
            bc += [
                f"LO{k},{ua},{ua},0",
                f"LO{k},{rot_b},{rot_b},0",
                f"HI{k},{rot_b},{rot_b},0",
                f"LO{k},6,6,0",
                f"HI{k},6,6,0",
            ]
            if test == "frame":  # the side platens, held in place
                L_side = (Lx, Ly)[other]
                s_lo = [int(n) for n in sh.ids[np.abs(c_other) < tol]]
                s_hi = [int(n) for n in sh.ids[np.abs(c_other - L_side) < tol]]
                lines += _fmt_set(f"SLO{k}", s_lo) + _fmt_set(f"SHI{k}", s_hi)
                rot_a = 4 + axis
                for name in (f"SLO{k}", f"SHI{k}"):
                    bc += [f"{name},{ub},{ub},0", f"{name},{rot_a},{rot_a},0", f"{name},6,6,0"]
                side_sets.append(f"SHI{k}")
                if rigid:
                    bc += [f"{a_node},3,3,0", f"{b_node},3,3,0"]
            elif rigid:
                bc += [f"{a_node},{ub},{ub},0", f"{a_node},3,3,0", f"{b_node},3,3,0"]
            load_sets.append(f"HI{k}")
        elif test == "bending4":
            quarter = np.abs(c_load - L_load / 4) < tol
            quarter |= np.abs(c_load - 3 * L_load / 4) < tol
            loads = [int(n) for n in sh.ids[quarter]]
            eighth = np.abs(c_load - 3 * L_load / 8) < tol
            eighth |= np.abs(c_load - 5 * L_load / 8) < tol
            gauges = [int(n) for n in sh.ids[eighth]]
            if not (loads and gauges):
                raise InputError(
                    "mesh.along",
                    mesh.along,
                    "a value with along x (n + 1) divisible by 8 for four-point bending",
                    reason="gives no node lines at 1/4 and 3/8 of the span",
                )
            mid_other = c_other[np.isin(sh.ids, mid)]
            m_node = mid[int(np.argmin(mid_other))]
            lines += _fmt_set(f"SUP{k}", lo + hi) + _fmt_set(f"LOAD{k}", loads)
            lines += _fmt_set(f"MID{k}", mid) + _fmt_set(f"GAUGE{k}", gauges)
            bc += [
                f"SUP{k},3,3,0",
                f"LOAD{k},3,3,{-delta:.12g}",
                f"MID{k},{ua},{ua},0",
            ]
            if rigid:
                bc.append(f"{m_node},{ub},{ub},0")
            load_sets.append(f"LOAD{k}")
            mid_sets += [f"MID{k}", f"GAUGE{k}"]
        else:
            mid_other = c_other[np.isin(sh.ids, mid)]
            m_node = mid[int(np.argmin(mid_other))]
            lines += _fmt_set(f"SUP{k}", lo + hi) + _fmt_set(f"MID{k}", mid)
            bc += [
                f"SUP{k},3,3,0",
                f"MID{k},3,3,{-delta:.12g}",
                f"MID{k},{ua},{ua},0",
            ]
            if rigid:
                bc.append(f"{m_node},{ub},{ub},0")
            load_sets.append(f"MID{k}")
    if test == "buckling":
        ref = max(int(sh.ids.max()) for sh in shells) + 1
        n_plane = (Lx, Ly)[axis]
        xyz_ref = [0.0, 0.0, 0.0]
        xyz_ref[axis] = n_plane
        lines += ["*NODE", f"{ref},{xyz_ref[0]:.10g},{xyz_ref[1]:.10g},{xyz_ref[2]:.10g}"]
        lines.append("*EQUATION")
        for node in platen:  # u_load(node) = u_load(ref)
            lines += ["2", f"{node},{ua},1.,{ref},{ua},-1."]
        lines += ["*STEP", "*BUCKLE", "3,1.e-6", "*BOUNDARY", *bc, "*CLOAD", f"{ref},{ua},-1."]
    else:
        lines += ["*STEP", "*STATIC", "*BOUNDARY", *bc]
    for name in [] if test == "buckling" else load_sets + side_sets:
        lines += [f"*NODE PRINT,NSET={name}", "RF"]
    for name in mid_sets:
        lines += [f"*NODE PRINT,NSET={name}", "U"]
    lines.append("*END STEP")
    n_nodes = sum(len(sh.ids) for sh in shells)
    mids = tuple(zip(mid_sets[0::2], mid_sets[1::2], strict=True)) if mid_sets else None
    info = DeckInfo(
        tuple(load_sets), mids, L_load, delta, axis, n_nodes, e_no - 1, tuple(side_sets)
    )
    return "\n".join(lines) + "\n", info


def solve_assembly(
    assembly: Assembly,
    test: LoadTest,
    mesh: AssemblyMesh | None = None,
    eta_deg: float = 0.0,
    *,
    connectors: bool = False,
    match_layers: bool | None = None,
    mesher: Mesher = "auto",
    bond: Bond = "edges",
    folder: Path | None = None,
    keep: bool = False,
    timeout: float = 600.0,
) -> AssemblyResult:
    """Run one load case of the assembly in CalculiX (see the module docstring for the model)."""
    mesh = mesh or AssemblyMesh()
    deck, info = assembly_deck(
        assembly,
        test,
        mesh,
        eta_deg,
        connectors=connectors,
        match_layers=match_layers,
        mesher=mesher,
        bond=bond,
    )
    with work_dir(folder, keep) as wd:
        run = run_ccx(deck, wd, job=test, timeout=timeout)
    if test == "buckling":
        if not run.buckling_factors:
            raise SolverError("ccx printed no buckling factor")
        return AssemblyResult(
            test,
            eta_deg,
            mesh,
            info.span,
            math.nan,
            math.nan,
            (math.nan, math.nan),
            K=None,
            D=None,
            EI=None,
            nodes=info.nodes,
            elements=info.elements,
            connectors=connectors,
            buckling_load=run.buckling_factors[0],
        )
    comp = info.axis if test in ("compression", "frame") else 2
    forces: list[float] = []
    for name in info.sets:
        blocks = run.find("forces", str(name))
        if not blocks:
            raise SolverError(f"ccx printed no reaction forces for {name}")
        forces.append(-blocks[-1].total()[comp])
    delta, span = info.delta, info.span
    P = sum(forces)
    side_force: float | None = None
    if test in ("compression", "frame"):
        parts = [f / delta for f in forces]
        K, D, EI = P / delta, None, None
        if test == "frame":
            side_force = 0.0
            for name in info.side_sets:
                blocks = run.find("forces", name)
                if not blocks:
                    raise SolverError(f"ccx printed no reaction forces for {name}")
                side_force -= blocks[-1].total()[1 - info.axis]
    elif test == "bending4":
        assert info.mid_sets is not None
        part_EI: list[float] = []
        # nodes on the mid-span / gauge lines of the band and of the layer bent along its creases
        # (see the docstring); the layer bent across them (layer 2 at eta = 0) is left out
        across = 1 if info.axis == 1 else 0
        all_uz: list[list[float]] = [[], []]
        for i, (f, names) in enumerate(zip(forces, info.mid_sets, strict=True)):
            mean_uz = []
            for j, name in enumerate(names):
                blocks = run.find("displacements", name)
                if not blocks:
                    raise SolverError(f"ccx printed no displacements for {name}")
                uz = [v[2] for v in blocks[-1].rows.values()]
                if i != across:
                    all_uz[j] += uz
                mean_uz.append(sum(uz) / len(uz))
            rel = mean_uz[1] - mean_uz[0]  # mid-span below the gauge lines at 3/8 and 5/8
            part_EI.append(f * span**3 / (1024 * rel))
        if connectors:  # one connected body: one deflection, each part's force share
            rel = sum(all_uz[1]) / len(all_uz[1]) - sum(all_uz[0]) / len(all_uz[0])
            part_EI = [f * span**3 / (1024 * rel) for f in forces]
        EI = sum(part_EI)
        K, D = None, EI / span
        parts = [v / span for v in part_EI]
    else:
        EI = P * span**3 / (48 * delta)
        K, D = None, EI / span
        parts = [f * span**2 / (48 * delta) for f in forces]
    return AssemblyResult(
        test,
        eta_deg,
        mesh,
        span,
        P,
        delta,
        (forces[0], forces[1]),
        K=K,
        D=D,
        EI=EI,
        nodes=info.nodes,
        elements=info.elements,
        layer_values=(parts[0], parts[1]),
        band_value=parts[2] if connectors else None,
        connectors=connectors,
        side_force=side_force,
    )
