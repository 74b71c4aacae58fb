"""Load cases on the design form, in a real browser (Chromium via Playwright).

The chassis plate of ``examples/chassis_plate.toml`` typed into the form: a load-case row (at
most 1 mm under 10 N in three-point bending over 120 mm) becomes the example's
``[[constraints.deflection]]``, the answer is a direct solve of that spec and shows the
deflection row in mm. Stiffness rows name their test; a bad load case is reported on its row;
no requirement-row input is too narrow to read.
"""

from __future__ import annotations

import json
from typing import Any
from urllib.parse import unquote

import pytest

from corrugate.spec.schema import parse_spec

from .test_browser import Watched, browser  # noqa: F401  (the module's browser fixture)
from .test_browser_specs import check_answer, design, open_design_tab, spec_of
from .test_design_api import spec_of as example

pytestmark = pytest.mark.browser  # needs Chromium and Playwright

#: Readable: about eight characters of the form's 16 px font.
MIN_WIDTH_PX = 64


def set_load_case(page: Any, i: int, test: str, load: str, most: str, span: str, eta: str) -> Any:
    row = page.locator("#d-req-rows .req").nth(i)
    row.locator(".req-kind").select_option("deflection")
    row.locator(".req-test").select_option(test)
    row.locator(".req-load").fill(load)
    row.locator(".req-min").fill(most)
    row.locator(".req-eta").fill(eta)
    if test != "platens":
        row.locator(".req-span").fill(span)
    return row


def narrow_controls(page: Any) -> list[dict[str, Any]]:
    """The visible controls of the requirement rows narrower than :data:`MIN_WIDTH_PX`."""
    boxes = page.eval_on_selector_all(
        "#d-req-rows input, #d-req-rows select",
        "els => els.filter(e => e.offsetParent !== null).map(e => ({"
        " cls: e.className, width: e.getBoundingClientRect().width }))",
    )
    assert boxes, "no visible requirement controls"
    return [b for b in boxes if b["width"] < MIN_WIDTH_PX]


def test_the_chassis_plate_as_a_load_case_row(browser: Any, live_server: str) -> None:  # noqa: F811
    w = Watched(browser, live_server)
    page = open_design_tab(w, live_server + "/")
    page.fill("#d-name", "chassis-plate")
    page.select_option("#d-material", "polypropylene")
    page.fill("#d-thickness", "0.5 mm")  # the example's sheet under the default tolerances
    page.select_option("#d-model", "refined")
    page.select_option("#d-layout", "rectangle")
    page.select_option("#d-layering", "independent")
    page.select_option("#d-joint", "band-edges")  # the example bonds the band along the edges
    page.select_option(
        "#d-tolerances", ""
    )  # the example is certified within the default tolerances
    page.fill("#d-side_x-min", "78 mm")
    page.fill("#d-side_x-max", "82 mm")
    page.fill("#d-side_y-min", "120 mm")
    page.fill("#d-side_y-max", "124 mm")
    page.fill("#d-thick-min", "")
    page.fill("#d-thick-max", "15 mm")
    page.fill("#d-sheet-max", "280 mm")
    for field, value in {
        "W-min": "5 mm",
        "W-max": "30 mm",
        "W-step": "1 mm",
        "n-min": "6",
        "n-max": "40",
        "alpha-min": "40 deg",
        "alpha-max": "120 deg",
        "alpha-step": "5 deg",
    }.items():
        page.fill(f"#d-{field}", value)
    page.locator("#d-req-rows .req .req-remove").last.click()
    assert page.locator("#d-req-rows .req").count() == 1
    row = set_load_case(page, 0, "platens", "10 N", "1 mm", "", "0 deg")
    assert row.locator(".req-span").is_hidden()  # platens compress the panel's whole length
    assert row.locator(".req-bearing").is_hidden()  # and load no line
    assert row.locator(".req-load").is_visible()
    row = set_load_case(page, 0, "three-point", "10", "1", "120 mm", "0 deg")
    assert row.locator(".req-span").is_visible()
    assert row.locator(".req-bearing").is_visible()  # left empty: the default 10 mm
    assert row.locator(".req-bearing").get_attribute("data-path") == (
        "constraints.deflection[0].bearing"
    )
    assert narrow_controls(page) == []
    page.set_viewport_size({"width": 420, "height": 900})  # a phone: the form is one column
    assert narrow_controls(page) == []
    page.set_viewport_size({"width": 1280, "height": 1000})

    body, answer = design(page)
    # The row is the example's [[constraints.deflection]] (plain numbers: N and mm).
    assert body["constraints"]["deflection"] == [
        {"test": "three-point", "load": "10 N", "max": "1 mm", "span": "120 mm", "eta": "0 deg"}
    ]
    assert "flexural_rigidity" not in body["constraints"]
    assert parse_spec(spec_of(body)) == parse_spec(example("chassis_plate.toml"))
    check_answer(page, body, answer)
    rows = {c["name"]: c for c in answer["design"]["constraints"]}
    c = rows["constraints.deflection[0].max"]
    assert c["unit"] == "mm" and c["sense"] == "max" and c["bound"] == pytest.approx(1.0)
    assert c["value"] == pytest.approx(c["load_N"] / c["stiffness_N_per_mm"])  # delta = P / k
    shown = page.locator("#d-constraints tr[data-name='constraints.deflection[0].max']")
    value = float(shown.locator("td[data-quantity='value']").text_content() or "nan")
    assert 0 < value <= 1.0
    assert value == pytest.approx(c["value"], rel=1e-4)
    cells = shown.locator("td").all_text_contents()
    assert cells[4] == "mm" and "three-point, 10 N" in cells[0], cells
    assert "constraints.deflection[0].span" in rows  # the panel reaches the supports

    # The URL holds the spec: a fresh page fills the load-case row back.
    url = page.url
    assert json.loads(unquote(url.split("spec=", 1)[1])) == body
    w2 = Watched(browser, live_server)
    page2 = w2.page
    page2.goto(url)
    page2.wait_for_selector("#design-form[data-ready='true']", state="attached")
    page2.wait_for_function("() => document.getElementById('d-name').value === 'chassis-plate'")
    filled = page2.locator("#d-req-rows .req").nth(0)
    assert filled.locator(".req-kind").input_value() == "deflection"
    assert filled.locator(".req-test").input_value() == "three-point"
    assert filled.locator(".req-span").input_value() == "120 mm"
    assert page2.evaluate("() => designBodyForTests()") == body
    for x in (w, w2):
        assert x.page_errors == [] and x.external == []
        x.page.close()


def test_stiffness_rows_name_their_test_and_a_bad_load_is_shown_on_its_row(
    browser: Any,  # noqa: F811
    live_server: str,
) -> None:
    w = Watched(browser, live_server)
    page = open_design_tab(w, live_server + "/")
    first = page.locator("#d-req-rows .req").nth(0)
    tests = first.locator(".req-test option").evaluate_all("os => os.map(o => o.value)")
    assert tests == ["", "three-point", "four-point", "cantilever"]  # '' is pure bending
    first.locator(".req-test").select_option("four-point")
    second = page.locator("#d-req-rows .req").nth(1)
    assert second.locator(".req-kind").input_value() == "inplane_stiffness"
    k_tests = second.locator(".req-test option").evaluate_all("os => os.map(o => o.value)")
    assert k_tests == ["", "wheel"]  # '' is between platens; the wheel test is a circle's
    second.locator(".req-kind").select_option("bending_stiffness")
    second.locator(".req-min").fill("500")
    second.locator(".req-test").select_option("cantilever")
    body = page.evaluate("() => designBodyForTests()")
    assert body["constraints"]["flexural_rigidity"] == [
        {"min": "80 mN*m^2", "eta": "0 deg", "test": "four-point"}
    ]
    assert body["constraints"]["bending_stiffness"] == [  # the row's eta was left empty
        {"min": "500 N*mm", "test": "cantilever"}
    ]
    # pure bending is the spec's default: no key
    first.locator(".req-test").select_option("")
    body = page.evaluate("() => designBodyForTests()")
    assert "test" not in body["constraints"]["flexural_rigidity"][0]

    # A load of 0: 422 from the spec parser, shown on the row's load field.
    page.click("#d-add-req")
    row = set_load_case(page, 2, "cantilever", "0 N", "2 mm", "40 mm", "0 deg")
    assert narrow_controls(page) == []
    with page.expect_response("**/api/jobs/design") as info:
        page.click("#d-submit")
    assert info.value.status == 422
    assert info.value.json()["field"] == "constraints.deflection[0].load"
    page.wait_for_selector("#design-form[data-state='error']")
    message = row.locator(".error").text_content() or ""
    assert message.startswith("requirement 3: load (N): you gave 0 N"), message
    assert message.endswith("constraints.deflection[0].load"), message
    assert row.locator(".req-load").get_attribute("aria-invalid") == "true"
    assert page.is_hidden("#design-results")
    assert w.page_errors == [] and w.external == []
    page.close()


def test_the_wheel_example_keeps_its_wheel_test_in_the_form(
    browser: Any,  # noqa: F811
    live_server: str,
) -> None:
    """examples/wheel_circle.toml opened in the form (its #design?spec= link) posts its K bounds
    in the wheel test (docs/load_cases.md 9), not between platens."""
    from urllib.parse import quote

    spec = example("wheel_circle.toml")
    w = Watched(browser, live_server)
    page = w.page
    page.goto(f"{live_server}/#design?spec={quote(json.dumps(spec))}")
    page.wait_for_selector("#design-form[data-ready='true']", state="attached")
    page.wait_for_function("() => document.getElementById('d-name').value !== ''")
    body = page.evaluate("() => designBodyForTests()")
    bounds = body["constraints"]["inplane_stiffness"]
    assert [b.get("test") for b in bounds] == ["wheel", "wheel"]
    assert [b["eta"] for b in bounds] == ["0 deg", "45 deg"]
    assert w.page_errors == []
    page.close()
