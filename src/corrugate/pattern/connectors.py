"""Connectors: the edge band that holds the two layers together and fixes their fold angle.

Design (DESIGN.md section 4 asks for connectors whose area counts in the mass):

* A **band** of height t_d (the folded thickness) wraps the whole perimeter of the outline, cut in
  segments: one per polygon edge (it folds at no corner, the joins sit at the corners), or equal arcs
  no longer than ``segment_max`` for a circle.
* Both long edges carry **glue tabs** of depth g (45 deg chamfers, valley folds of 90 deg) that fold
  inwards: layer 1's valleys rest and are glued on the bottom tabs, the top tabs fold over layer 2's
  ridges. A straight run of length e has k = ceil(e / tab_length) equal tabs of length l = e / k.
* Each segment ends in an **overlap tab** (length ``overlap``) glued behind the start of the next
  segment; at a corner it folds by the outline's turning angle.
* **Marks**: where every crease of a layer meets the perimeter, a vertical mark on the band spans
  that layer's height (layer 1: 0..h1, layer 2: h1..t_d). Lining up each crease end with its mark
  sets the pitch, hence the fold angle, without measuring.

Area of one segment of length e: (e + overlap) t_d + 2 k g_e (l - g_e), with g_e = min(g, l/2)
(a tab of length l <= 2 g is a triangle). :func:`connector_area` evaluates it vectorised; the cut
file's polygons have exactly this area.
"""

from __future__ import annotations

import numpy as np
from numpy.typing import ArrayLike, NDArray

from ..layouts import Layout
from .options import DEFAULT_FABRICATION, FabricationOptions

__all__ = ["band_segments", "connector_area", "tab_area"]

FloatArray = NDArray[np.float64]


def tab_area(run: ArrayLike, opts: FabricationOptions) -> FloatArray:
    """Area (mm^2) of the glue tabs along one edge of a straight run of length ``run`` (mm)."""
    e = np.asarray(run, dtype=np.float64)
    k = np.maximum(1.0, np.ceil(e / opts.tab_length - 1e-9))
    ell = e / k
    g = np.minimum(opts.tab_depth, ell / 2)
    return np.asarray(k * g * (ell - g))


def band_segments(
    layout: Layout, Lx: ArrayLike, Ly: ArrayLike, opts: FabricationOptions = DEFAULT_FABRICATION
) -> list[tuple[FloatArray, FloatArray]]:
    """The band's segments as (length in mm, count) pairs, vectorised over Lx, Ly.

    A run that ends at a corner is one segment; a smooth run (a circle) is cut into
    ceil(length / segment_max) equal arcs.
    """
    out: list[tuple[FloatArray, FloatArray]] = []
    for length, cornered in layout.perimeter_runs(Lx, Ly):
        if cornered:
            out.append((length, np.ones_like(length)))
        else:
            count = np.maximum(1.0, np.ceil(length / opts.segment_max - 1e-9))
            out.append((np.asarray(length / count), count))
    return out


def connector_area(
    layout: Layout,
    Lx: ArrayLike,
    Ly: ArrayLike,
    thickness: ArrayLike,
    opts: FabricationOptions = DEFAULT_FABRICATION,
) -> FloatArray:
    """Flat area (mm^2) of the band: every segment with its two rows of tabs and its overlap."""
    td = np.asarray(thickness, dtype=np.float64)
    total = np.zeros(np.broadcast_shapes(np.shape(Lx), np.shape(Ly), td.shape))
    for length, count in band_segments(layout, Lx, Ly, opts):
        total = total + count * ((length + opts.overlap) * td + 2 * tab_area(length, opts))
    return np.asarray(total)
