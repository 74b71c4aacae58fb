"""Shell meshes of the two layers for the assembly FE (:mod:`corrugate.fea.assembly`).

* :func:`layer_shell`: the structured S8R mesh of one layer over the layout itself (eta = 0 or
  90 deg), ``along`` elements across each facet;
* :func:`oblique_shells`: both layers over a square coupon cut along any eta, meshed by gmsh
  (:mod:`corrugate.fea.planmesh`) in a test frame with y along eta;
* :func:`specimen` and :func:`principal_axis`: which specimen a direction eta gets.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field, replace
from typing import TYPE_CHECKING

import numpy as np
from numpy.typing import NDArray

from corrugate.core.errors import InputError
from corrugate.geometry.layer import Assembly, Layer, crease_layer, require_zigzag

if TYPE_CHECKING:
    from corrugate.fea.planmesh import PlanMesh

__all__ = [
    "STRIP_FRACTION",
    "Shell",
    "Strip",
    "check_shift",
    "crease_strip",
    "layer_shell",
    "oblique_shells",
    "plan_shell",
    "principal_axis",
    "quad8_elements",
    "section_lines",
    "specimen",
    "strip_half_width",
    "strip_stations",
]

FloatArray = NDArray[np.float64]


@dataclass(frozen=True, slots=True)
class Strip:
    """The section of the compliant strips along a layer's creases (:func:`crease_strip`): the
    modulus ``E_across`` (MPa) across the crease, in the sheet's plane and through its
    thickness, and the crease direction ``along`` (a unit vector in the plan's x, y), along
    which the sheet keeps its E; its shear moduli along the crease keep the sheet's G."""

    E_across: float
    along: tuple[float, float]


@dataclass(frozen=True, slots=True)
class Shell:
    """Nodes (global ids, coordinates) and connectivity of one part: S8R ``elements`` and, from
    the gmsh mesher, S6 triangles ``triangles``; with compliant creases, the elements of the
    narrow strips along them (``strip_elements``, ``strip_triangles``) and their section
    ``strip`` (:class:`Strip`)."""

    ids: NDArray[np.int64]
    xyz: FloatArray
    elements: list[list[int]]
    t: float
    E: float
    nu: float
    triangles: list[list[int]] = field(default_factory=list)
    strip_elements: list[list[int]] = field(default_factory=list)
    strip_triangles: list[list[int]] = field(default_factory=list)
    strip: Strip | None = None


#: The width of the compliant strip along each crease, as a fraction of the facet's developed
#: width W: half of it on each facet (:func:`crease_strip`).
STRIP_FRACTION = 1.0 / 10.0


def crease_strip(
    t: float,
    E: float,
    nu: float,
    k: float,
    width: float,
    along: tuple[float, float],
    W: float = 0.0,
) -> Strip:
    """The section of a strip ``width`` mm wide along a crease (direction ``along``) that makes
    it a rotational spring of stiffness ``k`` (N mm/(rad mm)) on a sheet of ``t`` mm, ``E`` MPa,
    ``nu``: under a moment M per unit length the strip turns by M width / D_s, which is the
    crease's M / k plus the M width / D of the sheet it replaces, so
    D_s = width / (1 / k + width / D), D = E t^3 / (12 (1 - nu^2)) (docs/offaxis.md,
    "Compliant creases"). The strip is orthotropic: E_a across the crease (in the facet's plane
    and through its thickness, isotropic in that plane), the sheet's E along it, so that only
    its bending across the crease softens (its in-plane shear and its stretching along the crease
    are the sheet's; its stretching across is E_a t, whose compliance is below 1e-3 of the
    crease's). Cylindrical bending gives D_s = E_a t^3 / (12 (1 - nu^2 E_a / E)), so
    E_a = d / (1 + nu^2 d / E), d = 12 D_s / t^3 (E_a = E for k = inf). The thickness stays t:
    CalculiX expands a shell node shared by two thicknesses to their mean, so a thinner strip
    would not be one. The moment is taken uniform over the strip: under the chordwise pull, where
    it falls linearly to zero at the facet's middle, the strip's rotation is
    1 - (width / W) + (1/3) (width / W)^2 of the crease's, 0.98 at :data:`STRIP_FRACTION`."""
    D = E * t**3 / (12.0 * (1.0 - nu * nu))
    f = 1.0 - width / W + (width / W) ** 2 / 3.0 if W else 1.0
    D_s = width * f / (1.0 / k + width * f / D)
    d = 12.0 * D_s / t**3
    return Strip(d / (1.0 + nu * nu * d / E), along)


def quad8_elements(ids: NDArray[np.int64], n1: int, n2: int) -> list[list[int]]:
    """The S8R elements of a structured grid of ``n1`` x ``n2`` elements whose node ids are
    ``ids[i, j]`` on the (2 n1 + 1) x (2 n2 + 1) grid of corner and mid-side points (no centre
    nodes): each element's corners counter-clockwise, then its mid-side nodes, CalculiX's order."""
    elements: list[list[int]] = []
    for ej in range(n2):
        for ei in range(n1):
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
    return elements


def section_lines(parts: list[tuple[int, Shell]]) -> list[str]:
    """The CalculiX material and shell-section cards of each part k (elements in set ``Lk``):
    its E (MPa), nu and thickness (mm); and of its crease strips (set ``Ck``) when it has them."""
    lines: list[str] = []
    for k, sh in parts:
        lines += [
            f"*MATERIAL,NAME=M{k}",
            "*ELASTIC",
            f"{sh.E:.10g},{sh.nu:.10g}",
            f"*SHELL SECTION,ELSET=L{k},MATERIAL=M{k}",
            f"{sh.t:.10g}",
        ]
        if sh.strip is not None and (sh.strip_elements or sh.strip_triangles):
            # axis 2 along the crease (the sheet's E, nu, G), axes 1 and 3 across it and
            # through the thickness (E_a, isotropic in that plane): Strip, crease_strip
            Ea, E, nu = sh.strip.E_across, sh.E, sh.nu
            ax, ay = sh.strip.along
            G, Ga = E / (2 * (1 + nu)), Ea / 2
            lines += [
                f"*ORIENTATION,NAME=OC{k},SYSTEM=RECTANGULAR",
                f"{ay:.10g},{-ax:.10g},0,{ax:.10g},{ay:.10g},0",
                f"*MATERIAL,NAME=MC{k}",
                "*ELASTIC,TYPE=ENGINEERING CONSTANTS",
                f"{Ea:.10g},{E:.10g},{Ea:.10g},{nu * Ea / E:.10g},0,0,{G:.10g},{Ga:.10g}",
                f"{G:.10g}",
                f"*SHELL SECTION,ELSET=C{k},MATERIAL=MC{k},ORIENTATION=OC{k}",
                f"{sh.t:.10g}",
            ]
    return lines


def strip_stations(p: float, along: int) -> FloatArray:
    """The element edges across one facet of plan width ``p`` (mm) with crease strips: its
    ends, the strips' inner edges at a = :data:`STRIP_FRACTION` p / 2 from each end, and every
    node line of the rigid mesh of ``along`` elements (its corners and mid-side nodes, j p /
    (2 along)) between them (those inside a strip left out), so that each node line a fixture
    needs on the rigid mesh (four-point's quarter and three-eighth lines, a three-point load
    line) is one here too: 2 ``along`` + 2 elements across a facet from 2 to 8 per facet."""
    a = STRIP_FRACTION * p / 2
    even = np.arange(1, 2 * along) * p / (2 * along)
    inner = even[(even > a * (1 + 1e-9)) & (even < (p - a) * (1 - 1e-9))]
    return np.concatenate([[0.0, a], inner, [p - a, p]])


def layer_shell(
    layer: Layer,
    span: float,
    along: int,
    first_id: int,
    chord_axis: int,
    z0: float,
    multiple: int = 2,
    nel_s: int | None = None,
    aspect: float = 1.0,
) -> Shell:
    """S8R mesh of a layer whose chord runs along ``chord_axis`` (0 = x, 1 = y); the number of
    elements along the creases is ``nel_s`` if given, else a multiple of ``multiple`` giving
    elements about ``aspect`` times as long as they are wide (W / ``along``)."""
    require_zigzag(layer, "FE mesh")
    nf = layer.n + 1
    p, h = layer.pitch, layer.height
    k = layer.material.crease_stiffness
    # a strip element at each end of a facet
    per = along if math.isinf(k) else len(strip_stations(layer.pitch, along)) - 1
    nel_c = per * nf
    if nel_s is None:
        nel_s = multiple * max(1, math.ceil(span / (aspect * layer.W / along) / multiple))
    ni, nj = 2 * nel_c + 1, 2 * nel_s + 1
    if math.isinf(k):
        chord = np.linspace(0.0, nf * p, ni)
    else:  # each facet: a strip (STRIP_FRACTION W / 2 wide), along elements, a strip
        edges = strip_stations(p, along)
        corners = np.concatenate([j * p + edges[:-1] for j in range(nf)] + [[nf * p]])
        chord = np.empty(ni)
        chord[0::2] = corners
        chord[1::2] = 0.5 * (corners[:-1] + corners[1:])
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
    elements = quad8_elements(ids, nel_c, nel_s)
    m = layer.material
    shell = Shell(
        np.asarray(order, dtype=np.int64), np.asarray(coords), elements, layer.t, m.E, m.nu
    )
    if math.isinf(k):
        return shell
    # the strips on either side of each interior crease (not at the layer's two free edges)
    strip = {ei for ei in range(1, nel_c - 1) if ei % per in (0, per - 1)}
    picked = [e for i, e in enumerate(elements) if i % nel_c in strip]
    rest = [e for i, e in enumerate(elements) if i % nel_c not in strip]
    crease = (0.0, 1.0) if chord_axis == 0 else (1.0, 0.0)  # the creases' direction
    section = crease_strip(layer.t, m.E, m.nu, k, STRIP_FRACTION * layer.W, crease, layer.W)
    return replace(shell, elements=rest, strip_elements=picked, strip=section)


def principal_axis(eta_deg: float) -> int | None:
    """The load axis (0 = x, 1 = y) of a direction eta along a layer's creases (eta = 0: layer
    1's, the y axis; eta = 90: layer 2's, the x axis), None for any other eta."""
    layer = crease_layer(eta_deg)
    return None if layer is None else 1 - layer


def specimen(assembly: Assembly, eta_deg: float) -> tuple[float, float]:
    """Width A (across eta) and length B (along eta) of the FE specimen, mm: the rectangle
    Lx x Ly itself at eta = 0 or 90 deg; at any other eta a coupon cut from the same two layers
    with its edges along and across eta, of the layout's proportions turned to the crease
    direction nearer to eta (Lx x Ly up to 45 deg, Ly x Lx above): the coupon the free-panel
    model of a rectangle describes (:func:`corrugate.mechanics.offaxis.assembly_directional`; at 45 deg
    the model is the smaller of the two orientations, so the Lx x Ly coupon checks it from
    above). A square's coupon is the square. A polygon at eta = 0 or 90 deg is its box: the
    assembly cuts the layers to the outline and the fixtures act where the outline lies on the
    box's edges (docs/fea.md 2.8). Circles, and polygons at any other eta, are refused
    (:class:`InputError`): they have no straight edges for platens and supports."""
    a = assembly
    polygon_ok = a.layout.name == "polygon" and principal_axis(eta_deg) is not None
    if a.layout.name not in ("square", "rectangle") and not polygon_ok:
        raise InputError(
            "layout",
            a.layout.name,
            "square or rectangle for the FE assembly, or a polygon at eta 0 or 90 deg (a circle: "
            "validate --fixture wheel; `corrugate docs fea`, section 2.8)",
            reason="has no straight loaded edges for the paper's tests (`corrugate docs fea`, section 2.1)",
        )
    axis = principal_axis(eta_deg)
    if axis == 1:
        return a.Lx, a.Ly
    if axis == 0:
        return a.Ly, a.Lx
    e = float(eta_deg) % 180.0
    return (a.Ly, a.Lx) if min(e, 180.0 - e) > 45.0 else (a.Lx, a.Ly)


def check_shift(shift: float) -> None:
    """Refuse a coupon shift (:func:`oblique_shells`) that is not a real number in [0, 1):
    :class:`InputError`."""
    ok = isinstance(shift, int | float) and not isinstance(shift, bool) and math.isfinite(shift)
    if not ok or not 0.0 <= shift < 1.0:
        raise InputError("shift", shift, "0 <= shift < 1 (a fraction of each layer's pitch)")


def oblique_shells(
    assembly: Assembly,
    eta_deg: float,
    along: int,
    fixture_y: tuple[float, ...],
    *,
    shift: float = 0.0,
    aspect: float = 1.0,
) -> list[Shell]:
    """Both layers over the specimen of :func:`specimen`, in the test frame (y along eta, x
    across), meshed by :mod:`corrugate.fea.planmesh`. The specimen's centre is the layout's
    centre; beyond the layout's extent the zig-zags continue periodically (the specimen is cut
    from the panel's material). ``shift`` (0 <= shift < 1, default 0) moves each layer's zig-zag
    by that fraction of its own pitch (the plan width p of a facet) along its chord direction,
    relative to the coupon: a crease at chordwise position u moves to u + shift p. Values outside
    [0, 1) are refused (:class:`InputError`): 1 would swap valleys and ridges, the same layer
    upside down. ``aspect``: elements that many times longer along the creases than across
    (:func:`corrugate.fea.planmesh.plan_mesh`)."""
    from corrugate.fea.planmesh import Corrugation, plan_mesh

    check_shift(shift)
    a = assembly
    for layer in a.layers:
        require_zigzag(layer, "FE mesh")
    A, B = specimen(a, eta_deg)
    e = math.radians(eta_deg)
    ce, se = math.cos(e), math.sin(e)
    # chordwise unit vectors of the layers in the test frame: layer 1 across its creases
    # (crease-frame x), layer 2 across its own (crease-frame y); origin: centre on centre
    chords = ((ce, se), (-se, ce))
    centres = (a.Lx / 2, a.Ly / 2)
    shells: list[Shell] = []
    first = 1
    for layer, chord, centre, z0 in zip(
        a.layers, chords, centres, (0.0, a.layer1.height), strict=True
    ):
        offset = centre - (chord[0] * A / 2 + chord[1] * B / 2) - shift * layer.pitch
        corr = Corrugation(chord, offset, layer.pitch, layer.height, z0)
        pm = plan_mesh(corr, A, B, along, fixture_y, aspect, strip=strip_half_width(layer))
        shells.append(plan_shell(layer, pm, first, chord))
        first = int(shells[-1].ids[-1]) + 1
    return shells


def strip_half_width(layer: Layer) -> float:
    """How far (mm, in plan, across the creases) each crease strip reaches from its crease:
    half of STRIP_FRACTION of the layer's pitch, 0 for rigid creases (no strips)."""
    return 0.0 if math.isinf(layer.material.crease_stiffness) else STRIP_FRACTION * layer.pitch / 2


def plan_shell(layer: Layer, pm: PlanMesh, first: int, chord: tuple[float, float]) -> Shell:
    """``layer`` on the plan mesh ``pm`` (meshed with :func:`strip_half_width`), its nodes
    numbered from ``first``, ``chord`` the unit vector across its creases in the mesh's frame:
    the elements in and out of the crease strips, and the strips' section at the material's
    crease stiffness (none for rigid creases)."""
    m = layer.material
    k = m.crease_stiffness
    ids = np.arange(first, first + len(pm.xyz), dtype=np.int64)
    crease = (-chord[1], chord[0])  # the creases' direction in the mesh's frame
    return Shell(
        ids,
        pm.xyz,
        _rows(pm, ids, "S8R", False),
        layer.t,
        m.E,
        m.nu,
        _rows(pm, ids, "S6", False),
        _rows(pm, ids, "S8R", True),
        _rows(pm, ids, "S6", True),
        None
        if math.isinf(k)
        else crease_strip(layer.t, m.E, m.nu, k, STRIP_FRACTION * layer.W, crease, layer.W),
    )


def _rows(pm: PlanMesh, ids: NDArray[np.int64], name: str, strip: bool) -> list[list[int]]:
    """The elements of type ``name`` of ``pm`` in (``strip``) or out of the crease strips, as
    rows of global node ids ``ids``."""
    mask = pm.in_strip.get(name) or [False] * len(pm.elements[name])
    return [
        [int(ids[i]) for i in r] for r, s in zip(pm.elements[name], mask, strict=True) if s == strip
    ]
