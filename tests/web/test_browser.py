"""The page in a real browser: Playwright driving Debian's Chromium against a live uvicorn server.

Never downloads a browser: ``/usr/bin/chromium`` (``make system-deps`` installs it). Where it is
missing the tests are skipped, except in CI (``CI=true``), where they fail. Every request the page
makes is checked to stay on the local server (the app works offline). Screenshots of each page go
to ``test-artifacts/`` (gitignored).
"""

from __future__ import annotations

import io
import os
from collections.abc import Iterator
from pathlib import Path
from typing import Any
from urllib.parse import urlsplit

import numpy as np
import pytest

from corrugate import Assembly, Layer, get_material
from corrugate.export.writers import WRITERS
from corrugate.fabrication.build import build_pattern
from corrugate.fabrication.folded import folded_mesh

#: Needs Chromium and Playwright (tests/conftest.py checks every user of the browser fixture).
pytestmark = pytest.mark.browser

CHROMIUM = Path("/usr/bin/chromium")
CHROMIUM_ARGS = [
    "--no-sandbox",
    "--disable-gpu",
    "--disable-background-networking",
    "--disable-component-update",
    "--no-first-run",
]
ARTIFACTS = Path(__file__).resolve().parents[2] / "test-artifacts"


def _unavailable(reason: str) -> None:
    if os.environ.get("CI", "").strip().lower() in ("true", "1", "yes"):
        pytest.fail(f"{reason} (required in CI)")
    pytest.skip(reason)


@pytest.fixture(scope="module")
def browser() -> Iterator[Any]:
    if not CHROMIUM.exists():
        _unavailable(f"{CHROMIUM} not found: run `make system-deps` as root")
    try:
        from playwright.sync_api import sync_playwright
    except ImportError:
        _unavailable("the playwright package is not installed (pip install -e '.[dev]')")
    with sync_playwright() as p:
        b = p.chromium.launch(executable_path=str(CHROMIUM), headless=True, args=CHROMIUM_ARGS)
        try:
            yield b
        finally:
            b.close()


class Watched:
    """A page with its console errors, uncaught exceptions and any non-local request recorded."""

    def __init__(self, browser: Any, base: str) -> None:
        self.page = browser.new_page(viewport={"width": 1280, "height": 1000})
        self.console_errors: list[str] = []
        self.page_errors: list[str] = []
        self.external: list[str] = []
        host = urlsplit(base).netloc
        self.page.on(
            "console",
            lambda m: self.console_errors.append(m.text) if m.type == "error" else None,
        )
        self.page.on("pageerror", lambda e: self.page_errors.append(str(e)))

        def guard(route: Any) -> None:
            url = route.request.url
            if urlsplit(url).netloc == host or url.startswith(("data:", "blob:")):
                route.continue_()
            else:
                self.external.append(url)
                route.abort()

        self.page.route("**/*", guard)

    def screenshot(self, name: str) -> Path:
        ARTIFACTS.mkdir(exist_ok=True)
        path = ARTIFACTS / name
        self.page.screenshot(path=str(path), full_page=True)
        assert path.stat().st_size > 0
        return path


@pytest.mark.parametrize(("ci", "outcome"), [("true", "fail"), ("", "skip"), ("false", "skip")])
def test_a_missing_browser_fails_in_ci_and_skips_elsewhere(
    monkeypatch: pytest.MonkeyPatch, ci: str, outcome: str
) -> None:
    monkeypatch.setenv("CI", ci)
    expected = pytest.fail.Exception if outcome == "fail" else pytest.skip.Exception
    with pytest.raises(expected):
        _unavailable("no browser")


def case1_faces() -> int:
    a = Assembly.identical(Layer(8, 8, 84, get_material("dura-lar")))
    _, faces = folded_mesh(a, build_pattern(a).parts)
    return len(faces)


def test_form_analysis_3d_view_and_field_errors(browser: Any, live_server: str) -> None:
    w = Watched(browser, live_server)
    page = w.page
    page.goto(live_server + "/")
    page.wait_for_selector("form[data-ready='true']")
    assert page.locator("#material option[value='kapton']").count() == 1  # from /api/materials

    # The paper's Table 1, case 1.
    page.fill("#W", "8")
    page.fill("#n", "8")
    page.fill("#alpha", "84")
    page.select_option("#material", "dura-lar")
    page.select_option("#model", "paper")
    page.fill("#eta", "0 90")
    page.click("#submit")
    page.wait_for_selector("#view3d[data-state='ready']", timeout=30_000)

    ei0 = page.text_content("#stiffness tr[data-eta='0'] td[data-quantity='EI_mNm2']")
    assert ei0 == "87.84"
    assert "mass" in (page.text_content("#summary") or "")
    assert "paper-model" in (page.text_content("#warnings") or "")
    # a command the warning quotes between backticks (the API's text) is shown as code, as
    # report.html shows it, not as printed backticks
    assert "`" not in (page.text_content("#warnings") or "")
    commands = page.locator("#warnings li code").all_text_contents()
    assert "corrugate docs fea" in commands, commands
    assert page.locator("#layers tbody tr").count() == 2
    # the plate-theory buckling bounds, as corrugate.mechanics.buckling gives them for this design
    from corrugate import Assembly, Layer, get_material
    from corrugate.analysis.evaluate import facet_buckling_load

    b = facet_buckling_load(
        Assembly.identical(Layer(8.0, 8, 84.0, get_material("dura-lar"))), 0.0, "paper"
    )
    assert f"buckle at {b.low:.3g}-{b.high:.3g} N" in (page.text_content("#buckling") or "")

    canvas = page.locator("#view3d canvas")
    assert canvas.count() == 1
    box = canvas.bounding_box()
    assert box is not None and box["width"] > 100 and box["height"] > 100
    assert page.get_attribute("#view3d", "data-triangles") == str(case1_faces())
    # Something was drawn: the canvas is not one flat colour.
    import matplotlib.image

    pixels = matplotlib.image.imread(io.BytesIO(canvas.screenshot()), format="png")[..., :3]
    assert np.ptp(pixels.reshape(-1, 3), axis=0).max() > 0.2
    assert page.locator("#downloads a[download='assembly.glb']").count() == 1

    w.screenshot("web-analysis.png")
    assert w.console_errors == []
    assert w.page_errors == []
    assert w.external == []

    # A bad value: the message appears beside its field.
    page.fill("#alpha", "190")
    page.click("#submit")
    page.wait_for_selector("form[data-state='error']")
    message = page.text_content("#error-alpha") or ""
    # plain words first (the field's label, the value given, what is allowed), the field second
    assert message.startswith("Fold angle α (deg): you gave 190 deg, which is out of range;")
    assert "allowed 0 < alpha < 180 deg" in message and message.endswith(" — alpha"), message
    assert page.get_attribute("#alpha", "aria-invalid") == "true"
    beside = page.evaluate(
        "() => document.getElementById('error-alpha').parentElement"
        " === document.getElementById('alpha').parentElement"
    )
    assert beside is True
    assert page.is_visible("#error-alpha")
    assert (page.text_content("#error-body") or "") == ""
    assert page.is_hidden("#results") and page.is_hidden("#view")  # no stale answer on show
    w.screenshot("web-error.png")
    assert w.page_errors == []
    # The only console message is the browser's own note of the 422 answer.
    assert all("422" in m for m in w.console_errors), w.console_errors
    assert w.external == []

    # Units in the form and a layer-2 error that lands beside its (folded-away) field.
    page.fill("#alpha", "1.4661 rad")
    page.click("#layer2 summary")  # open the layer 2 block, fill, and fold it away again
    page.fill("#alpha2", "200 deg")
    page.click("#layer2 summary")
    assert page.evaluate("() => document.getElementById('layer2').open") is False
    page.click("#submit")
    page.wait_for_selector("form[data-state='error']")
    message2 = page.text_content("#error-alpha2") or ""
    assert message2.startswith("α2 (deg): you gave 200 deg") and message2.endswith(" — alpha2")
    assert page.evaluate("() => document.getElementById('layer2').open") is True
    assert (page.text_content("#error-alpha") or "") == ""
    page.close()


def test_openapi_page_renders_offline(browser: Any, live_server: str) -> None:
    w = Watched(browser, live_server)
    w.page.goto(live_server + "/docs")
    w.page.wait_for_selector(".opblock-summary-path[data-path='/api/analyze']", timeout=30_000)
    assert "corrugate" in (w.page.text_content(".swagger-ui .info") or "")
    w.screenshot("web-docs.png")
    assert w.external == []
    assert w.page_errors == []
    assert w.console_errors == []
    w.page.close()


#: The blimp gripper spec (examples/blimp_gripper.toml) as the design form takes it.
BLIMP_FORM = {
    "#d-name": "blimp-gripper",
    "#d-thickness": "0.125 mm",
    "#d-side-min": "48 mm",
    "#d-side-max": "60 mm",
    "#d-thick-min": "10 mm",
    "#d-thick-max": "12.5 mm",
    "#d-sheet-max": "250 mm",
    "#d-ei-min": "80 mN*m^2",
    "#d-ei-eta": "0 deg",
    "#d-k-min": "",
    "#d-W-min": "1 mm",
    "#d-W-max": "30 mm",
    "#d-W-step": "1 mm",
    "#d-n-min": "1",
    "#d-n-max": "200",
    "#d-alpha-min": "1 deg",
    "#d-alpha-max": "120 deg",
    "#d-alpha-step": "1 deg",
}


def test_design_form_files_3d_view_and_field_errors(browser: Any, live_server: str) -> None:
    import ezdxf

    w = Watched(browser, live_server)
    page = w.page
    requested: list[str] = []
    page.on("request", lambda r: requested.append(urlsplit(r.url).path))
    page.goto(live_server + "/")
    page.wait_for_selector("#design-form[data-ready='true']", state="attached")
    page.click("#tab-design")
    assert page.is_visible("#design-form") and page.is_hidden("#analyze-form")
    assert page.locator("#d-material option[value='kapton']").count() == 1  # /api/materials

    # The paper's case study, from requirements.
    page.select_option("#d-material", "dura-lar")
    page.select_option("#d-model", "paper")
    page.select_option("#d-layout", "square")
    page.click("#d-variables summary")  # the bounds of W, n and alpha are folded away
    for selector, value in BLIMP_FORM.items():
        page.fill(selector, value)
    page.select_option("#d-cutter", "cameo4-12x12")
    page.select_option("#d-paper", "letter")
    page.click("#d-submit")
    page.wait_for_selector("#d-view3d[data-state='ready']", timeout=60_000)

    summary = page.text_content("#d-summary") or ""
    assert "W = 8 mm" in summary and "n = 8" in summary and "\u03b1 = 84 deg" in summary, summary
    rows = page.locator("#d-layers tbody tr")
    assert rows.count() == 2
    for i in range(2):
        row = rows.nth(i)
        assert row.locator("td[data-quantity='W_mm']").text_content() == "8"
        assert row.locator("td[data-quantity='n']").text_content() == "8"
        assert row.locator("td[data-quantity='alpha_deg']").text_content() == "84"
    assert "optimal (certified)" in (page.text_content("#d-verdict") or "")
    assert "connectors" in (page.text_content("#d-mass") or "")
    rigidity = page.locator("#d-constraints tr[data-name='constraints.flexural_rigidity[0].min']")
    assert rigidity.count() == 1
    assert rigidity.get_attribute("data-binding") in ("yes", "no")
    assert page.locator("#d-constraints tbody tr").count() >= 5
    assert "paper-model" in (page.text_content("#d-warnings") or "")
    # The pattern preview is the first sheet's SVG, loaded and drawn.
    page.wait_for_function(
        "() => { const i = document.getElementById('d-pattern');"
        " return i.complete && i.naturalWidth > 0; }"
    )
    assert (page.get_attribute("#d-pattern", "src") or "").endswith("/sheet-1.svg")
    assert int(page.get_attribute("#d-view3d", "data-triangles") or 0) > 0
    names = page.eval_on_selector_all("#d-downloads a", "els => els.map(e => e.dataset.name)")
    for name in ("sheet-1.svg", "cut-1.dxf", "pattern.pdf", "layer1.fold", "layer2.fold"):
        assert name in names
    assert {"assembly.glb", "assembly.stl"} <= set(names)
    assert "pattern-letter.pdf" in names  # the paper option reached the files
    # The buttons in the writers registry's download order (read once, from GET /api/formats);
    # for this one-sheet design the order the page had before the registry.
    assert requested.count("/api/formats") == 1
    assert names[0] == "all.zip"
    ranks = [next(w.order for w in WRITERS if w.matches(n)) for n in names[1:]]
    assert ranks == sorted(ranks)
    assert names[1:] == [
        "sheet-1.svg",
        "cut-1.dxf",
        "pattern.pdf",
        "pattern-letter.pdf",
        "layer1.fold",
        "layer2.fold",
        "assembly.glb",
        "assembly.stl",
        "report.html",
        "ASSEMBLY.md",
        "assembly.png",
        "design.json",
    ]
    # the preview shows every sheet that was written, in order
    sheets = sorted(n for n in names if n.startswith("sheet-") and n.endswith(".svg"))
    shown = page.eval_on_selector_all(
        "#d-patterns img", "els => els.map(e => e.getAttribute('src'))"
    )
    assert len(shown) == len(sheets) >= 1
    assert [s.rsplit("/", 1)[-1] for s in shown] == sheets
    if "report.html" in names:  # once write_design_files writes the report: it opens, whole
        assert page.is_visible("#d-report-link")
        with page.context.expect_page() as opened:
            page.click("#d-report-link")
        report = opened.value
        report_errors: list[str] = []
        report.on("console", lambda m: report_errors.append(m.text) if m.type == "error" else None)
        report.wait_for_load_state("load")
        broken = report.evaluate(
            "() => [...document.images].filter(i => !(i.complete && i.naturalWidth > 0)).length"
        )
        assert broken == 0 and report.evaluate("() => document.images.length") > 0
        assert report_errors == []
        report.close()
    else:
        assert page.is_hidden("#d-report")

    # The DXF through its download button.
    with page.expect_download() as info:
        page.click("#d-downloads a[data-name='cut-1.dxf']")
    download = info.value
    assert download.suggested_filename == "cut-1.dxf"
    doc = ezdxf.readfile(download.path())
    assert not doc.audit().has_errors
    assert len(doc.modelspace()) > 0

    w.screenshot("web-design.png")
    assert w.console_errors == []
    assert w.page_errors == []
    assert w.external == []

    # A bad value: side min above max; the message appears beside that field.
    page.fill("#d-side-min", "70 mm")
    page.click("#d-submit")
    page.wait_for_selector("#design-form[data-state='error']")
    message = page.text_content("#d-side-min ~ .error, .field:has(#d-side-min) .error") or ""
    assert message.startswith("Side L: you gave 70 mm, which is greater than max;"), message
    assert message.endswith(" — constraints.side.min"), message
    assert page.get_attribute("#d-side-min", "aria-invalid") == "true"
    beside = page.evaluate(
        "() => document.getElementById('d-side-min').closest('.field')"
        ".querySelector('.error').textContent"
    )
    assert beside == message
    assert page.is_visible(".field:has(#d-side-min) .error")
    assert (page.text_content("#d-error-body") or "") == ""
    assert page.is_hidden("#design-results")  # no stale answer on show
    w.screenshot("web-design-error.png")
    assert w.page_errors == []
    assert all("422" in m for m in w.console_errors), w.console_errors

    # An error in the folded-away bounds opens them and lands beside its field.
    page.fill("#d-side-min", "48 mm")
    page.fill("#d-n-max", "2.5")
    page.click("#d-variables summary")
    assert page.evaluate("() => document.getElementById('d-variables').open") is False
    page.click("#d-submit")
    page.wait_for_selector("#design-form[data-state='error']")
    assert page.evaluate("() => document.getElementById('d-variables').open") is True
    assert "variables.n.max" in (page.text_content(".field:has(#d-n-max) .error") or "")
    assert w.external == []
    page.close()


def test_form_takes_holes(browser: Any, live_server: str) -> None:
    """The Holes field ('d@x,y'): the analysis has the hole (its mass is the holed one) and a
    hole that cuts the outline is reported beside the field."""
    from corrugate.geometry.holes import Hole
    from corrugate.geometry.layouts import make_layout
    from corrugate.mechanics.mass import assembly_mass

    w = Watched(browser, live_server)
    page = w.page
    page.goto(live_server + "/")
    page.wait_for_selector("form[data-ready='true']")
    page.fill("#W", "8")
    page.fill("#n", "12")
    page.fill("#alpha", "90")
    page.select_option("#material", "dura-lar")
    page.select_option("#layout", "circle")
    page.fill("#holes", "6@0,0")
    page.click("#submit")
    page.wait_for_selector("#view3d[data-state='ready']", timeout=30_000)
    summary = page.text_content("#summary") or ""
    layout = make_layout("circle", holes=(Hole("circle", (0.0, 0.0), 6.0),))
    mass = assembly_mass(Assembly.identical(Layer(8.0, 12, 90.0, get_material("dura-lar")), layout))
    assert "holes d 6 mm at (0, 0) mm" in summary
    assert f"mass {float(f'{mass.total:.4g}'):g} g" in summary
    page.fill("#holes", "6@36,0")
    page.click("#submit")
    page.wait_for_selector("form[data-state='error']")
    assert "cuts the outline" in (page.text_content("#error-holes") or "")
    assert w.page_errors == []
