"""FE fixtures of any outline (circles and polygons, holes included): a wheel between a ground
patch and its hub, and a plate bolted or clamped at its corners (docs/fea.md section 2.8).

The paper's tests (:mod:`corrugate.fea.assembly`) load straight edges between platens or on line
supports; a disc or a polygon has none, and the closed forms' K and D of such an outline (springs
summed over facets of different lengths) are no bench test (docs/fea.md 2.1). These fixtures are
the tests the users of such outlines run:

* **Mesh** (:func:`outline_shells`). A circle with no hole or one circular hole at its centre:
  both layers meshed to the rim and the hole, a node at each end of the wheel's ground patch
  (:mod:`corrugate.fea.discmesh`: mapped, nested meshes whose series settle). Any other outline:
  both layers on the structured S8R mesh of the layout's box
  (:func:`corrugate.fea.shells.layer_shell`, as the assembly at eta = 0: ``along`` elements across
  each facet, elements about as long along the creases), less every element whose centroid (in
  plan) lies outside the outline and every element whose centroid lies in a hole: a staircase
  outline that converges to the true one as the mesh is refined, as the holes of the assembly
  (:mod:`corrugate.fea.cuts`). For a square or rectangle, or a polygon that is
  its box, nothing is cut: the mesh is the assembly's. The layers are not connected to each
  other; each is loaded by the same rigid fixture and the force is the sum of their reactions
  (the parallel-spring reading of the closed forms, as in the assembly).
The fixtures are entries of :mod:`corrugate.fea.fixtures` (kind ``outline``), each in its module
there; a deck is the mesh, the fixture and a step (:mod:`corrugate.fea.steps`):

* **Wheel** (``wheel``, radial stiffness K(eta), N/mm; :mod:`corrugate.fea.fixtures.wheel`). The hub: a rigid axle pinned through the
  hole that contains the layout's centre, i.e. every node on that hole's edge (its arc on a disc
  mesh, a staircase on the box's mesh) held
  in its three translations, rotations free; without such a hole, every node within
  ``hub_radius`` of the centre (a hub bonded to the disc). The ground: a rigid flat patch under
  the rim on the side opposite to eta, every rim node (a node on the outer edge of the mesh)
  whose direction from the centre is within ``patch_deg`` of -e, with e = (sin eta, cos eta)
  the unit vector along eta in plan (eta from layer 1's creases, the y axis); the patch moves
  by delta along e towards the hub and does not slip (the displacement across e is 0, the
  out-of-plane one free). K = (the patch's reaction along e) / delta: the wheel's radial
  stiffness between the ground and the axle, load along eta.
* **Corners** (``corners``: bolted, ``clamped-corners``: clamped; P / delta, N/mm;
  :mod:`corrugate.fea.fixtures.corners`). Every node
  within ``bolt_radius`` of a vertex of the outline (the nearest node when none is) held in its
  three translations (bolted: a pin through each corner) or in its translations and rotations
  (clamped); a rigid load pad at the outline's centroid, every node within ``load_radius`` (the
  nearest when none is), moves by delta out of plane. k = (the pad's reaction) / delta. A circle
  has no corners and is refused.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from pathlib import Path

import numpy as np
from numpy.typing import NDArray

from corrugate.core.errors import InputError
from corrugate.fea.assembly import AssemblyMesh
from corrugate.fea.ccx import SolverError, run_ccx, work_dir
from corrugate.fea.cuts import cut_holes, cut_outline
from corrugate.fea.deck import mesh_lines
from corrugate.fea.discmesh import Disc
from corrugate.fea.fixtures import Fixture, OutlinePart, fixtures, get_fixture
from corrugate.fea.shells import Shell, layer_shell, quad8_elements
from corrugate.fea.steps import STATIC, BoundaryItem, LinearBuckling, Step
from corrugate.geometry.layer import Assembly, require_zigzag

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

#: The name of an outline fixture (:func:`corrugate.fea.fixtures.fixtures` of kind ``outline``).
OutlineTest = str
#: The outline fixtures registered, and what each measures (for progress lines and tables).
OUTLINE_TESTS: tuple[str, ...] = tuple(f.name for f in fixtures("outline"))
OUTLINE_NAMES: dict[str, str] = {f.name: f.label for f in fixtures("outline")}
FloatArray = NDArray[np.float64]


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
    the mesh's size. A buckling step (``step`` ``buckle``) gives the fixture's load (N) at each
    buckling mode in ``buckling_factors``, lowest first, and ``value`` the first (force,
    displacement and the layers' forces are then NaN)."""

    test: OutlineTest
    eta_deg: float
    mesh: AssemblyMesh
    value: float
    force: float
    displacement: float
    layer_forces: tuple[float, ...]
    nodes: int
    elements: int
    step: str = "static"
    buckling_factors: tuple[float, ...] = ()


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


def disc_hole(assembly: Assembly) -> Disc | None:
    """The disc of a circle layout with no hole or one circular hole at its centre (plan mm),
    the outline :func:`corrugate.fea.discmesh.disc_mesh` meshes to; None for any other."""
    a = assembly
    if a.layout.name != "circle":
        return None
    holes = a.layout.holes
    if len(holes) > 1 or any(h.shape != "circle" or h.center != (0.0, 0.0) for h in holes):
        return None
    r = holes[0].diameter / 2 if holes else 0.0
    R = a.Lx / 2
    return Disc((a.Lx / 2, a.Ly / 2), R, r) if r < R else None


def _disc_shells(
    assembly: Assembly, disc: Disc, along: int, rim_angles: tuple[float, ...]
) -> list[Shell]:
    """Both layers of a disc ``assembly`` meshed to its rim and hole
    (:func:`corrugate.fea.discmesh.disc_mesh`), layer 1's chord along x, layer 2's along y."""
    from corrugate.fea.discmesh import disc_mesh
    from corrugate.fea.planmesh import Corrugation
    from corrugate.fea.shells import plan_shell, strip_half_width

    a = assembly
    shells: list[Shell] = []
    first = 1
    for layer, chord, z0 in zip(
        a.layers, ((1.0, 0.0), (0.0, 1.0)), (0.0, a.layer1.height), strict=True
    ):
        require_zigzag(layer, "FE mesh")
        corr = Corrugation(chord, 0.0, layer.pitch, layer.height, z0)
        pm = disc_mesh(corr, disc, along, rim_angles, strip=strip_half_width(layer))
        shells.append(plan_shell(layer, pm, first, chord))
        first = int(shells[-1].ids[-1]) + 1
    return shells


def outline_shells(
    assembly: Assembly,
    mesh: AssemblyMesh,
    rim_angles: tuple[float, ...] = (),
    *,
    staircase: bool = False,
) -> list[Shell]:
    """Both layers of ``assembly``: a disc with no hole or a central circular one meshed to its
    rim and hole, with a node at each plan angle of ``rim_angles`` (deg) on the rim
    (:func:`corrugate.fea.discmesh.disc_mesh`); any other outline, or any with ``staircase``
    (the mesh of the wheel sweep's first discs, docs/load_cases.md 9), on the structured mesh of
    its box, cut to its outline and its holes (module docstring)."""
    a = assembly
    disc = None if staircase else disc_hole(a)
    if disc is not None:
        return _disc_shells(a, disc, mesh.along, rim_angles)
    shells = [layer_shell(a.layer1, a.Ly, mesh.along, 1, 0, 0.0)]
    shells.append(
        layer_shell(a.layer2, a.Lx, mesh.along, int(shells[0].ids.max()) + 1, 1, a.layer1.height)
    )
    if a.layout.name not in ("square", "rectangle"):
        ring = a.layout.plan_outline(a.Lx, a.Ly)
        shells = [cut_outline(sh, ring) for sh in shells]
    if a.layout.holes:
        shells = [cut_holes(sh, a) for sh in shells]
    return shells


def outline_deck(
    shells: list[Shell],
    test: str | Fixture,
    outline: FloatArray,
    holes: list[FloatArray],
    eta_deg: float = 0.0,
    fixture: OutlineFixture | None = None,
    delta: float | None = None,
    *,
    step: Step = STATIC,
) -> tuple[str, tuple[str, ...], tuple[float, float], float]:
    """CalculiX deck of the outline fixture ``test`` on ``shells`` (mm, N) whose plan is the
    polygon ``outline`` with the hole polygons ``holes`` (module docstring), run as ``step``;
    returns the deck, the node sets whose reactions make the load (one per shell), the load's
    unit vector (x, y components; (0, 0) for an out-of-plane load) and delta (mm)."""
    fx_test = get_fixture(test, ("outline",), "test")
    fx = fixture or OutlineFixture()
    ring = np.asarray(outline, dtype=np.float64)
    span = float(np.max(ring.max(axis=0) - ring.min(axis=0)))
    if delta is None:
        delta = 1e-3 * span
    heading = f"corrugate outline fixture {fx_test.name} at eta = {eta_deg:g} deg"
    if isinstance(step, LinearBuckling):
        heading += f" ({step.name})"
    lines, _ = mesh_lines(list(enumerate(shells, start=1)), heading)
    bc: list[BoundaryItem] = []
    sets: list[str] = []
    for k, sh in enumerate(shells, start=1):
        b = fx_test.boundary(OutlinePart(k, sh, ring, holes, eta_deg, fx, span))
        lines += b.sets
        bc += b.bc
        sets.append(b.load_set)
    direction = _direction(fx_test, eta_deg)
    if isinstance(step, LinearBuckling):
        ref = max(int(sh.ids.max()) for sh in shells) + 1
        cx, cy = (ring.min(axis=0) + ring.max(axis=0)) / 2
        lines += step.lines(bc, ref, (float(cx), float(cy), 0.0))
    else:
        lines += step.lines(bc, delta, sets, [], global_axes=True)
    return "\n".join(lines) + "\n", tuple(sets), direction, delta


def _direction(fixture: Fixture, eta_deg: float) -> tuple[float, float]:
    """The in-plane unit vector of the load (x, y) of a fixture that measures K along eta, (0, 0)
    for one loaded out of plane."""
    if fixture.measures != "K":
        return (0.0, 0.0)
    e = math.radians(eta_deg)
    return (math.sin(e), math.cos(e))


def solve_shells(
    shells: list[Shell],
    test: str | Fixture,
    outline: FloatArray,
    holes: list[FloatArray],
    eta_deg: float = 0.0,
    fixture: OutlineFixture | None = None,
    *,
    step: Step = STATIC,
    folder: Path | None = None,
    keep: bool = False,
    timeout: float = 600.0,
) -> tuple[float, float, float, tuple[float, ...]]:
    """Run ``test`` on ``shells`` in CalculiX: (force / delta (N/mm), force (N), delta (mm),
    each shell's force); the force is the reactions' resultant along the load. As a
    :class:`~corrugate.fea.steps.LinearBuckling` step: (the first buckling load (N), NaN, NaN,
    every buckling load (N), lowest first)."""
    fx_test = get_fixture(test, ("outline",), "test")
    deck, sets, (ex, ey), delta = outline_deck(
        shells, fx_test, outline, holes, eta_deg, fixture, step=step
    )
    buckling = isinstance(step, LinearBuckling)
    job = fx_test.name if not buckling else f"{fx_test.name}-{step.name}"
    with work_dir(folder, keep) as wd:
        run = run_ccx(deck, wd, job=job, timeout=timeout)
    if buckling:
        if not run.buckling_factors:
            raise SolverError("ccx printed no buckling factor")
        return run.buckling_factors[0], math.nan, math.nan, run.buckling_factors
    forces: list[float] = []
    for name in sets:
        blocks = run.find("forces", name)
        if not blocks:
            raise SolverError(f"ccx printed no reaction forces for {name}")
        fx_, fy_, fz_ = blocks[-1].total()
        forces.append(fx_ * ex + fy_ * ey if fx_test.measures == "K" else -fz_)
    P = sum(forces)
    return P / delta, P, delta, tuple(forces)


def solve_outline(
    assembly: Assembly,
    test: str,
    mesh: AssemblyMesh | None = None,
    eta_deg: float = 0.0,
    fixture: OutlineFixture | None = None,
    *,
    step: Step = STATIC,
    folder: Path | None = None,
    keep: bool = False,
    timeout: float = 600.0,
) -> OutlineResult:
    """Run the outline fixture ``test`` on both layers of ``assembly`` (module docstring) as
    ``step`` (static, or linear buckling: :class:`OutlineResult`)."""
    from corrugate.fea.fixtures.wheel import patch_ends
    from corrugate.geometry.holes import hole_rings

    mesh = mesh or AssemblyMesh()
    a = assembly
    if test not in OUTLINE_TESTS:
        raise InputError("fixture", test, " or ".join(OUTLINE_TESTS))
    if get_fixture(test).measures != "K" and a.layout.name == "circle":
        raise InputError(
            "fixture", test, "wheel for a circle", reason="needs corners, which a circle has not"
        )
    fx = fixture or OutlineFixture()
    ends = patch_ends(eta_deg, fx.patch_deg) if test == "wheel" else ()
    shells = outline_shells(a, mesh, ends)
    k, P, delta, forces = solve_shells(
        shells,
        test,
        a.layout.plan_outline(a.Lx, a.Ly),
        hole_rings(a.layout.holes, a.Lx, a.Ly),
        eta_deg,
        fixture,
        step=step,
        folder=folder,
        keep=keep,
        timeout=timeout,
    )
    buckling = isinstance(step, LinearBuckling)
    return OutlineResult(
        test,
        eta_deg,
        mesh,
        k,
        P,
        delta,
        (math.nan, math.nan) if buckling else forces,
        sum(len(sh.ids) for sh in shells),
        sum(len(sh.elements) + len(sh.triangles) for sh in shells),
        step.name,
        forces if buckling else (),
    )
