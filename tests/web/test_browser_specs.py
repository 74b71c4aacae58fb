"""The design form at parity with the spec, in a real browser (Chromium via Playwright).

Three users of the issue: a roboticist's 50 mm finger pad (EI rows at 0 and 90 deg and a mass
bound), a maker's foldable wheel (a circle with an axle hole, K at 0 and 45 deg, D, two
materials) and a chassis plate with independent layers. For each, the spec the page posts is
checked against the one the user meant, and the page's answer against
:func:`corrugate.solver.solve` called directly on that spec. The page URL carries the spec: a
fresh page opened on it fills the form back.
"""

from __future__ import annotations

import json
from pathlib import Path
from typing import Any
from urllib.parse import unquote

import pytest

from .test_browser import Watched, browser  # noqa: F401  (the module's browser fixture)
from .test_design_api import direct_design, without_timings

pytestmark = pytest.mark.browser  # needs Chromium and Playwright

#: Output options the page sends beside the spec (corrugate design's --cutter ... --paper).
OUTPUT_KEYS = ("cutter", "fold_style", "cut", "gap", "paper")


def open_design_tab(w: Watched, url: str) -> Any:
    page = w.page
    page.goto(url)
    page.wait_for_selector("#design-form[data-ready='true']", state="attached")
    page.click("#tab-design")
    page.click("#d-variables summary")
    return page


def set_requirements(page: Any, rows: list[tuple[str, str, str, str]]) -> None:
    """Fill the requirement rows: (kind, least value, eta, support)."""
    while page.locator("#d-req-rows .req").count() < len(rows):
        page.click("#d-add-req")
    while page.locator("#d-req-rows .req").count() > len(rows):
        page.locator("#d-req-rows .req .req-remove").last.click()
    for i, (kind, least, eta, support) in enumerate(rows):
        row = page.locator("#d-req-rows .req").nth(i)
        row.locator(".req-kind").select_option(kind)
        row.locator(".req-min").fill(least)
        row.locator(".req-eta").fill(eta)
        if kind != "buckling_load":
            row.locator(".req-support").select_option(support)


def design(page: Any, timeout_ms: float = 300_000) -> tuple[dict[str, Any], dict[str, Any]]:
    """Submit; (the body the page posted, the answer's JSON). The page runs the design as a job
    (``POST /api/jobs/design``, 202) and shows it when the job is done; the answer is the done
    job's ``result``, as ``POST /api/design`` answers (``test_jobs_api.py`` checks that). The
    answer comes first: the page then asks for its files (``POST files_url``, made once per
    design) and is done once it shows them; the answer returned here has them as ``result``
    (asked for again: the same stored result)."""
    with page.expect_response("**/api/jobs/design", timeout=timeout_ms) as info:
        page.click("#d-submit")
    response = info.value
    assert response.status == 202, response.text()
    body = json.loads(response.request.post_data)
    page.wait_for_selector("#design-form[data-state='done']", timeout=timeout_ms)
    job = page.evaluate(
        "id => fetch('/api/jobs/' + id).then((r) => r.json())", response.json()["id"]
    )
    assert job["status"] == "done", job
    answer: dict[str, Any] = job["result"]
    if answer["result"] is None and answer["files_url"] is not None:  # made after the answer
        made = page.evaluate(
            "url => fetch(url, {method: 'POST'}).then((r) => r.json())", answer["files_url"]
        )
        answer = {**answer, "result": made}
    return body, answer


def spec_of(body: dict[str, Any]) -> dict[str, Any]:
    """The spec the page posted: its keys but the output options."""
    return {k: v for k, v in body.items() if k not in OUTPUT_KEYS}


def solved_spec_of(body: dict[str, Any]) -> dict[str, Any]:
    """The spec the web solves for a posted body: :func:`spec_of`, with the posted cutter as the
    spec's machine (as design --machine does)."""
    spec = spec_of(body)
    if "cutter" in body:
        spec["fabrication"] = {**spec.get("fabrication", {}), "machine": body["cutter"]}
    return spec


def check_answer(page: Any, body: dict[str, Any], answer: dict[str, Any]) -> None:
    """The page shows the certified answer a direct solve of the posted spec gives."""
    expected = direct_design(solved_spec_of(body))
    assert without_timings(answer["design"]) == expected
    assert expected["status"] == "optimal" and expected["certified"]
    shown = page.eval_on_selector_all(
        "#d-constraints tbody tr", "rows => rows.map(r => r.dataset.name)"
    )
    assert shown == [c["name"] for c in expected["constraints"]]
    for c in expected["constraints"]:
        assert c["margin"] >= 0, c


def test_finger_pad_with_EI_at_0_and_90_and_a_mass_bound(browser: Any, live_server: str) -> None:  # noqa: F811
    w = Watched(browser, live_server)
    page = open_design_tab(w, live_server + "/")
    # the form is the paper's case study under the default model (as its example file)
    assert page.input_value("#d-model") == "refined"
    page.fill("#d-name", "finger-pad")
    page.fill("#d-side-min", "48 mm")
    page.fill("#d-side-max", "52 mm")
    page.fill("#d-thick-min", "6 mm")
    page.fill("#d-thick-max", "12.5 mm")
    page.fill("#d-mass-max", "3 g")
    set_requirements(
        page,
        [
            ("flexural_rigidity", "40 mN*m^2", "0 deg", ""),
            ("flexural_rigidity", "40", "90 deg", ""),  # a plain number: the label's mN m^2
        ],
    )
    body, answer = design(page)
    assert body["constraints"]["flexural_rigidity"] == [
        {"min": "40 mN*m^2", "eta": "0 deg"},
        {"min": "40 mN*m^2", "eta": "90 deg"},
    ]
    assert body["constraints"]["mass"] == {"max": "3 g"}
    assert body["model"] == "refined" and body["objective"] == {"minimize": "mass"}
    check_answer(page, body, answer)
    link = page.locator("#d-downloads a[data-name='all.zip']")
    assert link.get_attribute("href") == f"/api/results/{answer['result']['id']}/all.zip"
    with page.expect_download() as download_info:
        link.click()
    import io
    import zipfile

    zipped = zipfile.ZipFile(io.BytesIO(Path(download_info.value.path()).read_bytes()))
    assert sorted(zipped.namelist()) == sorted(f["name"] for f in answer["result"]["files"])
    names = [c["name"] for c in answer["design"]["constraints"]]
    assert "constraints.flexural_rigidity[1].min" in names and "constraints.mass.max" in names

    # The URL holds the spec: a new page opened on it fills the form back and posts the same.
    url = page.url
    assert "#design?spec=" in url and json.loads(unquote(url.split("spec=", 1)[1])) == body
    w2 = Watched(browser, live_server)
    page2 = w2.page
    page2.goto(url)
    page2.wait_for_selector("#design-form[data-ready='true']", state="attached")
    page2.wait_for_function("() => document.getElementById('d-mass-max').value === '3 g'")
    assert page2.is_visible("#design-form")
    assert page2.locator("#d-req-rows .req").count() == 2
    assert page2.evaluate("() => designBodyForTests()") == body
    for x in (w, w2):
        assert x.page_errors == [] and x.external == []
        x.page.close()


def test_wheel_with_an_axle_hole_two_materials_and_off_axis_K(
    browser: Any,  # noqa: F811
    live_server: str,
) -> None:
    w = Watched(browser, live_server)
    page = open_design_tab(w, live_server + "/")
    page.fill("#d-name", "foldable-car-wheel")
    page.select_option("#d-model", "refined")
    page.select_option("#d-material", "dura-lar")
    page.fill("#d-more-materials", "polypropylene")
    page.fill("#d-thickness", "")
    page.select_option("#d-layout", "circle")
    page.fill("#d-holes", "6@0,0")
    page.fill("#d-diameter-min", "70 mm")
    page.fill("#d-diameter-max", "80 mm")
    page.fill("#d-thick-min", "6 mm")
    page.fill("#d-thick-max", "12 mm")
    page.fill("#d-sheet-max", "300 mm")
    page.fill("#d-W-min", "2 mm")
    page.fill("#d-W-max", "20 mm")
    page.fill("#d-W-step", "0.5 mm")
    page.fill("#d-n-min", "6")
    page.fill("#d-n-max", "60")
    page.fill("#d-alpha-min", "40 deg")
    page.fill("#d-alpha-max", "150 deg")
    page.fill("#d-alpha-step", "")
    set_requirements(
        page,
        [
            ("inplane_stiffness", "400 N/mm", "0 deg", ""),
            ("inplane_stiffness", "18 N/mm", "45 deg", "free"),
            ("bending_stiffness", "500 N*mm", "0 deg", ""),
        ],
    )
    page.select_option("#d-cutter", "laser")
    page.fill("#d-laser-bed", "600x400")
    body, answer = design(page)
    assert body["materials"] == [{"name": "dura-lar"}, {"name": "polypropylene"}]
    assert "material" not in body
    assert body["layout"] == {
        "shape": "circle",
        "holes": [{"shape": "circle", "diameter": "6 mm", "center": ["0 mm", "0 mm"]}],
    }
    assert body["constraints"]["inplane_stiffness"][1] == {
        "min": "18 N/mm",
        "eta": "45 deg",
        "support": "free",
    }
    assert body["cutter"] == "laser:600x400"
    check_answer(page, body, answer)
    files = {f["name"] for f in answer["result"]["files"]}
    assert {"cut-1.svg", "cut-1.dxf"} <= files  # a laser gets both
    assert answer["design"]["design"]["layout"]["holes"]
    assert w.page_errors == []
    page.close()


def test_rectangle_with_independent_layers(browser: Any, live_server: str) -> None:  # noqa: F811
    w = Watched(browser, live_server)
    page = open_design_tab(w, live_server + "/")
    page.fill("#d-name", "chassis-plate")
    page.select_option("#d-model", "refined")
    page.select_option("#d-layout", "rectangle")
    page.select_option("#d-layering", "independent")
    page.fill("#d-side_x-min", "80 mm")
    page.fill("#d-side_x-max", "100 mm")
    page.fill("#d-side_y-min", "40 mm")
    page.fill("#d-side_y-max", "60 mm")
    page.fill("#d-thick-min", "8 mm")
    page.fill("#d-thick-max", "16 mm")
    page.fill("#d-W-min", "4 mm")
    page.fill("#d-W-max", "16 mm")
    page.fill("#d-n-min", "4")
    page.fill("#d-n-max", "30")
    page.fill("#d-alpha-min", "40 deg")
    page.fill("#d-alpha-max", "140 deg")
    page.fill("#d-alpha-step", "5 deg")
    set_requirements(
        page,
        [
            ("flexural_rigidity", "150 mN*m^2", "0 deg", ""),
            ("flexural_rigidity", "40 mN*m^2", "90 deg", ""),
        ],
    )
    body, answer = design(page)
    assert body["layers"] == "independent"
    check_answer(page, body, answer)
    layers = answer["design"]["design"]["layers"]
    assert len(layers) == 2 and layers[0] != layers[1] | {"index": 1}
    assert w.page_errors == []
    page.close()


def test_an_infeasible_spec_shows_its_diagnosis_and_the_hint_line(
    browser: Any,  # noqa: F811
    live_server: str,
) -> None:
    """A finger pad asked for 100x the rigidity its 3 g allow: the page lists the diagnosis and,
    on a line of its own, the hint the answer carries (the CLI's ``hint:`` line)."""
    w = Watched(browser, live_server)
    page = open_design_tab(w, live_server + "/")
    page.select_option("#d-model", "refined")
    page.fill("#d-side-min", "48 mm")
    page.fill("#d-side-max", "52 mm")
    page.fill("#d-mass-max", "3 g")
    set_requirements(page, [("flexural_rigidity", "4000 mN*m^2", "0 deg", "")])
    body, answer = design(page)
    d = answer["design"]
    assert d["status"] == "infeasible" and answer["result"] is None
    assert without_timings(d) == direct_design(solved_spec_of(body))
    assert d["hint"]
    assert page.is_visible("#d-hint")
    assert page.inner_text("#d-hint") == f"hint: {d['hint']}"
    shown = page.eval_on_selector_all("#d-diagnosis li", "items => items.map(i => i.textContent)")
    assert shown == [x["message"] for x in d["diagnosis"]]
    assert w.page_errors == [] and w.external == []
    w.page.close()
