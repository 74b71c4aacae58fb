"""Labels a person reads on the printed sheets (issue 36, item 8: "the PDF's labels on narrow parts
are vertical and too small to read"; "the A4/Letter tiled PDFs have no legend").

A design at the default narrowest facet (W 3 mm, n 20, alpha 60 deg: its layers' strips are too
narrow for "L1" at 2 mm) is written as pattern.pdf and pattern-a4.pdf and read back with pypdf:
every text on a part's page is at least 2 mm tall (READABLE_TEXT_MM), turned only where it is at
least that tall, and a name that does not fit on its part is a callout whose box (grown by the
0.5 mm a pen's line takes) meets no line of any part (distances by sampling each segment, not the
writer's clipping); the tiles' last page is a key with every part's full label and the fold map's
legend.
"""

from __future__ import annotations

import itertools
import math
from pathlib import Path

import numpy as np
import pytest
from pypdf import PdfReader

from corrugate import Assembly, Layer, get_material
from corrugate.export.files import write_files
from corrugate.export.labels import label_text
from corrugate.export.pdf import printed_labels
from corrugate.fabrication.build import build_pattern
from corrugate.fabrication.sheets import SheetPlan, place, plan_sheets

GAP = 0.5  # mm: docs/fabrication.md, "Labels"


@pytest.fixture(scope="module")
def plan() -> SheetPlan:
    layer = Layer(3, 20, 60, get_material("dura-lar"), t=0.125)
    return plan_sheets(build_pattern(Assembly.identical(layer)), "maker-12x12", margin=5.0)


@pytest.fixture(scope="module")
def files(plan: SheetPlan, tmp_path_factory: pytest.TempPathFactory) -> dict[str, Path]:
    out = tmp_path_factory.mktemp("narrow")
    return {p.name: p for p in write_files(plan, out, formats=("pdf",), paper="a4")}


def _runs(page: object) -> list[tuple[str, float]]:
    """Every text run of a PDF page and its height on paper (mm)."""
    runs: list[tuple[str, float]] = []

    def visit(text: str, cm: list[float], tm: list[float], font: object, size: float) -> None:
        if text.strip():
            m = [tm[0] * cm[0] + tm[1] * cm[2], tm[0] * cm[1] + tm[1] * cm[3]]
            runs.append((text.strip(), size * math.hypot(*m) * 25.4 / 72))

    page.extract_text(visitor_text=visit)  # type: ignore[attr-defined]
    return runs


def _gap(
    box: tuple[float, float, float, float], a: tuple[float, float], b: tuple[float, float]
) -> float:
    x0, y0, x1, y1 = box
    n = max(2, int(math.hypot(b[0] - a[0], b[1] - a[1]) / 0.01) + 1)
    t = np.linspace(0.0, 1.0, n)
    xs, ys = a[0] + t * (b[0] - a[0]), a[1] + t * (b[1] - a[1])
    dx = np.maximum(np.maximum(x0 - xs, xs - x1), 0.0)
    dy = np.maximum(np.maximum(y0 - ys, ys - y1), 0.0)
    return float(np.min(np.hypot(dx, dy)))


def test_the_narrow_parts_names_are_too_small_on_the_part(plan: SheetPlan) -> None:
    """The premise: on the layers' strips "L1" fits at under 2 mm (so it must be a callout)."""
    from corrugate.export.labels import label_spot

    layers = [p for p in plan.sheets[0].placements if p.part.name in ("L1", "L2")]
    assert layers and all(label_spot(place(p), p.part.name).size < 2.0 for p in layers)


def test_every_printed_label_is_readable_and_callouts_are_clear_of_every_line(
    plan: SheetPlan, files: dict[str, Path]
) -> None:
    labels = printed_labels(plan, 1)
    names = sorted(p.part.name for p in plan.sheets[0].placements if p.part.label)
    assert sorted(lb.text for lb in labels) == names
    callouts = [lb for lb in labels if lb.leader is not None]
    assert {lb.text for lb in callouts} >= {"L1", "L2"}
    lines = []
    for p in plan.sheets[0].placements:
        pp = place(p)
        for ring in (pp.outline, *pp.holes):
            lines += list(itertools.pairwise([*ring, ring[0]]))
        lines += [(ln.a, ln.b) for ln in pp.lines]
    for lb in labels:
        assert lb.spot.size >= 2.0 - 1e-9, lb  # readable, turned or not
    for lb in callouts:
        (x0, y0), _, (x1, y1), _ = lb.spot.corners()
        box = (x0 - GAP, y0 - GAP, x1 + GAP, y1 + GAP)
        assert min(_gap(box, a, b) for a, b in lines) > 0, lb.text
    # read back: every name on the page, at least 2 mm tall
    runs = _runs(PdfReader(files["pattern.pdf"]).pages[0])
    for name in names:
        sizes = [s for t, s in runs if t == name or t.startswith(f"{name}:")]
        assert sizes and min(sizes) >= 2.0 - 1e-6, (name, runs)


def test_the_tiles_end_with_a_key_of_every_full_label(
    plan: SheetPlan, files: dict[str, Path]
) -> None:
    reader = PdfReader(files["pattern-a4.pdf"])
    count = len(reader.pages)
    key = reader.pages[-1].extract_text()
    assert key.startswith("Key")
    for p in plan.sheets[0].placements:
        assert label_text(place(p)) in key, label_text(place(p))
    assert "red: mountain crease" in key and "blue: valley crease" in key
    assert f"page {count} of {count}" in key
    names = {p.part.name for p in plan.sheets[0].placements}
    shown = set()
    for page in reader.pages[:-1]:  # the tiles count the key among the pages
        assert f"of {count}" in page.extract_text()
        on_page = [(t, s) for t, s in _runs(page) if t in names]
        assert all(s >= 2.0 - 1e-6 for _, s in on_page), on_page
        shown |= {t for t, _ in on_page}
    assert shown == names
