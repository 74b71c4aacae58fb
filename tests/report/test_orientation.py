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
