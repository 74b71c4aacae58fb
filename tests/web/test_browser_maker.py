"""A maker's first hour on the design page, in a real browser (Chromium via Playwright; issue 36).

The page's defaults are the command line's: the default design's cut files carry the machine's
fold operations (a Silhouette's DXF and a Cricut's SVG hold their mountain and valley creases, as
``corrugate design`` writes them, read back with ezdxf and ElementTree); a spec saved from the page
is a file ``corrugate design`` reads to the page's own answer (the CLI run in-process on the
downloaded file) and loads back into the same form; a requirement switched to a quantity of
another unit keeps no value of the old one, and the load case's inputs carry visible labels.
"""

from __future__ import annotations

import io
import json
import tomllib
import xml.etree.ElementTree as ET
import zipfile
from pathlib import Path
from typing import TYPE_CHECKING, Any

import ezdxf
import pytest

from .test_browser import Watched, browser  # noqa: F401  (the module's browser fixture)
from .test_browser_specs import check_answer, design, open_design_tab
from .test_design_api import without_timings

if TYPE_CHECKING:
    from conftest import CliRun

pytestmark = pytest.mark.browser  # needs Chromium and Playwright

SVG = "{http://www.w3.org/2000/svg}"


def _files(page: Any, answer: dict[str, Any]) -> dict[str, bytes]:
    """Every file of the answer, through the page's "all.zip" link."""
    with page.expect_download() as info:
        page.click("#d-downloads a[data-name='all.zip']")
    archive = zipfile.ZipFile(io.BytesIO(Path(info.value.path()).read_bytes()))
    assert sorted(archive.namelist()) == sorted(f["name"] for f in answer["result"]["files"])
    return {name: archive.read(name) for name in archive.namelist()}


def test_default_design_cut_files_carry_creases_and_runner_ups_as_the_cli(
    browser: Any,  # noqa: F811
    live_server: str,
    tmp_path: Path,
) -> None:
    w = Watched(browser, live_server)
    page = open_design_tab(w, live_server + "/")
    # the defaults: the machine's fold operations, the Silhouette Cameo 4 (the CLI's machine)
    assert page.input_value("#d-fold-style") == "machine"
    assert page.input_value("#d-cutter") == "cameo4-12x12"
    body, answer = design(page)
    assert body["fold_style"] == "machine" and body["cutter"] == "cameo4-12x12"
    check_answer(page, body, answer)  # the CLI's answer (a direct solve of the posted spec)
    # runner-ups as the CLI lists them: one row per n, the answer's marked
    runners = answer["design"]["runner_ups"]
    assert len(runners) > 1
    rows = page.locator("#d-runner-ups tbody tr")
    assert rows.count() == len(runners)
    shown_n = [
        rows.nth(i).locator("td[data-quantity='n']").text_content() for i in range(len(runners))
    ]
    assert shown_n == [str(r["n"]) for r in runners]
    files = _files(page, answer)
    dxf = tmp_path / "cut-1.dxf"
    dxf.write_bytes(files["cut-1.dxf"])
    layers: dict[str, int] = {}
    for e in ezdxf.readfile(dxf).modelspace():
        layers[e.dxf.layer] = layers.get(e.dxf.layer, 0) + 1
    # the Silhouette's default (docs/fabrication.md): mountains perforated, valleys cut-scored
    assert layers.get("MOUNTAIN-PERFORATE", 0) > 0, layers
    assert layers.get("VALLEY-CUT-SCORE", 0) > 0, layers
    assert layers.get("CUT", 0) > 0 and layers.get("MARK-PEN", 0) > 0

    # the Cricut: its SVG cut file, the same creases reach its machine
    page.select_option("#d-cutter", "maker-12x12")
    body, answer = design(page)
    assert body["fold_style"] == "machine" and body["cutter"] == "maker-12x12"
    root = ET.fromstring(_files(page, answer)["cut-1.svg"])
    groups = {g.attrib["id"]: len(list(g)) for g in root.iter(f"{SVG}g") if "id" in g.attrib}
    assert groups.get("MOUNTAIN-PERFORATE", 0) > 0, groups
    assert groups.get("VALLEY-SCORE", 0) > 0, groups
    assert w.console_errors == [] and w.page_errors == [] and w.external == []


def test_a_spec_saved_from_the_page_gives_the_cli_the_same_answer_and_loads_back(
    browser: Any,  # noqa: F811
    live_server: str,
    tmp_path: Path,
    cli: CliRun,
) -> None:
    w = Watched(browser, live_server)
    page = open_design_tab(w, live_server + "/")
    page.fill("#d-name", "saved-pad")
    page.fill("#d-side-min", "50 mm")
    page.fill("#d-side-max", "56 mm")
    page.select_option("#d-cutter", "maker-12x12")
    page.click("#d-fabrication summary")
    page.fill("#d-min-facet", "5")  # a plain number: the field's mm
    page.select_option("#d-valley", "perforate")
    body, answer = design(page)
    assert body["fabrication"] == {"min_facet": "5 mm", "valley": "perforate"}
    with page.expect_download() as info:
        page.click("#d-save")
    assert info.value.suggested_filename == "saved-pad.toml"
    saved = tmp_path / "saved-pad.toml"
    saved.write_bytes(Path(info.value.path()).read_bytes())
    text = saved.read_text()
    data = tomllib.loads(text)
    # the page's spec, the cutter as the spec's machine; the output options are not spec keys
    spec = {
        k: v for k, v in body.items() if k not in ("cutter", "fold_style", "cut", "gap", "paper")
    }
    spec["fabrication"] = {**spec["fabrication"], "machine": "maker-12x12"}
    assert data == spec
    # the CLI reads the file to the page's answer
    code, out, err = cli(["design", str(saved), "--json"])
    assert code == 0, err
    assert without_timings(json.loads(out)) == without_timings(answer["design"])

    # a fresh page loads the file into its form: it posts the same spec
    w2 = Watched(browser, live_server)
    page2 = open_design_tab(w2, live_server + "/")
    page2.set_input_files("#d-load", str(saved))
    page2.wait_for_function("() => /loaded/.test(document.getElementById('d-status').textContent)")
    assert "not in the form" not in (page2.text_content("#d-status") or "")
    assert page2.input_value("#d-cutter") == "maker-12x12"
    assert page2.input_value("#d-min-facet") == "5 mm"
    reloaded = page2.evaluate("() => window.designBodyForTests()")
    assert reloaded == body
    # a file the CLI refuses is refused in one line naming the key; the form stays as it was
    bad = tmp_path / "bad.toml"
    bad.write_text(text.replace('min = "50 mm"', 'min = "50 kg"'))
    page2.set_input_files("#d-load", str(bad))
    page2.wait_for_function("() => document.getElementById('d-error-body').textContent !== ''")
    message = page2.text_content("#d-error-body") or ""
    assert message.startswith("bad.toml:") and "constraints.side.min" in message, message
    assert page2.evaluate("() => window.designBodyForTests()") == body
    assert w.console_errors == [] and w.page_errors == [] and w.external == []
    # Chromium logs the refused file's 422 answer, and nothing else
    assert [e for e in w2.console_errors if "status of 422" not in e] == []
    assert len(w2.console_errors) == 1 and w2.page_errors == [] and w2.external == []


def test_a_requirement_switched_between_kinds_keeps_no_stale_value(
    browser: Any,  # noqa: F811
    live_server: str,
) -> None:
    w = Watched(browser, live_server)
    page = open_design_tab(w, live_server + "/")
    row = page.locator("#d-req-rows .req").first
    assert row.locator(".req-min").input_value() == "80 mN*m^2"
    assert row.locator(".req-min-text").text_content() == "at least (mN*m^2)"
    row.locator(".req-kind").select_option("deflection")
    # no "80 mN*m^2" left in a field of mm; its label says what the field now holds
    assert row.locator(".req-min").input_value() == ""
    assert row.locator(".req-min-text").text_content() == "at most (mm)"
    # load, eta and span each under a visible label (not a placeholder that typing hides)
    for cls, label in (
        (".req-load", "load (N)"),
        (".req-eta", "eta (deg)"),
        (".req-span", "span (mm)"),
    ):
        field = row.locator(cls)
        assert field.is_visible(), cls
        text = field.evaluate("el => el.closest('label').querySelector('.sub-text').textContent")
        assert text == label
        assert row.locator(f"label.sub:has({cls}) .sub-text").is_visible()
    row.locator(".req-min").fill("2")
    row.locator(".req-load").fill("5")
    row.locator(".req-span").fill("40")
    body = page.evaluate("() => window.designBodyForTests()")
    (case,) = body["constraints"]["deflection"]
    assert case["max"] == "2 mm" and case["load"] == "5 N" and case["span"] == "40 mm"
    assert "flexural_rigidity" not in body["constraints"]
    # back to EI: the deflection, load and span go; nothing of a load case is posted
    row.locator(".req-kind").select_option("flexural_rigidity")
    assert row.locator(".req-min").input_value() == ""
    assert (
        row.locator(".req-load").input_value() == ""
        and row.locator(".req-span").input_value() == ""
    )
    assert not row.locator(".req-load").is_visible()
    # between two quantities of the same unit the value stays (K's N/mm is nobody else's: EI to
    # EI through the menu is no switch); a typed EI goes when the row becomes a buckling load
    row.locator(".req-min").fill("90")
    row.locator(".req-kind").select_option("buckling_load")
    assert row.locator(".req-min").input_value() == ""
    assert row.locator(".req-min-text").text_content() == "at least (N)"
    body = page.evaluate("() => window.designBodyForTests()")
    assert (
        "deflection" not in body["constraints"] and "flexural_rigidity" not in body["constraints"]
    )
    w.screenshot("web-requirement-labels.png")
    assert w.console_errors == [] and w.page_errors == [] and w.external == []
