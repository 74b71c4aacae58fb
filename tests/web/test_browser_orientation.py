"""The panel's directions on the page (issue 36 item 2): the drawing of x, y, eta and each
layer's creases (``static/orientation.svg``, :func:`corrugate.report.orientation.orientation_svg`)
sits between the design form's size and requirement fields and is seen whole on a phone (390 px)
and a desktop (1280 px); screenshots of it are saved to the test's tmp_path."""

from __future__ import annotations

from pathlib import Path
from typing import Any

import pytest

from .test_browser import Watched, browser  # noqa: F401  (the module's browser fixture)

pytestmark = pytest.mark.browser  # needs Chromium and Playwright

#: Where the figure is, how large, whether its image loaded, and what is just above and below it.
FIGURE_JS = """() => {
  const fig = document.getElementById('d-orientation');
  const img = fig.querySelector('img');
  const r = img.getBoundingClientRect();
  const prev = fig.previousElementSibling, next = fig.nextElementSibling;
  return { left: r.left, right: r.right, width: r.width, height: r.height,
    natural: img.naturalWidth, page: document.documentElement.clientWidth,
    prev: prev.querySelector('legend').textContent, next: next.querySelector('legend').textContent,
    alt: img.alt };
}"""


@pytest.mark.parametrize("width", [390, 1280])
def test_the_orientation_picture_is_seen_beside_size_and_requirements(
    browser: Any,  # noqa: F811
    live_server: str,
    tmp_path: Path,
    width: int,
) -> None:
    w = Watched(browser, live_server)
    page = w.page
    page.set_viewport_size({"width": width, "height": 900})
    page.goto(live_server + "/")
    page.wait_for_selector("#design-form[data-ready='true']", state="attached")
    page.click("#tab-design")
    page.select_option("#d-layout", "rectangle")  # where side_x and side_y are asked
    fig = page.locator("#d-orientation")
    fig.scroll_into_view_if_needed()
    assert fig.is_visible()
    box = page.evaluate(FIGURE_JS)
    assert box["natural"] == 360  # the SVG loaded (its own width), not a broken image
    # whole inside the page's width, and not shrunk below legibility (the text is 11 px at 360 px)
    assert box["left"] >= 0 and box["right"] <= box["page"], box
    assert box["width"] >= min(300, width - 60) and box["height"] >= 0.7 * box["width"]
    # between the size fields and the requirements
    assert box["prev"].startswith("Size") and box["next"] == "Requirements"
    assert "eta = 0 deg runs along y" in box["alt"]
    # the caption says it in words too, and the side fields are on screen next to it
    caption = fig.locator("figcaption").text_content() or ""
    assert "side_y" in caption and "side_x" in caption
    assert page.is_visible("#d-side_x-min") and page.is_visible("#d-side_y-min")
    shot = tmp_path / f"orientation-{width}px.png"
    fig.screenshot(path=str(shot))
    assert shot.stat().st_size > 5000  # a drawing, not an empty box
    full = tmp_path / f"design-form-{width}px.png"
    page.screenshot(path=str(full), full_page=False)
    print(f"screenshots: {shot} {full}")
    assert not w.page_errors and not w.external
