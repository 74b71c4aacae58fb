"""Fold-line styles: the perforation dash rule and its errors."""

from __future__ import annotations

import math

import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from corrugate.core.errors import InputError, UnknownNameError
from corrugate.fabrication.linestyle import (
    LineStyle,
    PerforationError,
    StyleKind,
    check_style,
    dash_layout,
    dashes,
    line_style,
)
from corrugate.fabrication.model import Line, Part, Role


@settings(max_examples=200, deadline=None)
@given(
    length=st.floats(0.5, 500.0),
    cut=st.floats(0.05, 20.0),
    gap=st.floats(0.05, 20.0),
)
def test_dashes_have_the_set_cut_and_gap_and_stop_short_of_the_ends(
    length: float, cut: float, gap: float
) -> None:
    if cut + gap > length:
        with pytest.raises(PerforationError):
            dash_layout(length, cut, gap)
        return
    starts = dash_layout(length, cut, gap)
    n = len(starts)
    assert n == math.floor(length / (cut + gap) + 1e-9)
    head, tail = starts[0], length - (starts[-1] + cut)
    assert head == pytest.approx(tail)  # centred
    assert head >= gap / 2 - 1e-9 and head > 0  # no dash touches an end
    assert head < gap / 2 + (cut + gap) / 2 + 1e-9  # and no room was left for one more dash
    for k in range(n - 1):
        assert starts[k + 1] - starts[k] - cut == pytest.approx(gap)  # exactly the gap asked for
    # dashes + gaps + the two ends tile the line exactly
    assert n * cut + (n - 1) * gap + 2 * head == pytest.approx(length)


def test_dash_segments_lie_on_the_crease() -> None:
    line = Line((10.0, 5.0), (10.0 + 30.0 * 0.6, 5.0 + 30.0 * 0.8), Role.VALLEY, 90.0)
    segs = dashes(line, 2.0, 1.0)
    assert len(segs) == 10
    for (ax, ay), (bx, by) in segs:
        assert math.hypot(bx - ax, by - ay) == pytest.approx(2.0)
        for x, y in ((ax, ay), (bx, by)):  # collinear with the crease, strictly inside it
            t = ((x - 10.0) * 0.6 + (y - 5.0) * 0.8) / 1.0
            assert 0.0 < t < 30.0
            assert (x - 10.0) * 0.8 - (y - 5.0) * 0.6 == pytest.approx(0.0, abs=1e-12)
    assert segs[0][0] == pytest.approx((10.0 + 0.5 * 0.6, 5.0 + 0.5 * 0.8))


def test_line_style_by_name() -> None:
    assert line_style("solid") == LineStyle()
    assert line_style("Scored").kind is StyleKind.SCORED
    assert line_style("perforated", cut=2, gap=1) == LineStyle(StyleKind.PERFORATED, 2.0, 1.0)
    with pytest.raises(UnknownNameError, match="perforated"):
        line_style("dotted")
    with pytest.raises(PerforationError):
        line_style("perforated", cut=2)


@pytest.mark.parametrize(("cut", "gap"), [(0.0, 1.0), (2.0, -1.0), (math.nan, 1.0)])
def test_non_positive_cut_or_gap_is_an_input_error(cut: float, gap: float) -> None:
    with pytest.raises(InputError, match="perforation"):
        line_style("perforated", cut=cut, gap=gap)


def test_perforation_longer_than_a_crease_names_crease_part_and_lengths() -> None:
    part = Part(
        "connector-3",
        "C3",
        ((0.0, 0.0), (40.0, 0.0), (40.0, 4.0), (0.0, 4.0)),
        (
            Line((0.0, 2.0), (40.0, 2.0), Role.MARK),
            Line((10.0, 0.0), (10.0, 4.0), Role.MOUNTAIN, 90.0),
            Line((20.0, 0.0), (20.0, 4.0), Role.VALLEY, 90.0),
        ),
    )
    check_style([part], line_style("perforated", cut=2.0, gap=1.0))  # 3 mm on 4 mm creases: ok
    with pytest.raises(PerforationError) as err:
        check_style([part], line_style("perforated", cut=3.5, gap=1.0))
    msg = str(err.value)
    assert "crease 1 of part 'connector-3'" in msg
    assert "cut 3.5 mm" in msg and "gap 1 mm" in msg and "4.000 mm" in msg
    check_style([part], line_style("solid"))  # solid lines need no check
