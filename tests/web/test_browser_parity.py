"""The page's legibility and its parity with the CLI, in a real browser (Chromium via Playwright).

At 360, 800, 1280 and 1920 px wide windows every visible input and choice is wide enough for the
text it holds (measured with the page's own font on a canvas) and the page never scrolls
sideways, whichever layout is chosen, with the answers on show. The design form's defaults are
the case study ``examples/blimp_gripper.toml``: the spec it posts parses to the example's and
its answer is ``corrugate design examples/blimp_gripper.toml --json``; the answer shows the
stiffness table and the runner-ups of that JSON. The tab list follows the WAI-ARIA tabs
pattern. Every quantity the forms post carries the unit its field shows.
"""

from __future__ import annotations

import json
import re
import subprocess
import sys
from collections.abc import Iterator
from typing import Any

import pytest

from corrugate.spec.schema import parse_spec

from .test_browser import Watched, browser  # noqa: F401  (the module's browser fixture)
from .test_browser_specs import design, open_design_tab, spec_of
from .test_design_api import EXAMPLES, without_timings
from .test_design_api import spec_of as example

pytestmark = pytest.mark.browser  # needs Chromium and Playwright

#: A phone, a small laptop, a laptop and a desktop monitor.
WIDTHS = (360, 800, 1280, 1920)
LAYOUTS = ("square", "rectangle", "circle", "polygon")

#: Room a choice's arrow takes beside its text (Chromium draws it inside the box), px.
ARROW_PX = 20

#: Every rendered input and choice whose text (its value and its placeholder; a choice's chosen
#: option) is wider than the room inside it, or that reaches past the window's right edge.
CLIPPED_JS = """(arrow) => {
  const ctx = document.createElement('canvas').getContext('2d');
  const edge = document.scrollingElement.clientWidth;
  const out = [];
  for (const el of document.querySelectorAll('input, select')) {
    if (el.type === 'hidden' || el.getClientRects().length === 0) continue;
    const cs = getComputedStyle(el);
    if (cs.visibility === 'hidden') continue;
    ctx.font = `${cs.fontStyle} ${cs.fontWeight} ${cs.fontSize} ${cs.fontFamily}`;
    const select = el.tagName === 'SELECT';
    const texts = select ? [el.selectedOptions[0] ? el.selectedOptions[0].text : '']
      : [el.value, el.placeholder || ''];
    const widths = texts.map((t) => Math.ceil(ctx.measureText(t).width));
    const need = Math.max(...widths);
    const text = texts[widths.indexOf(need)];
    const room = el.clientWidth - parseFloat(cs.paddingLeft) - parseFloat(cs.paddingRight)
      - (select ? arrow : 0);
    const right = el.getBoundingClientRect().right;
    if (need > room || right > edge + 0.5) {
      out.push(`${el.id || el.className} ${JSON.stringify(text)}: text ${need} px, room `
        + `${Math.floor(room)} px, right edge ${Math.round(right)} of ${edge} px`);
    }
  }
  return out;
}"""

#: The page's width beyond the window's (0: no sideways scroll).
OVERFLOW_JS = "() => document.scrollingElement.scrollWidth - document.scrollingElement.clientWidth"


def problems(page: Any, where: str) -> list[str]:
    """What cannot be read at the page's current size, and any sideways scroll, as lines."""
    found = [f"{where}: {c}" for c in page.evaluate(CLIPPED_JS, ARROW_PX)]
    overflow = page.evaluate(OVERFLOW_JS)
    if overflow > 0:
        found.append(f"{where}: the page scrolls {overflow} px sideways")
    return found


@pytest.fixture(scope="module")
def cli_answer() -> dict[str, Any]:
    """``corrugate design examples/blimp_gripper.toml --json``, run as a user runs it."""
    spec = str(EXAMPLES / "blimp_gripper.toml")
    run = subprocess.run(
        [sys.executable, "-m", "corrugate", "design", spec, "--json"],
        capture_output=True,
        text=True,
        check=False,
        timeout=300,
    )
    assert run.returncode == 0, run.stderr
    answer: dict[str, Any] = json.loads(run.stdout)
    return answer


@pytest.fixture
def watched(browser: Any, live_server: str) -> Iterator[Watched]:  # noqa: F811
    w = Watched(browser, live_server)
    yield w
    assert w.page_errors == [] and w.external == []
    w.page.close()


def test_every_input_is_readable_and_nothing_scrolls_sideways(
    watched: Watched, live_server: str
) -> None:
    page = watched.page
    page.goto(live_server + "/")
    page.wait_for_selector("form[data-ready='true']")
    found: list[str] = []
    # The analyse tab with its answer on show, layer 2's fields open and a custom material's
    # fields shown.
    page.click("#submit")
    page.wait_for_selector("#view3d[data-state='ready']", timeout=60_000)
    page.click("#layer2 summary")
    page.select_option("#material", "__custom__")
    for layout in LAYOUTS:
        page.select_option("#layout", layout)
        for width in WIDTHS:
            page.set_viewport_size({"width": width, "height": 900})
            found += problems(page, f"analyse, {layout}, {width} px")

    # The design tab with its answer on show, every optional field shown: a load-case row,
    # perforated fold lines, a laser's bed, a stiffness objective's direction.
    page.set_viewport_size({"width": 1280, "height": 900})
    page.click("#tab-design")
    page.click("#d-variables summary")
    design(page)
    page.click("#d-add-req")
    row = page.locator("#d-req-rows .req").last
    row.locator(".req-kind").select_option("deflection")
    row.locator(".req-load").fill("10 N")
    row.locator(".req-min").fill("1 mm")
    row.locator(".req-span").fill("120 mm")
    page.select_option("#d-fold-style", "perforated")
    page.select_option("#d-cutter", "laser")
    page.select_option("#d-objective", "maximize:flexural_rigidity")
    page.fill("#d-objective-eta", "0 deg")
    for layout in LAYOUTS:
        page.select_option("#d-layout", layout)
        for width in WIDTHS:
            page.set_viewport_size({"width": width, "height": 900})
            found += problems(page, f"design, {layout}, {width} px")
    assert found == [], "\n".join(found)


def test_the_design_forms_defaults_answer_as_the_cli(
    watched: Watched, live_server: str, cli_answer: dict[str, Any]
) -> None:
    page = open_design_tab(watched, live_server + "/")
    body, answer = design(page)
    # The form's spec is the example's, and so is its answer: the CLI's to the last digit.
    assert parse_spec(spec_of(body)) == parse_spec(example("blimp_gripper.toml"))
    assert without_timings(answer["design"]) == without_timings(cli_answer)
    mass = cli_answer["mass_g"]
    assert f"mass {float(f'{mass:.4g}'):g} g" in (page.text_content("#d-mass") or "")
    # The page says what the two models give: refined (the default) holds in FE, paper reproduces.
    note = page.text_content("#d-model-note") or ""
    assert "refined" in note and "finite elements" in note and "W 8, n 8" in note, note
    assert page.input_value("#d-model") == "refined"

    # The stiffness table: a row per direction with the CLI's K, D and EI (mN m^2).
    rows = page.locator("#d-stiffness tbody tr")
    assert rows.count() == len(cli_answer["stiffness"]) > 0
    for i, s in enumerate(cli_answer["stiffness"]):
        cells = rows.nth(i)
        assert float(cells.get_attribute("data-eta") or "nan") == s["eta_deg"]
        for quantity, expected in (
            ("K_N_per_mm", s["K_N_per_mm"]),
            ("D_Nmm", s["D_Nmm"]),
            ("EI_mNm2", s["EI_Nmm2"] / 1000),
        ):
            shown = cells.locator(f"td[data-quantity='{quantity}']").text_content() or "nan"
            assert float(shown) == pytest.approx(expected, rel=1e-4), (quantity, shown)

    # The runner-ups: the CLI's, best design for each n, the optimum marked.
    runner_ups = cli_answer["runner_ups"]
    assert runner_ups
    shown_rows = page.locator("#d-runner-ups tbody tr")
    assert shown_rows.count() == len(runner_ups)
    for i, r in enumerate(runner_ups):
        cells = shown_rows.nth(i)
        layer = r["layers"][0]
        assert cells.locator("td[data-quantity='n']").text_content() == str(r["n"])
        w = cells.locator("td[data-quantity='W_mm']").text_content() or "nan"
        alpha = cells.locator("td[data-quantity='alpha_deg']").text_content() or "nan"
        objective = cells.locator("td[data-quantity='objective']").text_content() or "nan"
        assert float(w) == pytest.approx(layer["W_mm"], rel=1e-5)
        assert float(alpha) == pytest.approx(layer["alpha_deg"], rel=1e-5)
        assert float(objective) == pytest.approx(r["objective"], rel=1e-4)
        best = r["objective"] == cli_answer["objective"]["value"]
        assert (cells.get_attribute("data-best") == "true") is best
    assert "mass (g)" in (page.text_content("#d-runner-ups thead") or "")


def test_the_tabs_take_the_arrow_keys(watched: Watched, live_server: str) -> None:
    page = watched.page
    page.goto(live_server + "/")
    page.wait_for_selector("form[data-ready='true']")

    def state() -> tuple[str, str, str, str, bool]:
        return (
            page.evaluate("() => document.activeElement.id"),
            page.get_attribute("#tab-analyze", "aria-selected") or "",
            page.get_attribute("#tab-analyze", "tabindex") or "",
            page.get_attribute("#tab-design", "tabindex") or "",
            page.is_visible("#panel-design"),
        )

    analyse = ("tab-analyze", "true", "0", "-1", False)
    design_tab = ("tab-design", "false", "-1", "0", True)
    page.focus("#tab-analyze")
    assert state() == analyse
    for key, expected in (
        ("ArrowRight", design_tab),
        ("ArrowRight", analyse),  # wraps round
        ("ArrowLeft", design_tab),  # wraps round
        ("ArrowLeft", analyse),
        ("End", design_tab),
        ("Home", analyse),
        ("End", design_tab),
    ):
        page.keyboard.press(key)
        assert state() == expected, key
    assert page.is_hidden("#panel-analyze")
    # Tab leaves the tab list (one tab stop) for the open panel.
    page.keyboard.press("Tab")
    assert page.evaluate("() => document.activeElement.getAttribute('role')") != "tab"
    assert page.evaluate(
        "() => document.getElementById('panel-design').contains(document.activeElement)"
    )


#: Spec keys whose values are names or counts, not quantities.
NOT_QUANTITIES = re.compile(
    r"^(name|model|layers|support|cutter|fold_style|paper|material\.name|layout\.shape"
    r"|objective\.(minimize|maximize)|variables\.n\.(min|max)|robust\.probability|tolerances"
    r"|constraints\.\w+\[\d+\]\.(support|test))$"
)
#: A number and a unit ("80 mN*m^2", "0 deg", "1.39 g/cm^3").
WITH_UNIT = re.compile(r"^[+-]?(\d+\.?\d*|\.\d+)(e[+-]?\d+)?\s+[A-Za-z].*$")


def leaves(obj: Any, path: str = "") -> Iterator[tuple[str, Any]]:
    """Every (spec path, value) of a JSON object, lists indexed as in the spec (``a[0].b``)."""
    if isinstance(obj, dict):
        for key, value in obj.items():
            yield from leaves(value, f"{path}.{key}" if path else key)
    elif isinstance(obj, list):
        for i, value in enumerate(obj):
            yield from leaves(value, f"{path}[{i}]")
    else:
        yield path, obj


def without_units(body: dict[str, Any]) -> list[str]:
    """The quantities of a posted body that are not a number with a unit."""
    return [
        f"{path} = {value!r}"
        for path, value in leaves(body)
        if not NOT_QUANTITIES.match(path) and not WITH_UNIT.match(str(value))
    ]


def test_every_quantity_the_forms_post_carries_its_unit(
    watched: Watched, live_server: str, cli_answer: dict[str, Any]
) -> None:
    page = open_design_tab(watched, live_server + "/")
    # Plain numbers typed into every field that shows a unit: the page adds that unit.
    typed = {
        "#d-thickness": ("0.125", "material.thickness", "0.125 mm"),
        "#d-side-min": ("48", "constraints.side.min", "48 mm"),
        "#d-side-max": ("60", "constraints.side.max", "60 mm"),
        "#d-thick-min": ("10", "constraints.thickness.min", "10 mm"),
        "#d-thick-max": ("12.5", "constraints.thickness.max", "12.5 mm"),
        "#d-sheet-max": ("250", "constraints.sheet_max", "250 mm"),
        "#d-mass-max": ("5", "constraints.mass.max", "5 g"),
        "#d-W-min": ("1", "variables.W.min", "1 mm"),
        "#d-W-max": ("30", "variables.W.max", "30 mm"),
        "#d-W-step": ("1", "variables.W.step", "1 mm"),
        "#d-alpha-min": ("1", "variables.alpha.min", "1 deg"),
        "#d-alpha-max": ("120", "variables.alpha.max", "120 deg"),
        "#d-alpha-step": ("1", "variables.alpha.step", "1 deg"),
        "#d-ei-min": ("80", "constraints.flexural_rigidity[0].min", "80 mN*m^2"),
        "#d-ei-eta": ("0", "constraints.flexural_rigidity[0].eta", "0 deg"),
    }
    for selector, (plain, _, _) in typed.items():
        page.fill(selector, plain)
    page.select_option("#d-fold-style", "perforated")
    page.fill("#d-cut", "1")
    page.fill("#d-gap", "0.5")
    row = page.locator("#d-req-rows .req").nth(1)
    row.locator(".req-kind").select_option("inplane_stiffness")
    row.locator(".req-min").fill("1")
    row.locator(".req-eta").fill("90")
    page.click("#d-add-req")
    load_case = page.locator("#d-req-rows .req").last
    load_case.locator(".req-kind").select_option("deflection")
    load_case.locator(".req-load").fill("0.01")
    load_case.locator(".req-min").fill("20")
    load_case.locator(".req-span").fill("40")
    load_case.locator(".req-eta").fill("0")
    body = page.evaluate("() => designBodyForTests()")
    flat = dict(leaves(body))
    for _, path, expected in typed.values():
        assert flat[path] == expected, (path, flat.get(path))
    assert (body["cut"], body["gap"]) == ("1 mm", "0.5 mm")
    assert body["constraints"]["inplane_stiffness"] == [{"min": "1 N/mm", "eta": "90 deg"}]
    (deflection,) = body["constraints"]["deflection"]
    assert deflection | {"test": None} == {
        "test": None,
        "load": "0.01 N",
        "max": "20 mm",
        "span": "40 mm",
        "eta": "0 deg",
    }
    assert without_units(body) == []
    page.select_option("#d-objective", "maximize:flexural_rigidity")
    page.fill("#d-objective-eta", "45")
    assert page.evaluate("() => designBodyForTests()")["objective"]["eta"] == "45 deg"
    page.select_option("#d-objective", "minimize:mass")

    # Posted, the plain-number form is the case study with three more bounds, all met by the
    # CLI's design (mass at most 5 g, K(90) >= 1 N/mm, at most 20 mm under 10 mN): its answer.
    posted, answer = design(page)
    assert posted == body
    assert without_units(posted) == []
    assert answer["design"]["design"] == cli_answer["design"]
    assert answer["design"]["mass_g"] == cli_answer["mass_g"]

    # The analyse tab: lengths in mm, angles in deg, E in MPa, density in g/cm^3, as labelled.
    page.click("#tab-analyze")
    page.select_option("#material", "__custom__")
    for selector, plain in {
        "#W": "8",
        "#n": "8",
        "#alpha": "84",
        "#thickness": "0.125",
        "#E": "2700",
        "#nu": "0.43",
        "#density": "1.39",
        "#eta": "0 90",
        "#holes": "6@0,0",
    }.items():
        page.fill(selector, plain)
    with page.expect_response("**/api/analyze", timeout=60_000) as info:
        page.click("#submit")
    response = info.value
    assert response.status == 200, response.text()
    sent = json.loads(response.request.post_data)
    assert sent == {
        "W": "8 mm",
        "n": "8",
        "alpha": "84 deg",
        "thickness": "0.125 mm",
        "E": "2700 MPa",
        "nu": "0.43",
        "density": "1.39 g/cm^3",
        "holes": [{"shape": "circle", "diameter": "6 mm", "center": ["0 mm", "0 mm"]}],
        "layout": "square",
        "model": "refined",
        "eta": ["0 deg", "90 deg"],
    }
    assert response.json()["mass_g"] > 0
