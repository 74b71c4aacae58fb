"""A custom material on the design page, in a real browser (Chromium via Playwright; issue 36,
"a custom material"): choosing "custom" shows E, nu, density and an optional yield strength; the
page posts them as the spec's inline ``[material]`` table (a plain number in the unit its field
shows), gets the answer a direct solve of that spec gives, saves a file the command line reads
to the same answer, and a fresh page loads the file back into the same form.
"""

from __future__ import annotations

import json
import tomllib
from pathlib import Path
from typing import TYPE_CHECKING, Any

import pytest

from .test_browser import Watched, browser  # noqa: F401  (the module's browser fixture)
from .test_browser_specs import check_answer, design, open_design_tab
from .test_design_api import without_timings

if TYPE_CHECKING:
    from conftest import CliRun

pytestmark = pytest.mark.browser  # needs Chromium and Playwright

#: What the spec's [material] must hold for the values typed below (plain numbers in the units
#: the fields show: MPa for E and the yield strength, g/cm^3, mm).
POSTED = {
    "E": "2.1 GPa",
    "nu": "0.4",
    "density": "1.27 g/cm^3",
    "thickness": "0.25 mm",
    "yield_strength": "50 MPa",
}


def test_a_custom_material_designs_saves_and_loads_as_the_cli_reads_it(
    browser: Any,  # noqa: F811
    live_server: str,
    tmp_path: Path,
    cli: CliRun,
) -> None:
    w = Watched(browser, live_server)
    page = open_design_tab(w, live_server + "/")
    assert page.is_hidden("#d-E")
    page.select_option("#d-material", "__custom__")
    for field in ("#d-E", "#d-nu", "#d-density", "#d-yield"):
        assert page.is_visible(field), field
    assert page.is_hidden("#d-more-materials")
    page.fill("#d-E", "2.1 GPa")
    page.fill("#d-nu", "0.4")
    page.fill("#d-density", "1.27")
    page.fill("#d-thickness", "0.25")
    page.fill("#d-yield", "50")
    body, answer = design(page)
    assert body["material"] == POSTED
    check_answer(page, body, answer)  # a direct solve of the posted spec
    assert answer["design"]["design"]["layers"][0]["t_mm"] == 0.25

    with page.expect_download() as info:
        page.click("#d-save")
    saved = tmp_path / "custom.toml"
    saved.write_bytes(Path(info.value.path()).read_bytes())
    assert tomllib.loads(saved.read_text())["material"] == POSTED
    code, out, err = cli(["design", str(saved), "--json"])
    assert code == 0, err
    assert without_timings(json.loads(out)) == without_timings(answer["design"])

    # a fresh page loads the file: custom chosen, its fields filled, the same spec posted
    w2 = Watched(browser, live_server)
    page2 = open_design_tab(w2, live_server + "/")
    page2.set_input_files("#d-load", str(saved))
    page2.wait_for_function("() => /loaded/.test(document.getElementById('d-status').textContent)")
    assert "not in the form" not in (page2.text_content("#d-status") or "")
    assert page2.input_value("#d-material") == "__custom__"
    assert page2.is_visible("#d-E") and page2.input_value("#d-yield") == "50 MPa"
    assert page2.evaluate("() => window.designBodyForTests()") == body

    # a bad modulus is shown on its field, as the CLI names it
    page2.fill("#d-nu", "0.7")
    with page2.expect_response("**/api/jobs/design") as refused:
        page2.click("#d-submit")
    assert refused.value.status == 422
    assert refused.value.json()["field"] == "material.nu"
    page2.wait_for_selector("#design-form[data-state='error']")
    assert page2.get_attribute("#d-nu", "aria-invalid") == "true"
    message = page2.text_content(".field:has(#d-nu) .error") or ""
    assert "0.7" in message and message.endswith("material.nu"), message
    assert w.console_errors == [] and w.page_errors == [] and w.external == []
    assert [e for e in w2.console_errors if "status of 422" not in e] == []


def test_a_custom_materials_crease_and_springback_are_posted_in_their_units(
    browser: Any,  # noqa: F811
    live_server: str,
) -> None:
    """The two optional fields of a custom material (docs/calibration.md 10): hidden until
    "custom" is chosen, a plain number posted in the unit the field shows, left out when empty."""
    w = Watched(browser, live_server)
    page = open_design_tab(w, live_server + "/")
    assert page.is_hidden("#d-crease") and page.is_hidden("#d-springback")
    page.select_option("#d-material", "__custom__")
    assert page.is_visible("#d-crease") and page.is_visible("#d-springback")
    page.fill("#d-E", "2.1 GPa")
    page.fill("#d-nu", "0.4")
    page.fill("#d-density", "1.27")
    body = page.evaluate("() => window.designBodyForTests()")
    assert "crease_stiffness" not in body["material"] and "springback" not in body["material"]
    page.fill("#d-crease", "0.1")
    page.fill("#d-springback", "-4")
    body = page.evaluate("() => window.designBodyForTests()")
    assert body["material"]["crease_stiffness"] == "0.1 N*mm/(rad*mm)"
    assert body["material"]["springback"] == "-4 deg"
