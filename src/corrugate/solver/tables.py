"""Per-n tables of a layout that the solver's bounds read (docs/theory.md 3.2).

The facets of a layer on an outline other than a rectangle differ in length; with S the other
layer's extent, Q(n) = S sum_j 1/L_j and F(n) = max_j L_j / S depend on n alone
(:mod:`corrugate.geometry.layouts`), so they are tabulated once per problem, and their minimum and
maximum over a range of n come from a sparse table (:class:`RangeTable`).
"""

from __future__ import annotations

from dataclasses import dataclass
from functools import cached_property

import numpy as np
from numpy.typing import NDArray

from corrugate.geometry.layouts import Rectangle, facet_lengths, inverse_length_sum
from corrugate.solver.problem import Problem

__all__ = ["RangeTable", "Tables"]

FloatArray = NDArray[np.float64]


class RangeTable:
    """Minimum and maximum of a table f(n), n = n0..n1, over index ranges (sparse table)."""

    def __init__(self, n0: int, values: FloatArray) -> None:
        self.n0 = n0
        v = np.asarray(values, dtype=np.float64)
        d = np.diff(v)
        #: +1 if f is non-decreasing in n, -1 if non-increasing, 0 otherwise (then the table)
        self.monotone = 1 if np.all(d >= 0) else (-1 if np.all(d <= 0) else 0)
        self._values = v
        self._min: list[FloatArray] = []
        self._max: list[FloatArray] = []
        if not self.monotone:  # a monotone f needs no table (its extremes are at the ends)
            self._min.append(v)
            self._max.append(v)
            k = 1
            while 2 * k <= len(v):
                a, b = self._min[-1], self._max[-1]
                self._min.append(np.minimum(a[:-k], a[k:]))
                self._max.append(np.maximum(b[:-k], b[k:]))
                k *= 2

    def bounds(self, lo: FloatArray, hi: FloatArray) -> tuple[FloatArray, FloatArray]:
        """min and max of f over n in [lo, hi] (arrays of integers)."""
        i = np.asarray(lo, dtype=np.int64) - self.n0
        j = np.asarray(hi, dtype=np.int64) - self.n0
        if self.monotone:  # the extremes sit at the ends of the range
            a, b = self._values[i], self._values[j]
            return (a, b) if self.monotone > 0 else (b, a)
        length = j - i + 1
        level = np.floor(np.log2(np.maximum(length, 1))).astype(np.int64)
        mins = np.empty(i.shape)
        maxs = np.empty(i.shape)
        # the levels present (not np.unique: it imports numpy.ma, 0.1 s, on its first call)
        for lv in np.flatnonzero(np.bincount(level)):
            sel = level == lv
            k = 1 << int(lv)
            a, b = i[sel], j[sel] - k + 1
            mins[sel] = np.minimum(self._min[lv][a], self._min[lv][b])
            maxs[sel] = np.maximum(self._max[lv][a], self._max[lv][b])
        return mins, maxs


@dataclass(frozen=True)
class Tables:
    """Per-n tables of the layout for a problem: Q(n) = (n + 1) G(n) and F(n), per axis."""

    problem: Problem

    def _table(self, what: str, axis: str) -> RangeTable:
        p = self.problem
        ns = np.arange(p.n_lo, p.n_hi + 1)
        if what == "Q":
            vals = inverse_length_sum(p.layout, ns, 1.0, axis)  # type: ignore[arg-type]
        elif isinstance(p.layout, Rectangle):
            vals = np.ones(len(ns))
        else:
            pick = np.max if what == "F" else np.min
            vals = np.array(
                [
                    pick(facet_lengths(p.layout, int(k), 1.0, axis))  # type: ignore[arg-type]
                    for k in ns
                ]
            )
        return RangeTable(p.n_lo, np.asarray(vals, dtype=np.float64))

    @cached_property
    def Qx(self) -> RangeTable:
        return self._table("Q", "x")

    @cached_property
    def Qy(self) -> RangeTable:
        return self._table("Q", "y")

    @cached_property
    def Fx(self) -> RangeTable:
        return self._table("F", "x")

    @cached_property
    def Fy(self) -> RangeTable:
        return self._table("F", "y")

    @cached_property
    def Fmin_x(self) -> RangeTable:
        """min_j L_j / S per n (layer 1), for the bounds with holes."""
        return self._table("Fmin", "x")

    @cached_property
    def Fmin_y(self) -> RangeTable:
        return self._table("Fmin", "y")

    def facet_factor(self, n: FloatArray, axis: str) -> FloatArray:
        """F(n) = max_j L_j / S at integer n (array)."""
        table = self.Fx if axis == "x" else self.Fy
        return table.bounds(n, n)[0]
