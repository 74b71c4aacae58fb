"""Sheet layout: cutters, the shelf packer, placed geometry, and its errors."""

from __future__ import annotations

import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from corrugate.core.errors import InputError, UnknownNameError
from corrugate.fabrication.model import Line, Part, Role, polygon_area
from corrugate.fabrication.sheets import (
    CUTTERS,
    PartTooLargeError,
    Placement,
    SheetPlan,
    get_cutter,
    place,
    plan_sheets,
)

INCH = 25.4


def rect(name: str, w: float, h: float, creases: int = 0) -> Part:
    """A w x h mm rectangle with ``creases`` evenly spaced creases across x (M, V, M, ...)."""
    lines = tuple(
        Line(
            (w * (k + 1) / (creases + 1), 0.0),
            (w * (k + 1) / (creases + 1), h),
            Role.MOUNTAIN if k % 2 == 0 else Role.VALLEY,
            96.0,
        )
        for k in range(creases)
    )
    return Part(name, name.upper(), ((0.0, 0.0), (w, 0.0), (w, h), (0.0, h)), lines)


def ell(name: str = "ell") -> Part:
    """A concave L-shaped part, 60 x 50 mm, with a square hole, a slit and a mark."""
    return Part(
        name,
        "L part",
        ((0.0, 0.0), (60.0, 0.0), (60.0, 20.0), (20.0, 20.0), (20.0, 50.0), (0.0, 50.0)),
        (
            Line((10.0, 0.0), (10.0, 50.0), Role.MARK),
            Line((30.0, 5.0), (50.0, 5.0), Role.CUT),
            Line((20.0, 10.0), (60.0, 10.0), Role.VALLEY, 90.0),
        ),
        holes=(((5.0, 30.0), (15.0, 30.0), (15.0, 40.0), (5.0, 40.0)),),
    )


def bbox(points: tuple[tuple[float, float], ...]) -> tuple[float, float, float, float]:
    xs = [p[0] for p in points]
    ys = [p[1] for p in points]
    return min(xs), min(ys), max(xs), max(ys)


def signed_area(points: tuple[tuple[float, float], ...]) -> float:
    n = len(points)
    return 0.5 * sum(
        points[i][0] * points[(i + 1) % n][1] - points[(i + 1) % n][0] * points[i][1]
        for i in range(n)
    )


def assert_valid_plan(plan: SheetPlan, parts: list[Part]) -> None:
    """Every part placed once; inside the usable area less the margin; no two bounding boxes of
    transformed outlines closer than the spacing; the reserved check-square box kept free."""
    placed_names = sorted(p.part.name for p in plan.placements)
    assert placed_names == sorted(p.name for p in parts)
    tol = 1e-9
    for k, sheet in enumerate(plan.sheets):
        assert all(p.sheet == k for p in sheet.placements)
        boxes = [bbox(place(p).outline) for p in sheet.placements]
        for (x0, y0, x1, y1), p in zip(boxes, sheet.placements, strict=True):
            assert x0 >= plan.margin - tol and y0 >= plan.margin - tol
            assert x1 <= sheet.width - plan.margin + tol
            assert y1 <= sheet.height - plan.margin + tol
            assert (x0, y0, x1, y1) == pytest.approx(p.bounds)
        if sheet.reserved is not None:  # the check-square box: inside the margins, free
            rx, ry, rw, rh = sheet.reserved
            assert rx >= plan.margin - tol and ry >= plan.margin - tol
            assert rx + rw <= sheet.width - plan.margin + tol
            assert ry + rh <= sheet.height - plan.margin + tol
            boxes_and_reserved = [*boxes, (rx, ry, rx + rw, ry + rh)]
        else:
            boxes_and_reserved = boxes
        for i in range(len(boxes_and_reserved)):
            for j in range(i + 1, len(boxes_and_reserved)):
                a, b = boxes_and_reserved[i], boxes_and_reserved[j]
                separated = (
                    a[2] + plan.spacing <= b[0] + tol
                    or b[2] + plan.spacing <= a[0] + tol
                    or a[3] + plan.spacing <= b[1] + tol
                    or b[3] + plan.spacing <= a[1] + tol
                )
                assert separated, (i, j)


# -- cutters ---------------------------------------------------------------------------------------


def test_cameo_and_maker_mats_usable_area() -> None:
    assert get_cutter("cameo4-12x12").width == pytest.approx(11.5 * INCH)
    assert get_cutter("cameo4-12x12").height == pytest.approx(11.5 * INCH)
    assert get_cutter("Cameo4-12x24").height == pytest.approx(23.5 * INCH)
    assert get_cutter("maker-12x24").width == pytest.approx(292.1)
    for cutter in CUTTERS.values():
        assert cutter.source and cutter.description


def test_laser_bed_is_parsed_in_mm() -> None:
    c = get_cutter("laser:600x400")
    assert (c.width, c.height) == (600.0, 400.0)
    assert get_cutter("laser:250.5x100mm").width == 250.5


@pytest.mark.parametrize("name", ["laser:600", "laser:axb", "laser:0x100"])
def test_bad_laser_bed_is_an_input_error(name: str) -> None:
    with pytest.raises(InputError, match="cutter"):
        get_cutter(name)


def test_unknown_cutter_lists_the_known_ones() -> None:
    with pytest.raises(UnknownNameError) as err:
        plan_sheets([rect("a", 10, 10)], "cameo5")
    msg = str(err.value)
    assert "cameo5" in msg and "cameo4-12x12" in msg and "cameo4-12x24" in msg
    assert "laser:WxH" in msg
    assert isinstance(err.value, InputError)


# -- packing ---------------------------------------------------------------------------------------


def test_mixed_parts_fit_one_mat_without_overlap() -> None:
    parts = [rect("layer-1", 72, 48.18, 8), rect("layer-2", 72, 48.18, 8), ell()]
    parts += [rect(f"strip-{i}", 10, 250) for i in range(4)]
    plan = plan_sheets(parts, "cameo4-12x12")
    assert len(plan.sheets) == 1
    assert plan.sheets[0].reserved is not None
    assert_valid_plan(plan, parts)
    # the 10 x 250 strips lie along x: turned 90 deg
    strips = [p for p in plan.placements if p.part.name.startswith("strip")]
    assert all(p.rotated for p in strips)


def test_check_box_costs_no_extra_sheet_when_space_is_free_elsewhere() -> None:
    # a 250 mm strip on the top shelf reaches the top-right corner; the box goes beside the blanks
    parts = [ell(), rect("layer-1", 72, 48.18, 8), rect("layer-2", 72, 48.18, 8)]
    parts.append(rect("strip", 10, 250))
    plan = plan_sheets(parts, "laser:270x80")
    assert len(plan.sheets) == 1
    assert plan.sheets[0].reserved is not None
    assert_valid_plan(plan, parts)


def test_check_box_is_kept_in_the_corner_when_no_spot_is_left() -> None:
    # 4 x 4 squares of 66 mm fill a 292 mm mat, corner included
    parts = [rect(f"sq{i}", 66, 66) for i in range(16)]
    plan = plan_sheets(parts, "cameo4-12x12", spacing=4, margin=5)
    assert all(s.reserved is not None for s in plan.sheets)
    assert_valid_plan(plan, parts)
    assert len(plan.sheets) == 2  # the box pushes one square to a second sheet


def test_layout_is_deterministic() -> None:
    parts = [rect(f"p{i}", 20 + 7 * i, 15 + 11 * (i % 4)) for i in range(15)] + [ell()]
    assert plan_sheets(parts, "laser:200x150") == plan_sheets(parts, "laser:200x150")


def test_several_sheets_when_needed() -> None:
    parts = [rect(f"big-{i}", 200, 200) for i in range(3)]
    plan = plan_sheets(parts, "cameo4-12x12")
    assert len(plan.sheets) == 3
    assert_valid_plan(plan, parts)


def test_long_part_needs_the_long_mat() -> None:
    long = rect("long", 20, 500)
    with pytest.raises(PartTooLargeError):
        plan_sheets([long], "cameo4-12x12")
    plan = plan_sheets([long], "cameo4-12x24")
    assert not plan.placements[0].rotated
    assert_valid_plan(plan, [long])


def test_part_that_only_fits_without_the_check_box_gets_a_sheet_without_it() -> None:
    big = rect("big", 280, 280)
    plan = plan_sheets([big, rect("small", 10, 10)], "cameo4-12x12")
    assert plan.sheets[0].reserved is None
    assert_valid_plan(plan, [big, rect("small", 10, 10)])


def test_oversize_part_error_names_part_size_and_sheet() -> None:
    parts = [rect("ok", 50, 50), rect("layer-2", 300, 40)]
    with pytest.raises(PartTooLargeError) as err:
        plan_sheets(parts, "laser:250x250", margin=5)
    msg = str(err.value)
    assert "'layer-2'" in msg
    assert "300.0 x 40.0 mm" in msg
    assert "240.0 x 240.0 mm" in msg  # usable area: 250 less two 5 mm margins
    assert "laser:250x250" in msg
    assert isinstance(err.value, InputError)


def test_part_names_must_be_unique() -> None:
    with pytest.raises(InputError, match="'a' is used twice"):
        plan_sheets([rect("a", 10, 10), rect("b", 10, 10), rect("a", 5, 5)], "laser:300x300")


@pytest.mark.parametrize(("spacing", "margin"), [(-1.0, 5.0), (5.0, -1.0), (5.0, 200.0)])
def test_bad_spacing_or_margin(spacing: float, margin: float) -> None:
    with pytest.raises(InputError):
        plan_sheets([rect("a", 10, 10)], "laser:300x300", spacing=spacing, margin=margin)


@settings(max_examples=60, deadline=None)
@given(
    sizes=st.lists(
        st.tuples(st.floats(1.0, 180.0), st.floats(1.0, 120.0)), min_size=1, max_size=25
    ),
    # subnormal spacings and margins are refused by plan_sheets (core.limits.is_normal)
    spacing=st.floats(0.0, 8.0, allow_subnormal=False),
    margin=st.floats(0.0, 10.0, allow_subnormal=False),
)
def test_random_parts_never_overlap(
    sizes: list[tuple[float, float]], spacing: float, margin: float
) -> None:
    parts = [rect(f"r{i}", w, h) for i, (w, h) in enumerate(sizes)]
    plan = plan_sheets(parts, "laser:200x200", spacing=spacing, margin=margin)
    assert_valid_plan(plan, parts)


# -- placed geometry -------------------------------------------------------------------------------


@pytest.mark.parametrize("rotated", [False, True])
def test_placement_is_a_rigid_motion_without_mirror(rotated: bool) -> None:
    part = ell()
    p = Placement(part, 0, 30.0, 40.0, rotated)
    placed = place(p)
    # same area, still counter-clockwise (no mirror), same line lengths and roles
    assert polygon_area(placed.outline) == pytest.approx(polygon_area(part.outline))
    assert signed_area(placed.outline) > 0
    for a, b in zip(placed.lines, part.lines, strict=True):
        assert a.length == pytest.approx(b.length)
        assert (a.role, a.fold_angle_deg) == (b.role, b.fold_angle_deg)
    assert bbox(placed.outline) == pytest.approx(p.bounds)
    assert bbox(placed.outline)[:2] == pytest.approx((30.0, 40.0))
    w, h = part.size
    assert p.size == ((h, w) if rotated else (w, h))
    # the hole stays inside the outline's box and keeps its size
    assert polygon_area(placed.holes[0]) == pytest.approx(100.0)
    if rotated:  # 90 deg counter-clockwise: local +x becomes sheet +y
        o = p.transform((0.0, 0.0))
        e = p.transform((1.0, 0.0))
        assert (e[0] - o[0], e[1] - o[1]) == pytest.approx((0.0, 1.0))


# -- the mat's origin is its top-left corner ------------------------------------------------------


@pytest.mark.parametrize("cutter", ["cameo4-12x12", "maker-12x24", "laser:400x300"])
def test_parts_are_packed_from_the_top_left_corner(cutter: str) -> None:
    parts = [rect("layer-1", 72, 48.18, 8), rect("layer-2", 72, 48.18, 8), ell()]
    plan = plan_sheets(parts, cutter, spacing=5, margin=7)
    sheet = plan.sheets[0]
    boxes = [bbox(place(p).outline) for p in sheet.placements]
    # y is up on a sheet: the top edge is y = height; the first shelf touches the top margin
    assert max(b[3] for b in boxes) == pytest.approx(sheet.height - 7)
    assert min(b[0] for b in boxes) == pytest.approx(7)
    # nothing lies in the lower half of the mat: the free space is below the parts
    assert min(b[1] for b in boxes) > sheet.height / 2
    if sheet.reserved is not None:
        rx, ry, rw, rh = sheet.reserved
        assert rx >= 7 - 1e-9 and ry >= 7 - 1e-9
        assert rx + rw <= sheet.width - 7 + 1e-9 and ry + rh <= sheet.height - 7 + 1e-9
