"""The whole OADLC assembly as shells in CalculiX: in-plane compression, 3-point, 4-point and
cantilever bending.

The meshes come from :mod:`corrugate.fea.shells` (the layers) and :mod:`corrugate.fea.connector_band`
(the connector band); this module writes the deck of each load case and reads the result.

Model (every choice stated; docs/theory.md section 6):

* **Geometry** (eta = 0 or 90 deg). Both layers of a rectangular layout (``square`` or
  ``rectangle``; the layers may differ), each as the
  zig-zag mid-surface of its n + 1 facets, L_j equal to the other layer's extent. Layer 1's creases
  run along y, its zig-zag spans x in [0, Lx] between z = 0 and z = h1 (it starts and ends on a
  bottom crease line); layer 2's creases run along x, it spans y in [0, Ly] between z = h1 and
  z = h1 + h2, resting on layer 1.
* **Connectors** (``connectors=True``, off by default). The band of :mod:`corrugate.fabrication.
  connectors` as four flat walls standing on the rectangle's outline from z = 0 to t_d = h1 + h2
  (as :func:`corrugate.fabrication.folded.band_walls`), S8R shells of layer 1's material and
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
  (docs/theory.md 3.3), checked without contact or connector models, which would add stiffness the
  closed forms neglect (the paper saw its experiments slightly stiffer for that reason).
* **Compression along eta** (eta = 0: along y, layer 1's creases; eta = 90: along x). Both loaded
  edges of each layer lie on rigid, frictionless, non-rotating platens: the displacement along the
  load axis is 0 on one edge and -delta on the other, the rotations about the two in-plane axes of
  each platen are held along a crease direction (a plane of symmetry, which makes the end facets
  of the chordwise layer behave as the interior, periodic ones); an oblique coupon has no such
  symmetry, so there the edge rotates freely on its platens (holding it made the case study's
  K at 15 deg 2.1 times stiffer at 4 elements per facet: 60.6 against 28.3 N/mm); the other translations are free except for three
  rigid-body constraints per layer. K = (sum of reactions on the moving platen) / delta, N/mm.
* **3-point bending about eta** (span along the load axis, equal to the panel's extent, as in
  ``analyze``: EI = D x span). Line supports at both ends (u_z = 0 on every node of each layer's end
  edge: an end diaphragm, free to rotate and slide), and a rigid line load at mid-span: every node
  of each layer on the mid-span line moves by u_z = -delta, with u along the span held there
  (symmetry) along a crease direction; on an oblique coupon, which has no such symmetry, the line
  slides freely along the span (a frictionless roller; one node holds the rigid-body motion).
  EI = P span^3 / (48 delta) (Euler-Bernoulli 3-point bending), D = EI / span, in N mm^2 and N mm. This is the apparent stiffness a bench test would measure: it includes the
  shear deformation of stubby panels, which the closed forms neglect, but not local crushing
  under the rollers (the fixtures act on whole node lines).
* **Buckling** (``buckling``): the compression fixture with the moving platens of all parts
  tied (``*EQUATION``) to one reference node loaded by 1 N, and a ``*BUCKLE`` step (linear
  eigenvalue buckling about the unloaded state, 3 modes, relative accuracy 1e-6; ccx's default
  is 1e-2): the first buckling factor is the
  platen force (N) of the first mode. Bounds from plate theory: :mod:`corrugate.mechanics.buckling`.
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
  (``along`` x (n + 1) divisible by 4: the chord holds 2 x along x (n + 1) node intervals,
  corner and mid-side nodes).
* **Cantilever bending about eta** (``cantilever``): the root, every node of each layer's end edge
  at the low end of the load axis, is clamped (the three displacements and the three rotations
  zero); the free end, every node of each layer's end edge at the high end, is a rigid line load
  u_z = -delta, free to slide along the span and to rotate (the clamped root holds every
  rigid-body motion, so no node is held there). EI = P span^3 / (3 delta) (Euler-Bernoulli
  cantilever with a tip load), D = EI / span, N mm^2 and N mm, as the 3-point test reports. Like
  the 3-point value this is an apparent stiffness: it includes the panel's shear deformation (for a
  Timoshenko beam a quarter of its share in 3-point bending over the same span) and the
  restraint of the clamp (which holds the root section against warping and lateral contraction).
  Along any eta the root and the free end are the coupon's edges across eta, so no fixture line is
  needed inside the specimen.

**Any other eta** (:mod:`corrugate.fea.shells`): the specimen is a square coupon of the
layout's side cut from the same two layers with its edges along and across eta (the layers'
zig-zags continue periodically past the layout's extent, centred on it), in a test frame with y
along eta. Its plan is meshed by gmsh (:mod:`corrugate.fea.planmesh`) with the creases and the
fixture lines as element edges and the nodes lifted onto the zig-zags: S8R quadrilaterals and a
few S6 triangles. Fixtures as above, on the coupon's edges; no band. ``shift`` (a fraction
0 <= shift < 1 of each layer's pitch, default 0) moves both layers' zig-zags along their chord
directions relative to the coupon, each by that fraction of its own pitch (the plan width of a
facet; a shift of 1 would swap valleys and ridges, the same layer upside down), so that the
coupon's edges cut the creases at other places. ``mesher="gmsh"`` meshes
eta = 0 and 90 this way too (a second discretisation of the same model, which the tests compare
with the structured mesh). Circles and polygons are refused: no straight edges for the fixtures.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, replace
from pathlib import Path
from typing import Literal

import numpy as np
from numpy.typing import NDArray

from corrugate.core.errors import InputError
from corrugate.fea.ccx import FrdStresses, SolverError, parse_frd_stresses, run_ccx, work_dir
from corrugate.fea.connector_band import Bond, band_shell
from corrugate.fea.shells import (
    Shell,
    check_shift,
    layer_shell,
    oblique_shells,
    principal_axis,
    section_lines,
    specimen,
)
from corrugate.geometry.layer import Assembly

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

LoadTest = Literal["compression", "bending", "bending4", "cantilever", "frame", "buckling"]
Mesher = Literal["auto", "structured", "gmsh"]
TESTS: tuple[LoadTest, ...] = (
    "compression",
    "bending",
    "bending4",
    "cantilever",
    "frame",
    "buckling",
)
FloatArray = NDArray[np.float64]


@dataclass(frozen=True, slots=True)
class AssemblyMesh:
    """Shell mesh: ``along`` S8R elements across each facet (even, >= 2); along the creases the
    element length is about ``aspect`` times the facet element width (``aspect`` = 1, the
    default: about square elements; on the structured mesh rounded to an even number of
    elements). ``aspect`` > 1 (at most 8) coarsens the mesh along the creases only, for about
    1 / ``aspect`` as many nodes and less ccx memory (docs/fea.md 2.9). With the connector band
    the layers are meshed to match the band and ``aspect`` is not used."""

    along: int = 4
    aspect: float = 1.0

    def __post_init__(self) -> None:
        v = self.along
        if isinstance(v, bool) or not isinstance(v, int) or v < 2 or v % 2:
            raise InputError("mesh.along", v, "an even integer >= 2")
        from corrugate.core.limits import check_count

        check_count("mesh", v, "mesh")
        r = self.aspect
        ok = isinstance(r, int | float) and not isinstance(r, bool) and math.isfinite(r)
        if not ok or not 1.0 <= r <= 8.0:
            raise InputError("mesh.aspect", r, "a number from 1 to 8")

    def refined(self, factor: float = 2.0) -> AssemblyMesh:
        """The mesh with ``along`` scaled by ``factor`` (kept even), the same ``aspect``."""
        return AssemblyMesh(max(2, 2 * round(self.along * factor / 2)), self.aspect)

    def label(self) -> str:
        return f"{self.along}/facet" + ("" if self.aspect == 1 else f" x{self.aspect:g}")


@dataclass(frozen=True, slots=True)
class AssemblyResult:
    """One FE load case of the assembly: K (N/mm) for compression and the frame test, D (N mm)
    and EI (N mm^2) for bending (the other entries None); for the frame test, ``side_force`` (N,
    compressive) on the far side platen, held in place; for ``buckling``, ``buckling_load`` (N,
    the platen force of the first buckling mode; force and displacement are then NaN);
    ``force`` (N) at the prescribed ``displacement`` (mm), the share of the force carried by
    each layer, and each layer's part of K or D (``layer_values``); with ``stresses=True`` the
    nodal stresses of the shells (``stresses``, :class:`~corrugate.fea.ccx.FrdStresses`; material
    k is part k: layer 1, layer 2, the band) at that displacement.
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
    stresses: FrdStresses | None = None

    def value(self) -> float:
        """K (N/mm) for compression and the frame, D (N mm) for bending (what ``analyze``
        reports), the first buckling load (N) for ``buckling``."""
        if self.test == "buckling":
            v = self.buckling_load
        else:
            v = self.K if self.test in ("compression", "frame") else self.D
        assert v is not None
        return v


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


def _span_hold(mid_set: str, node: int, ua: int, symmetric: bool, rigid: bool) -> list[str]:
    """Boundary lines that hold the displacement along the span (dof ``ua``) at mid-span.

    Along a crease direction (eta = 0 or 90 deg) mid-span is a plane of symmetry of the specimen,
    so every node of the mid-span line is held along the span. An oblique coupon has no such
    plane (the mirror image of a corrugation at +eta runs at -eta): holding the whole line
    would clamp the section against warping under the loading nose, which made the case
    study's 3-point D at 45 deg 6 times stiffer (503 against 80 N mm at 4 elements per facet,
    docs/fea.md 2.5). There the loading line slides freely (a frictionless roller) and one node
    takes the rigid-body motion along the span."""
    if symmetric:
        return [f"{mid_set},{ua},{ua},0"]
    return [f"{node},{ua},{ua},0"] if rigid else []


def _cut_holes(sh: Shell, a: Assembly) -> Shell:
    """The shell less every element whose centroid (in plan) lies inside one of the layout's
    holes, and less the nodes no element uses: a staircase hole that converges to the true one as
    the mesh is refined."""
    from corrugate.geometry.holes import hole_rings

    rings = hole_rings(a.layout.holes, a.Lx, a.Ly)
    index = {int(n): i for i, n in enumerate(sh.ids)}

    def keep(elems: list[list[int]], corners: int) -> list[list[int]]:
        if not elems:
            return elems
        xy = np.array([sh.xyz[[index[n] for n in e[:corners]], :2].mean(axis=0) for e in elems])
        inside = np.zeros(len(elems), dtype=bool)
        for ring in rings:
            inside |= _inside_ring(xy, ring)
        return [e for e, cut in zip(elems, inside, strict=True) if not cut]

    elements = keep(sh.elements, 4)
    triangles = keep(sh.triangles, 3)
    used = np.isin(sh.ids, np.array([n for e in elements + triangles for n in e], dtype=np.int64))
    return replace(sh, ids=sh.ids[used], xyz=sh.xyz[used], elements=elements, triangles=triangles)


def _inside_ring(xy: FloatArray, ring: FloatArray) -> NDArray[np.bool_]:
    x, y = xy[:, 0][:, None], xy[:, 1][:, None]
    x0, y0 = ring[:, 0], ring[:, 1]
    x1, y1 = np.roll(x0, -1), np.roll(y0, -1)
    cond = (y0 > y) != (y1 > y)
    xc = x0 + (y - y0) * (x1 - x0) / np.where(y1 == y0, 1.0, y1 - y0)
    return np.asarray(np.count_nonzero(cond & (x < xc), axis=1) % 2 == 1)


def _deck_text(
    a: Assembly,
    parts: list[tuple[int, Shell]],
    test: LoadTest,
    mesh: AssemblyMesh,
    eta_deg: float,
    delta: float,
    L_load: float,
    axis: int,
    principal: int | None,
    tol: float,
    connectors: bool,
    stresses: bool,
    span: float | None = None,
) -> tuple[str, DeckInfo]:
    """The deck of :func:`assembly_deck` for the parts ``parts`` (part number k, 1-based, and its
    shell): all of them, or one layer alone when the parts are not connected; ``span``: the
    3-point supports' spacing when shorter than the specimen (None: at its ends)."""
    short = span is not None
    other = 1 - axis
    Lx, Ly = a.Lx, a.Ly
    lines = [
        "*HEADING",
        f"corrugate OADLC assembly, {test} at eta = {eta_deg:g} deg (S8R shells)",
        "*NODE",
    ]
    for _, sh in parts:
        for n, (x, y, z) in zip(sh.ids, sh.xyz, strict=True):
            lines.append(f"{n},{x:.10g},{y:.10g},{z:.10g}")
    e_no = 1
    for k, sh in parts:
        for etype, elems in (("S8R", sh.elements), ("S6", sh.triangles)):
            if not elems:
                continue
            lines.append(f"*ELEMENT,TYPE={etype},ELSET=L{k}")
            for e in elems:
                lines.append(f"{e_no}," + ",".join(map(str, e)))
                e_no += 1
    lines += section_lines(parts)
    bc: list[str] = []
    load_sets: list[str] = []
    mid_sets: list[str] = []
    side_sets: list[str] = []
    platen: list[int] = []
    ua, ub = axis + 1, other + 1
    for k, sh in parts:
        c_load = sh.xyz[:, axis]
        c_other = sh.xyz[:, other]
        lo = [int(n) for n in sh.ids[np.abs(c_load) < tol]]
        hi = [int(n) for n in sh.ids[np.abs(c_load - L_load) < tol]]
        mid = [int(n) for n in sh.ids[np.abs(c_load - L_load / 2) < tol]]
        if not (lo and hi and (mid or test in ("compression", "cantilever"))):
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
            bc.append(f"LO{k},{ua},{ua},0")
            if principal is not None:  # a plane of symmetry only along the creases
                bc += [
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
        elif test == "cantilever":
            # root clamped (u and rotations), free end a rigid line load free to slide and rotate
            lines += _fmt_set(f"ROOT{k}", lo) + _fmt_set(f"TIP{k}", hi)
            bc += [f"ROOT{k},1,6,0", f"TIP{k},3,3,{-delta:.12g}"]
            load_sets.append(f"TIP{k}")
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
                    "a value with along x (n + 1) divisible by 4 for four-point bending (the facets across the span: n + 1)",
                    reason="gives no node lines at 1/4 and 3/8 of the span",
                )
            mid_other = c_other[np.isin(sh.ids, mid)]
            m_node = mid[int(np.argmin(mid_other))]
            lines += _fmt_set(f"SUP{k}", lo + hi) + _fmt_set(f"LOAD{k}", loads)
            lines += _fmt_set(f"MID{k}", mid) + _fmt_set(f"GAUGE{k}", gauges)
            bc += [f"SUP{k},3,3,0", f"LOAD{k},3,3,{-delta:.12g}"]
            bc += _span_hold(f"MID{k}", m_node, ua, principal is not None, rigid)
            if rigid:
                bc.append(f"{m_node},{ub},{ub},0")
            load_sets.append(f"LOAD{k}")
            mid_sets += [f"MID{k}", f"GAUGE{k}"]
        else:
            mid_other = c_other[np.isin(sh.ids, mid)]
            m_node = mid[int(np.argmin(mid_other))]
            if short and span is not None:  # supports inside the specimen, the ends overhang
                at_lo = np.abs(c_load - (L_load - span) / 2) < tol
                at_hi = np.abs(c_load - (L_load + span) / 2) < tol
                lo, hi = [int(n) for n in sh.ids[at_lo]], [int(n) for n in sh.ids[at_hi]]
                if not (lo and hi):
                    raise SolverError("assembly mesh has no node line at a support")
            lines += _fmt_set(f"SUP{k}", lo + hi) + _fmt_set(f"MID{k}", mid)
            bc += [f"SUP{k},3,3,0", f"MID{k},3,3,{-delta:.12g}"]
            bc += _span_hold(f"MID{k}", m_node, ua, principal is not None, rigid)
            if rigid:
                bc.append(f"{m_node},{ub},{ub},0")
            load_sets.append(f"MID{k}")
    if test == "buckling":
        ref = max(int(sh.ids.max()) for _, sh in parts) + 1
        xyz_ref = [0.0, 0.0, 0.0]
        xyz_ref[axis] = L_load  # on the moving platen
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
    if stresses and test != "buckling":
        lines += ["*EL FILE", "S"]
    lines.append("*END STEP")
    n_nodes = sum(len(sh.ids) for _, sh in parts)
    mids = tuple(zip(mid_sets[0::2], mid_sets[1::2], strict=True)) if mid_sets else None
    L_span = span if short and span is not None else L_load
    info = DeckInfo(
        tuple(load_sets), mids, L_span, delta, axis, n_nodes, e_no - 1, tuple(side_sets)
    )
    return "\n".join(lines) + "\n", info


def _decks(
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
    stresses: bool = False,
    shift: float = 0.0,
    split: bool = False,
    span: float | None = None,
) -> list[tuple[str, DeckInfo]]:
    """The decks of :func:`assembly_deck`: one, or with ``split`` one per layer (each layer alone
    with its own fixtures; only for parts that are not connected: no band, not ``buckling``)."""
    if test not in TESTS:
        raise InputError("test", test, " or ".join(TESTS))
    check_shift(shift)
    # the specimen's length along eta (the span); refuses what the FE cannot model
    L_load = specimen(assembly, eta_deg)[1]
    short = span is not None and abs(span - L_load) > 1e-9 * L_load
    if span is not None and (
        test != "bending" or not math.isfinite(span) or not 0 < span <= L_load * (1 + 1e-9)
    ):
        raise InputError(
            "span",
            f"{span:g} mm",
            f"0 < span <= {L_load:.6g} mm (the specimen's length) for 3-point bending",
        )
    if mesher not in ("auto", "structured", "gmsh"):
        raise InputError("mesher", mesher, "auto, structured or gmsh")
    if bond not in ("edges", "flanges"):
        raise InputError("bond", bond, "edges or flanges")
    mesh = mesh or AssemblyMesh()
    a = assembly
    Lx, Ly = a.Lx, a.Ly
    tol = 1e-7 * max(Lx, Ly)
    principal = principal_axis(eta_deg)
    use_gmsh = mesher == "gmsh" or (mesher == "auto" and (principal is None or short))
    if short and not use_gmsh:
        raise InputError("mesher", mesher, "auto or gmsh for a span shorter than the specimen")
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
        fixture: tuple[float, ...] = {
            "compression": (),
            "bending": (
                ((L_load - span) / 2, L_load / 2, (L_load + span) / 2)
                if short and span is not None
                else (L_load / 2,)
            ),
            "bending4": tuple(L_load * f for f in (1 / 4, 3 / 8, 1 / 2, 5 / 8, 3 / 4)),
            "cantilever": (),
        }[test]
        shells = oblique_shells(a, eta_deg, mesh.along, fixture, shift=shift, aspect=mesh.aspect)
        axis = 1
    else:
        if principal is None:
            raise InputError("eta", f"{eta_deg:g} deg", "0 or 90 deg for the structured mesh")
        if shift != 0:
            raise InputError(
                "shift",
                shift,
                "0 on the structured mesh (the layout's own edges; mesher='gmsh' takes a shift)",
            )
        axis = principal
        mult = 8 if test == "bending4" else 2
        match = connectors if match_layers is None else match_layers
        ns1 = mesh.along * (a.layer2.n + 1) if match else None
        ns2 = mesh.along * (a.layer1.n + 1) if match else None
        shells = [layer_shell(a.layer1, Ly, mesh.along, 1, 0, 0.0, mult, ns1, mesh.aspect)]
        shells.append(
            layer_shell(
                a.layer2,
                Lx,
                mesh.along,
                int(shells[0].ids.max()) + 1,
                1,
                a.layer1.height,
                mult,
                ns2,
                mesh.aspect,
            )
        )
        if connectors:
            shells.append(band_shell(a, mesh.along, shells, tol, bond))
    if a.layout.name == "polygon":  # cut to the outline (docs/fea.md 2.8)
        from corrugate.fea.outline import cut_outline

        if use_gmsh or connectors:
            raise InputError(
                "layout",
                "polygon",
                "the structured mesh without connectors (mesher auto, eta 0 or 90 deg)",
            )
        ring = a.layout.plan_outline(Lx, Ly)
        shells = [cut_outline(sh, ring) for sh in shells]
    if a.layout.holes:
        shells = [_cut_holes(sh, a) for sh in shells]
    if delta is None:
        delta = 1e-3 * L_load
    numbered = list(enumerate(shells, start=1))
    if split:
        if connectors or test == "buckling":
            raise InputError(
                "split",
                split,
                "False with the connector band or for buckling (the parts are then coupled)",
            )
        groups = [[item] for item in numbered]
    else:
        groups = [numbered]
    return [
        _deck_text(
            a,
            g,
            test,
            mesh,
            eta_deg,
            delta,
            L_load,
            axis,
            principal,
            tol,
            connectors,
            stresses,
            span if short else None,
        )
        for g in groups
    ]


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
    stresses: bool = False,
    shift: float = 0.0,
    span: float | None = None,
) -> tuple[str, DeckInfo]:
    """CalculiX deck of one load case of the assembly, and its bookkeeping (sets, span, delta).

    ``connectors`` adds the band (see the module docstring); ``match_layers`` (default: as
    ``connectors``) meshes each layer with along x (n_other + 1) elements along its creases, the
    mesh the band needs, so that a run without the band can be compared on the same layer mesh.
    ``stresses`` asks ccx for the nodal stresses in the ``.frd`` file (``*EL FILE`` with ``S``;
    not for ``buckling``); it adds output only, the model and the printed reactions are the
    same.
    ``shift`` moves the zig-zags of a gmsh-meshed coupon by that fraction of each layer's pitch
    (:func:`corrugate.fea.shells.oblique_shells`); the structured mesh takes only 0.
    ``span`` (mm, 3-point bending only; default the specimen's length): line supports at
    (L - span) / 2 and (L + span) / 2 of the specimen's length L, symmetric about the load line,
    the panel overhanging them; a span shorter than L is meshed by gmsh with the support lines
    as element edges."""
    return _decks(
        assembly,
        test,
        mesh,
        eta_deg,
        delta,
        connectors=connectors,
        match_layers=match_layers,
        mesher=mesher,
        bond=bond,
        stresses=stresses,
        shift=shift,
        span=span,
    )[0]


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
    shift: float = 0.0,
    folder: Path | None = None,
    keep: bool = False,
    timeout: float = 600.0,
    stresses: bool = False,
    split: bool | None = None,
    span: float | None = None,
) -> AssemblyResult:
    """Run one load case of the assembly in CalculiX (see the module docstring for the model);
    ``stresses``: also read the shells' nodal stresses (:class:`AssemblyResult` ``stresses``).

    ``split``: solve each layer in a ccx run of its own. Without the band the two layers share
    no node and no constraint (each has its own fixtures; the assembly's force is the sum of
    theirs), so the stiffness matrix is block-diagonal and the two runs solve exactly the same
    equations as one, with about half the peak memory of ccx's direct solver (docs/fea.md 2.9).
    None (the default): split whenever the parts are not connected (no band, not ``buckling``,
    whose platen ties the layers) and no ``stresses`` are asked for; True where that is not
    possible is refused (:class:`InputError`).

    ``span``: 3-point bending over supports that far apart (:func:`assembly_deck`)."""
    mesh = mesh or AssemblyMesh()
    separable = not connectors and test != "buckling"
    if split is None:
        split = separable and not stresses
    elif split and (not separable or stresses):
        raise InputError(
            "split",
            split,
            "False with the connector band, for buckling or with stresses (one run)",
        )
    decks = _decks(
        assembly,
        test,
        mesh,
        eta_deg,
        connectors=connectors,
        match_layers=match_layers,
        mesher=mesher,
        bond=bond,
        stresses=stresses,
        shift=shift,
        split=split,
        span=span,
    )
    field: FrdStresses | None = None
    with work_dir(folder, keep) as wd:
        runs = [
            run_ccx(deck, wd, job=test if len(decks) == 1 else f"{test}{k}", timeout=timeout)
            for k, (deck, _) in enumerate(decks, start=1)
        ]
        if stresses and test != "buckling":
            frd = wd / f"{test}.frd"
            if not frd.exists():
                raise SolverError(f"ccx wrote no {frd.name} in {wd}")
            field = parse_frd_stresses(frd.read_text())
    infos = [info for _, info in decks]
    mids = [m for i in infos for m in (i.mid_sets or ())]
    info = replace(
        infos[0],
        sets=tuple(name for i in infos for name in i.sets),
        mid_sets=tuple(mids) if mids else None,
        nodes=sum(i.nodes for i in infos),
        elements=sum(i.elements for i in infos),
        side_sets=tuple(name for i in infos for name in i.side_sets),
    )
    run = replace(runs[0], blocks=tuple(b for r in runs for b in r.blocks))
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
    elif test == "cantilever":
        EI = P * span**3 / (3 * delta)
        K, D = None, EI / span
        parts = [f * span**2 / (3 * delta) for f in forces]
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
        stresses=field,
    )
