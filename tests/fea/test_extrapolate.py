"""Richardson extrapolation of mesh series (corrugate.fea.extrapolate): hand-made series of known
order and limit, and the series it must not extrapolate; when a series counts for verify's
verdict (``judge``): issue 35's three constructed series and hand-checked Richardson cases."""

from __future__ import annotations

import math

import pytest

from corrugate.fea.extrapolate import MARGIN_SHARE, extrapolate, judge, observed_order, richardson


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


def test_a_series_that_is_not_asymptotic_gives_no_value_without_a_sense() -> None:
    """Steps of alternating sign, growing steps (p < 0.5) and too high an order (p > 4): no
    extrapolation and, without the side a bound lies on, no value at all: "not converged",
    naming the finest value (kept in ``finest``). Steps that vanish (a mesh-independent value)
    are converged: the finest value."""
    for s in (
        {2: 10.0, 4: 12.0, 8: 11.0},  # not monotone
        {2: 10.0, 4: 10.5, 8: 11.5},  # steps grow: p = -1
        _series(100.0, 5.0, 5.0),  # p = 5 > 4
    ):
        e = extrapolate(s)
        assert not e.asymptotic and e.value is None
        assert e.how.startswith("not converged: not asymptotic") and e.finest == s[8]
        assert richardson(s) is None
    assert observed_order({2: 10.0, 4: 10.5, 8: 11.5}) == pytest.approx(-1.0)
    flat = extrapolate({2: 10.0, 4: 10.0, 8: 10.0})
    assert flat.value == 10.0 and flat.how.startswith("converged")


def test_issue_35_the_slow_softening_series_has_no_safe_value_under_a_minimum() -> None:
    """100 / 90 / 82.42 (p = log2(10 / 7.58) = 0.40): it softens as the mesh refines and
    continues geometrically to 58.7 (test below), so against a minimum (a stiffness, a failure
    load) its finest value 82.42 is no lower bound: no value, "not converged". Against a
    maximum it is an upper bound (the limit lies below it, the series falling). Mirrored (80 /
    90 / 97.58, rising), the finest value is a lower bound and no upper one."""
    s = {2: 100.0, 4: 90.0, 8: 82.42}
    low = extrapolate(s, "min")
    assert low.value is None and low.order == pytest.approx(0.3997, abs=1e-4)
    assert low.how.startswith("not converged") and "82.42 is no lower bound" in low.how
    high = extrapolate(s, "max")
    assert high.value == 82.42 and "an upper bound" in high.how
    rising = {k: 180.0 - v for k, v in s.items()}
    assert extrapolate(rising, "min").value == pytest.approx(97.58)
    assert "a lower bound" in extrapolate(rising, "min").how
    assert extrapolate(rising, "max").value is None


def test_a_limit_of_the_other_sign_is_not_asymptotic() -> None:
    """The first yield of the case study's 4-point fixture (a stress concentration at the load
    lines): 102.635 / 55.875 / 30.230 N at 2 / 4 / 8, steps 46.76 and 25.65, p = log2(46.76 /
    25.65) = 0.87 and by hand a Richardson limit of 30.230 - 25.65 / (2^0.87 - 1) = -0.92 N: a
    load that cannot be. Not asymptotic: no value without a sense or against a minimum (it
    falls), the finest value as an upper bound."""
    s = {2: 102.6350356857923, 4: 55.875161366395155, 8: 30.2298454570541}
    assert richardson(s) is not None and richardson(s)[0] == pytest.approx(-0.918, abs=1e-3)
    e = extrapolate(s)
    assert not e.asymptotic and e.value is None and "has the other sign" in e.how
    assert extrapolate(s, "min").value is None
    assert extrapolate(s, "max").value == pytest.approx(30.2298454570541)


def test_issue_35_a_turning_series_has_no_value_either_side() -> None:
    """100 / 92 / 94 against a minimum of 90: every value meets the bound, but the steps turn
    (-8, +2): neither side has a bound, no value."""
    s = {2: 100.0, 4: 92.0, 8: 94.0}
    for sense in ("min", "max"):
        e = extrapolate(s, sense)
        assert e.value is None and e.finest == 94.0 and e.how.startswith("not converged")


def test_issue_35_the_k15_series_extrapolates_from_its_finest_three() -> None:
    """docs/fea.md 2.9's K(15) series 126.24 / 93.20 / 85.22 / 81.60 N/mm: by hand (test of
    judge below) 2 / 4 / 8 give 82.676 (p = 2.05) and 4 / 8 / 16 give 78.590 (p = 1.14).
    extrapolate takes the finest three, 78.590, and says what it moved from; the three-mesh
    estimate, 5 % above it, is what judge refuses to count alone."""
    s = {2: 126.23668, 4: 93.202237, 8: 85.219855, 16: 81.597965}
    e = extrapolate(s, "min")
    assert e.asymptotic and e.value == pytest.approx(78.590, abs=1e-3)
    assert e.order == pytest.approx(1.140, abs=1e-3)
    assert "82.676 from 2 / 4 / 8 (p = 2.05)" in e.how
    three = extrapolate({k: s[k] for k in (2, 4, 8)}, "min")
    assert three.value == pytest.approx(82.676, abs=1e-3)
    assert three.value / e.value - 1 == pytest.approx(0.052, abs=1e-3)
    assert judge({k: s[k] for k in (2, 4, 8)}, 75.0, "min").verdict == "open"


def test_short_series_and_missing_values() -> None:
    """One mesh gives its value and says so; two give the finest value without a sense, and
    with one only on the safe side (2.5 after 3.0 falls: an upper bound, no lower one); meshes
    that do not double give no order; NaN entries (a failed run) are left out; an empty series
    has no value."""
    assert extrapolate({4: 3.0}).value == 3.0
    assert extrapolate({4: 3.0}, "min").how.startswith("one mesh")
    two = extrapolate({2: 3.0, 4: 2.5})
    assert (two.value, two.order, two.asymptotic) == (2.5, None, False)
    assert "two meshes" in two.how
    assert extrapolate({2: 3.0, 4: 2.5}, "max").value == 2.5
    assert extrapolate({2: 3.0, 4: 2.5}, "min").value is None
    assert observed_order({2: 3.0, 6: 2.0, 8: 1.9}) is None
    e = extrapolate({2: math.nan, 4: 2.5, 8: 2.4})
    assert e.value == 2.4 and not e.asymptotic
    assert extrapolate({2: 3.0, 6: 2.0, 8: 1.9}).value is None  # three meshes, no order
    assert extrapolate({}).value is None


# --- when a series counts for verify's verdict (judge) ----------------------------------------


def test_issue_35_the_slow_softening_series_is_not_a_pass_until_refined() -> None:
    """100 / 90 / 82.42 (steps 10 and 7.58, p = log2(10 / 7.58) = 0.40) against a minimum of 70:
    not "holds" from three meshes. Its geometric continuation (each step 0.758 of the one
    before, 82.42 - 7.58 x 0.758 = 76.675 at 16) ends at 100 - 10 / (1 - 0.758) = 58.68, below
    the bound: with that fourth mesh both extrapolations give 58.68 and the row fails."""
    s = {2: 100.0, 4: 90.0, 8: 82.42}
    j = judge(s, 70.0, "min")
    assert j.verdict == "open" and "four meshes" in j.why
    assert j.order == pytest.approx(math.log2(10 / 7.58))
    assert j.value == pytest.approx(100 - 10 / (1 - 0.758), abs=1e-9)  # not the finest 82.42
    more = {**s, 16: 82.42 - 7.58 * 0.758}
    done = judge(more, 70.0, "min")
    assert done.verdict == "fails"
    assert done.value == pytest.approx(58.6777, abs=1e-4)
    assert done.how.startswith("converged")


def test_issue_35_a_series_that_is_not_monotone_is_not_a_pass() -> None:
    """100 / 92 / 94 against a minimum of 90: every value meets the bound, but the series turns
    (steps -8, +2): no order, no estimate to trust, open; a fourth mesh that keeps turning
    leaves it open (verify then says not converged)."""
    s = {2: 100.0, 4: 92.0, 8: 94.0}
    j = judge(s, 90.0, "min")
    assert j.verdict == "open" and j.value == 94.0 and j.order is None
    turning = judge({**s, 16: 93.0}, 90.0, "min")
    assert turning.verdict == "open" and "not monotone" in turning.why


def test_issue_35_the_k15_series_is_not_converged_at_2_4_8_nor_at_16() -> None:
    """docs/fea.md 2.9: the certified K(15) design, 126.24 / 93.20 / 85.22 N/mm at 2 / 4 / 8,
    bound 75 (model 75.30). From 2 / 4 / 8 alone: open (one extrapolation, 82.68, cannot be
    checked against another). With 81.60 at 16: the extrapolations from 2 / 4 / 8 and 4 / 8 / 16
    are by hand d = 33.035, 7.982, 3.622; p1 = log2(33.035 / 7.982) = 2.049, R1 = 85.220 -
    7.982 / (2^p1 - 1) = 82.676; p2 = log2(7.982 / 3.622) = 1.140, R2 = 81.598 - 3.622 /
    (2^p2 - 1) = 78.590. They differ by 4.09, more than a quarter of the margin 78.59 - 75 =
    3.59: still open, so at the default cap of 16 per facet the row is not converged."""
    s = {2: 126.23668, 4: 93.202237, 8: 85.219855}
    j = judge(s, 75.0, "min")
    assert j.verdict == "open"
    assert j.value == pytest.approx(82.676, abs=1e-3)
    j16 = judge({**s, 16: 81.597965}, 75.0, "min")
    assert j16.verdict == "open"
    assert j16.value == pytest.approx(78.590, abs=1e-3)
    assert j16.order == pytest.approx(1.140, abs=1e-3)
    assert "82.676" in j16.why and "78.59" in j16.why and "differ by 4.09" in j16.why
    # the same two estimates decide a bound four disagreements (16.4) below 78.59, not one above
    assert judge({**s, 16: 81.597965}, 62.0, "min").verdict == "holds"
    assert judge({**s, 16: 81.597965}, 63.0, "min").verdict == "open"


@pytest.mark.parametrize("p", [0.4, 1.0, 2.0])
@pytest.mark.parametrize("A", [30.0, -30.0])
def test_an_exact_series_c_plus_A_h_p_converges_to_c(p: float, A: float) -> None:
    """v = c + A h^p with h = 1 / along on 2 / 4 / 8 / 16: both extrapolations are c exactly
    (Richardson is exact for one power term, whatever p), so the row is decided by c against the
    bound, even an inch from it; from three meshes it is open."""
    c = 50.0
    s = _series(c, A, p, (2, 4, 8, 16))
    assert judge(s, c - 0.01, "min").verdict == "holds"
    assert judge(s, c + 0.01, "min").verdict == "fails"
    assert judge(s, c + 0.01, "max").verdict == "holds"
    j = judge(s, c - 1.0, "min")
    assert j.value == pytest.approx(c, abs=1e-9) and j.order == pytest.approx(p)
    assert judge({k: s[k] for k in (2, 4, 8)}, c - 1.0, "min").verdict == "open"


def test_the_margin_share_by_hand() -> None:
    """116 / 108 / 104 / 101 at 2 / 4 / 8 / 16: steps 8, 4, 3. By hand R1 = 104 - 4 / (2 - 1) =
    100 (p = 1); R2 = 101 - 3 / (4/3 - 1) = 92 (2^p = 4/3). They differ by 8: a minimum of 60
    (margin 32 = 8 / 0.25) is decided, holds; one of 61 (margin 31) is open."""
    assert MARGIN_SHARE == 0.25
    s = {2: 116.0, 4: 108.0, 8: 104.0, 16: 101.0}
    j = judge(s, 60.0, "min")
    assert j.verdict == "holds" and j.value == pytest.approx(92.0, abs=1e-12)
    assert j.order == pytest.approx(math.log2(4 / 3))
    assert judge(s, 61.0, "min").verdict == "open"
    # a maximum far above: decided too (92 + 32 = 124)
    assert judge(s, 124.0, "max").verdict == "holds"
    assert judge(s, 123.0, "max").verdict == "open"


def test_a_series_past_its_bound_and_moving_away_fails_early() -> None:
    """A softening series already below its minimum only goes further below (fails from three
    meshes); a stiffening one below its minimum may still cross (open). A deflection growing
    past its maximum fails; one growing below it is open."""
    assert judge({2: 12.0, 4: 10.0, 8: 9.5}, 10.0, "min").verdict == "fails"
    assert judge({2: 8.0, 4: 9.0, 8: 9.5}, 10.0, "min").verdict == "open"
    assert judge({2: 0.40, 4: 0.45, 8: 0.47}, 0.46, "max").verdict == "fails"
    assert judge({2: 0.40, 4: 0.45, 8: 0.47}, 0.50, "max").verdict == "open"
    # past the bound but turning: open
    assert judge({2: 9.0, 4: 8.0, 8: 8.5}, 10.0, "min").verdict == "open"


def test_a_mesh_independent_series_is_decided_by_its_last_two_steps() -> None:
    """K of the layer loaded along its creases is exact at any mesh (docs/fea.md 2.2): the last
    two steps vanish (to round-off), the finest value decides, from three meshes; two meshes
    are not enough."""
    s = {2: 477.3, 4: 477.3 * (1 + 1e-12), 8: 477.3}
    assert judge(s, 477.0, "min").verdict == "holds"
    assert judge(s, 478.0, "min").verdict == "fails"
    assert judge({4: 477.3, 8: 477.3}, 477.0, "min").verdict == "open"


def test_short_broken_and_empty_series_are_open() -> None:
    """One or two meshes, meshes that do not double, NaN entries (a failed run, skipped) and an
    empty series: open, never holds."""
    assert judge({}, 1.0, "min").value is None
    for s in (
        {8: 2.0},
        {4: 2.1, 8: 2.0},
        {2: 3.0, 6: 2.5, 8: 2.4},
        {2: 3.0, 4: math.nan, 8: 2.4, 16: 2.39},
    ):
        assert judge(s, 1.0, "min").verdict == "open", s
    with pytest.raises(ValueError, match="sense must be min or max"):
        judge({2: 1.0}, 1.0, "less")
