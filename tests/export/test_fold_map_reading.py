"""The case study's fold map, cut file and PDF read back as a third party reads them (issue 36).

Origami Simulator's SVG import (amandaghassaei/OrigamiSimulator ``js/pattern.js``, ``loadSVG`` and
``typeForStroke``): it deletes every ``<symbol>`` and every child of ``<defs>`` but styles, then
reads the strokes of ``path``, ``line``, ``rect``, ``polygon`` and ``polyline`` elements by colour:
black boundary, red mountain, blue valley, green cut, yellow triangulation, magenta hinge
("undriven"). The reading below follows that source, not the writer: a band mark it read as a
hinge ends inside a face and kept the sheet from folding (benchmarks/origami_simulator.py folds it
in the app itself). Labels are checked with plain geometry on the files parsed back.
"""

from __future__ import annotations

import itertools
import math
import re
import xml.etree.ElementTree as ET
from pathlib import Path

import numpy as np
import pytest
from pypdf import PdfReader

from corrugate import Assembly, Layer, get_material
from corrugate.export.files import write_files
from corrugate.fabrication.build import build_pattern
from corrugate.fabrication.model import Role
from corrugate.fabrication.sheets import SheetPlan, place, plan_sheets

SVG = "{http://www.w3.org/2000/svg}"
#: js/pattern.js typeForStroke: the stroke colours the app imports, and as what.
OS_TYPES = {
    "#000000": "border",
    "#ff0000": "mountain",
    "#0000ff": "valley",
    "#00ff00": "cut",
    "#ffff00": "triangulation",
    "#ff00ff": "hinge",
}
#: The least gap (mm) a label keeps from every line: the stroke of a pen or a scoring wheel
#: (0.5 mm) is clear of it (docs/fabrication.md, "Labels").
GAP = 0.5


@pytest.fixture(scope="module")
def plan() -> SheetPlan:
    """The case study's answer (examples/blimp_gripper.toml: W 8, n 9, alpha 78, Dura-Lar
    0.125 mm) on a Cricut Maker's mat (its cut file is an SVG)."""
    layer = Layer(8, 9, 78, get_material("dura-lar"), t=0.125)
    return plan_sheets(build_pattern(Assembly.identical(layer)), "maker-12x12", margin=5.0)


@pytest.fixture(scope="module")
def files(plan: SheetPlan, tmp_path_factory: pytest.TempPathFactory) -> dict[str, Path]:
    out = tmp_path_factory.mktemp("case")
    return {p.name: p for p in write_files(plan, out, formats=("svg", "cut", "pdf"))}


def _as_origami_simulator_reads(root: ET.Element) -> list[tuple[str, ET.Element]]:
    """The stroked elements the app reads and the type it gives each (None: ignored)."""
    dropped = {id(e) for d in root.iter(f"{SVG}defs") for e in d.iter() if e.tag != f"{SVG}style"}
    dropped |= {id(e) for s in root.iter(f"{SVG}symbol") for e in s.iter()}
    kinds = ("path", "line", "rect", "polygon", "polyline")
    return [
        (OS_TYPES.get(e.attrib.get("stroke", "").lower(), "ignored"), e)
        for e in root.iter()
        if id(e) not in dropped and e.tag in {SVG + k for k in kinds}
    ]


def test_origami_simulator_reads_creases_only_and_the_marks_stay_drawn(
    plan: SheetPlan, files: dict[str, Path]
) -> None:
    root = ET.parse(files["sheet-1.svg"]).getroot()
    read = _as_origami_simulator_reads(root)
    types = [t for t, _ in read]
    placed = [place(p) for p in plan.sheets[0].placements]
    creases = [ln for p in placed for ln in p.lines if ln.role in (Role.MOUNTAIN, Role.VALLEY)]
    marks = [ln for p in placed for ln in p.lines if ln.role is Role.MARK]
    assert marks  # the band carries its angle marks (one per crease end it meets)
    # no mark read as an undriven crease, nothing ignored; every crease read, as itself
    assert "hinge" not in types and "ignored" not in types and "triangulation" not in types
    assert types.count("mountain") + types.count("valley") == len(creases)
    for t, e in read:
        if t in ("mountain", "valley"):
            assert e.attrib["class"] == f"crease {t}" and "data-crease" in e.attrib
    # the marks are still in the file, magenta, and drawn where they are by one <use>
    (defs,) = root.iter(f"{SVG}defs")
    drawn = [e for e in defs.iter(f"{SVG}line") if e.attrib.get("class") == "mark"]
    assert len(drawn) == len(marks)
    assert {e.attrib["stroke"] for e in drawn} == {"#ff00ff"}
    (group,) = defs
    assert [u.attrib["href"] for u in root.iter(f"{SVG}use")] == ["#" + group.attrib["id"]]


def _box_gap(
    box: tuple[float, float, float, float], a: tuple[float, float], b: tuple[float, float]
) -> float:
    """Least distance (mm) from segment a-b to the box (x0, y0, x1, y1), sampled every 0.005 mm
    of the segment; 0 where it enters the box."""
    x0, y0, x1, y1 = box
    n = max(2, int(math.hypot(b[0] - a[0], b[1] - a[1]) / 0.005) + 1)
    t = np.linspace(0.0, 1.0, n)
    xs, ys = a[0] + t * (b[0] - a[0]), a[1] + t * (b[1] - a[1])
    dx = np.maximum(np.maximum(x0 - xs, xs - x1), 0.0)
    dy = np.maximum(np.maximum(y0 - ys, ys - y1), 0.0)
    return float(np.min(np.hypot(dx, dy)))


def _plan_lines(plan: SheetPlan) -> list[tuple[tuple[float, float], tuple[float, float]]]:
    """Every line of the sheet (sheet mm, y up): outlines, holes, creases, marks, slits."""
    segs = []
    for p in plan.sheets[0].placements:
        pp = place(p)
        for ring in (pp.outline, *pp.holes):
            segs += list(itertools.pairwise([*ring, ring[0]]))
        segs += [(ln.a, ln.b) for ln in pp.lines]
    return segs


def test_cut_file_labels_keep_a_gap_from_every_line(
    plan: SheetPlan, files: dict[str, Path]
) -> None:
    # the Cricut cut file: each label's pen strokes, parsed back, against every line of the sheet
    # (the crease an "L" of "L1" sat on, issue 36)
    root = ET.parse(files["cut-1.svg"]).getroot()
    H = float(root.attrib["viewBox"].split()[3])
    (group,) = (g for g in root.iter(f"{SVG}g") if g.attrib["id"] == "LABEL")
    by_part: dict[str, list[tuple[float, float]]] = {}
    for path in group:
        nums = [float(v) for v in re.findall(r"-?\d+\.?\d*", path.attrib["d"])]
        by_part.setdefault(path.attrib["data-part"], []).extend(
            (nums[i], H - nums[i + 1]) for i in range(0, len(nums), 2)
        )
    assert sorted(by_part) == sorted(p.part.name for p in plan.sheets[0].placements)
    lines = _plan_lines(plan)
    for name, pts in by_part.items():
        xy = np.asarray(pts)
        box = (*xy.min(axis=0), *xy.max(axis=0))
        gap = min(_box_gap(box, a, b) for a, b in lines)  # type: ignore[arg-type]
        assert gap >= GAP, (name, gap)


def test_fold_map_labels_keep_a_gap_from_every_line(
    plan: SheetPlan, files: dict[str, Path]
) -> None:
    root = ET.parse(files["sheet-1.svg"]).getroot()
    unit = float(root.attrib["width"][:-2]) / float(root.attrib["viewBox"].split()[2])
    H = plan.sheets[0].height
    (group,) = (g for g in root.iter(f"{SVG}g") if g.attrib.get("id") == "labels")
    lines = _plan_lines(plan)
    for t in group:
        x, y = float(t.attrib["x"]) * unit, H - float(t.attrib["y"]) * unit
        size, length = float(t.attrib["font-size"]) * unit, float(t.attrib["textLength"]) * unit
        half_l, half_h = length / 2, 0.6 * size  # the text's box: its length by 1.2 em
        if "rotate" in t.attrib.get("transform", ""):
            half_l, half_h = half_h, half_l
        box = (x - half_l, y - half_h, x + half_l, y + half_h)
        gap = min(_box_gap(box, a, b) for a, b in lines)
        assert gap >= GAP, (t.text, gap)
        assert size >= 2.0, t.text  # readable at 1:1


def test_pdf_labels_are_readable_and_every_full_label_is_on_the_page(
    plan: SheetPlan, files: dict[str, Path]
) -> None:
    # pattern.pdf at 1:1: every part's label at least 2 mm tall (5.7 pt), and each part's full
    # label ("L1: layer 1: W 8 mm, ...") written somewhere on its page (on the part or the legend)
    reader = PdfReader(files["pattern.pdf"])
    runs: list[tuple[str, float]] = []

    def visit(text: str, cm: list[float], tm: list[float], font: object, size: float) -> None:
        if text.strip():
            m = [tm[0] * cm[0] + tm[1] * cm[2], tm[0] * cm[1] + tm[1] * cm[3]]
            runs.append((text.strip(), size * math.hypot(*m) * 25.4 / 72))

    reader.pages[0].extract_text(visitor_text=visit)
    texts = [t for t, _ in runs]
    for p in plan.sheets[0].placements:
        name, label = p.part.name, p.part.label
        full = label if label.startswith(name) else f"{name}: {label}"
        on_part = [(t, s) for t, s in runs if t in (name, full)]
        assert on_part, (name, texts)
        assert all(s >= 2.0 - 1e-6 for _, s in on_part), on_part
        assert any(full in t for t in texts), (full, texts)
