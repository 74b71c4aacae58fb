"""Vectorised interval arithmetic with outward rounding, for rigorous bounds in the solver.

An :class:`Interval` holds two float arrays ``lo <= hi`` that broadcast together; every operation
returns an interval that contains the exact result for every choice of operands inside the operand
intervals (the fundamental theorem of interval arithmetic). Each result is widened outward by one
unit in the last place (``numpy.nextafter``; on arrays of :data:`_BITWISE_FROM` elements or more
the same floats by an integer step on their bit patterns, :func:`_next_up`) so that
floating-point rounding cannot make a bound too tight.

It supports what the moduli variants of :mod:`corrugate.mechanics.moduli` use (``+ - * /``, integer powers,
``np.sin``, ``np.cos``, ``np.sqrt``, ``np.abs``, ``np.maximum``), so the functions of
:func:`corrugate.mechanics.moduli.get_model` can be called with interval arguments unchanged: the solver
bounds the very formulas that :func:`corrugate.analysis.evaluate.evaluate` computes, not a copy of them.
"""

from __future__ import annotations

import math
from typing import Any, ClassVar

import numpy as np
from numpy.typing import ArrayLike, NDArray

__all__ = ["Interval", "number"]

FloatArray = NDArray[np.float64]
_INF = np.inf


#: Elements from which :func:`_up`, :func:`_down` and :func:`_down0` step by integer arithmetic
#: on the bit patterns instead of ``numpy.nextafter`` (a libm call per element, about 7 ns each:
#: 8 us for 1000 elements against 5 us; below some 500 elements the few extra array operations
#: cost more than they save). Both give the same float, bit for bit.
_BITWISE_FROM = 512


def _bitwise(x: Any) -> bool:
    """Whether ``x`` is a float64 array large enough for the integer step (:data:`_BITWISE_FROM`)."""
    return isinstance(x, np.ndarray) and x.size >= _BITWISE_FROM and x.dtype == np.float64


def _next_up(x: FloatArray) -> FloatArray:
    """``numpy.nextafter(x, inf)``, bit for bit, by integer arithmetic on the bit patterns.

    IEEE 754 binary64 orders the non-negative floats as their bit patterns read as integers,
    and the negative ones in reverse: for a float y other than a zero, an infinity or a NaN,
    the next float up has the pattern of y plus 1 when y > 0, minus 1 when y < 0 (its
    magnitude one unit in the last place smaller; -5e-324 steps to -0.0); -inf steps to
    -max (its pattern minus 1), +inf and NaN stay. Adding 0.0 first turns -0.0 into +0.0
    (round to nearest: -0 + 0 = +0), whose pattern plus 1 is 5e-324, the next float up of
    both zeros. So the step is +1 where y < inf (every finite y and -inf) and a further -2
    where y < 0: the patterns of nextafter for every input, NaN included."""
    y = x + 0.0
    step = np.less(y, _INF).view(np.int8) - np.less(y, 0.0).view(np.int8) * np.int8(2)
    return np.asarray((y.view(np.int64) + step).view(np.float64))


def _down(x: FloatArray) -> FloatArray:
    """The next float below each element (``numpy.nextafter(x, -inf)``: a lower bound of an
    exact value that rounding to nearest put at x or above): -(next float up of -x), the float
    line being symmetric."""
    if _bitwise(x):
        return np.asarray(-_next_up(-x))
    return np.nextafter(x, -_INF)


def _up(x: FloatArray) -> FloatArray:
    """The next float above each element (``numpy.nextafter(x, inf)``: an upper bound of an
    exact value that rounding to nearest put at x or below), by :func:`_next_up` on large
    arrays, the same floats."""
    if _bitwise(x):
        return _next_up(x)
    return np.nextafter(x, _INF)


def _up0(x: FloatArray) -> FloatArray:
    """:func:`_up` of an upper bound known to be >= 0 (or NaN): the upper end of an interval
    whose lower end is >= 0, so every non-empty one. On large arrays the pattern plus 1 where
    y < inf (y = x + 0.0: -0.0 becomes +0.0, whose next float up 5e-324 is that of both zeros;
    +inf and NaN stay), two array operations fewer than :func:`_next_up` and the same floats
    for every x >= 0 (it steps down a negative x: the callers have none). Stepped in place when
    ``x`` owns its data (:func:`_scratch`)."""
    if _bitwise(x):
        y = _scratch(x)
        i = y.view(np.int64)
        i += np.less(y, _INF)
        return y
    return np.nextafter(x, _INF)


def _down0(x: FloatArray) -> FloatArray:
    """Round a lower bound down when the exact value is known to be >= 0: the next float
    towards 0, and 0 itself stays 0 (a bound below 0 would be valid but needlessly loose).

    ``numpy.nextafter(x, 0)``, bit for bit, for every x >= 0 (and NaN): on large arrays the
    pattern minus 1 where y > 0 (y = x + 0.0: -0.0 becomes +0.0, as nextafter returns it; every
    positive float and +inf move one unit in the last place towards 0; +0.0 and NaN stay). A
    negative x (no caller has one: the operands are >= 0) stays x, below nextafter's step
    towards 0, so a lower bound still. Stepped in place when ``x`` owns its data
    (:func:`_scratch`)."""
    if _bitwise(x):
        y = _scratch(x)
        i = y.view(np.int64)
        i -= np.greater(y, 0.0)
        return y
    return np.nextafter(x, 0.0)


def _scratch(x: FloatArray) -> FloatArray:
    """``x + 0.0`` (-0.0 made +0.0, every other float and NaN kept), written over ``x`` itself
    when it owns its writable data: :func:`_up0` and :func:`_down0` are handed the fresh result
    of an operation (a sum, product, quotient, power or square root of the operands' ends),
    which nothing else holds, so stepping it in place saves two temporaries (about 15 % of the
    step: 3.4 against 4.0 us for 2000 elements); a view or a read-only array is copied."""
    if x.flags.owndata and x.flags.writeable:
        np.add(x, 0.0, out=x)
        return x
    return x + 0.0


def _cos_extrema(
    x_lo: FloatArray, x_hi: FloatArray, lo: FloatArray, hi: FloatArray
) -> tuple[FloatArray, FloatArray]:
    """The range (lo, hi) of cos over [x_lo, x_hi] (rad) from its endpoint values (lo, hi):
    hi made 1 where a maximum 2 k pi lies inside, lo made -1 where a minimum (2 k + 1) pi
    does."""
    k_max = np.floor(x_hi / (2 * math.pi))  # a maximum 2 k pi in [lo, hi]?
    has_max = 2 * math.pi * k_max >= x_lo
    k_min = np.floor((x_hi - math.pi) / (2 * math.pi))  # a minimum (2k + 1) pi?
    has_min = 2 * math.pi * k_min + math.pi >= x_lo
    return np.where(has_min, -1.0, lo), np.where(has_max, 1.0, hi)


def _between_extrema(x_lo: FloatArray, x_hi: FloatArray) -> bool:
    """Whether every [x_lo, x_hi] (rad) lies in (0, pi) or every one in (-pi, -1e-9) (pi: the
    float ``math.pi``), where :func:`_cos_extrema` changes nothing, as evaluated in floating
    point. In (0, pi): x_hi / 2pi < 1/2 floors to 0 and 0 >= x_lo > 0 is false; x_hi - pi < 0
    (exact or rounded, never 0), so its quotient floors to -1 and -pi >= x_lo is false. In
    (-pi, -1e-9): x_hi / 2pi lies in (-1/2, 0) without underflow and floors to -1, -2pi >= x_lo
    is false; (x_hi - pi) / 2pi lies in [-1, -1/2), floors to -1, and -pi >= x_lo is false. (A
    NaN makes it False: the general way.) The sines of the fold angles, cos(alpha / 2 - pi/2),
    and their cosines are all of the one kind or the other."""
    a = float(x_lo.min(initial=math.inf))
    b = float(x_hi.max(initial=-math.inf))
    return (a > 0.0 and b < math.pi) or (-math.pi < a and b < -1e-9)


def _arr(x: ArrayLike) -> FloatArray:
    return np.asarray(x, dtype=np.float64)


class Interval:
    """Closed intervals ``[lo, hi]`` elementwise (arrays broadcast together)."""

    __slots__ = ("_nn", "hi", "lo")
    #: Make ``ndarray <op> Interval`` dispatch to :meth:`__array_ufunc__`.
    __array_priority__ = 1000

    def __init__(self, lo: ArrayLike, hi: ArrayLike | None = None) -> None:
        lo_a = _arr(lo)
        hi_a = lo_a if hi is None else _arr(hi)
        if lo_a.shape == hi_a.shape:
            self.lo, self.hi = lo_a, hi_a
        else:
            self.lo, self.hi = np.broadcast_arrays(lo_a, hi_a)
        self._nn: bool | None = None

    @property
    def nonneg(self) -> bool:
        """Whether every lower bound is >= 0 (checked once, then known; results of operations
        on non-negative intervals know it without a check)."""
        if self._nn is None:
            self._nn = bool(self.lo.min(initial=0.0) >= 0)  # False with a NaN
        return self._nn

    # -- helpers -----------------------------------------------------------------------------
    @staticmethod
    def of(x: Interval | ArrayLike) -> Interval:
        """``x`` itself, or a point interval of the number/array ``x``."""
        if isinstance(x, Interval):
            return x
        if isinstance(x, np.ndarray) and x.dtype == object and x.ndim == 0:
            return Interval.of(x.item())
        return Interval(x)

    @property
    def mid(self) -> FloatArray:
        return np.asarray(0.5 * (self.lo + self.hi))

    def __repr__(self) -> str:
        return f"Interval(lo={self.lo!r}, hi={self.hi!r})"

    # -- arithmetic --------------------------------------------------------------------------
    def __add__(self, other: Interval | ArrayLike) -> Interval:
        if isinstance(other, float | int):  # a number: no conversion
            if other >= 0 and self._nn:
                return Interval._raw(_down0(self.lo + other), _up0(self.hi + other), True)
            return Interval(_down(self.lo + other), _up(self.hi + other))
        o = Interval.of(other)
        if self._nn and o._nn:
            return Interval._raw(_down0(self.lo + o.lo), _up0(self.hi + o.hi), True)
        return Interval(_down(self.lo + o.lo), _up(self.hi + o.hi))

    __radd__ = __add__

    def __neg__(self) -> Interval:
        return Interval(-self.hi, -self.lo)

    def __sub__(self, other: Interval | ArrayLike) -> Interval:
        if isinstance(other, float | int):
            return Interval(_down(self.lo - other), _up(self.hi - other))
        o = Interval.of(other)
        return Interval(_down(self.lo - o.hi), _up(self.hi - o.lo))

    def __rsub__(self, other: Interval | ArrayLike) -> Interval:
        return Interval.of(other) - self

    @classmethod
    def _raw(cls, lo: FloatArray, hi: FloatArray, nonneg: bool | None = None) -> Interval:
        """An interval from arrays of one shape (no copy, no checks); ``nonneg`` if known."""
        out = cls.__new__(cls)
        out.lo, out.hi, out._nn = lo, hi, nonneg
        return out

    def __mul__(self, other: Interval | ArrayLike) -> Interval:
        if isinstance(other, float | int) and math.isfinite(other):  # a number: scale
            if other >= 0:
                if self._nn:
                    return Interval._raw(_down0(self.lo * other), _up0(self.hi * other), True)
                return Interval._raw(_down(self.lo * other), _up(self.hi * other))
            return Interval._raw(_down(self.hi * other), _up(self.lo * other))
        if not isinstance(other, Interval):
            c = np.asarray(
                other.item() if isinstance(other, np.ndarray) and other.dtype == object else other,
                dtype=np.float64,
            )
            if c.ndim == 0 and math.isfinite(float(c)):  # scale by a number
                cv = float(c)
                lo, hi = (self.lo, self.hi) if cv >= 0 else (self.hi, self.lo)
                return Interval._raw(_down(lo * cv), _up(hi * cv))
            other = Interval(c)
        o = other
        if self.nonneg and o.nonneg:  # both non-negative: the usual case here
            lo, hi = self.lo * o.lo, self.hi * o.hi
            if lo.shape == hi.shape and not np.isnan(hi.max(initial=0.0)):  # no 0 * inf
                return Interval._raw(_down0(lo), _up0(hi), True)
        with np.errstate(invalid="ignore"):
            p = np.stack(
                np.broadcast_arrays(self.lo * o.lo, self.lo * o.hi, self.hi * o.lo, self.hi * o.hi)
            )
        p = np.where(np.isnan(p), 0.0, p)  # 0 * inf inside an unbounded interval
        return Interval(_down(p.min(axis=0)), _up(p.max(axis=0)))

    __rmul__ = __mul__

    def reciprocal(self) -> Interval:
        """1 / x; the whole real line when the interval contains 0."""
        contains_zero = (self.lo <= 0) & (self.hi >= 0)
        with np.errstate(divide="ignore", invalid="ignore", over="ignore"):
            lo = np.where(contains_zero, -_INF, _down(1.0 / self.hi))
            hi = np.where(contains_zero, _INF, _up(1.0 / self.lo))
        return Interval(lo, hi)

    def __truediv__(self, other: Interval | ArrayLike) -> Interval:
        if isinstance(other, float | int) and other != 0 and math.isfinite(other):
            lo, hi = (self.lo, self.hi) if other > 0 else (self.hi, self.lo)
            return Interval._raw(_down(lo / other), _up(hi / other))
        o = Interval.of(other)
        if (
            self.nonneg and o.lo.min(initial=1.0) > 0 and np.isfinite(o.hi.max(initial=0.0))
        ):  # x >= 0 over finite y > 0: [x_lo / y_hi, x_hi / y_lo], one rounding each
            lo, hi = self.lo / o.hi, self.hi / o.lo
            if lo.shape == hi.shape:
                return Interval._raw(_down0(lo), _up0(hi), True)
        return self * o.reciprocal()

    def __rtruediv__(self, other: Interval | ArrayLike) -> Interval:
        return Interval.of(other) / self

    def __pow__(self, k: int) -> Interval:
        if not (isinstance(k, int | np.integer) and k >= 0):
            raise TypeError("Interval ** k needs a non-negative integer k")
        k = int(k)
        if k == 0:
            return Interval(np.ones_like(self.lo))
        if k == 1:
            return self
        a, b = self.lo**k, self.hi**k
        if self._nn:  # x >= 0: x^k increasing
            return Interval._raw(_down0(a), _up0(b), True)
        if k % 2 == 1:
            return Interval(_down(a), _up(b))
        lo = np.where((self.lo <= 0) & (self.hi >= 0), 0.0, np.minimum(a, b))
        return Interval(_down(lo), _up(np.maximum(a, b)))

    def abs(self) -> Interval:
        lo = np.where(self.lo >= 0, self.lo, np.where(self.hi <= 0, -self.hi, 0.0))
        hi = np.maximum(np.abs(self.lo), np.abs(self.hi))
        return Interval(lo, hi)

    def maximum(self, other: Interval | ArrayLike) -> Interval:
        """max(x, y): monotone in both, so the bounds are the endpoints' maxima (exact)."""
        o = Interval.of(other)
        return Interval(np.maximum(self.lo, o.lo), np.maximum(self.hi, o.hi))

    def minimum(self, other: Interval | ArrayLike) -> Interval:
        """min(x, y): monotone in both, so the bounds are the endpoints' minima (exact)."""
        o = Interval.of(other)
        return Interval(np.minimum(self.lo, o.lo), np.minimum(self.hi, o.hi))

    def sqrt(self) -> Interval:
        return Interval._raw(
            _down0(np.sqrt(np.maximum(self.lo, 0.0))), _up0(np.sqrt(self.hi)), True
        )

    def cos(self) -> Interval:
        """cos over the interval: endpoint values, widened to +-1 where a multiple of pi lies
        inside (cos has its extrema at k pi; :func:`_cos_extrema`, skipped when every interval
        lies inside (0, pi) or (-pi, -1e-9), where it widens none: :func:`_between_extrema`)."""
        lo_v, hi_v = np.cos(self.lo), np.cos(self.hi)
        lo = np.minimum(lo_v, hi_v)
        hi = np.maximum(lo_v, hi_v)
        if not _between_extrema(self.lo, self.hi):
            lo, hi = _cos_extrema(self.lo, self.hi, lo, hi)
        return Interval(np.maximum(_down(lo), -1.0), np.minimum(_up(hi), 1.0))

    def sin(self) -> Interval:
        """sin x = cos(x - pi/2)."""
        return (self - math.pi / 2).cos()

    # -- numpy interoperability ----------------------------------------------------------------
    _UFUNCS: ClassVar[dict[Any, str]] = {
        np.add: "add",
        np.subtract: "sub",
        np.multiply: "mul",
        np.true_divide: "div",
        np.power: "pow",
        np.negative: "neg",
        np.sin: "sin",
        np.cos: "cos",
        np.sqrt: "sqrt",
        np.absolute: "abs",
        np.maximum: "max",
        np.minimum: "min",
    }

    def __array_ufunc__(self, ufunc: Any, method: str, *inputs: Any, **kwargs: Any) -> Any:
        if method != "__call__" or kwargs or ufunc not in self._UFUNCS:
            return NotImplemented
        name = self._UFUNCS[ufunc]
        if name in {"neg", "sin", "cos", "sqrt", "abs"}:
            x = Interval.of(inputs[0])
            return {"neg": x.__neg__, "sin": x.sin, "cos": x.cos, "sqrt": x.sqrt, "abs": x.abs}[
                name
            ]()
        a, b = inputs
        if name == "pow":
            k = np.asarray(b)
            if not isinstance(a, Interval) or k.ndim != 0 or not float(k).is_integer():
                return NotImplemented
            return a ** int(k)
        x, y = Interval.of(a), Interval.of(b)
        if name == "add":
            return x + y
        if name == "sub":
            return x - y
        if name == "mul":
            return x * y
        if name == "max":
            return x.maximum(y)
        if name == "min":
            return x.minimum(y)
        return x / y


def number(x: Any) -> Any:
    """``x`` as a float, or ``x`` itself when it is an :class:`Interval` (a sheet's E or t over
    its worst-case tolerances, :mod:`corrugate.solver.tolerance_box`)."""
    return x if isinstance(x, Interval) else float(x)
