"""The boxes of the branch and bound (:mod:`corrugate.solver.boxes`): a split is a partition,
checked against the grid values of each box listed one by one (``itertools.product`` over
``DesignVariable.values``) and, for continuous coordinates, against the box's volume."""

from __future__ import annotations

import itertools

import numpy as np
import pytest

from corrugate.solver.boxes import cut_widest, grid_points, snap, split, widths
from corrugate.solver.problem import DesignVariable

GRID = [DesignVariable(1.0, 40.0, 1.0), DesignVariable(5.0, 20.0, 0.5), DesignVariable(40, 120, 5)]


def _values(lo: np.ndarray, hi: np.ndarray) -> set[tuple[float, ...]]:
    """The grid points of the box [lo, hi], listed one by one."""
    axes = [
        [float(x) for x in v.values() if lo[i] - 1e-9 <= x <= hi[i] + 1e-9]
        for i, v in enumerate(GRID)
    ]
    return set(itertools.product(*axes))


@pytest.mark.parametrize("multi", [False, True])
def test_a_split_of_grid_boxes_partitions_their_grid_points(multi: bool) -> None:
    rng = np.random.default_rng(7)
    k = [rng.integers(0, v.count(), size=(2, 12)) for v in GRID]
    lo = np.stack([v.lo + v.step * k_.min(axis=0) for v, k_ in zip(GRID, k, strict=True)], axis=1)
    hi = np.stack([v.lo + v.step * k_.max(axis=0) for v, k_ in zip(GRID, k, strict=True)], axis=1)
    lo[:, 0] = np.minimum(lo[:, 0], 37.0)
    hi[:, 0] = lo[:, 0] + 3  # every box wider than one point, inside n's range
    tag = np.arange(len(lo), dtype=np.float64)
    c_lo, c_hi, c_tag = split(
        lo, hi, widths(lo, hi, np.array([1.0, 0.0, 0.0])), GRID, multi, tag, 20_000
    )
    assert len(c_lo) > len(lo)
    for b in range(len(lo)):
        children = np.flatnonzero(c_tag == b)
        seen: list[tuple[float, ...]] = []
        for c in children:
            pts = _values(c_lo[c], c_hi[c])
            assert pts  # no empty part
            seen += pts
        assert len(seen) == len(set(seen))  # the parts do not overlap
        assert set(seen) == _values(lo[b], hi[b])  # and hold every grid point of the box
        # grid_points lists the same points (its counts: grid values per coordinate)
        counts = np.round((c_hi[children] - c_lo[children]) / [v.step for v in GRID]) + 1
        listed = grid_points(c_lo[children], counts, GRID)
        assert sorted(map(tuple, listed.tolist())) == sorted(seen)


def test_a_split_of_continuous_boxes_keeps_their_volume() -> None:
    cont = [DesignVariable(1.0, 40.0, 1.0), DesignVariable(5.0, 20.0), DesignVariable(40, 120)]
    lo = np.array([[3.0, 5.0, 40.0], [10.0, 7.25, 90.0]])
    hi = np.array([[3.0, 20.0, 120.0], [17.0, 9.5, 91.0]])
    for multi in (False, True):
        c_lo, c_hi, tag = split(
            lo,
            hi,
            widths(lo, hi, np.array([1.0, 0.0, 0.0])),
            cont,
            multi,
            np.array([0.0, 1.0]),
            20_000,
        )
        for b in range(2):
            kids = tag == b
            assert np.all(c_lo[kids] >= lo[b]) and np.all(c_hi[kids] <= hi[b])
            # n is a grid: its parts hold whole values; the volume of W x alpha adds up
            n_values = c_hi[kids, 0] - c_lo[kids, 0] + 1
            volume = n_values * np.prod(c_hi[kids, 1:] - c_lo[kids, 1:], axis=1)
            assert volume.sum() == pytest.approx(
                (hi[b, 0] - lo[b, 0] + 1) * np.prod(hi[b, 1:] - lo[b, 1:])
            )


def test_snap_rounds_to_the_grid_and_leaves_continuous_values() -> None:
    v = DesignVariable(5.0, 20.0, 0.5)
    x = np.array([5.0, 5.2, 5.5 - 1e-12, 19.9])
    assert snap(x, v, up=False).tolist() == [5.0, 5.0, 5.5, 19.5]
    assert snap(x, v, up=True).tolist() == [5.0, 5.5, 5.5, 20.0]
    assert snap(x, DesignVariable(5.0, 20.0), up=False) is x


@pytest.mark.parametrize("parts", [2, 3, 8])
def test_cutting_grid_boxes_along_the_widest_partitions_them_as_a_split_does(parts: int) -> None:
    """:func:`cut_widest` (the joint search's cheaper cuts of its start boxes): each box of two
    or more grid points becomes non-empty parts that hold its grid points once each (listed one
    by one), along one coordinate; a box of one point is kept whole; in two, the same two boxes
    as :func:`split` in two (``multi`` False)."""
    rng = np.random.default_rng(11)
    k = [rng.integers(0, v.count(), size=(2, 40)) for v in GRID]
    lo = np.stack([v.lo + v.step * k_.min(axis=0) for v, k_ in zip(GRID, k, strict=True)], axis=1)
    hi = np.stack([v.lo + v.step * k_.max(axis=0) for v, k_ in zip(GRID, k, strict=True)], axis=1)
    hi[:3] = lo[:3]  # three boxes of one point each
    tag = np.arange(len(lo), dtype=np.float64)
    width = widths(lo, hi, np.array([1.0, 0.0, 0.0]))
    c_lo, c_hi, c_tag = cut_widest(lo, hi, width, GRID, tag, parts)
    wide = np.any(hi > lo, axis=1)
    s_lo, s_hi, s_tag = split(lo[wide], hi[wide], width[wide], GRID, False, tag[wide], 20_000)
    for b in range(len(lo)):
        mine = np.flatnonzero(c_tag == b)
        if not wide[b]:
            assert len(mine) == 1 and np.array_equal(c_lo[mine[0]], lo[b])
            assert np.array_equal(c_hi[mine[0]], hi[b])
            continue
        along = int(np.argmax(width[b]))
        values = round((hi[b, along] - lo[b, along]) / GRID[along].step) + 1
        assert len(mine) == min(parts, values)
        other = [i for i in range(len(GRID)) if i != along]
        assert np.all(c_lo[mine][:, other] == lo[b, other])
        assert np.all(c_hi[mine][:, other] == hi[b, other])
        seen: list[tuple[float, ...]] = []
        for c in mine:
            pts = _values(c_lo[c], c_hi[c])
            assert pts
            seen += pts
        assert len(seen) == len(set(seen)) and set(seen) == _values(lo[b], hi[b])
        if parts == 2:
            theirs = np.flatnonzero(s_tag == b)
            boxes = sorted(tuple(c_lo[c]) + tuple(c_hi[c]) for c in mine)
            assert boxes == sorted(tuple(s_lo[c]) + tuple(s_hi[c]) for c in theirs)
