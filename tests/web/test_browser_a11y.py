"""The page in a real browser (Chromium via Playwright): every form control has an accessible
name and the buttons are reachable by keyboard; the 3D view colours each layer and explodes;
the analyse tab makes the cut files (the same as ``corrugate pattern``) and zips them."""

from __future__ import annotations

import io
import zipfile
from pathlib import Path
from typing import Any

import numpy as np
import pytest

from .test_browser import Watched, browser  # noqa: F401  (the module's browser fixture)

pytestmark = pytest.mark.browser  # needs Chromium and Playwright

#: Roles of the accessibility tree that are form controls or buttons.
CONTROL_ROLES = {
    "textbox",
    "combobox",
    "button",
    "checkbox",
    "radio",
    "spinbutton",
    "listbox",
    "tab",
    "slider",
    "searchbox",
}

#: Every control of the page (hidden ones too) and the name a screen reader would get from the
#: markup: aria-labelledby, aria-label, a <label for>, a wrapping <label>, or a button's text.
NAMES_JS = """() => [...document.querySelectorAll('input, select, textarea, button')].map((el) => {
  const byIds = (el.getAttribute('aria-labelledby') || '').split(/\\s+/).filter(Boolean)
    .map((id) => (document.getElementById(id) || {}).textContent || '').join(' ');
  const forLabel = el.id ? [...document.querySelectorAll('label')]
    .filter((l) => l.htmlFor === el.id).map((l) => l.textContent).join(' ') : '';
  const wrapping = el.closest('label') ? el.closest('label').textContent : '';
  const text = el.tagName === 'BUTTON' ? el.textContent : '';
  const name = [byIds, el.getAttribute('aria-label') || '', forLabel, wrapping, text]
    .map((s) => s.trim()).find((s) => s) || '';
  return { id: el.id, tag: el.tagName, cls: el.className, name, tabindex: el.getAttribute('tabindex') };
})"""


def _unnamed_in_ax_tree(page: Any) -> list[dict[str, Any]]:
    """Controls of Chromium's own accessibility tree (what a screen reader gets) without a name."""
    cdp = page.context.new_cdp_session(page)
    try:
        nodes = cdp.send("Accessibility.getFullAXTree")["nodes"]
    finally:
        cdp.detach()
    bad = []
    for node in nodes:
        role = (node.get("role") or {}).get("value")
        if node.get("ignored") or role not in CONTROL_ROLES:
            continue
        if not str((node.get("name") or {}).get("value") or "").strip():
            bad.append(node)
    return bad


def test_every_control_has_an_accessible_name_and_buttons_take_the_keyboard(
    browser: Any,  # noqa: F811
    live_server: str,
) -> None:
    w = Watched(browser, live_server)
    page = w.page
    page.goto(live_server + "/")
    page.wait_for_selector("form[data-ready='true']")
    controls = page.evaluate(NAMES_JS)
    assert len(controls) > 60  # both tabs' forms, the requirement rows, the view's buttons
    unnamed = [c for c in controls if not c["name"]]
    assert unnamed == [], unnamed
    # every button is a real <button> none of which is taken out of the tab order, but the
    # tabs: the chosen one is the tab list's one tab stop (roving tabindex)
    buttons = [c for c in controls if c["tag"] == "BUTTON" and not c["id"].startswith("tab-")]
    assert all(c["tabindex"] in (None, "0") for c in buttons)
    tabs = {c["id"]: c["tabindex"] for c in controls if c["id"].startswith("tab-")}
    assert tabs == {"tab-analyze": "0", "tab-design": "-1"}
    assert _unnamed_in_ax_tree(page) == []
    page.click("#tab-design")
    assert (
        _unnamed_in_ax_tree(page) == []
    )  # the design tab's visible controls, as Chromium names them

    # Keyboard only: Tab reaches the chosen tab, the right arrow opens the design tab (the
    # WAI-ARIA tabs pattern: test_browser_parity.py), Tab reaches "Design".
    page.click("#tab-analyze")
    page.focus("#nav-docs")
    page.keyboard.press("Tab")
    assert page.evaluate("() => document.activeElement.id") == "tab-analyze"
    page.keyboard.press("ArrowRight")
    assert page.evaluate("() => document.activeElement.id") == "tab-design"
    assert page.is_visible("#panel-design") and page.is_hidden("#panel-analyze")
    for _ in range(200):
        if page.evaluate("() => document.activeElement.id") == "d-submit":
            break
        page.keyboard.press("Tab")
    assert page.evaluate("() => document.activeElement.id") == "d-submit"
    assert w.page_errors == [] and w.external == []
    page.close()


def _pixels(canvas: Any) -> np.ndarray:
    import matplotlib.image

    return matplotlib.image.imread(io.BytesIO(canvas.screenshot()), format="png")[..., :3]


def _clear_border(image: Any, inset: int = 6, width: int = 4) -> bool:
    """Whether a band ``width`` pixels wide, ``inset`` pixels inside the edge of an RGB image
    (values 0-1), is all background (the colour at the band's top-left corner): nothing drawn is
    cut off by the canvas edge. The inset skips the container's rounded border."""
    a, b = inset, inset + width
    band = np.concatenate(
        [
            image[a:b, a:-a].reshape(-1, 3),
            image[-b:-a, a:-a].reshape(-1, 3),
            image[a:-a, a:b].reshape(-1, 3),
            image[a:-a, -b:-a].reshape(-1, 3),
        ]
    )
    return bool(np.abs(band - image[a, a]).max() < 0.05)


def test_layers_in_colours_exploded_view_and_cut_files_from_the_analyse_tab(
    browser: Any,  # noqa: F811
    live_server: str,
    tmp_path: Path,
) -> None:
    w = Watched(browser, live_server)
    page = w.page
    page.goto(live_server + "/")
    page.wait_for_selector("form[data-ready='true']")
    page.fill("#W", "8")
    page.fill("#n", "8")
    page.fill("#alpha", "84")
    page.click("#submit")
    page.wait_for_selector("#view3d[data-state='ready']", timeout=30_000)

    # one mesh per part, each in its own colour (the GLB's materials)
    assert page.get_attribute("#view3d", "data-parts") == "layer 1,layer 2,band"
    colours = (page.get_attribute("#view3d", "data-colors") or "").split(",")
    assert len(colours) == 3 and len(set(colours)) == 3
    canvas = page.locator("#view3d canvas")
    assert page.get_attribute("#view3d canvas", "role") == "img"
    assert "layer 1" in (page.get_attribute("#view3d canvas", "aria-label") or "")
    before = _pixels(canvas)
    w.screenshot("web-layers.png")
    # layer 2 (orange) is in sight; layer 1 (blue) sits inside the band
    flat = before.reshape(-1, 3)
    assert ((flat[:, 0] - flat[:, 2]) > 0.15).sum() > 100  # orange-dominant pixels

    page.click("#explode")
    assert page.get_attribute("#explode", "aria-pressed") == "true"
    assert page.get_attribute("#view3d", "data-exploded") == "true"
    exploded = _pixels(canvas)
    w.screenshot("web-exploded.png")
    assert np.abs(exploded - before).max() > 0.2  # the picture changed
    flat = exploded.reshape(-1, 3)  # the exploded view shows layer 1, blue, below the band
    assert ((flat[:, 2] - flat[:, 0]) > 0.15).sum() > 100
    assert _clear_border(before) and _clear_border(exploded)  # the whole model stays in view
    page.click("#explode")
    assert page.get_attribute("#view3d", "data-exploded") == "false"

    # the cut files of this design, from the analyse tab
    page.select_option("#cutter", "maker-12x12")
    page.click("#make-cut-files")
    page.wait_for_selector(
        "#cut-downloads:is([data-state='ready'], [data-state='error'])", state="attached"
    )
    assert page.get_attribute("#cut-downloads", "data-state") == "ready", (
        page.text_content("#error-cutter"),
        page.text_content("#error-body"),
    )
    names = page.eval_on_selector_all("#cut-downloads a", "els => els.map((a) => a.dataset.name)")
    assert names[0] == "all.zip"
    assert {"cut-1.svg", "assembly.glb", "assembly.stl", "design.json"} <= set(names)
    with page.expect_download() as download_info:
        page.click("#cut-downloads a[data-name='all.zip']")
    target = tmp_path / "all.zip"
    target.write_bytes(Path(download_info.value.path()).read_bytes())
    archive = zipfile.ZipFile(target)
    assert archive.testzip() is None
    assert sorted(archive.namelist()) == sorted(names[1:])
    svg = archive.read("cut-1.svg").decode("utf-8")
    assert svg.lstrip().startswith("<?xml") or "<svg" in svg[:400]

    # a bad design: the error names the field in plain words, beside it, no stale files
    page.fill("#W", "-3")
    page.click("#make-cut-files")
    page.wait_for_selector("#cut-downloads[data-state='error']", state="attached")
    message = page.text_content("#error-W") or ""
    assert message.startswith("Facet width W (mm): you gave -3 mm"), message
    assert message.endswith(" — W")
    assert page.locator("#cut-downloads a").count() == 0
    assert w.page_errors == [] and w.external == []
    page.close()
