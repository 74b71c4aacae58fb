"""The outward rounding of :mod:`corrugate.solver.interval` on large arrays (integer steps on the
bit patterns) against ``numpy.nextafter`` (the second method: the libm step it replaces), bit
for bit, and the interval operations' containment at random points on arrays that take it."""

from __future__ import annotations

import math

import numpy as np
from hypothesis import given, settings
from hypothesis import strategies as st
from hypothesis.extra.numpy import arrays

from corrugate.solver import interval as iv
from corrugate.solver.interval import Interval

N = iv._BITWISE_FROM  # the smallest array that takes the integer step

SPECIAL = np.array(
    [
        0.0,
        -0.0,
        5e-324,
        -5e-324,
        2.0**-1022,
        -(2.0**-1022),
        np.nextafter(2.0**-1022, 0.0),
        1.0,
        -1.0,
        np.nextafter(1.0, 0.0),
        np.nextafter(-1.0, 0.0),
        1.7976931348623157e308,
        -1.7976931348623157e308,
        np.inf,
        -np.inf,
        np.nan,
        -np.nan,
    ]
)


def _same_bits(a: np.ndarray, b: np.ndarray) -> bool:
    """Equal bit patterns, any NaN equal to any NaN (nextafter keeps a NaN's payload)."""
    nan = np.isnan(a) & np.isnan(b)
    return bool(np.all((a.view(np.int64) == b.view(np.int64)) | nan))


def _padded(x: np.ndarray) -> np.ndarray:
    """``x`` repeated to at least :data:`N` elements (so the integer step is taken)."""
    return np.resize(x, max(N, len(x)))


def _check(x: np.ndarray) -> None:
    with np.errstate(all="ignore"):
        assert _same_bits(iv._up(x), np.nextafter(x, np.inf))
        assert _same_bits(iv._down(x), np.nextafter(x, -np.inf))
        nonneg = np.where(x < 0, -x, x)  # -0.0 kept: both zeros
        want_down, want_up = np.nextafter(nonneg, 0.0), np.nextafter(nonneg, np.inf)
        # (_down0 and _up0 step an array that owns its data in place: a copy each)
        assert _same_bits(iv._down0(nonneg.copy()), want_down)
        assert _same_bits(iv._up0(nonneg.copy()), want_up)
        flat = nonneg.ravel()
        view = np.broadcast_to(flat, (2, flat.size))[1]  # not its own data: left as it is
        assert _same_bits(iv._up0(view), want_up.ravel())
        assert _same_bits(iv._down0(view), want_down.ravel())
        assert _same_bits(view, flat)


def test_specials_bit_for_bit() -> None:
    """Zeros of both signs, subnormals, the binade edges, the largest float, infinities and
    NaNs step to exactly the floats nextafter gives (on arrays large and small)."""
    assert iv._bitwise(_padded(SPECIAL))
    assert not iv._bitwise(SPECIAL)
    _check(_padded(SPECIAL))
    _check(SPECIAL)


def test_random_patterns_bit_for_bit() -> None:
    """Every float64 bit pattern is as likely: 200 000 of them, all the binades and signs."""
    bits = np.random.default_rng(7).integers(-(2**63), 2**63 - 1, size=200_000, dtype=np.int64)
    _check(bits.view(np.float64))


@settings(max_examples=60, deadline=None)
@given(arrays(np.float64, st.integers(N, N + 40), elements=st.floats(allow_subnormal=True)))
def test_hypothesis_bit_for_bit(x: np.ndarray) -> None:
    _check(x)


def test_views_and_shapes() -> None:
    """Strided, broadcast and 2-D arrays step as nextafter steps them (the step makes its own
    contiguous copy), and the input is left as it was."""
    rng = np.random.default_rng(3)
    base = rng.normal(size=(4 * N,)) * 10.0 ** rng.integers(-300, 300, size=4 * N)
    keep = base.copy()
    for x in (
        base[::3],
        base.reshape(4, N).T,
        np.broadcast_to(base[:1], (N,)),
        base.reshape(2, 2 * N),
    ):
        _check(np.asarray(x))
    assert _same_bits(base, keep)


def _interval(rng: np.random.Generator, n: int, nonneg: bool) -> tuple[Interval, np.ndarray]:
    """A random interval array and a random point inside each element."""
    a = rng.uniform(0.1 if nonneg else -3.0, 3.0, size=n) * 10.0 ** rng.uniform(-3, 3, size=n)
    b = a + rng.uniform(0.0, 2.0, size=n) * np.abs(a)
    t = rng.uniform(0.0, 1.0, size=n)
    return Interval(a, b), a + t * (b - a)


def test_operations_contain_points_on_large_arrays() -> None:
    """Sums, differences, products, quotients, powers, square roots and cosines of intervals of
    :data:`N`-odd elements (the integer step) contain the same operations on points inside
    them, evaluated in exact rational arithmetic (fractions) or to within the float's own
    rounding for sqrt and cos, and they are the intervals nextafter gives, bit for bit."""
    from fractions import Fraction

    rng = np.random.default_rng(11)
    n = N + 17
    for nonneg in (True, False):
        x, px = _interval(rng, n, nonneg)
        y, py = _interval(rng, n, True)
        results = {
            "add": (x + y, [Fraction(a) + Fraction(b) for a, b in zip(px, py, strict=True)]),
            "sub": (x - y, [Fraction(a) - Fraction(b) for a, b in zip(px, py, strict=True)]),
            "mul": (x * y, [Fraction(a) * Fraction(b) for a, b in zip(px, py, strict=True)]),
            "div": (x / y, [Fraction(a) / Fraction(b) for a, b in zip(px, py, strict=True)]),
            "scale": (x * 0.3, [Fraction(a) * Fraction(0.3) for a in px]),
            "pow": (x**3, [Fraction(a) ** 3 for a in px]),
        }
        for name, (got, exact) in results.items():
            lo = [Fraction(v) for v in got.lo]
            hi = [Fraction(v) for v in got.hi]
            assert all(a <= e <= b for a, e, b in zip(lo, exact, hi, strict=True)), name
        s = y.sqrt()
        assert np.all(s.lo <= np.sqrt(py)) and np.all(np.sqrt(py) <= s.hi)
        c = x.cos()
        assert np.all(c.lo <= np.cos(px)) and np.all(np.cos(px) <= c.hi)
    # the same intervals as the libm step gives
    x, _ = _interval(rng, n, False)
    y, _ = _interval(rng, n, True)
    saved = iv._BITWISE_FROM
    try:
        new = [x + y, x - y, x * y, y * y, x / y, y / x, x**2, y.sqrt(), x.cos(), x * -2.5]
        iv._BITWISE_FROM = math.inf  # type: ignore[assignment]
        old = [x + y, x - y, x * y, y * y, x / y, y / x, x**2, y.sqrt(), x.cos(), x * -2.5]
    finally:
        iv._BITWISE_FROM = saved
    for a, b in zip(new, old, strict=True):
        assert _same_bits(a.lo, b.lo) and _same_bits(a.hi, b.hi)


def test_cos_between_extrema_widens_nothing() -> None:
    """Where :func:`~corrugate.solver.interval._between_extrema` lets cos skip the extrema,
    the extrema's rule (the general way, evaluated) changes no endpoint: intervals drawn in
    (0, pi) and (-pi, -1e-9), their ends on the float pi's neighbours too; and intervals that
    hold a multiple of pi are not let through, and are widened to +-1 there."""
    rng = np.random.default_rng(5)
    pi = math.pi
    edges = np.array([np.nextafter(0.0, 1.0), 1e-300, np.nextafter(pi, 0.0), 0.5 * pi])
    for sign in (1.0, -1.0):
        a = np.concatenate([rng.uniform(0.0, pi, size=3000), edges])
        b = np.concatenate([rng.uniform(0.0, pi, size=3000), edges[::-1]])
        lo, hi = np.minimum(a, b), np.maximum(a, b)
        if sign < 0:
            lo, hi = -hi, -lo
            keep = hi < -1e-9
            lo, hi = lo[keep], hi[keep]
        lo = np.maximum(lo, np.nextafter(-pi, 0.0))
        lo = np.where(lo == 0.0, 5e-324, lo)
        assert iv._between_extrema(lo, hi)
        v_lo, v_hi = np.cos(lo), np.cos(hi)
        e_lo, e_hi = np.minimum(v_lo, v_hi), np.maximum(v_lo, v_hi)
        got_lo, got_hi = iv._cos_extrema(lo, hi, e_lo, e_hi)
        assert _same_bits(got_lo, e_lo) and _same_bits(got_hi, e_hi)
        c = Interval(lo, hi).cos()  # contains cos at points inside
        t = rng.uniform(0.0, 1.0, size=lo.size)
        x = lo + t * (hi - lo)
        assert np.all(c.lo <= np.cos(x)) and np.all(np.cos(x) <= c.hi)
    for lo, hi in ((0.0, 1.0), (-0.5, 0.5), (3.0, 3.5), (-1.0, -1e-12), (-3.5, -3.0)):
        x_lo, x_hi = np.array([lo]), np.array([hi])
        assert not iv._between_extrema(x_lo, x_hi)
    c = Interval(np.array([3.0, -0.5]), np.array([3.5, 0.5])).cos()
    assert c.lo[0] == -1.0 and c.hi[1] == 1.0
