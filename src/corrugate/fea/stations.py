"""Node lines at a fixture's stations on the structured mesh (docs/fea.md 2.1, "Spans shorter
than the panel").

The structured mesh (:func:`corrugate.fea.shells.layer_shell`, the connector band of
:mod:`corrugate.fea.connector_band`) puts its node lines across the load axis at even steps:
``along`` per facet of the layer whose creases run across the load axis (its chord runs along
it), and even steps over the length for the other layer. A fixture whose supports or loads lie
between them (a span shorter than the panel) gets its node lines by moving nodes along the load
axis with a piecewise-linear map phi (lengths in mm):

* phi fixes the panel's ends, every crease of the layer whose chord runs along the load axis
  (so every facet stays flat, and its nodes are lifted back onto the zig-zag after the move) and
  every node line already at a station;
* between two fixed lines, the node line nearest to each station (by its share of the interval)
  moves onto it and the node lines between are spread evenly: inside one facet, m elements
  between the facet's first crease and the station, ``along`` - m between it and the next;
* an element keeps its mid-side nodes at the middle of its sides (phi is linear on each element).

The band's walls carry the zig-zag of that layer as triangles (two per facet): their nodes
between the zig-zag's valley and ridge heights are moved in height too, scaled between the
triangle's horizontal side and the zig-zag edge, so that the wall stays meshed to the layer's
moved edge nodes (:func:`morph_band`).
"""

from __future__ import annotations

import bisect
import itertools
from collections.abc import Sequence
from dataclasses import dataclass, replace

import numpy as np
from numpy.typing import NDArray

from corrugate.core.errors import InputError
from corrugate.fea.shells import Shell
from corrugate.geometry.layer import Assembly, Layer

__all__ = [
    "StationMap",
    "Zigzag",
    "corner_stations",
    "morph_band",
    "morph_layer",
    "on_stations",
    "station_map",
]

FloatArray = NDArray[np.float64]


@dataclass(frozen=True, slots=True)
class StationMap:
    """The piecewise-linear map phi along the load axis: knots ``old`` -> ``new`` (mm,
    increasing), the identity outside them."""

    old: tuple[float, ...]
    new: tuple[float, ...]

    def __call__(self, c: FloatArray) -> FloatArray:
        out: FloatArray = np.interp(c, self.old, self.new)
        return out

    @property
    def identity(self) -> bool:
        return self.old == self.new


@dataclass(frozen=True, slots=True)
class Zigzag:
    """A layer's zig-zag along the load axis: valleys at z0 on the even creases k p (k = 0,
    2, ...), ridges at z0 + h on the odd ones (mm)."""

    pitch: float
    height: float
    z0: float
    facets: int

    @classmethod
    def of(cls, layer: Layer, z0: float) -> Zigzag:
        return cls(layer.pitch, layer.height, z0, layer.n + 1)

    def creases(self) -> FloatArray:
        """The crease positions k p (mm), k = 0 .. facets."""
        out: FloatArray = np.arange(self.facets + 1, dtype=np.float64) * self.pitch
        return out

    def z(self, c: FloatArray) -> FloatArray:
        """Height (mm) of the zig-zag edge at ``c`` along the load axis."""
        k = np.arange(self.facets + 1)
        out: FloatArray = np.interp(c, k * self.pitch, self.z0 + self.height * (k % 2))
        return out


def corner_stations(sh: Shell, axis: int, tol: float, shells: Sequence[Shell] = ()) -> FloatArray:
    """The distinct coordinates (mm) along ``axis`` of the corner nodes of the shell's elements:
    its node lines across the load axis (the mid-side lines left out); ``shells``: the parts
    whose nodes its elements may share (the band merges coincident layer nodes)."""
    where = {
        int(n): float(x[axis])
        for part in (*shells, sh)
        for n, x in zip(part.ids, part.xyz, strict=True)
    }
    c = np.sort(np.array(sorted({where[n] for e in sh.elements for n in e[:4]})))
    keep = np.concatenate(([True], np.diff(c) > tol))
    out: FloatArray = c[keep]
    return out


def station_map(
    grid: FloatArray,
    fixed: Sequence[float],
    targets: Sequence[float],
    tol: float,
    what: str = "the fixture's lines",
    along: int = 0,
) -> StationMap:
    """phi (module docstring) for the node lines ``grid`` (increasing, mm), the lines ``fixed``
    that stay (crease lines, the ends) and the ``targets`` that need a node line. Refuses
    (:class:`InputError` on ``mesh.along``) an interval between two fixed lines with more
    stations than it has inner node lines."""
    g = [float(v) for v in grid]
    lo, hi = g[0], g[-1]

    def snap(t: float) -> int | None:
        """The index of the node line at ``t``, None when there is none."""
        i = bisect.bisect_left(g, t)
        near = [j for j in (i - 1, i) if 0 <= j < len(g) and abs(g[j] - t) <= tol]
        return near[0] if near else None

    held = {snap(float(t)) for t in (*fixed, lo, hi, *targets)}
    keep = [g[i] for i in sorted(i for i in held if i is not None)]
    moving = sorted(float(t) for t in targets if snap(float(t)) is None)
    old: list[float] = list(keep)
    new: list[float] = list(keep)
    for f0, f1 in itertools.pairwise(keep):
        inside = [t for t in moving if f0 < t < f1]
        if not inside:
            continue
        i0, i1 = g.index(f0), g.index(f1)
        m = i1 - i0  # elements between the two fixed lines
        if len(inside) > m - 1:
            raise InputError(
                "mesh.along",
                along,
                f"a finer mesh: {what} at {', '.join(f'{t:.6g}' for t in inside)} mm fall "
                f"between {f0:.6g} and {f1:.6g} mm, which hold {m} element(s) along the span",
            )
        picks: list[int] = []
        for j, t in enumerate(inside):  # the nearest line by share, kept in order
            want = round(m * (t - f0) / (f1 - f0))
            least = (picks[-1] + 1) if picks else 1
            most = m - (len(inside) - j)
            picks.append(min(max(want, least), most))
        for i, t in zip(picks, inside, strict=True):
            old.append(g[i0 + i])
            new.append(t)
    order = np.argsort(old)
    return StationMap(tuple(float(old[i]) for i in order), tuple(float(new[i]) for i in order))


def morph_layer(sh: Shell, axis: int, phi: StationMap, zig: Zigzag | None) -> Shell:
    """The layer ``sh`` with its nodes moved along ``axis`` by ``phi`` and, when its chord runs
    along the axis (``zig``), lifted back onto its zig-zag."""
    if phi.identity:
        return sh
    xyz = sh.xyz.copy()
    xyz[:, axis] = phi(sh.xyz[:, axis])
    if zig is not None:
        xyz[:, 2] = zig.z(xyz[:, axis])
    return replace(sh, xyz=xyz)


def morph_band(
    sh: Shell, axis: int, phi: StationMap, zig: Zigzag, walls: tuple[float, float], tol: float
) -> Shell:
    """The band ``sh`` with its nodes moved along ``axis`` by ``phi``; on the two walls along the
    axis (at ``walls``, the coordinates across it), which carry ``zig`` as two triangles per
    facet, a node between the zig-zag's valley and ridge heights is also moved in height: below
    the zig-zag edge its height above the valleys scales with the edge's, above the edge its
    depth below the ridges does (the horizontal sides stay, the edge meets the layer's moved
    nodes)."""
    if phi.identity:
        return sh
    xyz = sh.xyz.copy()
    c = sh.xyz[:, axis]
    c2 = phi(c)
    xyz[:, axis] = c2
    z = sh.xyz[:, 2]
    zlo, zhi = zig.z0, zig.z0 + zig.height
    other = sh.xyz[:, 1 - axis]
    wall = (np.abs(other - walls[0]) < tol) | (np.abs(other - walls[1]) < tol)
    band = wall & (z > zlo + tol) & (z < zhi - tol) & (np.abs(c2 - c) > 0)
    d, d2 = zig.z(c), zig.z(c2)
    below = band & (z <= d)
    above = band & (z > d)
    with np.errstate(divide="ignore", invalid="ignore"):
        zb = zlo + (z - zlo) * (d2 - zlo) / (d - zlo)
        za = zhi - (zhi - z) * (zhi - d2) / (zhi - d)
    xyz[below, 2] = zb[below]
    xyz[above, 2] = za[above]
    return replace(sh, xyz=xyz)


def on_stations(
    a: Assembly,
    shells: list[Shell],
    axis: int,
    targets: Sequence[float],
    tol: float,
    connectors: bool,
    along: int,
) -> list[Shell]:
    """The structured shells of :func:`corrugate.fea.assembly.assembly_deck` (layer 1, layer 2
    and, with ``connectors``, the band) with node lines at ``targets`` (mm along the load axis
    ``axis``; module docstring). The layer whose chord runs along the axis (layer 1 for x,
    layer 2 for y) keeps its creases; with the band every part shares one map (their node lines
    coincide), without it each layer gets its own."""
    chord = axis  # layer 1's chord runs along x (axis 0), layer 2's along y (axis 1)
    zig = Zigzag.of(a.layers[chord], 0.0 if chord == 0 else a.layer1.height)
    creases = [float(v) for v in zig.creases()]
    what = "the supports and load lines"

    def phi_of(sh: Shell, fixed: Sequence[float]) -> StationMap:
        return station_map(corner_stations(sh, axis, tol, shells), fixed, targets, tol, what, along)

    phi_chord = phi_of(shells[chord], creases)
    out: list[Shell] = []
    for k, sh in enumerate(shells):
        if k == 2:  # the band: its walls along the axis carry the chord layer's zig-zag
            walls = (0.0, (a.Lx, a.Ly)[1 - axis])
            out.append(morph_band(sh, axis, phi_chord, zig, walls, tol))
        elif k == chord:
            out.append(morph_layer(sh, axis, phi_chord, zig))
        else:
            phi = phi_chord if connectors else phi_of(sh, ())
            out.append(morph_layer(sh, axis, phi, None))
    return out
