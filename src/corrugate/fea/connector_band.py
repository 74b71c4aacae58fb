"""The connector band as shells for the assembly FE (:mod:`corrugate.fea.assembly`, whose
docstring states the model): four walls on the rectangle's outline, meshed to conform to the
layers' zig-zag edges, bonded along the layer edges (``bond="edges"``) or, as cut, glued only on
their flanges (``bond="flanges"``).
"""

from __future__ import annotations

import itertools
from typing import Literal

import numpy as np
from numpy.typing import NDArray

from corrugate.fea.ccx import SolverError
from corrugate.fea.coincident import CoincidentKeys
from corrugate.fea.shells import Shell
from corrugate.geometry.connectors import slit_count
from corrugate.geometry.fabrication_options import DEFAULT_FABRICATION, FabricationOptions
from corrugate.geometry.layer import Assembly, Layer

__all__ = ["Bond", "band_shell"]

FloatArray = NDArray[np.float64]


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
    equal tabs as the cut file has along that edge (:func:`corrugate.geometry.connectors.
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


def band_shell(
    a: Assembly, along: int, shells: list[Shell], tol: float, bond: Bond = "edges"
) -> Shell:
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

    # one key per place, the same for a layer's node and the band's point on it even where a
    # coordinate falls on a rounding tie of tol (corrugate.fea.coincident)
    key = CoincidentKeys(tol).key

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
            shells[i] = Shell(sh.ids[keep], sh.xyz[keep], merged, sh.t, sh.E, sh.nu)
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
    return Shell(np.asarray(ids, dtype=np.int64), np.asarray(coords), elements, l1.t, m.E, m.nu)
