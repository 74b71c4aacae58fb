"""FE fixtures of any outline (circles and polygons, holes included): a wheel between a ground
patch and its hub, and a plate bolted or clamped at its corners (docs/fea.md section 2.8).

The paper's tests (:mod:`corrugate.fea.assembly`) load straight edges between platens or on line
supports; a disc or a polygon has none, and the closed forms' K and D of such an outline (springs
summed over facets of different lengths) are no bench test (docs/fea.md 2.1). These fixtures are
the tests the users of such outlines run:

* **Mesh** (:func:`outline_shells`). Both layers on the structured S8R mesh of the layout's box
  (:func:`corrugate.fea.shells.layer_shell`, as the assembly at eta = 0: ``along`` elements across
  each facet, elements about as long along the creases), less every element whose centroid (in
  plan) lies outside the outline and every element whose centroid lies in a hole: a staircase
  outline that converges to the true one as the mesh is refined, as the holes of the assembly
  (:func:`corrugate.fea.assembly._cut_holes`). For a square or rectangle, or a polygon that is
  its box, nothing is cut: the mesh is the assembly's. The layers are not connected to each
  other; each is loaded by the same rigid fixture and the force is the sum of their reactions
  (the parallel-spring reading of the closed forms, as in the assembly).
* **Wheel** (``wheel``, radial stiffness K(eta), N/mm). The hub: a rigid axle pinned through the
  hole that contains the layout's centre, i.e. every node on that hole's (staircase) edge held
  in its three translations, rotations free; without such a hole, every node within
  ``hub_radius`` of the centre (a hub bonded to the disc). The ground: a rigid flat patch under
  the rim on the side opposite to eta, every rim node (a node on the outer edge of the mesh)
  whose direction from the centre is within ``patch_deg`` of -e, with e = (sin eta, cos eta)
  the unit vector along eta in plan (eta from layer 1's creases, the y axis); the patch moves
  by delta along e towards the hub and does not slip (the displacement across e is 0, the
  out-of-plane one free). K = (the patch's reaction along e) / delta: the wheel's radial
  stiffness between the ground and the axle, load along eta.
* **Corners** (``corners``: bolted, ``clamped-corners``: clamped; P / delta, N/mm). Every node
  within ``bolt_radius`` of a vertex of the outline (the nearest node when none is) held in its
  three translations (bolted: a pin through each corner) or in its translations and rotations
  (clamped); a rigid load pad at the outline's centroid, every node within ``load_radius`` (the
  nearest when none is), moves by delta out of plane. k = (the pad's reaction) / delta. A circle
  has no corners and is refused.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, replace
from pathlib import Path
from typing import Literal

import numpy as np
from numpy.typing import NDArray

from corrugate.core.errors import InputError
from corrugate.fea.assembly import AssemblyMesh, _cut_holes, _fmt_set, _inside_ring
from corrugate.fea.ccx import SolverError, run_ccx, work_dir
from corrugate.fea.shells import Shell, layer_shell, quad8_elements, section_lines
from corrugate.geometry.layer import Assembly

__all__ = [
    "OUTLINE_NAMES",
    "OUTLINE_TESTS",
    "OutlineFixture",
    "OutlineResult",
    "OutlineTest",
    "cut_outline",
    "outline_deck",
    "outline_shells",
    "plate_shell",
    "solve_outline",
    "solve_shells",
]

OutlineTest = Literal["wheel", "corners", "clamped-corners"]
OUTLINE_TESTS: tuple[OutlineTest, ...] = ("wheel", "corners", "clamped-corners")
FloatArray = NDArray[np.float64]

#: What each fixture measures, for progress lines and tables.
OUTLINE_NAMES: dict[str, str] = {
    "wheel": "the wheel between a ground patch and its hub",
    "corners": "the plate bolted at its corners, loaded at its centre",
    "clamped-corners": "the plate clamped at its corners, loaded at its centre",
}


@dataclass(frozen=True, slots=True)
class OutlineFixture:
    """The sizes of the fixtures (mm, deg): the ground patch's half-angle ``patch_deg`` seen
    from the centre, the hub's radius ``hub_radius`` (used when no hole contains the centre),
    the bolts' ``bolt_radius`` around each corner and the load pad's ``load_radius``."""

    patch_deg: float = 15.0
    hub_radius: float = 3.0
    bolt_radius: float = 3.0
    load_radius: float = 3.0

    def __post_init__(self) -> None:
        for name in ("patch_deg", "hub_radius", "bolt_radius", "load_radius"):
            v = getattr(self, name)
            if isinstance(v, bool) or not isinstance(v, int | float) or not math.isfinite(v):
                raise InputError(name, v, "a positive number")
            if v <= 0:
                raise InputError(name, v, "a positive number")
        if self.patch_deg > 180:
            raise InputError("patch_deg", self.patch_deg, "0 < patch_deg <= 180 deg")


@dataclass(frozen=True, slots=True)
class OutlineResult:
    """One run of an outline fixture: ``value`` is K (N/mm) of the wheel or P / delta (N/mm) of
    the corner-supported plate; ``force`` (N) at ``displacement`` (mm), each layer's force,
    the mesh's size."""

    test: OutlineTest
    eta_deg: float
    mesh: AssemblyMesh
    value: float
    force: float
    displacement: float
    layer_forces: tuple[float, ...]
    nodes: int
    elements: int


def plate_shell(
    Lx: float, Ly: float, size: float, E: float, nu: float, t: float, first_id: int = 1
) -> Shell:
    """A flat isotropic plate over the box [0, Lx] x [0, Ly] (mm) at z = 0, structured S8R
    elements of about ``size`` mm (an even number along each side): the limit case on which
    the tests check these fixtures against plate and plane-elasticity solutions."""
    nx = 2 * max(1, math.ceil(Lx / size / 2))
    ny = 2 * max(1, math.ceil(Ly / size / 2))
    xs, ys = np.linspace(0.0, Lx, 2 * nx + 1), np.linspace(0.0, Ly, 2 * ny + 1)
    ids = np.zeros((len(xs), len(ys)), dtype=np.int64)
    coords: list[tuple[float, float, float]] = []
    order: list[int] = []
    nid = first_id
    for j, y in enumerate(ys):
        for i, x in enumerate(xs):
            if i % 2 and j % 2:
                continue
            ids[i, j] = nid
            order.append(nid)
            coords.append((float(x), float(y), 0.0))
            nid += 1
    elements = quad8_elements(ids, nx, ny)
    return Shell(np.asarray(order, dtype=np.int64), np.asarray(coords), elements, t, E, nu)


def cut_outline(sh: Shell, outline: FloatArray) -> Shell:
    """The shell less every element whose centroid (in plan) lies outside the closed polygon
    ``outline`` (k x 2, mm), and less the nodes no element uses (a staircase outline)."""
    index = {int(n): i for i, n in enumerate(sh.ids)}

    def keep(elems: list[list[int]], corners: int) -> list[list[int]]:
        if not elems:
            return elems
        xy = np.array([sh.xyz[[index[n] for n in e[:corners]], :2].mean(axis=0) for e in elems])
        inside = _inside_ring(xy, np.asarray(outline, dtype=np.float64))
        return [e for e, ok in zip(elems, inside, strict=True) if ok]

    elements = keep(sh.elements, 4)
    triangles = keep(sh.triangles, 3)
    if not elements and not triangles:
        raise SolverError("the outline leaves no element of the mesh")
    used = np.isin(sh.ids, np.array([n for e in elements + triangles for n in e], dtype=np.int64))
    return replace(sh, ids=sh.ids[used], xyz=sh.xyz[used], elements=elements, triangles=triangles)


def outline_shells(assembly: Assembly, mesh: AssemblyMesh) -> list[Shell]:
    """Both layers of ``assembly`` on the structured mesh of its box, cut to its outline and
    its holes (module docstring)."""
    a = assembly
    shells = [layer_shell(a.layer1, a.Ly, mesh.along, 1, 0, 0.0)]
    shells.append(
        layer_shell(a.layer2, a.Lx, mesh.along, int(shells[0].ids.max()) + 1, 1, a.layer1.height)
    )
    if a.layout.name not in ("square", "rectangle"):
        ring = a.layout.plan_outline(a.Lx, a.Ly)
        shells = [cut_outline(sh, ring) for sh in shells]
    if a.layout.holes:
        shells = [_cut_holes(sh, a) for sh in shells]
    return shells


def _rim(sh: Shell) -> NDArray[np.int64]:
    """The nodes on the edge of the mesh (on an element edge that only one element has)."""
    count: dict[tuple[int, int], list[int]] = {}
    for elems, k in ((sh.elements, 4), (sh.triangles, 3)):
        for e in elems:
            for i in range(k):
                a, b = e[i], e[(i + 1) % k]
                key = (min(a, b), max(a, b))
                count.setdefault(key, []).append(e[k + i])
    nodes: set[int] = set()
    for (a, b), mids in count.items():
        if len(mids) == 1:
            nodes.update((a, b, mids[0]))
    return np.array(sorted(nodes), dtype=np.int64)


def _near(sh: Shell, point: tuple[float, float], radius: float) -> list[int]:
    """Nodes within ``radius`` (mm, in plan) of ``point``; the nearest ones when none is."""
    d = np.hypot(sh.xyz[:, 0] - point[0], sh.xyz[:, 1] - point[1])
    r = max(radius, float(d.min()) * (1 + 1e-9))
    return [int(n) for n in sh.ids[d <= r]]


def _centroid(ring: FloatArray) -> tuple[float, float]:
    x, y = ring[:, 0], ring[:, 1]
    x1, y1 = np.roll(x, -1), np.roll(y, -1)
    cross = x * y1 - x1 * y
    A = cross.sum() / 2
    return float(((x + x1) * cross).sum() / (6 * A)), float(((y + y1) * cross).sum() / (6 * A))


def outline_deck(
    shells: list[Shell],
    test: OutlineTest,
    outline: FloatArray,
    holes: list[FloatArray],
    eta_deg: float = 0.0,
    fixture: OutlineFixture | None = None,
    delta: float | None = None,
) -> tuple[str, tuple[str, ...], tuple[float, float], float]:
    """CalculiX deck of ``test`` on ``shells`` (mm, N) whose plan is the polygon ``outline``
    with the hole polygons ``holes`` (module docstring); returns the deck, the node sets whose
    reactions make the load (one per shell), the load's unit vector (x, y components; (0, 0)
    for an out-of-plane load) and delta (mm)."""
    if test not in OUTLINE_TESTS:
        raise InputError("test", test, " or ".join(OUTLINE_TESTS))
    fx = fixture or OutlineFixture()
    ring = np.asarray(outline, dtype=np.float64)
    span = float(np.max(ring.max(axis=0) - ring.min(axis=0)))
    if delta is None:
        delta = 1e-3 * span
    lines = ["*HEADING", f"corrugate outline fixture {test} at eta = {eta_deg:g} deg", "*NODE"]
    for sh in shells:
        for nid, (x, y, z) in zip(sh.ids, sh.xyz, strict=True):
            lines.append(f"{nid},{x:.10g},{y:.10g},{z:.10g}")
    e_no = 1
    for k, sh in enumerate(shells, start=1):
        for etype, elems in (("S8R", sh.elements), ("S6", sh.triangles)):
            if not elems:
                continue
            lines.append(f"*ELEMENT,TYPE={etype},ELSET=L{k}")
            for el in elems:
                lines.append(f"{e_no}," + ",".join(map(str, el)))
                e_no += 1
    lines += section_lines(list(enumerate(shells, start=1)))
    bc: list[str] = []
    sets: list[str] = []
    direction: tuple[float, float] = (0.0, 0.0)
    if test == "wheel":
        e = math.radians(eta_deg)
        ex, ey = math.sin(e), math.cos(e)
        direction = (ex, ey)
        cx, cy = (ring.min(axis=0) + ring.max(axis=0)) / 2  # the box's centre: the axle
        hub_ring = next(
            (h for h in holes if _inside_ring(np.array([[cx, cy]]), h)[0]),
            None,
        )
        cos_patch = math.cos(math.radians(fx.patch_deg))
        for k, sh in enumerate(shells, start=1):
            rim = _rim(sh)
            index = {int(n): i for i, n in enumerate(sh.ids)}
            xy = sh.xyz[[index[int(n)] for n in rim], :2] - np.array([cx, cy])
            r = np.hypot(xy[:, 0], xy[:, 1])
            if hub_ring is not None:
                reach = float(np.max(np.hypot(hub_ring[:, 0] - cx, hub_ring[:, 1] - cy)))
                size = _element_size(sh)
                hub = [int(n) for n, ri in zip(rim, r, strict=True) if ri <= reach + 1.5 * size]
            else:
                hub = _near(sh, (cx, cy), fx.hub_radius)
            outer = r > 0.5 * float(r.max())
            s = -(xy[:, 0] * ex + xy[:, 1] * ey)  # distance towards the ground
            in_patch = outer & (s >= cos_patch * r - 1e-9 * span)
            patch = [int(n) for n in rim[in_patch]]
            if not hub or not patch:
                raise SolverError("the wheel fixture found no hub or no ground patch node")
            lines += _fmt_set(f"HUB{k}", hub) + _fmt_set(f"PATCH{k}", patch)
            # local axes of the patch: x along e (towards the hub), y across it
            lines += [
                f"*TRANSFORM,NSET=PATCH{k},TYPE=R",
                f"{ex:.15g},{ey:.15g},0,{-ey:.15g},{ex:.15g},0",
            ]
            bc += [f"HUB{k},1,3,0", f"PATCH{k},1,1,{delta:.12g}", f"PATCH{k},2,2,0"]
            sets.append(f"PATCH{k}")
    else:
        centre = _centroid(ring)
        dofs = 6 if test == "clamped-corners" else 3
        for k, sh in enumerate(shells, start=1):
            support: list[int] = []
            for vx, vy in ring:
                support += _near(sh, (float(vx), float(vy)), fx.bolt_radius)
            pad = _near(sh, centre, fx.load_radius)
            lines += _fmt_set(f"BOLT{k}", sorted(set(support))) + _fmt_set(f"PAD{k}", pad)
            bc += [f"BOLT{k},1,{dofs},0", f"PAD{k},3,3,{-delta:.12g}"]
            sets.append(f"PAD{k}")
    lines += ["*STEP", "*STATIC", "*BOUNDARY", *bc]
    for name in sets:
        lines += [f"*NODE PRINT,NSET={name},GLOBAL=YES", "RF"]
    lines.append("*END STEP")
    return "\n".join(lines) + "\n", tuple(sets), direction, delta


def _element_size(sh: Shell) -> float:
    """The longest corner-to-corner edge (plan, mm) of the shell's first element."""
    index = {int(n): i for i, n in enumerate(sh.ids)}
    el = sh.elements[0] if sh.elements else sh.triangles[0]
    k = 4 if sh.elements else 3
    p = sh.xyz[[index[n] for n in el[:k]], :2]
    return float(np.max(np.hypot(*(np.roll(p, -1, axis=0) - p).T)))


def solve_shells(
    shells: list[Shell],
    test: OutlineTest,
    outline: FloatArray,
    holes: list[FloatArray],
    eta_deg: float = 0.0,
    fixture: OutlineFixture | None = None,
    *,
    folder: Path | None = None,
    keep: bool = False,
    timeout: float = 600.0,
) -> tuple[float, float, float, tuple[float, ...]]:
    """Run ``test`` on ``shells`` in CalculiX: (force / delta (N/mm), force (N), delta (mm),
    each shell's force); the force is the reactions' resultant along the load."""
    deck, sets, (ex, ey), delta = outline_deck(shells, test, outline, holes, eta_deg, fixture)
    with work_dir(folder, keep) as wd:
        run = run_ccx(deck, wd, job=test, timeout=timeout)
    forces: list[float] = []
    for name in sets:
        blocks = run.find("forces", name)
        if not blocks:
            raise SolverError(f"ccx printed no reaction forces for {name}")
        fx_, fy_, fz_ = blocks[-1].total()
        forces.append(fx_ * ex + fy_ * ey if test == "wheel" else -fz_)
    P = sum(forces)
    return P / delta, P, delta, tuple(forces)


def solve_outline(
    assembly: Assembly,
    test: OutlineTest,
    mesh: AssemblyMesh | None = None,
    eta_deg: float = 0.0,
    fixture: OutlineFixture | None = None,
    *,
    folder: Path | None = None,
    keep: bool = False,
    timeout: float = 600.0,
) -> OutlineResult:
    """Run the outline fixture ``test`` on both layers of ``assembly`` (module docstring)."""
    from corrugate.geometry.holes import hole_rings

    mesh = mesh or AssemblyMesh()
    a = assembly
    if test not in OUTLINE_TESTS:
        raise InputError("fixture", test, " or ".join(OUTLINE_TESTS))
    if test != "wheel" and a.layout.name == "circle":
        raise InputError(
            "fixture", test, "wheel for a circle", reason="needs corners, which a circle has not"
        )
    shells = outline_shells(a, mesh)
    k, P, delta, forces = solve_shells(
        shells,
        test,
        a.layout.plan_outline(a.Lx, a.Ly),
        hole_rings(a.layout.holes, a.Lx, a.Ly),
        eta_deg,
        fixture,
        folder=folder,
        keep=keep,
        timeout=timeout,
    )
    return OutlineResult(
        test,
        eta_deg,
        mesh,
        k,
        P,
        delta,
        forces,
        sum(len(sh.ids) for sh in shells),
        sum(len(sh.elements) + len(sh.triangles) for sh in shells),
    )
