"""The tiled PDF (``pattern-a4.pdf`` / ``pattern-letter.pdf``): 1:1 office pages with overlap and
registration marks, read back with pypdf and checked against the sheet plan."""

from __future__ import annotations

import itertools
import math
import os
from pathlib import Path
from typing import TYPE_CHECKING

import pytest

from corrugate import Assembly, Layer, get_material
from corrugate.core.errors import UnknownNameError
from corrugate.export import write_files
from corrugate.export.pdf import (
    CHECK_SQUARE_MM,
    FOOTER_MM,
    MARK_PITCH_MM,
    MARK_SIZE_MM,
    OVERLAP_MM,
    PAGE_MARGIN_MM,
    PAPERS,
    drawing_area,
    plan_tiles,
    registration_marks,
    write_tiled_pdf,
)
from corrugate.export.plan import cut_plan
from corrugate.fabrication.build import build_pattern
from corrugate.fabrication.linestyle import line_style
from corrugate.fabrication.model import Line, Part, Role
from corrugate.fabrication.sheets import SheetPlan, place, plan_sheets

if TYPE_CHECKING:
    from conftest import CliRun

try:
    from pypdf import PdfReader
except ImportError:  # pragma: no cover - a dev dependency (pyproject.toml)
    if os.environ.get("CI", "").strip().lower() in ("true", "1", "yes"):
        raise
    pytest.skip("pypdf is not installed: pip install -e '.[dev]'", allow_module_level=True)

from pdf_readers import PT, Point, SubPath, page_paths

TOL_MM = 0.1
#: Page sizes in pt as the PDF must state them.
PAGE_PT = {"a4": (595.28, 841.89), "letter": (612.0, 792.0)}


def crosses(paths: list[SubPath]) -> list[Point]:
    """Centres (page mm) of the registration crosses: a black horizontal and a black vertical
    stroke, each MARK_SIZE_MM long, with the same midpoint."""
    tol = 0.05
    horiz: list[Point] = []
    vert: list[Point] = []
    for sp in paths:
        if len(sp.points) != 2 or sp.closed or sp.stroke != (0.0, 0.0, 0.0):
            continue
        (x0, y0), (x1, y1) = sp.points
        mid = ((x0 + x1) / 2, (y0 + y1) / 2)
        if abs(y0 - y1) < tol and abs(abs(x1 - x0) - MARK_SIZE_MM) < tol:
            horiz.append(mid)
        elif abs(x0 - x1) < tol and abs(abs(y1 - y0) - MARK_SIZE_MM) < tol:
            vert.append(mid)
    return [h for h in horiz if any(math.dist(h, v) < tol for v in vert)]


def boxes(paths: list[SubPath]) -> list[tuple[float, float, float, float, tuple[float, ...]]]:
    """(x, y, width, height, stroke) of every closed axis-aligned 4-corner sub-path (page mm)."""
    out = []
    for sp in paths:
        pts = sp.points[:-1] if len(sp.points) == 5 and sp.points[0] == sp.points[-1] else sp.points
        if not sp.closed or len(pts) != 4:
            continue
        xs = sorted({round(p[0], 4) for p in pts})
        ys = sorted({round(p[1], 4) for p in pts})
        if len(xs) == 2 and len(ys) == 2:
            out.append((xs[0], ys[0], xs[1] - xs[0], ys[1] - ys[0], sp.stroke))
    return out


# -- plans -------------------------------------------------------------------------------------


def _square(name: str, side: float) -> Part:
    lines = tuple(
        Line((side * k / 4, 0.0), (side * k / 4, side), Role.MOUNTAIN if k % 2 else Role.VALLEY, 90)
        for k in (1, 2, 3)
    )
    return Part(name, f"part {name}", ((0, 0), (side, 0), (side, side), (0, side)), lines)


@pytest.fixture(scope="module")
def real_plan() -> SheetPlan:
    """The paper's case 1 (W 8, n 8, alpha 84, Dura-Lar) on one 12 x 24 in mat."""
    a = Assembly.identical(Layer(8.0, 8, 84.0, get_material("dura-lar")))
    return plan_sheets(build_pattern(a), "maker-12x24")


@pytest.fixture(scope="module")
def multi_plan() -> SheetPlan:
    """Three 12 x 12 in sheets, each holding a 250 mm square larger than an A4 page."""
    return plan_sheets([_square(n, 250.0) for n in "abc"], "cameo4-12x12")


@pytest.fixture(scope="module")
def pdfs(
    real_plan: SheetPlan, multi_plan: SheetPlan, tmp_path_factory: pytest.TempPathFactory
) -> dict[tuple[str, str], Path]:
    out = tmp_path_factory.mktemp("tiles")
    written = {}
    for name, plan in (("real", real_plan), ("multi", multi_plan)):
        for paper in PAPERS:
            written[name, paper] = write_tiled_pdf(plan, out / f"{name}-{paper}.pdf", paper)
    return written


CASES = [(name, paper) for name in ("real", "multi") for paper in PAPERS]


def _plan(name: str, real_plan: SheetPlan, multi_plan: SheetPlan) -> SheetPlan:
    return real_plan if name == "real" else multi_plan


# -- the tests ---------------------------------------------------------------------------------


@pytest.mark.slow
@pytest.mark.parametrize(("name", "paper"), CASES)
def test_pages_are_office_paper_one_per_tile(
    name: str,
    paper: str,
    pdfs: dict[tuple[str, str], Path],
    real_plan: SheetPlan,
    multi_plan: SheetPlan,
) -> None:
    plan = _plan(name, real_plan, multi_plan)
    reader = PdfReader(pdfs[name, paper])
    tiles = plan_tiles(plan, paper)
    # a mat needs several pages; the last page is the key (every part's full label)
    assert len(reader.pages) == len(tiles) + 1 and len(tiles) > len(plan.sheets)
    count = len(reader.pages)
    assert reader.pages[-1].extract_text().startswith("Key")
    for k, (page, tile) in enumerate(zip(reader.pages[:-1], tiles, strict=True), start=1):
        box = page.mediabox
        assert (float(box.left), float(box.bottom)) == (0.0, 0.0)
        assert float(box.width) == pytest.approx(PAGE_PT[paper][0], abs=0.01)
        assert float(box.height) == pytest.approx(PAGE_PT[paper][1], abs=0.01)
        text = page.extract_text()
        assert f"page {k} of {count}" in text
        assert f"row {tile.row} of {tile.rows}, column {tile.column} of {tile.columns}" in text
        assert f"sheet {tile.sheet}/{len(plan.sheets)}" in text


@pytest.mark.parametrize(("name", "paper"), CASES)
def test_frame_and_check_square_are_one_to_one(
    name: str,
    paper: str,
    pdfs: dict[tuple[str, str], Path],
    real_plan: SheetPlan,
    multi_plan: SheetPlan,
) -> None:
    reader = PdfReader(pdfs[name, paper])
    cw, ch = drawing_area(PAPERS[paper])
    for page in reader.pages[:-1]:  # the tiles (the last page is the key)
        found = boxes(page_paths(reader, page))
        squares = [b for b in found if abs(b[2] - 10) < TOL_MM and abs(b[3] - 10) < TOL_MM]
        assert [b[4] for b in squares if b[4] == (0.0, 0.0, 0.0)], "no black 10 mm square"
        for _x, _y, w, h, _ in squares:
            assert w == pytest.approx(CHECK_SQUARE_MM, abs=TOL_MM)
            assert h == pytest.approx(CHECK_SQUARE_MM, abs=TOL_MM)
        frames = [b for b in found if abs(b[2] - cw) < TOL_MM and abs(b[3] - ch) < TOL_MM]
        assert len(frames) == 1  # the drawing area's frame, the trim line


@pytest.mark.parametrize(("name", "paper"), CASES)
def test_registration_marks_at_the_stated_spacing(
    name: str,
    paper: str,
    pdfs: dict[tuple[str, str], Path],
    real_plan: SheetPlan,
    multi_plan: SheetPlan,
) -> None:
    plan = _plan(name, real_plan, multi_plan)
    reader = PdfReader(pdfs[name, paper])
    tiles = plan_tiles(plan, paper)
    cw, ch = drawing_area(PAPERS[paper])
    found = [crosses(page_paths(reader, page)) for page in reader.pages[:-1]]  # not the key
    spaced = 0
    for tile, marks in zip(tiles, found, strict=True):
        sheet = plan.sheets[tile.sheet - 1]
        expected = [tile.to_page(p) for p in registration_marks(tile, sheet.width, sheet.height)]
        assert len(marks) == len(expected) > 0
        for p in expected:
            assert min(math.dist(p, m) for m in marks) < TOL_MM
        # along each overlap (the middle of the drawing area's edge strips), neighbouring marks
        # are MARK_PITCH_MM apart on paper
        left, bottom = PAGE_MARGIN_MM, FOOTER_MM
        half = OVERLAP_MM / 2
        bands = (
            (0, left + half),
            (0, left + cw - half),
            (1, bottom + half),
            (1, bottom + ch - half),
        )
        for axis, at in bands:
            run = sorted(m[1 - axis] for m in marks if abs(m[axis] - at) < TOL_MM)
            for a, b in itertools.pairwise(run):
                assert b - a == pytest.approx(MARK_PITCH_MM, abs=TOL_MM)
                spaced += 1
    assert spaced > 0
    # a neighbour shows the same marks of the shared overlap, one step of the grid away on paper
    index = {(t.sheet, t.row, t.column): k for k, t in enumerate(tiles)}
    pairs = 0
    for k, tile in enumerate(tiles):
        for dr, dc, shift in ((0, 1, (cw - OVERLAP_MM, 0.0)), (1, 0, (0.0, -(ch - OVERLAP_MM)))):
            other = index.get((tile.sheet, tile.row + dr, tile.column + dc))
            if other is None:
                continue
            band = [
                m
                for m in found[k]
                if (dc and m[0] > cw)
                or (dr and m[1] < FOOTER_MM + OVERLAP_MM)  # right / bottom edge
            ]
            assert band
            for m in band:
                moved = (m[0] - shift[0], m[1] - shift[1])
                assert min(math.dist(moved, q) for q in found[other]) < TOL_MM
                pairs += 1
    assert pairs > 0


@pytest.mark.slow
@pytest.mark.parametrize(("name", "paper"), CASES)
def test_tiles_cover_the_drawn_sheet(
    name: str,
    paper: str,
    pdfs: dict[tuple[str, str], Path],
    real_plan: SheetPlan,
    multi_plan: SheetPlan,
) -> None:
    plan = _plan(name, real_plan, multi_plan)
    reader = PdfReader(pdfs[name, paper])
    tiles = plan_tiles(plan, paper)
    grid = plan_tiles(plan, paper, empty=True)
    # the whole grid covers every sheet, edge to edge
    for number, sheet in enumerate(plan.sheets, start=1):
        windows = [t.window for t in grid if t.sheet == number]
        for i in range(int(sheet.width) + 1):
            for j in range(int(sheet.height) + 1):
                x, y = min(i, sheet.width), min(j, sheet.height)
                assert any(a <= x <= c and b <= y <= d for a, b, c, d in windows), (x, y)
    # the pages left out hold no part; the pages printed cover every part's bounding box
    for t in grid:
        if t in tiles:
            continue
        x0, y0, x1, y1 = t.window
        for pl in plan.sheets[t.sheet - 1].placements:
            a, b, c, d = pl.bounds
            assert c <= x0 or a >= x1 or d <= y0 or b >= y1, (t, pl.part.name)
    for pl in plan.placements:
        windows = [t.window for t in tiles if t.sheet == pl.sheet + 1]
        a, b, c, d = pl.bounds
        for i in range(math.ceil(c - a) + 1):
            for j in range(math.ceil(d - b) + 1):
                x, y = min(a + i, c), min(b + j, d)
                assert any(p <= x <= r and q <= y <= u for p, q, r, u in windows), (x, y)
    # every outline corner of every part is drawn at 1:1 on a page whose window holds it
    black = [
        [p for sp in page_paths(reader, page) if sp.stroke == (0.0, 0.0, 0.0) for p in sp.points]
        for page in reader.pages
    ]
    corners = 0
    for placement in plan.placements:
        for v in place(placement).outline:
            shown = False
            for k, tile in enumerate(tiles):
                x0, y0, x1, y1 = tile.window
                if tile.sheet != placement.sheet + 1:
                    continue
                if not (x0 + 0.5 < v[0] < x1 - 0.5 and y0 + 0.5 < v[1] < y1 - 0.5):
                    continue
                p = tile.to_page(v)
                assert min(math.dist(p, q) for q in black[k]) < TOL_MM
                shown = True
            assert shown, (placement.part.name, v)
            corners += 1
    assert corners >= 4 * len(plan.placements)


@pytest.mark.slow
def test_pages_with_nothing_to_cut_are_left_out(real_plan: SheetPlan, tmp_path: Path) -> None:
    """Case 1's parts fill the upper part of the 12 x 24 in mat (packed from its top-left
    corner): its lower pages are left out, unless asked for; the pages kept keep their row and
    column."""
    kept = PdfReader(write_tiled_pdf(real_plan, tmp_path / "kept.pdf", "a4"))
    full = PdfReader(write_tiled_pdf(real_plan, tmp_path / "full.pdf", "a4", empty=True))
    grid = plan_tiles(real_plan, "a4", empty=True)
    assert len(full.pages) - 1 == len(grid) == grid[0].rows * grid[0].columns  # and the key
    assert 0 < len(kept.pages) < len(full.pages)
    rows = {t.row for t in plan_tiles(real_plan, "a4")}
    assert 1 in rows and grid[0].rows not in rows  # the bottom of the mat is empty
    text = kept.pages[0].extract_text()
    assert "left out" in text and f"page 1 of {len(kept.pages)}" in text


def test_write_files_adds_the_tiles_beside_the_mat_pages(
    real_plan: SheetPlan, tmp_path: Path
) -> None:
    out = tmp_path / "out"
    written = write_files(real_plan, out, line_style("perforated", cut=2, gap=1), paper="Letter")
    names = sorted(p.name for p in written)
    assert names == sorted(p.name for p in out.iterdir())
    assert "pattern.pdf" in names and "pattern-letter.pdf" in names
    mat = PdfReader(out / "pattern.pdf").pages[0].mediabox
    assert float(mat.width) == pytest.approx(real_plan.cutter.width * PT, abs=0.01)
    letter = PdfReader(out / "pattern-letter.pdf")
    assert len(letter.pages) == len(plan_tiles(real_plan, "letter")) + 1  # the tiles, the key
    assert float(letter.pages[0].mediabox.width) == pytest.approx(612.0, abs=0.01)
    # the default writes the mat pages only
    default = write_files(real_plan, tmp_path / "plain", formats=("pdf",))
    assert [p.name for p in default] == ["pattern.pdf"]


def test_bad_paper_names_the_field_and_writes_nothing(real_plan: SheetPlan, tmp_path: Path) -> None:
    out = tmp_path / "out"
    with pytest.raises(UnknownNameError) as err:
        write_files(real_plan, out, paper="a3")
    assert err.value.field == "paper"
    assert "one of a4, letter, mat" in str(err.value)
    assert not out.exists() or list(out.iterdir()) == []


@pytest.mark.slow
def test_cli_paper_option(tmp_path: Path, cli: CliRun) -> None:
    case1 = ["pattern", "--W", "8", "--n", "8", "--alpha", "84", "--material", "dura-lar"]
    bad = tmp_path / "bad"
    code, _, err = cli([*case1, "--out", str(bad), "--paper", "A3"])
    assert code == 2
    assert len(err.strip().splitlines()) == 1 and "paper" in err
    assert not bad.exists()
    spec = Path(__file__).resolve().parents[2] / "examples" / "blimp_gripper.toml"
    code, _, err = cli(["design", str(spec), "--out", str(bad), "--paper", "tabloid"])
    assert code == 2
    assert len(err.strip().splitlines()) == 1 and "paper = 'tabloid' is unknown" in err
    assert not bad.exists()
    good = tmp_path / "good"
    code, _, err = cli([*case1, "--out", str(good), "--paper", "a4"])
    assert code == 0, err
    reader = PdfReader(good / "pattern-a4.pdf")
    a = Assembly.identical(Layer(8.0, 8, 84.0, get_material("dura-lar")))
    tiles = plan_tiles(cut_plan(a).plan, "a4")  # the CLI's defaults
    assert len(reader.pages) == len(tiles) + 1 and tiles[0].rows * tiles[0].columns == 4
    for page in reader.pages:
        assert float(page.mediabox.width) == pytest.approx(595.28, abs=0.01)
        assert float(page.mediabox.height) == pytest.approx(841.89, abs=0.01)
    assert (good / "pattern.pdf").exists()


def test_each_mat_page_carries_the_fold_map_legend_naming_the_cut_files_operations(
    tmp_path: Path,
) -> None:
    from pypdf import PdfReader

    from corrugate.export.legend import fold_map_legend
    from corrugate.export.machines import get_machine
    from corrugate.export.operations import default_operations

    m = get_material("dura-lar")
    a = Assembly.identical(Layer(W=8.0, n=8, alpha_deg=84.0, material=m))
    plan = plan_sheets(build_pattern(a).parts, "cameo4-12x12")
    ops = default_operations(get_machine("cameo4-12x12"), "dura-lar")
    (path,) = write_files(plan, tmp_path, operations=ops, formats=("pdf",))
    pages = PdfReader(str(path)).pages
    assert len(pages) == len(plan.sheets)
    rows = [r.text for r in fold_map_legend(ops, steps=False)]  # its labels carry no step
    assert rows[0].startswith("FOLD MAP: for people, not the cutter")
    assert "(cut file: perforate)" in rows[1]  # the mountains, as the cut file makes them
    for page in pages:
        text = " ".join(page.extract_text().split())
        for row in rows:
            assert " ".join(row.split()) in text, row


@pytest.mark.parametrize("paper", ["mat", "a4"])
def test_the_printed_legend_says_what_the_printed_labels_carry(tmp_path: Path, paper: str) -> None:
    """The PDF's legend speaks of the labels on its own pages: the fold map's "grey: labels, with
    the step in the folding order" was printed on pattern.pdf (and the tiled key) whose labels are
    the parts' names without a step ("L1", not "1. L1"). Read back with pypdf: where the legend
    says the labels carry a step, each part's name on the page follows its step number."""
    import re

    from pypdf import PdfReader

    from corrugate.export.machines import get_machine
    from corrugate.export.operations import default_operations

    a = Assembly.identical(Layer(W=8.0, n=9, alpha_deg=78.0, material=get_material("dura-lar")))
    plan = plan_sheets(build_pattern(a).parts, "cameo4-12x12")
    ops = default_operations(get_machine("cameo4-12x12"), "dura-lar")
    written = write_files(plan, tmp_path, operations=ops, formats=("pdf",), paper=paper)
    path = [p for p in written if p.suffix == ".pdf"][-1]
    assert path.name == ("pattern.pdf" if paper == "mat" else f"pattern-{paper}.pdf")
    text = " ".join(" ".join(p.extract_text().split()) for p in PdfReader(str(path)).pages)
    names = [p.part.name for p in plan.placements]
    assert {"L1", "L2", "B1"} <= set(names)
    assert "grey: labels" in text  # the legend's row on the labels is printed
    claims_steps = "step in the folding order" in text
    carries_steps = all(re.search(rf"\b\d+\. {name}\b", text) for name in names)
    assert claims_steps == carries_steps, (claims_steps, carries_steps)
