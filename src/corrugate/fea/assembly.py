"""The whole OADLC assembly as shells in CalculiX: a deck is the mesh, one fixture of
:mod:`corrugate.fea.fixtures` (``platens``, ``three-point``, ``four-point``, ``cantilever``,
``frame``: named as the spec names the tests) and an analysis step of :mod:`corrugate.fea.steps`
(static, or linear buckling for any fixture).

The meshes come from :mod:`corrugate.fea.shells` (the layers) and :mod:`corrugate.fea.connector_band`
(the connector band); this module cuts them to the layout, writes the deck
(:mod:`corrugate.fea.deck` for the mesh cards, the fixture's boundary conditions, the step's
cards) and reads the result with the fixture's own reading.

Model (every choice stated; docs/theory.md section 6):

* **Geometry** (eta = 0 or 90 deg). Both layers of a rectangular layout (``square`` or
  ``rectangle``; the layers may differ), each as the
  zig-zag mid-surface of its n + 1 facets, L_j equal to the other layer's extent. Layer 1's creases
  run along y, its zig-zag spans x in [0, Lx] between z = 0 and z = h1 (it starts and ends on a
  bottom crease line); layer 2's creases run along x, it spans y in [0, Ly] between z = h1 and
  z = h1 + h2, resting on layer 1.
* **Connectors** (``connectors=True``, off by default). The band of :mod:`corrugate.geometry.connectors`
  as four flat walls standing on the rectangle's outline from z = 0 to t_d = h1 + h2
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
* **The fixtures** (each described in its module of :mod:`corrugate.fea.fixtures`):
  ``platens`` (compression along eta between rigid platens, K = P / delta, N/mm), ``three-point``
  (EI = P span^3 / (48 delta), D = EI / span), ``four-point`` (the pure-bending gauge between the
  load lines, EI = P span^3 / (1024 Delta)), ``cantilever`` (EI = P span^3 / (3 delta)) and
  ``frame`` (platens on all four edges; :mod:`corrugate.fea.frame` makes K_frame(eta) of two
  runs). The bending values are apparent stiffnesses, as a bench test measures them. A span
  shorter than the specimen (three-point, four-point, cantilever) puts the supports (the clamp's
  edge) inside it, the ends overhanging (held in the clamp); the structured mesh moves its
  nearest node lines onto those stations (:mod:`corrugate.fea.stations`), the band's with them.
* **Buckling** (any fixture with :class:`~corrugate.fea.steps.LinearBuckling`): the fixture's
  driven nodes tied (``*EQUATION``) to one reference node loaded by 1 N, and a ``*BUCKLE`` step
  (linear eigenvalue buckling about the unloaded state, 3 modes, relative accuracy 1e-6; ccx's
  default is 1e-2): the first buckling factor is the fixture's load (N) at the first mode. For
  the platens, bounds from plate theory: :mod:`corrugate.mechanics.buckling`.

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

from corrugate.core.errors import InputError
from corrugate.fea.ccx import FrdStresses, SolverError, parse_frd_stresses, run_ccx, work_dir
from corrugate.fea.connector_band import Bond, band_shell
from corrugate.fea.cuts import cut_holes, cut_outline
from corrugate.fea.deck import DeckInfo, mesh_lines
from corrugate.fea.fixtures import Fixture, Part, fixtures, get_fixture
from corrugate.fea.shells import (
    Shell,
    check_shift,
    layer_shell,
    oblique_shells,
    principal_axis,
    specimen,
)
from corrugate.fea.stations import on_stations
from corrugate.fea.steps import STATIC, AnyStep, BoundaryItem, LinearBuckling, Nonlinear, Step
from corrugate.geometry.layer import Assembly

__all__ = [
    "AssemblyMesh",
    "AssemblyResult",
    "Bond",
    "DeckInfo",
    "assembly_deck",
    "principal_axis",
    "solve_assembly",
    "specimen",
]

Mesher = Literal["auto", "structured", "gmsh"]
#: The fixture kinds whose decks this module writes (the frame's single runs included).
_KINDS: tuple[Literal["coupon", "frame"], ...] = ("coupon", "frame")


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
    """One FE run of a fixture on the assembly (``test``: the fixture's name,
    :mod:`corrugate.fea.fixtures`; ``step``: ``static`` or ``buckle``): K (N/mm) for the
    platens and the frame, D (N mm) and EI (N mm^2) for bending (the other entries None); for the
    frame, ``side_force`` (N, compressive) on the far side platen, held in place; for a buckling
    step, ``buckling_load`` (N, the fixture's load at the first buckling mode) and every factor
    ccx printed (``buckling_factors``, N, lowest first; force and displacement are then NaN);
    ``force`` (N) at the prescribed ``displacement`` (mm), the share of the force carried by
    each layer, and each layer's part of K or D (``layer_values``); with ``stresses=True`` the
    nodal stresses of the shells (``stresses``, :class:`~corrugate.fea.ccx.FrdStresses`; material
    k is part k: layer 1, layer 2, the band) at that displacement.
    With ``connectors`` the band's own nodes carry ``band_value``; nodes shared by a layer and the
    band count for the layer, so the split between the parts is bookkeeping, the total is not."""

    test: str
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
    step: str = "static"
    buckling_factors: tuple[float, ...] = ()

    def value(self) -> float:
        """K (N/mm) for the platens and the frame, D (N mm) for bending (what ``analyze``
        reports), the first buckling load (N) of a buckling step."""
        if self.buckling_load is not None:
            return self.buckling_load
        v = self.K if self.K is not None else self.D
        assert v is not None
        return v


def with_creases(assembly: Assembly, k: float | None) -> Assembly:
    """``assembly`` with every layer's material at the crease stiffness ``k`` (N mm/(rad mm),
    inf: rigid; None: as it is)."""
    if k is None:
        return assembly
    if not (k > 0.0):
        raise InputError("crease_stiffness", f"{k:g}", "k > 0 N*mm/(rad*mm), or inf (rigid)")
    layers = [
        replace(lay, material=replace(lay.material, crease_stiffness=k)) for lay in assembly.layers
    ]
    return replace(assembly, layer1=layers[0], layer2=layers[1])


def _deck_text(
    a: Assembly,
    parts: list[tuple[int, Shell]],
    fixture: Fixture,
    step: AnyStep,
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
    fixture's span when shorter than the specimen (None: at its ends). The mesh
    (:func:`corrugate.fea.deck.mesh_lines`), then the fixture on each part, then the step."""
    heading = f"corrugate OADLC assembly, {fixture.name} ({step.name}) at eta = {eta_deg:g} deg"
    lines, elements = mesh_lines(parts, heading + " (S8R shells)")
    bc: list[BoundaryItem] = []
    load_sets: list[str] = []
    gauges: list[str] = []
    sides: list[str] = []
    for k, sh in parts:
        part = _part(k, sh, fixture, mesh, L_load, axis, principal, tol, connectors, span, a)
        b = fixture.boundary(part)
        lines += b.sets
        bc += b.bc
        load_sets.append(b.load_set)
        gauges += b.gauges
        sides += b.sides
    if isinstance(step, LinearBuckling | Nonlinear):  # drives tied to a reference node
        ref = max(int(sh.ids.max()) for _, sh in parts) + 1
        where = [0.0, 0.0, 0.0]
        where[axis] = L_load  # on the moving platen
        lines += step.lines(bc, ref, (where[0], where[1], where[2]))
        gauges = []
    else:
        lines += step.lines(bc, delta, load_sets + sides, gauges, stresses=stresses)
    n_nodes = sum(len(sh.ids) for _, sh in parts)
    mids = tuple(zip(gauges[0::2], gauges[1::2], strict=True)) if gauges else None
    L_span = span if span is not None else L_load
    info = DeckInfo(tuple(load_sets), mids, L_span, delta, axis, n_nodes, elements, tuple(sides))
    return "\n".join(lines) + "\n", info


def _part(
    k: int,
    sh: Shell,
    fixture: Fixture,
    mesh: AssemblyMesh,
    L_load: float,
    axis: int,
    principal: int | None,
    tol: float,
    connectors: bool,
    span: float | None,
    a: Assembly,
) -> Part:
    """Part ``k`` as the fixture sees it (:class:`corrugate.fea.fixtures.Part`): its end and
    mid-span node lines and the ends of its ``lo`` line."""
    import numpy as np

    c_load, c_other = sh.xyz[:, axis], sh.xyz[:, 1 - axis]
    lo = [int(n) for n in sh.ids[np.abs(c_load) < tol]]
    hi = [int(n) for n in sh.ids[np.abs(c_load - L_load) < tol]]
    mid = [int(n) for n in sh.ids[np.abs(c_load - L_load / 2) < tol]]
    if not (lo and hi and (mid or not fixture.needs_mid)):
        raise SolverError("assembly mesh has no node line at an end or at mid-span")
    lo_other = c_other[np.isin(sh.ids, lo)]
    a_node, b_node = lo[int(np.argmin(lo_other))], lo[int(np.argmax(lo_other))]
    # with the band, the parts form one body: rigid-body constraints on layer 1 only
    rigid = k == 1 or not connectors
    return Part(
        k, sh, axis, L_load, tol, lo, hi, mid, a_node, b_node, rigid, principal, span,
        (a.Lx, a.Ly), mesh.along,
    )  # fmt: skip


def _decks(
    assembly: Assembly,
    test: str | Fixture,
    mesh: AssemblyMesh | None = None,
    eta_deg: float = 0.0,
    delta: float | None = None,
    *,
    step: AnyStep = STATIC,
    connectors: bool = False,
    match_layers: bool | None = None,
    mesher: Mesher = "auto",
    bond: Bond = "edges",
    stresses: bool = False,
    shift: float = 0.0,
    split: bool = False,
    span: float | None = None,
    crease_stiffness: float | None = None,
) -> list[tuple[str, DeckInfo]]:
    """The decks of :func:`assembly_deck`: one, or with ``split`` one per layer (each layer alone
    with its own fixtures; only for parts that are not connected: no band, not a step that ties
    them)."""
    fixture = get_fixture(test, _KINDS, "test")
    check_shift(shift)
    # the specimen's length along eta (the span); refuses what the FE cannot model
    L_load = specimen(assembly, eta_deg)[1]
    short = span is not None and abs(span - L_load) > 1e-9 * L_load
    if span is not None and not fixture.takes_span:
        raise InputError(
            "span",
            f"{span:g} mm",
            f"none for {fixture.label} (its fixture acts on the specimen's ends); a span for "
            + ", ".join(f.label for f in fixtures("coupon") if f.takes_span),
        )
    if span is not None and (not math.isfinite(span) or not 0 < span <= L_load * (1 + 1e-9)):
        raise InputError(
            "span", f"{span:g} mm", f"0 < span <= {L_load:.6g} mm (the specimen's length)"
        )
    if mesher not in ("auto", "structured", "gmsh"):
        raise InputError("mesher", mesher, "auto, structured or gmsh")
    if bond not in ("edges", "flanges"):
        raise InputError("bond", bond, "edges or flanges")
    mesh = mesh or AssemblyMesh()
    a = with_creases(assembly, crease_stiffness)
    if connectors and not all(math.isinf(lay.material.crease_stiffness) for lay in a.layers):
        raise InputError(
            "crease_stiffness",
            "finite",
            "rigid creases (inf) with the connector band (its walls are meshed on the layers' "
            "evenly spaced edge nodes, which the crease strips move)",
        )
    Lx, Ly = a.Lx, a.Ly
    tol = 1e-7 * max(Lx, Ly)
    principal = principal_axis(eta_deg)
    use_gmsh = mesher == "gmsh" or (mesher == "auto" and principal is None)
    if use_gmsh and fixture.structured_only:
        raise InputError(
            "eta", f"{eta_deg:g} deg", "0 or 90 deg for the frame test (the layout's own edges)"
        )
    if use_gmsh:
        if connectors and principal is not None:
            raise InputError(
                "mesher",
                mesher,
                "auto or structured with connectors (the band is modelled on the structured "
                "mesh only)",
            )
        if connectors:
            raise InputError(
                "eta",
                f"{eta_deg:g} deg",
                "0 or 90 deg with connectors (the band is modelled on the structured mesh only)",
            )
        stations = fixture.stations(L_load, span if short else None)
        shells = oblique_shells(a, eta_deg, mesh.along, stations, shift=shift, aspect=mesh.aspect)
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
        mult = fixture.crease_multiple
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
        if short:  # node lines at the fixture's stations inside the panel
            shells = on_stations(
                a, shells, axis, fixture.stations(L_load, span), tol, connectors, mesh.along
            )
    if a.layout.name == "polygon":  # cut to the outline (docs/fea.md 2.8)
        if use_gmsh or connectors:
            raise InputError(
                "layout",
                "polygon",
                "the structured mesh without connectors (mesher auto, eta 0 or 90 deg)",
            )
        ring = a.layout.plan_outline(Lx, Ly)
        shells = [cut_outline(sh, ring) for sh in shells]
    if a.layout.holes:
        shells = [cut_holes(sh, a) for sh in shells]
    if delta is None:
        delta = 1e-3 * L_load
    numbered = list(enumerate(shells, start=1))
    if split:
        if connectors or step.ties_parts:
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
            fixture,
            step,
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
    test: str | Fixture,
    mesh: AssemblyMesh | None = None,
    eta_deg: float = 0.0,
    delta: float | None = None,
    *,
    step: AnyStep = STATIC,
    connectors: bool = False,
    match_layers: bool | None = None,
    mesher: Mesher = "auto",
    bond: Bond = "edges",
    stresses: bool = False,
    shift: float = 0.0,
    span: float | None = None,
    crease_stiffness: float | None = None,
) -> tuple[str, DeckInfo]:
    """CalculiX deck of the fixture ``test`` (a name of :mod:`corrugate.fea.fixtures` of kind
    ``coupon`` or ``frame``: ``platens``, ``three-point``, ``four-point``, ``cantilever``,
    ``frame``) on the assembly, run as ``step`` (:mod:`corrugate.fea.steps`: static, or
    :class:`~corrugate.fea.steps.LinearBuckling`), and its bookkeeping (sets, span, delta).

    ``connectors`` adds the band (see the module docstring); ``match_layers`` (default: as
    ``connectors``) meshes each layer with along x (n_other + 1) elements along its creases, the
    mesh the band needs, so that a run without the band can be compared on the same layer mesh.
    ``stresses`` asks ccx for the nodal stresses in the ``.frd`` file (``*EL FILE`` with ``S``;
    static steps only); it adds output only, the model and the printed reactions are the
    same.
    ``shift`` moves the zig-zags of a gmsh-meshed coupon by that fraction of each layer's pitch
    (:func:`corrugate.fea.shells.oblique_shells`); the structured mesh takes only 0.
    ``span`` (mm; three-point, four-point and cantilever bending; default the specimen's
    length L): line supports at (L - span) / 2 and (L + span) / 2, symmetric about mid-span, the
    panel overhanging them (four-point: its load and gauge lines at their fractions of the
    span); the cantilever's clamp holds the panel up to L - span, the free end at L. Along a
    crease direction the structured mesh moves its nearest node lines onto these stations
    (:mod:`corrugate.fea.stations`; the band too), off them the gmsh coupon has them as
    element edges (docs/fea.md 2.1).
    ``crease_stiffness`` (N mm/(rad mm); None: each layer's material's, inf for a library
    sheet): a compliant strip along every crease that turns as a rotational spring of that
    stiffness (:func:`corrugate.fea.shells.crease_strip`, docs/offaxis.md "Compliant
    creases"); rigid creases (inf) give the mesh without strips."""
    return _decks(
        assembly,
        test,
        mesh,
        eta_deg,
        delta,
        step=step,
        connectors=connectors,
        match_layers=match_layers,
        mesher=mesher,
        bond=bond,
        stresses=stresses,
        shift=shift,
        span=span,
        crease_stiffness=crease_stiffness,
    )[0]


def solve_assembly(
    assembly: Assembly,
    test: str | Fixture,
    mesh: AssemblyMesh | None = None,
    eta_deg: float = 0.0,
    *,
    step: Step = STATIC,
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
    crease_stiffness: float | None = None,
) -> AssemblyResult:
    """Run the fixture ``test`` on the assembly in CalculiX as ``step`` (see the module docstring
    for the model; :func:`assembly_deck` for the fixtures); ``stresses``: also read the shells'
    nodal stresses (:class:`AssemblyResult` ``stresses``). A
    :class:`~corrugate.fea.steps.LinearBuckling` step gives ``buckling_load`` (N): the first
    buckling factor, the fixture's load at which the part buckles.

    ``split``: solve each layer in a ccx run of its own. Without the band the two layers share
    no node and no constraint (each has its own fixtures; the assembly's force is the sum of
    theirs), so the stiffness matrix is block-diagonal and the two runs solve exactly the same
    equations as one, with about half the peak memory of ccx's direct solver (docs/fea.md 2.9).
    None (the default): split whenever the parts are not connected (no band, not a buckling
    step, whose reference node ties the layers) and no ``stresses`` are asked for; True where
    that is not possible is refused (:class:`InputError`).

    ``span``: bending over supports (a free length) that far apart; ``crease_stiffness``: the
    creases as rotational springs (:func:`assembly_deck`)."""
    mesh = mesh or AssemblyMesh()
    fixture = get_fixture(test, _KINDS, "test")
    if isinstance(step, Nonlinear):
        raise InputError(
            "step", step.name, "static or buckle (a nonlinear ramp: corrugate.fea.nonlinear.ramp)"
        )
    buckling = isinstance(step, LinearBuckling)
    separable = not connectors and not step.ties_parts
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
        fixture,
        mesh,
        eta_deg,
        step=step,
        connectors=connectors,
        match_layers=match_layers,
        mesher=mesher,
        bond=bond,
        stresses=stresses,
        shift=shift,
        split=split,
        span=span,
        crease_stiffness=crease_stiffness,
    )
    job = fixture.name if not buckling else f"{fixture.name}-{step.name}"
    field: FrdStresses | None = None
    with work_dir(folder, keep) as wd:
        runs = [
            run_ccx(deck, wd, job=job if len(decks) == 1 else f"{job}{k}", timeout=timeout)
            for k, (deck, _) in enumerate(decks, start=1)
        ]
        if stresses and not buckling:
            frd = wd / f"{job}.frd"
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
    if buckling:
        if not run.buckling_factors:
            raise SolverError("ccx printed no buckling factor")
        return AssemblyResult(
            fixture.name,
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
            step=step.name,
            buckling_factors=run.buckling_factors,
        )
    comp = info.axis if fixture.measures == "K" else 2
    forces: list[float] = []
    for name in info.sets:
        blocks = run.find("forces", str(name))
        if not blocks:
            raise SolverError(f"ccx printed no reaction forces for {name}")
        forces.append(-blocks[-1].total()[comp])
    assert fixture.read is not None
    r = fixture.read(forces, info, run, connectors)
    parts = r.parts
    return AssemblyResult(
        fixture.name,
        eta_deg,
        mesh,
        info.span,
        sum(forces),
        info.delta,
        (forces[0], forces[1]),
        K=r.K,
        D=r.D,
        EI=r.EI,
        nodes=info.nodes,
        elements=info.elements,
        layer_values=(parts[0], parts[1]),
        band_value=parts[2] if connectors else None,
        connectors=connectors,
        side_force=r.side_force,
        stresses=field,
    )
