"""The 2D writers (SVG, DXF, PDF), checked by reading the written files back."""

from __future__ import annotations

import re
import subprocess
import sys
import xml.etree.ElementTree as ET
from pathlib import Path

import pytest
from ezdxf.entities.dxfgfx import DXFGraphic
from ezdxf.filemanagement import readfile

from corrugate.core.errors import InputError, UnknownNameError
from corrugate.export import files as files_module
from corrugate.export import write_dxf, write_files, write_pdf, write_svg
from corrugate.export.labels import label_spot
from corrugate.export.pdf import CHECK_SQUARE_MM, check_square_spot
from corrugate.fabrication.linestyle import (
    SOLID,
    LineStyle,
    PerforationError,
    dash_layout,
    line_style,
)
from corrugate.fabrication.model import Line, Part, Role
from corrugate.fabrication.sheets import PartTooLargeError, SheetPlan, place, plan_sheets
from plan_readers import svg_mm_per_unit

SVG = "{http://www.w3.org/2000/svg}"
COLOUR = {
    Role.MOUNTAIN: "#ff0000",
    Role.VALLEY: "#0000ff",
    Role.CUT: "#00ff00",
    Role.MARK: "#ff00ff",
}


def blank(name: str, n: int = 8, W: float = 8.0, L: float = 48.18, angle: float = 96.0) -> Part:
    """A layer blank: (n + 1) W x L with n creases alternating mountain / valley."""
    lines = tuple(
        Line(
            ((k + 1) * W, 0.0),
            ((k + 1) * W, L),
            Role.MOUNTAIN if k % 2 == 0 else Role.VALLEY,
            angle + k,  # distinct angles, so a swapped crease would show
        )
        for k in range(n)
    )
    return Part(
        name, f"Layer {name}", ((0.0, 0.0), ((n + 1) * W, 0.0), ((n + 1) * W, L), (0.0, L)), lines
    )


def ell() -> Part:
    """Concave L part with a hole, a slit (cut), a mark and one valley crease."""
    return Part(
        "ell",
        "L part",
        ((0.0, 0.0), (60.0, 0.0), (60.0, 20.0), (20.0, 20.0), (20.0, 50.0), (0.0, 50.0)),
        (
            Line((10.0, 0.0), (10.0, 50.0), Role.MARK),
            Line((30.0, 5.0), (50.0, 5.0), Role.CUT),
            Line((20.0, 12.0), (60.0, 12.0), Role.VALLEY, 90.0),
        ),
        holes=(((5.0, 30.0), (15.0, 30.0), (15.0, 40.0), (5.0, 40.0)),),
        kind="connector",
    )


def strip(name: str) -> Part:
    """A 10 x 250 mm connector strip with two mountain creases across it."""
    return Part(
        name,
        name,
        ((0.0, 0.0), (10.0, 0.0), (10.0, 250.0), (0.0, 250.0)),
        (
            Line((0.0, 100.0), (10.0, 100.0), Role.MOUNTAIN, 45.0),
            Line((0.0, 150.0), (10.0, 150.0), Role.MOUNTAIN, 45.0),
        ),
        kind="connector",
    )


@pytest.fixture
def parts() -> list[Part]:
    return [blank("layer-1"), blank("layer-2"), ell(), strip("strip-a"), strip("strip-b")]


@pytest.fixture
def plan(parts: list[Part]) -> SheetPlan:
    return plan_sheets(parts, "cameo4-12x12")


@pytest.fixture
def multi_plan(parts: list[Part]) -> SheetPlan:
    """The same parts on a small laser bed: several sheets."""
    return plan_sheets(parts, "laser:270x80")


def all_creases(plan: SheetPlan) -> list[tuple[str, int, Line]]:
    """(part name, 1-based crease number, placed line) for every crease of the plan."""
    out = []
    for p in plan.placements:
        k = 0
        for ln in place(p).lines:
            if ln.role in (Role.MOUNTAIN, Role.VALLEY):
                k += 1
                out.append((p.part.name, k, ln))
    return out


def listing(path: Path) -> list[str]:
    return sorted(f.name for f in path.iterdir())


# -- SVG -------------------------------------------------------------------------------------------


def test_svg_size_in_mm_matches_viewbox(plan: SheetPlan, tmp_path: Path) -> None:
    path = write_svg(plan.sheets[0], tmp_path / "s.svg")
    root = ET.parse(path).getroot()
    assert root.tag == f"{SVG}svg"
    w, h = root.attrib["width"], root.attrib["height"]
    assert w.endswith("mm") and h.endswith("mm")
    assert [float(w[:-2]), float(h[:-2])] == pytest.approx(
        [plan.sheets[0].width, plan.sheets[0].height], abs=1e-4
    )
    # the viewBox has the page's proportions, so the drawing prints at its size in mm
    vb = [float(v) for v in root.attrib["viewBox"].split()]
    unit = svg_mm_per_unit(root)
    assert vb[:2] == [0.0, 0.0]
    assert [vb[2] * unit, vb[3] * unit] == pytest.approx([float(w[:-2]), float(h[:-2])])
    # Origami Simulator's SVG import merges vertices closer than 3 user units (its default
    # vertex merge tolerance, js/globals.js vertTol = 3): that must stay below what a cutter can
    # tell apart (about 0.1 mm), so no two points of a pattern are merged
    assert 3 * unit <= 0.05


def test_svg_every_crease_once_with_its_colour_and_opacity(plan: SheetPlan, tmp_path: Path) -> None:
    sheet = plan.sheets[0]
    root = ET.parse(write_svg(sheet, tmp_path / "s.svg")).getroot()
    H, unit = sheet.height, svg_mm_per_unit(root)
    crease_elems = [e for e in root.iter(f"{SVG}line") if "data-crease" in e.attrib]
    expected = all_creases(plan)
    assert len(crease_elems) == len(expected) == 8 + 8 + 1 + 2 + 2
    by_id = {e.attrib["data-crease"]: e for e in crease_elems}
    assert len(by_id) == len(crease_elems)  # each crease once
    for name, k, ln in expected:
        e = by_id[f"{name}:{k}"]
        assert e.attrib["stroke"] == COLOUR[ln.role]
        assert e.attrib["class"] == f"crease {ln.role.value}"
        assert float(e.attrib["opacity"]) == pytest.approx(ln.fold_angle_deg / 180, abs=1e-6)
        assert float(e.attrib["data-fold-angle"]) == pytest.approx(ln.fold_angle_deg)
        got = [float(e.attrib[a]) * unit for a in ("x1", "y1", "x2", "y2")]
        assert got == pytest.approx([ln.a[0], H - ln.a[1], ln.b[0], H - ln.b[1]], abs=1e-4)
    # colours are plain hex, opacity an attribute: no rgba() anywhere, no stroke-opacity in colour
    text = (tmp_path / "s.svg").read_text()
    assert "rgba" not in text and "rgb(" not in text


def test_svg_outlines_holes_cuts_marks_and_labels(plan: SheetPlan, tmp_path: Path) -> None:
    root = ET.parse(write_svg(plan.sheets[0], tmp_path / "s.svg")).getroot()
    polygons = list(root.iter(f"{SVG}polygon"))
    outlines = [p for p in polygons if "outline" in p.attrib["class"]]
    holes = [p for p in polygons if "hole" in p.attrib["class"]]
    assert len(outlines) == len(plan.placements) and len(holes) == 1
    for p in polygons:
        assert p.attrib["stroke"] == "#000000" and p.attrib["opacity"] == "1"
        assert p.attrib["fill"] == "none"
    cuts = [e for e in root.iter(f"{SVG}line") if e.attrib.get("class") == "cut"]
    marks = [e for e in root.iter(f"{SVG}line") if e.attrib.get("class") == "mark"]
    assert (
        len(cuts) == 1
        and cuts[0].attrib["stroke"] == "#00ff00"
        and cuts[0].attrib["opacity"] == "1"
    )
    assert (
        len(marks) == 1
        and marks[0].attrib["stroke"] == "#ff00ff"
        and marks[0].attrib["opacity"] == "1"
    )
    # the marks sit in <defs> (Origami Simulator deletes its children unread), drawn by a <use>
    (defs,) = root.iter(f"{SVG}defs")
    assert marks[0] in list(defs.iter(f"{SVG}line"))
    assert [u.attrib["href"] for u in root.iter(f"{SVG}use")] == ["#band-marks"]
    (group,) = (g for g in root.iter(f"{SVG}g") if g.attrib.get("id") == "labels")
    (legend,) = (g for g in root.iter(f"{SVG}g") if g.attrib.get("id") == "legend")
    labels = {t.attrib["data-part"]: t.text or "" for t in group.iter(f"{SVG}text")}
    rows = [t.text for t in legend.iter(f"{SVG}text")]
    # each label leads with the part's name, as ASSEMBLY.md's steps call the part; one too long
    # to read on its part is the part's name there and in full in a row of the legend
    for p in plan.placements:
        full = (
            p.part.label
            if p.part.label.startswith(p.part.name)
            else f"{p.part.name}: {p.part.label}"
        )
        assert labels[p.part.name] == full or (labels[p.part.name] == p.part.name and full in rows)
    # without marks (for Origami Simulator) the marks are gone and the creases stay
    root2 = ET.parse(write_svg(plan.sheets[0], tmp_path / "m.svg", marks=False)).getroot()
    assert not [e for e in root2.iter(f"{SVG}line") if e.attrib.get("class") == "mark"]
    assert len([e for e in root2.iter(f"{SVG}line") if "data-crease" in e.attrib]) == 21


def test_fold_map_draws_perforated_creases_solid(plan: SheetPlan, tmp_path: Path) -> None:
    # the fold map is for people and Origami Simulator: no dash pattern a cutter would ignore
    style = line_style("perforated", cut=2.0, gap=1.0)
    path = write_svg(plan.sheets[0], tmp_path / "p.svg", style)
    assert "dasharray" not in path.read_text()
    root = ET.parse(path).getroot()
    elems = {
        e.attrib["data-crease"]: e for e in root.iter(f"{SVG}line") if "data-crease" in e.attrib
    }
    assert len(elems) == len(list(all_creases(plan))) > 0
    for e in elems.values():
        assert e.attrib["data-style"] == "perforated"


def test_svg_scored_creases_are_solid_and_tagged(plan: SheetPlan, tmp_path: Path) -> None:
    root = ET.parse(write_svg(plan.sheets[0], tmp_path / "s.svg", line_style("scored"))).getroot()
    creases = [e for e in root.iter(f"{SVG}line") if "data-crease" in e.attrib]
    assert len(creases) == 21
    assert all(e.attrib["data-style"] == "scored" for e in creases)
    assert not any("stroke-dasharray" in e.attrib for e in creases)


# -- DXF -------------------------------------------------------------------------------------------


@pytest.mark.parametrize(
    "style", [SOLID, line_style("scored"), line_style("perforated", cut=2, gap=1)]
)
def test_dxf_audits_clean_in_mm_with_a_layer_per_role(
    plan: SheetPlan, tmp_path: Path, style: LineStyle
) -> None:
    path = write_dxf(plan.sheets[0], tmp_path / "s.dxf", style)
    doc = readfile(path)
    auditor = doc.audit()
    assert not auditor.has_errors, [str(e) for e in auditor.errors]
    assert doc.header["$INSUNITS"] == 4
    msp = doc.modelspace()
    creases = all_creases(plan)
    n_m = sum(1 for c in creases if c[2].role is Role.MOUNTAIN)
    n_v = sum(1 for c in creases if c[2].role is Role.VALLEY)

    def on(layer: str, kind: str) -> list[DXFGraphic]:
        return list(msp.query(f'{kind}[layer=="{layer}"]'))

    outlines = on("CUT", "LWPOLYLINE")
    assert len(outlines) == len(plan.placements) + 1  # + the hole
    assert all(e.dxf.flags & 1 for e in outlines)  # closed
    assert len(on("CUT", "LINE")) == 1  # the slit
    assert len(on("MOUNTAIN", "LINE")) == n_m
    assert len(on("VALLEY", "LINE")) == n_v
    assert len(on("MARK", "LINE")) == 1
    assert len(on("LABEL", "TEXT")) == len(plan.placements)
    layers = {"CUT", "MOUNTAIN", "VALLEY", "MARK", "LABEL"}
    if style.kind.value == "scored":
        layers.add("SCORE")
        assert len(on("SCORE", "LINE")) == n_m + n_v
    if style.kind.value == "perforated":
        layers.add("PERFORATE")
        expected = sum(len(dash_layout(c[2].length, 2.0, 1.0)) for c in creases)
        dashes = on("PERFORATE", "LINE")
        assert len(dashes) == expected
        for d in dashes:
            length = (d.dxf.end - d.dxf.start).magnitude
            assert length == pytest.approx(2.0)
    for name in layers:
        assert name in doc.layers
    colours = [doc.layers.get(n).color for n in layers]
    assert len(set(colours)) == len(colours)  # distinct colours
    # every entity sits on one of those layers
    assert {e.dxf.layer for e in msp} == layers


def test_dxf_crease_geometry_and_fold_angle(plan: SheetPlan, tmp_path: Path) -> None:
    doc = readfile(write_dxf(plan.sheets[0], tmp_path / "s.dxf"))
    lines = [e for e in doc.modelspace().query("LINE") if e.dxf.layer in ("MOUNTAIN", "VALLEY")]
    got = sorted(
        (
            round(e.dxf.start.x, 6),
            round(e.dxf.start.y, 6),
            round(e.dxf.end.x, 6),
            round(e.dxf.end.y, 6),
        )
        for e in lines
    )
    want = sorted(
        (round(ln.a[0], 6), round(ln.a[1], 6), round(ln.b[0], 6), round(ln.b[1], 6))
        for _, _, ln in all_creases(plan)
    )
    assert got == want
    for e in lines:
        xdata = e.get_xdata("CORRUGATE")
        assert xdata[0].value.startswith("crease ")
        assert 0 < xdata[2].value <= 180


# -- PDF -------------------------------------------------------------------------------------------


def pdf_pages(path: Path) -> list[tuple[float, float]]:
    """(width, height) in pt of every page, from the MediaBox entries of the file."""
    data = path.read_bytes()
    assert data.startswith(b"%PDF-") and data.rstrip().endswith(b"%%EOF")
    boxes = re.findall(
        rb"/MediaBox\s*\[\s*([-\d.]+)\s+([-\d.]+)\s+([-\d.]+)\s+([-\d.]+)\s*\]", data
    )
    n_pages = len(re.findall(rb"/Type\s*/Page\b(?!s)", data))
    assert len(boxes) == n_pages
    return [(float(x1) - float(x0), float(y1) - float(y0)) for x0, y0, x1, y1 in boxes]


def test_pdf_pages_are_the_sheets_at_one_to_one(multi_plan: SheetPlan, tmp_path: Path) -> None:
    assert len(multi_plan.sheets) > 1
    pages = pdf_pages(write_pdf(multi_plan, tmp_path / "p.pdf"))
    assert len(pages) == len(multi_plan.sheets)
    for (w, h), sheet in zip(pages, multi_plan.sheets, strict=True):
        assert w == pytest.approx(sheet.width / 25.4 * 72, abs=0.01)
        assert h == pytest.approx(sheet.height / 25.4 * 72, abs=0.01)


def test_pdf_mat_page_and_perforated_lines(plan: SheetPlan, tmp_path: Path) -> None:
    style = line_style("perforated", cut=2, gap=1)
    pages = pdf_pages(write_pdf(plan, tmp_path / "p.pdf", style))
    assert pages == [pytest.approx((11.5 * 72, 11.5 * 72), abs=0.01)]


def test_check_square_is_in_a_free_spot(plan: SheetPlan, multi_plan: SheetPlan) -> None:
    for p in (plan, multi_plan):
        for sheet in p.sheets:
            corner = check_square_spot(sheet, p.spacing)
            if corner is None:
                continue
            x, y = corner
            s = CHECK_SQUARE_MM
            assert x >= 0 and x + s <= sheet.width and y >= 0 and y + s <= sheet.height
            for b in (q.bounds for q in sheet.placements):
                assert x + s <= b[0] or b[2] <= x or y + s <= b[1] or b[3] <= y
    assert check_square_spot(plan.sheets[0], plan.spacing) is not None


def test_labels_sit_on_the_material(plan: SheetPlan) -> None:
    for placement in plan.placements:
        placed = place(placement)
        spot = label_spot(placed)
        x0, y0, x1, y1 = placement.bounds
        assert x0 < spot.x < x1 and y0 < spot.y < y1
        assert 0 < spot.size <= 4.0
    # the L part's label is on the L (not in its empty corner) and not in its hole
    ell_place = next(p for p in plan.placements if p.part.name == "ell")
    spot = label_spot(place(ell_place))
    lx, ly = spot.x - ell_place.x, spot.y - ell_place.y  # not rotated: local coordinates
    assert not (lx > 20 and ly > 20)
    assert not (5 <= lx <= 15 and 30 <= ly <= 40)


# -- write_files: all or nothing -------------------------------------------------------------------


def test_write_files_writes_every_sheet_and_one_pdf(multi_plan: SheetPlan, tmp_path: Path) -> None:
    out = tmp_path / "out"
    written = write_files(multi_plan, out, line_style("perforated", cut=2, gap=1))
    n = len(multi_plan.sheets)
    expected = sorted(  # laser:270x80: cut files in SVG and DXF
        [f"sheet-{k}.svg" for k in range(1, n + 1)]
        + [f"cut-{k}.svg" for k in range(1, n + 1)]
        + [f"cut-{k}.dxf" for k in range(1, n + 1)]
        + ["pattern.pdf"]
    )
    assert listing(out) == expected  # and no temporary file left
    assert sorted(p.name for p in written) == expected
    for k in range(1, n + 1):
        ET.parse(out / f"sheet-{k}.svg")
        ET.parse(out / f"cut-{k}.svg")
        assert not readfile(out / f"cut-{k}.dxf").audit().has_errors
    assert len(pdf_pages(out / "pattern.pdf")) == n
    # SVG sheet k holds exactly the parts placed on sheet k - 1
    for k, sheet in enumerate(multi_plan.sheets, start=1):
        root = ET.parse(out / f"sheet-{k}.svg").getroot()
        names = sorted(
            g.attrib["data-part"] for g in root.iter(f"{SVG}g") if "data-part" in g.attrib
        )
        assert names == sorted(p.part.name for p in sheet.placements)


def test_bad_perforation_leaves_no_file(plan: SheetPlan, tmp_path: Path) -> None:
    out = tmp_path / "out"
    out.mkdir()
    (out / "keep.txt").write_text("earlier")
    with pytest.raises(PerforationError) as err:
        write_files(plan, out, line_style("perforated", cut=9.0, gap=2.0))  # strip creases: 10 mm
    assert "part 'strip-a'" in str(err.value) or "part 'strip-b'" in str(err.value)
    assert isinstance(err.value, InputError)
    assert listing(out) == ["keep.txt"]
    bad = line_style("perforated", cut=9.0, gap=2.0)
    with pytest.raises(PerforationError):
        write_svg(plan.sheets[0], out / "x.svg", bad)
    with pytest.raises(PerforationError):
        write_dxf(plan.sheets[0], out / "x.dxf", bad)
    with pytest.raises(PerforationError):
        write_pdf(plan, out / "x.pdf", bad)
    assert listing(out) == ["keep.txt"]


def test_oversize_part_and_unknown_cutter_leave_no_file(parts: list[Part], tmp_path: Path) -> None:
    out = tmp_path / "out"

    def run(cutter: str, extra: list[Part]) -> None:
        write_files(plan_sheets([*parts, *extra], cutter), out)

    with pytest.raises(PartTooLargeError, match="'huge'"):
        run("cameo4-12x12", [blank("huge", n=40)])  # 41 x 8 = 328 mm long
    with pytest.raises(UnknownNameError, match="cutter"):
        run("cameo3", [])
    assert not out.exists()
    with pytest.raises(UnknownNameError, match="format"):
        write_files(plan_sheets(parts, "cameo4-12x12"), out, formats=("svg", "png"))
    assert not out.exists() or listing(out) == []


def test_failure_while_writing_leaves_no_partial_file(
    plan: SheetPlan, tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    out = tmp_path / "out"
    out.mkdir()
    (out / "sheet-1.svg").write_text("old")

    def broken(plan: SheetPlan, path: Path, *args: object, **kwargs: object) -> None:
        path.write_bytes(b"%PDF-1.4 half a file")
        raise OSError("disk full")

    monkeypatch.setattr(files_module, "render_pdf", broken)
    with pytest.raises(OSError, match="disk full"):
        write_files(plan, out)
    assert listing(out) == ["sheet-1.svg"]  # no new file, no temporary file
    assert (out / "sheet-1.svg").read_text() == "old"  # the earlier file untouched


def test_core_package_imports_no_heavy_library() -> None:
    code = (
        "import sys, corrugate, corrugate.fabrication.sheets, corrugate.fabrication.linestyle, "
        "corrugate.export; "
        "bad = [m for m in ('ezdxf', 'matplotlib', 'trimesh') if m in sys.modules]; "
        "assert not bad, bad"
    )
    subprocess.run([sys.executable, "-c", code], check=True)
