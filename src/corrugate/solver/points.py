"""Design points and boxes of the solver as typed values (docs/theory.md section 5).

A design of the solver is, per layer, the integer creases ``n``, the facet width ``W`` (mm) and
the fold angle ``alpha`` (deg): a :class:`LayerPoints` holds them for many points at once (arrays
that broadcast together, or floats for one point), with optional per-point overrides of the
sheet's Young's modulus ``E`` (MPa) and thickness ``t`` (mm) (the tolerance analysis). A
:class:`DesignPoints` holds the layers of a design: ``count`` layers, of which only the distinct
ones are stored, so identical layers (the problem's ``identical``: layer 2 is layer 1) are one
stored layer that :meth:`DesignPoints.layer` returns for every index. A box of the branch and
bound is a pair ``(lo, hi)`` of :class:`DesignPoints` (``lo is hi``: the boxes are points).

The search's flat coordinates (one column per variable of each searched layer, in the order of
:data:`VARIABLES`, layer by layer) are :func:`coordinates`; :meth:`DesignPoints.from_columns`
and :meth:`DesignPoints.columns` convert between them and the typed value. A new design variable
of a layer (a profile parameter) is a new field of :class:`LayerPoints` and its entry in
:data:`VARIABLES` and :func:`coordinates`; a new layer is a larger ``count``.
"""

from __future__ import annotations

from dataclasses import dataclass, replace
from typing import Any

import numpy as np
from numpy.typing import NDArray

from corrugate.geometry.profile import ZIGZAG, ProfileKind
from corrugate.solver.problem import DesignVariable, Problem

__all__ = [
    "LAYERS",
    "VARIABLES",
    "Coordinate",
    "DesignPoints",
    "LayerPoints",
    "blank_width",
    "coordinates",
]

FloatArray = NDArray[np.float64]

#: The design variables of one layer (fields of :class:`LayerPoints`), in the search's order.
VARIABLES: tuple[str, ...] = ("n", "W", "alpha")
#: The layers of a design unless told (:attr:`~.problem.Problem.layer_count`).
LAYERS = 2


@dataclass(frozen=True, slots=True)
class LayerPoints:
    """One layer at many points: creases ``n`` (integer values as floats), facet width ``W``
    (mm), fold angle ``alpha`` (deg), and, when set, the sheet's Young's modulus ``E`` (MPa)
    and thickness ``t`` (mm) at each point instead of its candidate sheet's."""

    n: Any
    W: Any
    alpha: Any
    E: Any = None
    t: Any = None

    def take(self, sel: Any) -> LayerPoints:
        """The points ``sel`` (an index or mask) of each array."""
        return LayerPoints(
            *(None if v is None else np.asarray(v)[sel] for v in (self.n, self.W, self.alpha)),
            *(None if v is None else np.asarray(v)[sel] for v in (self.E, self.t)),
        )

    @property
    def overrides(self) -> bool:
        """Whether E or t is given per point."""
        return self.E is not None or self.t is not None


def blank_width(b: LayerPoints, kind: ProfileKind = ZIGZAG) -> FloatArray:
    """The flat blank across the creases of the layer ``b`` folded to ``kind`` (mm): (n + 1) W
    for the zig-zag, (n + 1) developed for another profile
    (:meth:`corrugate.geometry.profile.Profile.flat_width`). It grows with n and W (and does not
    fall with alpha: :class:`~corrugate.geometry.profile.ProfileKind`), so a box's corners
    bound it."""
    n, W = np.asarray(b.n, np.float64), np.asarray(b.W, np.float64)
    if kind.is_default:
        return np.asarray((n + 1) * W)
    return np.asarray(kind.of(W, np.asarray(b.alpha, np.float64)).flat_width(n))


@dataclass(frozen=True, slots=True)
class DesignPoints:
    """The layers of a design at many points (module docstring): ``layers`` are the distinct
    ones, ``count`` the design's; one stored layer of a two-layer design is both layers."""

    layers: tuple[LayerPoints, ...]
    count: int = LAYERS

    def __post_init__(self) -> None:
        if not 1 <= len(self.layers) <= self.count:
            raise ValueError(f"{len(self.layers)} layers stored for a design of {self.count}")

    @classmethod
    def of(cls, *layers: LayerPoints, count: int = LAYERS) -> DesignPoints:
        """A design of ``count`` layers from its distinct ``layers`` (one: identical layers)."""
        return cls(tuple(layers), count)

    @property
    def identical(self) -> bool:
        """Whether every layer is the first (one stored layer)."""
        return len(self.layers) == 1 < self.count

    def layer(self, i: int) -> LayerPoints:
        """Layer ``i`` (0-based): the first for identical layers."""
        if not 0 <= i < self.count:
            raise IndexError(f"layer {i} of a design of {self.count}")
        return self.layers[i] if i < len(self.layers) else self.layers[0]

    def __len__(self) -> int:
        return int(np.size(self.layers[0].n))

    def take(self, sel: Any) -> DesignPoints:
        """The points ``sel`` (an index array or mask) of every layer."""
        return DesignPoints(tuple(lay.take(sel) for lay in self.layers), self.count)

    def point(self, k: int) -> DesignPoints:
        """Point ``k`` as Python floats (a search's answer)."""
        return DesignPoints(
            tuple(
                LayerPoints(*(float(np.asarray(getattr(lay, v))[k]) for v in VARIABLES))
                for lay in self.layers
            ),
            self.count,
        )

    def arrays(self) -> DesignPoints:
        """One point (floats) as arrays of one point, for the vectorised quantities."""
        return DesignPoints(
            tuple(
                LayerPoints(
                    *(None if v is None else np.array([v]) for v in (lay.n, lay.W, lay.alpha)),
                    *(None if v is None else np.array([v]) for v in (lay.E, lay.t)),
                )
                for lay in self.layers
            ),
            self.count,
        )

    @classmethod
    def from_columns(cls, values: FloatArray, count: int = LAYERS) -> DesignPoints:
        """The points of the rows of ``values`` (points x coordinates, :func:`coordinates`'
        order): ``len(VARIABLES)`` columns per stored layer."""
        per = len(VARIABLES)
        stored = values.shape[1] // per
        return cls(
            tuple(
                LayerPoints(*(values[:, per * i + j] for j in range(per))) for i in range(stored)
            ),
            count,
        )

    def columns(self) -> FloatArray:
        """The points as rows (points x coordinates, :func:`coordinates`' order)."""
        return np.stack(
            [
                np.asarray(getattr(lay, v), dtype=np.float64)
                for lay in self.layers
                for v in VARIABLES
            ],
            axis=1,
        )

    def with_layers(self, *layers: LayerPoints) -> DesignPoints:
        """The same design with other stored layers."""
        return replace(self, layers=tuple(layers))


@dataclass(frozen=True, slots=True)
class Coordinate:
    """One coordinate of the search: ``variable`` (a field of :class:`LayerPoints`) of stored
    layer ``layer`` (0-based), ranging over ``var`` (n: a grid of step 1)."""

    layer: int
    variable: str
    var: DesignVariable


def coordinates(problem: Problem, n_fixed: tuple[int, int] | None = None) -> list[Coordinate]:
    """The coordinates the search of ``problem`` spans (n within ``n_fixed`` when given): the
    variables of each layer the search spans (:attr:`~.problem.Problem.searched_layers`: layer 1
    alone for identical layers), layer by layer."""
    n_lo, n_hi = (problem.n_lo, problem.n_hi) if n_fixed is None else n_fixed
    var = {"n": DesignVariable(float(n_lo), float(n_hi), 1.0), "W": problem.W}
    var["alpha"] = problem.alpha
    return [Coordinate(i, v, var[v]) for i in range(problem.searched_layers) for v in VARIABLES]
