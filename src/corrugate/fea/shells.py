"""Shell meshes of the two layers for the assembly FE (:mod:`corrugate.fea.assembly`).

* :func:`layer_shell`: the structured S8R mesh of one layer over the layout itself (eta = 0 or
  90 deg), ``along`` elements across each facet;
* :func:`oblique_shells`: both layers over a square coupon cut along any eta, meshed by gmsh
  (:mod:`corrugate.fea.planmesh`) in a test frame with y along eta;
* :func:`specimen` and :func:`principal_axis`: which specimen a direction eta gets.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np
from numpy.typing import NDArray

from corrugate.core.errors import InputError
from corrugate.geometry.layer import Assembly, Layer, crease_layer, require_zigzag

__all__ = [
    "Shell",
    "check_shift",
    "layer_shell",
    "oblique_shells",
    "principal_axis",
    "quad8_elements",
    "section_lines",
    "specimen",
]

FloatArray = NDArray[np.float64]


@dataclass(frozen=True, slots=True)
class Shell:
    """Nodes (global ids, coordinates) and connectivity of one part: S8R ``elements`` and, from
    the gmsh mesher, S6 triangles ``triangles``."""

    ids: NDArray[np.int64]
    xyz: FloatArray
    elements: list[list[int]]
    t: float
    E: float
    nu: float
    triangles: list[list[int]] = field(default_factory=list)


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
    its E (MPa), nu and thickness (mm)."""
    lines: list[str] = []
    for k, sh in parts:
        lines += [
            f"*MATERIAL,NAME=M{k}",
            "*ELASTIC",
            f"{sh.E:.10g},{sh.nu:.10g}",
            f"*SHELL SECTION,ELSET=L{k},MATERIAL=M{k}",
            f"{sh.t:.10g}",
        ]
    return lines


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
    nel_c = along * nf
    if nel_s is None:
        nel_s = multiple * max(1, math.ceil(span / (aspect * layer.W / along) / multiple))
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
    elements = quad8_elements(ids, nel_c, nel_s)
    m = layer.material
    return Shell(
        np.asarray(order, dtype=np.int64), np.asarray(coords), elements, layer.t, m.E, m.nu
    )


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
        pm = plan_mesh(corr, A, B, along, fixture_y, aspect)
        ids = np.arange(first, first + len(pm.xyz), dtype=np.int64)
        m = layer.material
        shells.append(
            Shell(
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
