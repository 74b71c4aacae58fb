"""The case study's labels read back from its files as the programs a maker uses read them (issue 36
item 8: "L1" overprinted by crease lines; issue 38: the files open in Inkscape and LibreCAD).

The files are those `corrugate design examples/blimp_gripper.toml --out` writes for a Cricut
(``--machine maker-12x12``: ``cut-1.svg``) and a Silhouette (``cameo4-12x12``: ``cut-1.dxf``), and
the fold map ``sheet-1.svg``: the answer W 8, n 9, alpha 78 on Dura-Lar 0.125 mm with a 5 mm margin
(byte for byte the same SVGs as design --out's, and the same DXF but for its timestamps and
GUIDs: `cmp` and `diff`, 2026-12-06). Everything is read from the files alone, with
``xml.etree`` and ``ezdxf``: each label's box (the extent of its pen strokes in a cut file; in the
fold map its anchor, ``textLength`` by 1.2 em, turned by its ``rotate``) must keep
:data:`GAP` from every cut, crease and mark segment in the same file; a perforated crease is
the line through its dashes, end to end, so a label cannot sit in a perforation's gap either.
The slow test draws the SVGs in Inkscape without their labels and finds no ink in any label's box.
"""

from __future__ import annotations

import itertools
import math
import os
import re
import shutil
import subprocess
import xml.etree.ElementTree as ET
from collections.abc import Iterable
from pathlib import Path

import numpy as np
import pytest
from ezdxf.filemanagement import readfile
from PIL import Image

from corrugate import Assembly, Layer, get_material
from corrugate.export.files import write_files
from corrugate.fabrication.build import build_pattern
from corrugate.fabrication.sheets import plan_sheets

SVG = "{http://www.w3.org/2000/svg}"
#: The least gap (mm) a label keeps from every line (docs/fabrication.md, "Labels": a pen's or a
#: scoring wheel's line, 0.25-0.5 mm wide, stays off the letters).
GAP = 0.5
#: The case study's parts: two layers and the band's four strips (ASSEMBLY.md's steps).
PARTS = ["B1", "B2", "B3", "B4", "L1", "L2"]

Pt = tuple[float, float]
Seg = tuple[Pt, Pt]
Box = tuple[float, float, float, float]


@pytest.fixture(scope="module")
def case(tmp_path_factory: pytest.TempPathFactory) -> dict[str, Path]:
    """The case study's cut files and fold maps on a Cricut's and a Silhouette's mat."""
    layer = Layer(8, 9, 78, get_material("dura-lar"), t=0.125)
    pattern = build_pattern(Assembly.identical(layer))
    out: dict[str, Path] = {}
    for machine in ("maker-12x12", "cameo4-12x12"):
        plan = plan_sheets(pattern, machine, margin=5.0)
        folder = tmp_path_factory.mktemp(machine)
        for p in write_files(plan, folder, formats=("svg", "cut")):
            out[f"{machine}/{p.name}"] = p
    return out


# -- reading the files back ----------------------------------------------------------------------


def _svg_cut(path: Path) -> list[tuple[str, list[Pt], bool]]:
    """(layer, points in mm with y up, closed) of every path of a cut SVG."""
    root = ET.parse(path).getroot()
    H = float(root.attrib["viewBox"].split()[3])
    assert root.attrib["height"] == f"{root.attrib['viewBox'].split()[3]}mm"  # 1 unit = 1 mm
    out = []
    for g in root.iter(f"{SVG}g"):
        for e in g.iter(f"{SVG}path"):
            nums = [float(v) for v in re.findall(r"-?\d+(?:\.\d+)?", e.attrib["d"])]
            pts = [(nums[i], H - nums[i + 1]) for i in range(0, len(nums), 2)]
            out.append((g.attrib["id"], pts, e.attrib["d"].rstrip().endswith("Z")))
    return out


def _dxf_cut(path: Path) -> list[tuple[str, list[Pt], bool]]:
    """(layer, points in mm, closed) of every LINE and LWPOLYLINE of a cut DXF (ezdxf)."""
    doc = readfile(path)
    assert doc.header["$INSUNITS"] == 4  # mm
    out = []
    for e in doc.modelspace():
        if e.dxftype() == "LINE":
            a, b = e.dxf.start, e.dxf.end
            out.append((e.dxf.layer, [(a.x, a.y), (b.x, b.y)], False))
        else:
            assert e.dxftype() == "LWPOLYLINE", e.dxftype()
            pts = [(float(x), float(y)) for x, y in e.get_points("xy")]
            out.append((e.dxf.layer, pts, bool(e.closed)))
    return out


def _segments(pts: list[Pt], closed: bool) -> list[Seg]:
    return list(itertools.pairwise([*pts, pts[0]] if closed else pts))


def _whole_creases(segs: list[Seg]) -> list[Seg]:
    """The dashes of a perforation joined into their line: collinear segments (same direction and
    offset within 1 micrometre) become one segment from the first dash's end to the last's."""
    groups: dict[tuple[float, float], list[Seg]] = {}
    for a, b in segs:
        dx, dy = b[0] - a[0], b[1] - a[1]
        angle = math.atan2(dy, dx) % math.pi
        ux, uy = math.cos(angle), math.sin(angle)
        offset = -uy * a[0] + ux * a[1]
        key = (round(angle, 6), round(offset, 3))
        groups.setdefault(key, []).append((a, b))
    whole = []
    for (angle, _), group in groups.items():
        ux, uy = math.cos(angle), math.sin(angle)
        pts = [p for s in group for p in s]
        proj = [p[0] * ux + p[1] * uy for p in pts]
        whole.append((pts[int(np.argmin(proj))], pts[int(np.argmax(proj))]))
    return whole


def _cut_file_lines(paths: list[tuple[str, list[Pt], bool]]) -> list[Seg]:
    """Every line of a cut file the machine cuts, scores or draws, but its labels and legend."""
    lines: list[Seg] = []
    for layer in {op for op, _, _ in paths} - {"LABEL", "LEGEND"}:
        segs = [s for op, pts, c in paths if op == layer for s in _segments(pts, c)]
        creases = layer.startswith(("MOUNTAIN-", "VALLEY-"))
        lines += _whole_creases(segs) if creases else segs
    return lines


def _inside(p: Pt, ring: list[Pt]) -> bool:
    """Even-odd point in polygon."""
    hits = 0
    for (x0, y0), (x1, y1) in _segments(ring, True):
        if (y0 > p[1]) != (y1 > p[1]) and p[0] < x0 + (p[1] - y0) * (x1 - x0) / (y1 - y0):
            hits += 1
    return hits % 2 == 1


def _cut_file_labels(paths: list[tuple[str, list[Pt], bool]]) -> list[Box]:
    """Each part's label box: the extent of the LABEL strokes inside its outline (the closed CUT
    rings that hold other rings are outlines; every stroke must lie inside one)."""
    rings = [pts for op, pts, c in paths if op == "CUT" and c]
    outlines = [r for r in rings if not any(_inside(r[0], o) for o in rings if o is not r)]
    strokes: dict[int, list[Pt]] = {}
    for op, pts, _ in paths:
        if op != "LABEL":
            continue
        (k,) = (i for i, o in enumerate(outlines) if all(_inside(p, o) for p in pts))
        strokes.setdefault(k, []).extend(pts)
    boxes = []
    for pts in strokes.values():
        a = np.asarray(pts)
        boxes.append((*a.min(axis=0), *a.max(axis=0)))
    return boxes


def _gap(box: Box, seg: Seg) -> float:
    """The exact least distance (mm) between a segment and an axis-aligned box; 0 if they meet."""
    x0, y0, x1, y1 = box
    (ax, ay), (bx, by) = seg

    def to_box(x: float, y: float) -> float:
        return math.hypot(max(x0 - x, 0.0, x - x1), max(y0 - y, 0.0, y - y1))

    def to_seg(x: float, y: float) -> float:
        dx, dy = bx - ax, by - ay
        t = ((x - ax) * dx + (y - ay) * dy) / max(dx * dx + dy * dy, 1e-300)
        t = min(max(t, 0.0), 1.0)
        return math.hypot(ax + t * dx - x, ay + t * dy - y)

    # Liang-Barsky: does the segment enter the box?
    t0, t1 = 0.0, 1.0
    enters = True
    for p, q in ((ax - bx, ax - x0), (bx - ax, x1 - ax), (ay - by, ay - y0), (by - ay, y1 - ay)):
        if abs(p) < 1e-15:
            enters &= q >= 0
        elif p < 0:
            t0 = max(t0, q / p)
        else:
            t1 = min(t1, q / p)
    if enters and t0 <= t1:
        return 0.0
    corners = ((x0, y0), (x1, y0), (x1, y1), (x0, y1))
    return min([to_box(ax, ay), to_box(bx, by)] + [to_seg(x, y) for x, y in corners])


def test_gap_is_the_hand_distance() -> None:
    box = (0.0, 0.0, 2.0, 1.0)
    assert _gap(box, ((3.0, -5.0), (3.0, 5.0))) == pytest.approx(1.0)  # a line beside it
    assert _gap(box, ((1.0, -5.0), (1.0, 5.0))) == 0.0  # through it
    assert _gap(box, ((3.0, 2.0), (4.0, 3.0))) == pytest.approx(math.sqrt(2))  # off a corner
    assert _gap(box, ((4.0, 0.0), (2.0, 2.0))) == pytest.approx(math.sqrt(2) / 2)  # past one
    # a perforation's dashes are one crease: a box in the gap between two dashes is on it
    dashes = [((1.0, -5.0), (1.0, -0.5)), ((1.0, 1.5), (1.0, 5.0))]
    assert min(_gap(box, s) for s in dashes) > 0
    (whole,) = _whole_creases(dashes)
    assert _gap(box, whole) == 0.0


def _assert_clear(boxes: Iterable[Box], lines: list[Seg], where: str) -> None:
    for box in boxes:
        gap = min(_gap(box, s) for s in lines)
        assert gap >= GAP, (where, box, gap)


@pytest.mark.parametrize(
    ("name", "reader"), [("maker-12x12/cut-1.svg", _svg_cut), ("cameo4-12x12/cut-1.dxf", _dxf_cut)]
)
def test_cut_file_labels_are_clear_of_every_line_in_the_file(
    case: dict[str, Path], name: str, reader: object
) -> None:
    paths = reader(case[name])  # type: ignore[operator]
    boxes = _cut_file_labels(paths)
    assert len(boxes) == len(PARTS)  # one label on each part, inside its outline
    creases = [op for op, _, _ in paths if op.startswith(("MOUNTAIN-", "VALLEY-"))]
    assert creases  # the creases reach the machine (the Cricut perforates its mountains)
    _assert_clear(boxes, _cut_file_lines(paths), name)


def _fold_map_labels(root: ET.Element) -> list[tuple[str, Box, float]]:
    """(text, box in mm with y up, text height in mm) of every label of a fold map."""
    unit = float(root.attrib["width"][:-2]) / float(root.attrib["viewBox"].split()[2])
    H = unit * float(root.attrib["viewBox"].split()[3])
    (group,) = (g for g in root.iter(f"{SVG}g") if g.attrib.get("id") == "labels")
    out = []
    for t in group.iter(f"{SVG}text"):
        x, y = float(t.attrib["x"]) * unit, H - float(t.attrib["y"]) * unit
        size, length = float(t.attrib["font-size"]) * unit, float(t.attrib["textLength"]) * unit
        # the box is the text's: about 0.6 em a character (a sans-serif's mean advance)
        assert length == pytest.approx(0.6 * size * len(t.text or ""), rel=0.25), t.text
        half_l, half_h = length / 2, 0.6 * size  # its length by 1.2 em
        if "rotate" in t.attrib.get("transform", ""):
            half_l, half_h = half_h, half_l
        out.append((t.text or "", (x - half_l, y - half_h, x + half_l, y + half_h), size))
    return out


def _fold_map_lines(root: ET.Element) -> list[Seg]:
    """Every line of a fold map in mm (y up): the outlines (polygons) and the crease, slit and
    mark lines, those drawn from ``<defs>`` by a ``<use>`` included."""
    unit = float(root.attrib["width"][:-2]) / float(root.attrib["viewBox"].split()[2])
    H = unit * float(root.attrib["viewBox"].split()[3])
    segs: list[Seg] = []
    for e in root.iter(f"{SVG}line"):
        a = (unit * float(e.attrib["x1"]), H - unit * float(e.attrib["y1"]))
        b = (unit * float(e.attrib["x2"]), H - unit * float(e.attrib["y2"]))
        segs.append((a, b))
    for e in root.iter(f"{SVG}polygon"):
        nums = [unit * float(v) for v in re.split(r"[ ,]+", e.attrib["points"].strip())]
        segs += _segments([(nums[i], H - nums[i + 1]) for i in range(0, len(nums), 2)], True)
    return segs


@pytest.mark.parametrize("machine", ["maker-12x12", "cameo4-12x12"])
def test_fold_map_labels_are_clear_of_every_line_in_the_file(
    case: dict[str, Path], machine: str
) -> None:
    root = ET.parse(case[f"{machine}/sheet-1.svg"]).getroot()
    labels = _fold_map_labels(root)
    assert sorted(text.split(". ")[1] for text, _, _ in labels) == PARTS
    assert min(size for _, _, size in labels) >= 2.0  # readable at 1:1
    _assert_clear((box for _, box, _ in labels), _fold_map_lines(root), machine)
    # the band's marks, drawn from <defs>, named as SVG 2 and as SVG 1.1 (Inkscape 1.2) read a <use>
    (use,) = root.iter(f"{SVG}use")
    assert use.attrib["href"] == use.attrib["{http://www.w3.org/1999/xlink}href"] == "#band-marks"


def _ink_in_boxes(svg: Path, boxes: list[Box], png: Path) -> list[int]:
    """Inkscape's drawing of ``svg`` at 10 px/mm: the count of inked pixels in each box (mm, y up)."""
    inkscape = shutil.which("inkscape")
    if inkscape is None:  # as tests/export/test_cutfile.py's need(): required in CI
        reason = "inkscape not found: run `make system-deps` as root"
        if os.environ.get("CI", "").strip().lower() in ("true", "1", "yes"):
            pytest.fail(f"{reason} (required in CI)")
        pytest.skip(reason)
    subprocess.run(
        [
            inkscape,
            "--export-type=png",
            "--export-dpi=254",
            "--export-background=white",
            "--export-background-opacity=1",
            f"--export-filename={png}",
            str(svg),
        ],
        check=True,
        capture_output=True,
        timeout=120,
    )
    img = np.asarray(Image.open(png).convert("L"))
    rows = img.shape[0]
    counts = []
    for x0, y0, x1, y1 in boxes:
        c0, c1 = math.floor(x0 * 10), math.ceil(x1 * 10)
        r0, r1 = rows - math.ceil(y1 * 10), rows - math.floor(y0 * 10)
        counts.append(int(np.count_nonzero(img[r0:r1, c0:c1] < 250)))
    return counts


@pytest.mark.slow
def test_inkscape_draws_no_line_in_any_label_box(case: dict[str, Path], tmp_path: Path) -> None:
    # the Cricut's cut file and the fold map drawn by Inkscape without their labels (and the cut
    # file's legend): no ink where the labels go; the fold map's band marks, drawn from <defs> by a
    # <use>, are drawn (magenta ink on the band), so they are in the check
    cut = ET.parse(case["maker-12x12/cut-1.svg"])
    boxes = _cut_file_labels(_svg_cut(case["maker-12x12/cut-1.svg"]))
    for g in [g for g in cut.getroot() if g.attrib.get("id") in ("LABEL", "LEGEND")]:
        cut.getroot().remove(g)
    cut.write(tmp_path / "cut.svg")
    assert _ink_in_boxes(tmp_path / "cut.svg", boxes, tmp_path / "cut.png") == [0] * len(PARTS)

    fold = ET.parse(case["maker-12x12/sheet-1.svg"])
    boxes = [box for _, box, _ in _fold_map_labels(fold.getroot())]
    for g in [g for g in fold.getroot() if g.attrib.get("id") in ("labels", "legend")]:
        fold.getroot().remove(g)
    fold.write(tmp_path / "fold.svg")
    assert _ink_in_boxes(tmp_path / "fold.svg", boxes, tmp_path / "fold.png") == [0] * len(PARTS)
    rgb = np.asarray(Image.open(tmp_path / "fold.png").convert("RGB")).astype(int)
    magenta = (rgb[..., 0] > 200) & (rgb[..., 1] < 100) & (rgb[..., 2] > 200)
    marks = sum(1 for e in fold.getroot().iter(f"{SVG}line") if e.attrib.get("class") == "mark")
    assert marks == 36  # the band's marks: one per crease end on the band (9 x 2 x 2 layers)
    # each mark is about 6 mm long at 10 px/mm: well over 36 x 30 magenta pixels when drawn
    assert np.count_nonzero(magenta) > 36 * 30
