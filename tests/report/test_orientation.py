"""The drawing of the panel's directions (:mod:`corrugate.report.orientation`, issue 36 item 2).

What it must show is the convention of docs/models.md "Layouts and facet lengths" ("Layer 1's creases run
along y, layer 2's along x") and docs/spec.md (eta "from layer 1's creases"): layer 1's crease
lines vertical (constant x), layer 2's horizontal, the eta = 0 arrow up (along y) and the eta = 90
deg arrow to the right (along x). The lines are read back from the SVG's own coordinates. The web
page's static copy must be the function's output, the report embeds it, and ``corrugate init``'s
template carries the same picture in words.
"""

from __future__ import annotations

import base64
import re
import xml.etree.ElementTree as ET
from pathlib import Path

import pytest

from corrugate.report.orientation import ORIENTATION_ALT, orientation_svg
from corrugate.spec.examples import template_text

NS = "{http://www.w3.org/2000/svg}"
STATIC = Path(__file__).resolve().parents[2] / "src" / "corrugate" / "web" / "static"


def _lines(svg: str) -> list[dict[str, str]]:
    return [e.attrib for e in ET.fromstring(svg).iter(f"{NS}line")]


@pytest.mark.parametrize(("aspect", "creases"), [(1.6, (7, 4)), (0.7, (3, 8)), (1.0, (12, 12))])
def test_layer_1_creases_run_along_y_and_layer_2_along_x(
    aspect: float, creases: tuple[int, int]
) -> None:
    svg = orientation_svg(aspect, creases)
    panel = next(ET.fromstring(svg).iter(f"{NS}rect")).attrib
    w, h = float(panel["width"]), float(panel["height"])
    assert w / h == pytest.approx(aspect)
    lines = _lines(svg)
    blue = [a for a in lines if a.get("stroke") == "#1f5fa8" and float(a["y2"]) != 16]
    orange = [a for a in lines if a.get("stroke") == "#c0561b" and float(a["y2"]) != 16]
    assert len(blue) == creases[0] and len(orange) == creases[1]
    for a in blue:  # vertical: constant x, the panel's whole height
        assert a["x1"] == a["x2"] and float(a["y2"]) - float(a["y1"]) == pytest.approx(h)
    for a in orange:  # horizontal: constant y, the panel's whole width
        assert a["y1"] == a["y2"] and float(a["x2"]) - float(a["x1"]) == pytest.approx(w)
    arrows = [a for a in lines if a.get("stroke-width") == "2.2"]
    up, right = arrows  # eta = 0 first: up the page (SVG y grows downwards), then eta = 90
    assert up["x1"] == up["x2"] and float(up["y2"]) < float(up["y1"])
    assert right["y1"] == right["y2"] and float(right["x2"]) > float(right["x1"])
    texts = [t.text for t in ET.fromstring(svg).iter(f"{NS}text")]
    assert "eta = 0 deg" in texts and "eta = 90 deg" in texts
    assert "Lx: side_x (eta = 90 deg)" in texts and "Ly: side_y (eta = 0 deg)" in texts


def test_the_page_shows_the_functions_drawing() -> None:
    assert (STATIC / "orientation.svg").read_text() == orientation_svg(), (
        "regenerate src/corrugate/web/static/orientation.svg from "
        "corrugate.report.orientation.orientation_svg()"
    )
    page = (STATIC / "index.html").read_text()
    assert 'src="/static/orientation.svg"' in page
    assert ORIENTATION_ALT.replace("'", "&#x27;") in page


def test_the_report_embeds_it(tmp_path: Path) -> None:
    from corrugate.report.html import _directions

    block = _directions(2.0, (5, 3))
    src = re.search(r'src="data:image/svg\+xml;base64,([^"]+)"', block)
    assert src is not None
    assert base64.b64decode(src.group(1)).decode() == orientation_svg(2.0, (5, 3))
    assert "eta = 0 deg runs along y" in block


def test_init_template_draws_the_directions_in_words() -> None:
    text = template_text()
    assert "eta = 0 deg: along y" in text and "eta = 90 deg: along x" in text
    assert "layer 1's creases run along y" in text and "layer 2's creases run along x" in text


@pytest.mark.parametrize(("aspect", "creases"), [(80.36 / 123.84, (12, 11)), (1.0, (10, 10))])
def test_inkscape_draws_no_eta_label_over_an_arrow(
    aspect: float, creases: tuple[int, int], tmp_path: Path
) -> None:
    """The drawn boxes (Inkscape's ``--query-all``: each element's visual box, an arrow's with its
    head) of the labels "eta = 0 deg" and "eta = 90 deg" meet neither arrow nor each other (the
    head of the eta = 0 arrow was drawn over the "e" of its label; the chassis plate's and the
    case study's drawings)."""
    import os
    import shutil
    import subprocess

    inkscape = shutil.which("inkscape")
    if inkscape is None:
        reason = "inkscape not found: run `make system-deps` as root"
        if os.environ.get("CI", "").strip().lower() in ("true", "1", "yes"):
            pytest.fail(f"{reason} (required in CI)")
        pytest.skip(reason)
    root = ET.fromstring(orientation_svg(aspect, creases))
    for k, e in enumerate(root.iter()):
        e.set("id", e.get("id", f"e{k}"))  # the arrowhead's marker keeps its own
    arrows = [e.get("id") for e in root.iter(f"{NS}line") if e.get("stroke-width") == "2.2"]
    labels = [e.get("id") for e in root.iter(f"{NS}text") if (e.text or "").startswith("eta = ")]
    assert len(arrows) == 2 and len(labels) == 2
    path = tmp_path / "orientation.svg"
    path.write_bytes(ET.tostring(root))
    rows = subprocess.run(
        [inkscape, "--query-all", str(path)],
        check=True,
        capture_output=True,
        text=True,
        timeout=120,
    ).stdout.split()
    box = {}
    for row in rows:
        name, *xywh = row.split(",")
        x, y, w, h = map(float, xywh)
        box[name] = (x, y, x + w, y + h)

    def meet(a: str, b: str) -> bool:
        (ax0, ay0, ax1, ay1), (bx0, by0, bx1, by1) = box[a], box[b]
        return ax0 < bx1 and bx0 < ax1 and ay0 < by1 and by0 < ay1

    for label in labels:
        for arrow in arrows:
            assert not meet(label, arrow), (label, arrow, box[label], box[arrow])
    assert not meet(*labels)
