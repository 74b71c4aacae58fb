"""The boxes of the branch and bound's search space (:mod:`.bnb`), as rows of flat arrays:
one row per box, one column per coordinate (lower corners ``lo``, upper corners ``hi``), each
coordinate a :class:`~.problem.DesignVariable` (continuous, or a grid of step ``step`` from
``lo``). Their relative widths, their cuts into parts (grid coordinates between two grid
values), their grid points, and values snapped to a grid; docs/theory.md section 5.
"""

from __future__ import annotations

from collections.abc import Sequence

import numpy as np
from numpy.typing import NDArray

from corrugate.solver.problem import DesignVariable

__all__ = [
    "MULTI_PARTS",
    "MULTI_SPLIT_CHILDREN",
    "cut_widest",
    "grid_points",
    "snap",
    "split",
    "widths",
]

FloatArray = NDArray[np.float64]

#: Parts per coordinate of a split along several coordinates at once (:func:`split`, ``multi``).
MULTI_PARTS = 8
#: Such a split cuts every coordinate when that makes at most this many boxes (grid
#: coordinates may give fewer), else only the coordinates at least half as wide as the widest.
MULTI_SPLIT_CHILDREN = 4096


def snap(v: FloatArray, var: DesignVariable, up: bool) -> FloatArray:
    """Grid value at or below (above if ``up``) v; v itself for a continuous variable."""
    if var.step is None:
        return v
    k = (v - var.lo) / var.step
    k = np.ceil(k - 1e-9) if up else np.floor(k + 1e-9)
    return np.asarray(var.lo + var.step * k)


def split(
    lo: FloatArray,
    hi: FloatArray,
    width: FloatArray,
    variables: Sequence[DesignVariable],
    multi: bool,
    tag: FloatArray,
    batch: int,
) -> tuple[FloatArray, FloatArray, FloatArray]:
    """Cut each box along its relatively widest coordinate (``width``: (hi - lo) / lo, with n
    counted as n + 1, so every coordinate is judged by how much it changes across the box) into
    two, and (``multi``) into :data:`MULTI_PARTS` along every coordinate if that makes at most
    :data:`MULTI_SPLIT_CHILDREN` boxes, else along every coordinate at least half as wide as the
    widest (so few boxes become many in few iterations: the per-iteration cost is mostly fixed;
    the case study then takes 2 iterations instead of 3).
    Grid coordinates are cut between two grid values, into at most as many parts as values."""
    widest = width.max(axis=1, keepdims=True)
    if multi:
        cut = width > 0  # every coordinate, while the children stay few
        if int((float(MULTI_PARTS) ** cut.sum(axis=1)).sum()) > MULTI_SPLIT_CHILDREN:
            cut &= width >= 0.5 * widest
        if int((float(MULTI_PARTS) ** cut.sum(axis=1)).sum()) > batch:
            multi = False  # still too many children for one batch: halve along the widest
    if not multi:
        cut = np.zeros(width.shape, dtype=bool)
        cut[np.arange(len(width)), np.argmax(width, axis=1)] = True
    parts = MULTI_PARTS if multi else 2
    for i, var in enumerate(variables):
        sel = cut[:, i]
        if not sel.any():
            continue
        a, b = lo[sel, i], hi[sel, i]
        j = np.arange(parts + 1, dtype=np.float64)[:, None]  # cut j of parts + 1 (0 and end)
        if var.step is None:
            edges = a + (b - a) * (j / parts)
            edges[-1] = b
            starts, ends = edges[:-1], edges[1:]
            valid = np.ones(starts.shape, dtype=bool)
        else:
            k_lo = np.round((a - var.lo) / var.step)
            k_hi = np.round((b - var.lo) / var.step)
            count = k_hi - k_lo + 1  # grid values in the box (>= 2 here)
            first = k_lo + np.ceil(j * count / parts)  # first grid index of each part
            starts = var.lo + var.step * first[:-1]
            ends = var.lo + var.step * (first[1:] - 1)
            valid = first[1:] > first[:-1]  # a part holds at least one grid value
        # rows: the boxes not cut here, then part by part each cut box's valid parts (no copies
        # of whole boxes per part: one gather, then this coordinate's new edges)
        keep = valid.reshape(-1)
        src = np.concatenate([np.flatnonzero(~sel), np.tile(np.flatnonzero(sel), parts)[keep]])
        first_child = len(lo) - len(a)
        lo, hi = lo[src], hi[src]
        lo[first_child:, i] = starts.reshape(-1)[keep]
        hi[first_child:, i] = ends.reshape(-1)[keep]
        cut, tag = cut[src], tag[src]
    return lo, hi, tag


def cut_widest(
    lo: FloatArray,
    hi: FloatArray,
    width: FloatArray,
    variables: Sequence[DesignVariable],
    tag: FloatArray,
    parts: int,
) -> tuple[FloatArray, FloatArray, FloatArray]:
    """:func:`split` of grid boxes along the relatively widest coordinate alone (``width``, as
    :func:`widths` gives) into ``parts`` parts, in fewer array operations (one coordinate per
    box, picked per row): part j of a coordinate of k grid values takes the indices from
    ceil(j k / parts) to ceil((j + 1) k / parts) - 1 (the parts :func:`split` makes; fewer
    when k < parts: no empty part), each value lo + step i as :func:`split` makes it; a box of
    one grid value along that coordinate (one point) is kept whole. Rows: part by part (every
    box's first part, then every box's second, ...); ``tag`` follows them. With ``parts`` 2,
    :func:`split` in two (``multi`` False) of the boxes of more than one point."""
    step = np.array([v.step for v in variables], dtype=np.float64)
    base = np.array([v.lo for v in variables], dtype=np.float64)
    assert not np.isnan(step).any(), "cut_widest: grid coordinates only"
    i = np.argmax(width, axis=1)
    r = np.arange(len(lo))
    k_lo = np.round((lo[r, i] - base[i]) / step[i])
    k_hi = np.round((hi[r, i] - base[i]) / step[i])
    j = np.arange(parts + 1, dtype=np.float64)[:, None]
    first = k_lo + np.ceil(j * (k_hi - k_lo + 1) / parts)  # (parts + 1) x boxes
    part, box = np.nonzero(first[1:] > first[:-1])  # the parts holding a grid value
    lo, hi, tag = lo[box], hi[box], tag[box]
    ib, rows = i[box], np.arange(len(box))
    lo[rows, ib] = base[ib] + step[ib] * first[part, box]
    hi[rows, ib] = base[ib] + step[ib] * (first[part + 1, box] - 1)
    return lo, hi, tag


def grid_points(
    lo: FloatArray, counts: FloatArray, variables: Sequence[DesignVariable]
) -> FloatArray:
    """Every grid point of each box (lower corners ``lo``, ``counts`` grid values per
    coordinate), as rows; values lo + step k exactly as :func:`split` and :func:`snap` make."""
    per_box = counts.prod(axis=1).astype(np.int64)
    r = np.arange(int(per_box.sum())) - np.repeat(np.cumsum(per_box) - per_box, per_box)
    out = np.empty((len(r), len(variables)))
    for i in range(len(variables) - 1, -1, -1):  # mixed radix, last coordinate fastest
        var = variables[i]
        assert var.step is not None
        # per box, then repeated for its points (cheaper than indexing by each point's box)
        c = np.repeat(counts[:, i].astype(np.int64), per_box)
        k0 = np.repeat(np.round((lo[:, i] - var.lo) / var.step), per_box)
        out[:, i] = var.lo + var.step * (k0 + r % c)
        r = r // c
    return out


def widths(lo: FloatArray, hi: FloatArray, offset: FloatArray) -> FloatArray:
    """Relative widths (hi - lo) / lo of boxes, with n counted as n + 1 (``offset``)."""
    return np.asarray((hi - lo) / np.maximum(lo + offset, 1e-300))
