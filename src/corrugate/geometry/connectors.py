"""Connectors: the edge band that holds the two layers together and fixes their fold angle.

Design (docs/theory.md section 4 asks for connectors whose area counts in the mass):

* A **band** of height t_d (the folded thickness) wraps the whole perimeter of the outline, cut in
  segments: one per polygon edge (it folds at no corner, the joins sit at the corners), or equal arcs
  no longer than ``segment_max`` for a circle.
* Both long edges carry a **glue flange** of depth g (a valley fold of 90 deg) that folds inwards:
  layer 1's valleys rest and are glued on the bottom flange, the top flange folds over layer 2's
  ridges. Slits (cuts of no area) divide each flange into tabs no longer than ``tab_length`` so it
  can follow a curve; at a corner the flange ends in a 45 deg chamfer.
* Each segment ends in an **overlap tab** (length ``overlap``) glued behind the start of the next
  segment; at a corner it folds by the outline's turning angle.
* **Marks**: where every crease of a layer meets the perimeter, a vertical mark on the band spans
  that layer's height (layer 1: 0..h1, layer 2: h1..t_d). Lining up each crease end with its mark
  sets the pitch, hence the fold angle, without measuring.

Area of one segment of length e: (e + overlap) t_d + 2 F(e), the flange F(e) = g_e (e - g_e) with
g_e = min(g, e/2) when it ends at corners (chamfered) and F(e) = g e along a smooth outline.
:func:`connector_area` evaluates it vectorised; the cut file's polygons have exactly this area.
It increases with Lx, Ly and t_d (a circle's band gains a segment, and an overlap, as it grows),
which the optimiser's bounds rely on.
"""

from __future__ import annotations

import math

import numpy as np
from numpy.typing import ArrayLike, NDArray

from corrugate.geometry.fabrication_options import DEFAULT_FABRICATION, FabricationOptions
from corrugate.geometry.layouts import Layout

__all__ = ["band_segments", "connector_area", "flange_area", "slit_count"]

FloatArray = NDArray[np.float64]


def flange_area(run: ArrayLike, cornered: bool, opts: FabricationOptions) -> FloatArray:
    """Area (mm^2) of one glue flange along a segment of length ``run`` (mm): chamfered at both
    ends when the segment ends at corners, g_e (e - g_e) with g_e = min(g, e/2); else g e."""
    e = np.asarray(run, dtype=np.float64)
    if not cornered:
        return np.asarray(opts.tab_depth * e)
    g = np.minimum(opts.tab_depth, e / 2)
    return np.asarray(g * (e - g))


def slit_count(run: float, opts: FabricationOptions) -> int:
    """Slits that divide a flange of length ``run`` (mm) into equal tabs <= ``tab_length``."""
    return max(1, math.ceil(run / opts.tab_length - 1e-9)) - 1


def band_segments(
    layout: Layout, Lx: ArrayLike, Ly: ArrayLike, opts: FabricationOptions = DEFAULT_FABRICATION
) -> list[tuple[FloatArray, FloatArray, bool]]:
    """The band's segments as (length in mm, count, ends at corners), vectorised over Lx, Ly.

    A run that ends at a corner is one segment; a smooth run (a circle) is cut into
    ceil(length / segment_max) equal arcs.
    """
    out: list[tuple[FloatArray, FloatArray, bool]] = []
    for length, cornered in layout.perimeter_runs(Lx, Ly):
        if cornered:
            out.append((length, np.ones_like(length), True))
        else:
            count = np.maximum(1.0, np.ceil(length / opts.segment_max - 1e-9))
            out.append((np.asarray(length / count), count, False))
    return out


def connector_area(
    layout: Layout,
    Lx: ArrayLike,
    Ly: ArrayLike,
    thickness: ArrayLike,
    opts: FabricationOptions = DEFAULT_FABRICATION,
) -> FloatArray:
    """Flat area (mm^2) of the band: every segment with its two flanges and its overlap tab."""
    td = np.asarray(thickness, dtype=np.float64)
    shape = np.broadcast_shapes(np.shape(Lx), np.shape(Ly), td.shape)
    # the segments of band_segments; a run that ends at corners is one segment, and runs of the
    # same length array (a rectangle's opposite sides; a square's four when Lx is Ly) are
    # computed once and counted k times
    runs: list[tuple[FloatArray, bool]] = []
    mult: list[int] = []
    for length, cornered in layout.perimeter_runs(Lx, Ly):
        for i, (other, c) in enumerate(runs):
            if cornered and c and other is length:
                mult[i] += 1
                break
        else:
            runs.append((length, cornered))
            mult.append(1)
    total: FloatArray | None = None
    for (length, cornered), k in zip(runs, mult, strict=True):
        e = np.asarray(length, dtype=np.float64)
        if cornered:
            term = (e + opts.overlap) * td + 2 * flange_area(e, True, opts)
        else:
            count = np.maximum(1.0, np.ceil(e / opts.segment_max - 1e-9))
            seg = np.asarray(e / count)
            term = count * ((seg + opts.overlap) * td + 2 * flange_area(seg, False, opts))
        if k != 1:
            term = k * term
        total = term if total is None else total + term
    assert total is not None
    return np.asarray(total if total.shape == shape else np.broadcast_to(total, shape))
