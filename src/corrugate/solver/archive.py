"""The archive of a branch and bound: every box it closed, in flat arrays, for the explanation.

The branch and bound (:mod:`.bnb`) tells its recorder each box it closes and why: closed by the
incumbent (:meth:`Recorder.closed`), shown to break constraints (:meth:`Recorder.infeasible`),
or enumerated point by point (:meth:`Recorder.dropped`, :meth:`Recorder.enumerated`). A search
that keeps no archive gets a :class:`NoRecorder`, which has the same methods and keeps nothing.
The explained answer (:mod:`.solve`: binding checks, runner-ups) and the diagnosis
(:mod:`.diagnosis`) reopen the archive's boxes instead of searching the whole domain again
(docs/theory.md section 5).
"""

from __future__ import annotations

import functools
import math
from dataclasses import dataclass

import numpy as np
from numpy.typing import NDArray

__all__ = [
    "ARCHIVE_DEPTH",
    "ARCHIVE_ROWS",
    "Archive",
    "NoRecorder",
    "Recorder",
    "bit_sets",
    "distinct",
]

FloatArray = NDArray[np.float64]
BoolArray = NDArray[np.bool_]

#: Rows the archive of a search keeps at most (about 110 bytes each for 6 coordinates): past
#: it the archive is dropped and the explanation re-solves instead.
ARCHIVE_ROWS = 1_000_000
#: The archive keeps boxes shown to break at most this many constraints (what the explanation
#: relaxes at once: one for the binding checks, two for the diagnosis' partners and pairs).
ARCHIVE_DEPTH = 2


#: Constraints up to which a bit set is summed in floating point (exact: every sum of distinct
#: powers of two below 2^53 is a float64) and up to which :func:`distinct` uses a table.
_EXACT_BITS = 52
_TABLE_BITS = 16


@functools.cache
def _weights(ncons: int) -> FloatArray:
    """(ncons x 2): the powers of two and ones that :func:`bit_sets` multiplies by."""
    out = np.stack([2.0 ** np.arange(ncons), np.ones(ncons)], axis=1)
    out.flags.writeable = False
    return out


def bit_sets(broken: BoolArray) -> tuple[NDArray[np.uint64], NDArray[np.int64]]:
    """Per row of ``broken`` (rows x constraints, at most 63), the bit set of its True entries
    (bit i: constraint i) and how many there are: one product with the powers of two and ones
    (exact integers in float64 up to :data:`_EXACT_BITS` constraints), else bit by bit."""
    rows, ncons = broken.shape
    if ncons <= _EXACT_BITS:
        both = broken.view(np.uint8) @ _weights(ncons)
        return both[:, 0].astype(np.uint64), both[:, 1].astype(np.int64)
    mask = np.zeros(rows, dtype=np.uint64)
    for i in range(ncons):
        mask |= broken[:, i].astype(np.uint64) << np.uint64(i)
    return mask, np.count_nonzero(broken, axis=1).astype(np.int64)


def distinct(mask: NDArray[np.uint64], ncons: int) -> tuple[NDArray[np.uint64], NDArray[np.int64]]:
    """The distinct bit sets of ``mask`` (ascending) and the index of each row's among them,
    as ``np.unique(mask, return_inverse=True)``: for at most :data:`_TABLE_BITS` constraints
    by a table of every bit set (no sort), else by ``np.unique``."""
    if ncons > _TABLE_BITS:
        found, index = np.unique(mask, return_inverse=True)
        return found, index.reshape(-1).astype(np.int64)
    present = np.zeros(1 << ncons, dtype=bool)
    m = mask.astype(np.int64)
    present[m] = True
    values = np.flatnonzero(present)
    rank = np.zeros(1 << ncons, dtype=np.int64)  # touched only at the bit sets present
    rank[values] = np.arange(len(values))
    return values.astype(np.uint64), rank[m]


@dataclass(frozen=True)
class Archive:
    """The closed boxes of a finished search, in flat arrays, for the explanation to reopen.

    Row k is a box ``lo[k] <= x <= hi[k]`` (the search's coordinates, :func:`.bnb._dims`) with
    ``bound[k]`` a lower bound of sign * objective over it (-inf when none was computed) and
    ``mask[k]`` a bit set of constraints (bit i: ``problem.constraints[i]``) each shown to be
    broken by every design of the box, or, for a box whose points were each evaluated, by some
    of its points. The boxes of a search cover its whole domain; the archive holds all of them
    except those shown to break more than :data:`ARCHIVE_DEPTH` constraints. So the designs
    that meet every constraint but those of a set R lie in the rows with ``mask`` inside R
    (:meth:`reopen`), and those better than the incumbent in the rows whose bound is below it.
    The mask of a box may miss constraints that were not bounded on it (a smaller mask reopens
    more, never less).
    """

    lo: FloatArray
    hi: FloatArray
    bound: FloatArray
    mask: NDArray[np.uint64]

    def reopen(
        self, relaxed: int = 0, below: float = math.inf
    ) -> tuple[FloatArray, FloatArray, FloatArray]:
        """The boxes (lo, hi, bound) that may hold a design meeting every constraint outside the
        bit set ``relaxed`` with sign * objective below ``below``."""
        sel = (self.mask & ~np.uint64(relaxed)) == 0
        if math.isfinite(below):
            sel &= self.bound < below
        return self.lo[sel], self.hi[sel], self.bound[sel]


class NoRecorder:
    """The recorder of a search that keeps no archive: every event is dropped (the methods of
    :class:`Recorder`, which documents them)."""

    def closed(self, lo: FloatArray, hi: FloatArray, bound: FloatArray, sel: BoolArray) -> None:
        """Nothing kept."""

    def infeasible(
        self, lo: FloatArray, hi: FloatArray, bound: FloatArray, broken: BoolArray, sel: BoolArray
    ) -> None:
        """Nothing kept."""

    def dropped(
        self,
        lo: FloatArray,
        hi: FloatArray,
        bound: FloatArray,
        dropped: list[tuple[NDArray[np.int64], BoolArray]],
    ) -> None:
        """Nothing kept."""

    def enumerated(
        self,
        lo: FloatArray,
        hi: FloatArray,
        bound: FloatArray,
        points: tuple[NDArray[np.int64], BoolArray, FloatArray, BoolArray],
        evaluated: tuple[BoolArray, FloatArray],
    ) -> None:
        """Nothing kept."""

    def archive(self, ndim: int) -> Archive | None:
        """None: no archive."""
        return None

    def child(self) -> NoRecorder:
        """A recorder whose rows :meth:`adopt` appends later (here: this one, keeping nothing)."""
        return self

    def adopt(self, other: NoRecorder) -> None:
        """Append the rows of ``other`` (a :meth:`child`), in its order (here: nothing)."""


class Recorder(NoRecorder):
    """Collects the closed boxes of a search into an :class:`Archive` (chunks of flat arrays),
    in the order the search closes them."""

    def __init__(self, ncons: int) -> None:
        self.ncons = ncons
        self.ok = ncons <= 63
        self.bits = np.uint64(1) << np.arange(max(ncons, 1), dtype=np.uint64)
        self.parts: list[tuple[FloatArray, FloatArray, FloatArray, NDArray[np.uint64]]] = []
        self.rows = 0

    def closed(self, lo: FloatArray, hi: FloatArray, bound: FloatArray, sel: BoolArray) -> None:
        """The boxes ``sel`` of (lo, hi, bound), closed with no constraint shown broken (by the
        incumbent, or single points already evaluated)."""
        self.add(lo[sel], hi[sel], bound[sel])

    def infeasible(
        self, lo: FloatArray, hi: FloatArray, bound: FloatArray, broken: BoolArray, sel: BoolArray
    ) -> None:
        """The boxes ``sel`` of (lo, hi, bound), closed by the constraints their rows of
        ``broken`` (boxes x constraints) show broken everywhere in them."""
        rows = np.flatnonzero(sel)
        if not len(rows) or not self.ok:
            return
        mask, kept = self.masks(broken[rows])
        rows = rows[kept]
        self.add(lo[rows], hi[rows], bound[rows], mask[kept])

    def dropped(
        self,
        lo: FloatArray,
        hi: FloatArray,
        bound: FloatArray,
        dropped: list[tuple[NDArray[np.int64], BoolArray]],
    ) -> None:
        """Enumerated boxes (lo, hi, bound): per layer, the points dropped because that layer
        alone breaks a bound (their boxes and broken constraints); each bounded by its box's
        bound."""
        for own, why in dropped:
            mask, kept = self.masks(why)
            self.add_points(lo, hi, bound, own[kept], mask[kept], bound[own[kept]])

    def enumerated(
        self,
        lo: FloatArray,
        hi: FloatArray,
        bound: FloatArray,
        points: tuple[NDArray[np.int64], BoolArray, FloatArray, BoolArray],
        evaluated: tuple[BoolArray, FloatArray],
    ) -> None:
        """Enumerated boxes (lo, hi, bound) from their points: ``points`` = (the box of each, its
        cheap constraints shown broken, a lower bound of its sign * objective, whether it was
        evaluated exactly); ``evaluated`` = (the constraints each point evaluated breaks, its
        sign * objective), which replace the bounds of those points."""
        owner, broken, point_bound, ok = points
        mask, kept = self.masks(broken)
        pb = np.array(point_bound, dtype=np.float64)
        p_broken, p_value = evaluated
        if len(p_value):  # the points evaluated: every constraint, and their objective
            full, full_kept = self.masks(p_broken)
            mask[ok], kept[ok] = full, full_kept
            pb[ok] = p_value
        self.add_points(lo, hi, bound, owner[kept], mask[kept], pb[kept])

    def masks(self, broken: BoolArray) -> tuple[NDArray[np.uint64], BoolArray]:
        """Bit sets of the rows of ``broken`` (boxes x constraints), and which rows to keep
        (:func:`bit_sets`)."""
        if not broken.shape[1]:
            return np.zeros(len(broken), dtype=np.uint64), np.ones(len(broken), dtype=bool)
        mask, count = bit_sets(broken)
        return mask, count <= ARCHIVE_DEPTH

    def add(
        self,
        lo: FloatArray,
        hi: FloatArray,
        bound: FloatArray,
        mask: NDArray[np.uint64] | None = None,
    ) -> None:
        """Rows (lo, hi, bound, mask; no mask: nothing shown broken)."""
        if not self.ok or not len(lo):
            return
        if mask is None:
            mask = np.zeros(len(lo), dtype=np.uint64)
        self.rows += len(lo)
        if self.rows > ARCHIVE_ROWS:  # memory bounded: no archive (the explanation re-solves)
            self.ok = False
            self.parts = []
            return
        self.parts.append((lo, hi, np.broadcast_to(bound, (len(lo),)).copy(), mask))

    def add_points(
        self,
        lo: FloatArray,
        hi: FloatArray,
        bound: FloatArray,
        owner: NDArray[np.int64],
        mask: NDArray[np.uint64],
        value: FloatArray,
    ) -> None:
        """Enumerated boxes (lo, hi, bound) from their points: point k lies in box ``owner[k]``,
        breaks the constraints of ``mask[k]`` and has sign * objective >= ``value[k]``. One row
        per box and bit set, bounded by the least value of its points."""
        if not self.ok or not len(owner):
            return
        masks, m_id = distinct(mask, self.ncons)  # few distinct bit sets
        key = owner.astype(np.int64) * len(masks) + m_id
        # a dense (box, bit set) table instead of sorting the keys: the same rows, in key order
        table = np.full(len(lo) * len(masks), np.inf)
        np.minimum.at(table, key, value)
        seen = np.zeros(len(table), dtype=bool)
        seen[key] = True
        groups = np.flatnonzero(seen)
        least = table[groups]
        b = groups // len(masks)
        self.add(lo[b], hi[b], np.maximum(bound[b], least), masks[groups % len(masks)])

    def child(self) -> Recorder:
        """An empty recorder of the same constraints: the rows of a step that must come after
        rows logged later (the enumerated grid points after the pairs dropped per layer)."""
        return Recorder(self.ncons)

    def adopt(self, other: NoRecorder) -> None:
        """Append the rows of ``other`` (a :meth:`child`), in its order, within
        :data:`ARCHIVE_ROWS`."""
        if not isinstance(other, Recorder):
            return
        if not other.ok:
            self.ok, self.parts = False, []
            return
        for lo, hi, bound, mask in other.parts:
            self.add(lo, hi, bound, mask)

    def archive(self, ndim: int) -> Archive | None:
        """The rows kept, as an :class:`Archive` (None past :data:`ARCHIVE_ROWS` or with more
        than 63 constraints)."""
        if not self.ok:
            return None
        if not self.parts:
            e = np.empty((0, ndim))
            return Archive(e, e, np.empty(0), np.empty(0, dtype=np.uint64))
        return Archive(*(np.concatenate(c) for c in zip(*self.parts, strict=True)))
