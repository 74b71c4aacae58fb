"""Richardson extrapolation of mesh series (corrugate.fea.extrapolate): hand-made series of known
order and limit, and the series it must not extrapolate."""

from __future__ import annotations

import math

import pytest

from corrugate.fea.extrapolate import extend_reason, extrapolate, observed_order, richardson


def _series(
    limit: float, c: float, p: float, alongs: tuple[int, ...] = (2, 4, 8)
) -> dict[int, float]:
    """v(h) = limit + c h^p with h = 1 / along: an exact series of order p."""
    return {a: limit + c * (1.0 / a) ** p for a in alongs}


@pytest.mark.parametrize("p", [0.75, 1.0, 1.5, 2.0, 3.0])
@pytest.mark.parametrize("c", [5.0, -5.0])
def test_a_series_of_known_order_gives_its_order_and_limit(p: float, c: float) -> None:
    """Converging from above (c > 0, as stiff coarse shells) or below: the observed order is p
    and the limit 100, to rounding."""
    s = _series(100.0, c, p)
    assert observed_order(s) == pytest.approx(p, rel=1e-9)
    r = richardson(s)
    assert r is not None
    assert r[0] == pytest.approx(100.0, rel=1e-12)
    assert r[1] == f"extrapolated (p = {p:.2f})"
    e = extrapolate(s)
    assert e.asymptotic and e.value == pytest.approx(100.0, rel=1e-12)
    assert e.order == pytest.approx(p)


def test_the_three_finest_meshes_are_used() -> None:
    """A coarse mesh off the asymptote (2 per facet) does not spoil the estimate from 4, 8, 16."""
    s = _series(50.0, 3.0, 2.0, (4, 8, 16))
    s[2] = 1000.0
    assert extrapolate(s).value == pytest.approx(50.0)


def test_a_series_that_is_not_asymptotic_is_said_so_and_gives_its_finest_value() -> None:
    """Steps of alternating sign, growing steps (p < 0.5) and too high an order (p > 4): no
    extrapolation, the finest value, 'not asymptotic'."""
    for s in (
        {2: 10.0, 4: 12.0, 8: 11.0},  # not monotone
        {2: 10.0, 4: 10.5, 8: 11.5},  # steps grow: p = -1
        _series(100.0, 5.0, 5.0),  # p = 5 > 4
        {2: 10.0, 4: 10.0, 8: 10.0},  # no step: no order
    ):
        e = extrapolate(s)
        assert not e.asymptotic
        assert e.value == s[8]
        assert e.how.startswith("not asymptotic")
        assert richardson(s) is None
    assert observed_order({2: 10.0, 4: 10.5, 8: 11.5}) == pytest.approx(-1.0)


def test_short_series_and_missing_values() -> None:
    """One or two meshes give the finest value and no order; meshes that do not double give no
    order; NaN entries (a failed run) are left out; an empty series has no value."""
    assert extrapolate({4: 3.0}).value == 3.0
    two = extrapolate({2: 3.0, 4: 2.5})
    assert (two.value, two.order, two.asymptotic) == (2.5, None, False)
    assert "two meshes" in two.how
    assert observed_order({2: 3.0, 6: 2.0, 8: 1.9}) is None
    e = extrapolate({2: math.nan, 4: 2.5, 8: 2.4})
    assert e.value == 2.4 and not e.asymptotic
    assert extrapolate({}).value is None


# --- when a series is extended (extend_reason) -------------------------------------------------


def test_the_k45_before_series_must_go_on() -> None:
    """docs/fea.md 6: K(45) of the W 9, n 8, alpha 94 design, 2 / 4 / 8 per facet, bound 1 N/mm.
    By hand: d1 = 0.761, d2 = 0.195, p = log2(3.903) = 1.964, estimate 1.117 - 0.195 / 2.901 =
    1.0498: 0.0498 from the bound, less than its correction 1.117 - 1.0498 = 0.0672."""
    s = {2: 2.073, 4: 1.312, 8: 1.117}
    why = extend_reason(s, 1.0)
    assert why is not None and "Richardson correction" in why
    assert "0.0498" in why and "0.0672" in why


def test_the_k15_after_series_is_settled() -> None:
    """K(15) of the relaxed design, 125.14 / 92.52 / 84.73 N/mm, bound 75: estimate 82.29 (p =
    2.07, by hand 84.73 - 7.79 / 3.19), 7.3 above the bound, its correction only 2.4."""
    assert extend_reason({2: 125.14, 4: 92.52, 8: 84.73}, 75.0) is None


def test_the_rule_on_an_exact_series_of_order_2() -> None:
    """v = 100 + 40 / a^2: 110, 102.5, 100.625 at 2 / 4 / 8, estimate 100 exactly, correction
    0.625: a bound 0.5 from the estimate may flip (extend), one 1.0 away may not; a converged
    series far from its bound is never extended, above or below it."""
    s = _series(100.0, 40.0, 2.0)
    assert extend_reason(s, 100.5) is not None
    assert extend_reason(s, 99.5) is not None
    assert extend_reason(s, 101.0) is None
    assert extend_reason(s, 99.0) is None
    assert extend_reason(_series(100.0, 1e-3, 2.0), 80.0) is None
    assert extend_reason(_series(100.0, -1e-3, 2.0), 120.0) is None


def test_without_an_extrapolation_the_last_step_is_the_scale() -> None:
    """Not asymptotic (non-monotone: 87682 / 86940 / 87213, the refined gripper's EI(0)) or two
    meshes only: the finest value stands, and it may flip when the bound is within the last
    step (273 here; 306 for 85559 / 85866 at 4 / 8); one mesh: nothing to go on."""
    s = {2: 87682.0, 4: 86940.0, 8: 87213.0}
    assert not extrapolate(s).asymptotic
    why = extend_reason(s, 87000.0)
    assert why is not None and why.startswith("not asymptotic")
    assert extend_reason(s, 80000.0) is None
    two = {4: 85559.0, 8: 85866.0}
    assert extend_reason(two, 86000.0) is not None
    assert extend_reason(two, 80000.0) is None
    assert extend_reason({8: 1.0}, 1.0) is None
    assert extend_reason({2: 2.0, 4: math.nan, 8: 1.1}, 1.0) is not None  # a failed run skipped
