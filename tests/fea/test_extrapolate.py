"""Richardson extrapolation of mesh series (corrugate.fea.extrapolate): hand-made series of known
order and limit, and the series it must not extrapolate."""

from __future__ import annotations

import math

import pytest

from corrugate.fea.extrapolate import extrapolate, observed_order, richardson


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
