"""report.html: self-contained, every figure present, every constraint reported; opens cleanly in
Chromium (no missing image, no console error)."""

from __future__ import annotations

import base64
import os
from html.parser import HTMLParser
from pathlib import Path

import pytest

from corrugate.design import Problem, solve
from corrugate.report import report_html
from corrugate.spec import load_spec

ROOT = Path(__file__).resolve().parents[1]
BLIMP = ROOT / "examples" / "blimp_gripper.toml"
CHROMIUM = Path("/usr/bin/chromium")
ARTIFACTS = ROOT / "test-artifacts"


class _Collect(HTMLParser):
    def __init__(self) -> None:
        super().__init__()
        self.images: list[dict[str, str | None]] = []
        self.headings: list[str] = []
        self.scripts = 0
        self.links: list[str] = []
        self._in_h2 = False

    def handle_starttag(self, tag: str, attrs: list[tuple[str, str | None]]) -> None:
        if tag == "img":
            self.images.append(dict(attrs))
        if tag == "script":
            self.scripts += 1
        if tag in ("link", "a") and dict(attrs).get("href"):
            self.links.append(str(dict(attrs)["href"]))
        self._in_h2 = tag == "h2"

    def handle_data(self, data: str) -> None:
        if self._in_h2:
            self.headings.append(data.strip())
            self._in_h2 = False


@pytest.fixture(scope="module")
def report(tmp_path_factory: pytest.TempPathFactory) -> Path:
    sol = solve(Problem.from_spec(load_spec(BLIMP)))
    path = tmp_path_factory.mktemp("report") / "report.html"
    path.write_text(report_html(sol, BLIMP.read_text()), encoding="utf-8")
    return path


def test_report_is_self_contained_and_complete(report: Path) -> None:
    text = report.read_text(encoding="utf-8")
    parsed = _Collect()
    parsed.feed(text)
    assert parsed.scripts == 0
    assert parsed.links == []  # nothing fetched from anywhere
    assert len(parsed.images) >= 5  # design space, mass by n, polar, sheet(s), folded part
    for img in parsed.images:
        src = str(img["src"])
        assert src.startswith("data:image/png;base64,")
        png = base64.b64decode(src.split(",", 1)[1])
        assert png[:8] == b"\x89PNG\r\n\x1a\n"
        assert img.get("alt")
    for heading in (
        "Design",
        "Constraints and margins",
        "Design space",
        "Stiffness in every direction",
        "The three model variants",
        "Flat pattern and folded part",
        "Assembly",
        "Warnings",
        "Spec",
        "Buckling in compression",
    ):
        assert heading in parsed.headings, heading
    for name in (
        "constraints.side.min",
        "constraints.thickness.max",
        "constraints.flexural_rigidity[0].min",
    ):
        assert name in text
    assert "name = &quot;blimp-gripper&quot;" in text  # the spec itself, escaped
    # the buckling bounds of the solved design (W 8, n 8, alpha 84; the spec's model 'paper')
    from corrugate import Assembly, Layer, get_material
    from corrugate.buckling import facet_buckling_load

    b = facet_buckling_load(
        Assembly.identical(Layer(8.0, 8, 84.0, get_material("dura-lar"))), 0.0, "paper"
    )
    assert f"buckle at {b.low:.3g}-{b.high:.3g} N" in text


def test_report_opens_in_chromium(report: Path) -> None:
    if not CHROMIUM.exists():
        if os.environ.get("CI", "").strip().lower() in ("true", "1", "yes"):
            pytest.fail(f"{CHROMIUM} not found (required in CI)")
        pytest.skip(f"{CHROMIUM} not found: run `make system-deps` as root")
    from playwright.sync_api import sync_playwright

    errors: list[str] = []
    with sync_playwright() as p:
        browser = p.chromium.launch(
            executable_path=str(CHROMIUM),
            headless=True,
            args=[
                "--no-sandbox",
                "--disable-gpu",
                "--disable-background-networking",
                "--disable-component-update",
                "--no-first-run",
            ],
        )
        try:
            page = browser.new_page(viewport={"width": 1100, "height": 1400})
            page.on("console", lambda m: errors.append(m.text) if m.type == "error" else None)
            page.on("pageerror", lambda e: errors.append(str(e)))
            page.goto(report.as_uri())
            page.wait_for_load_state("load")
            broken = page.evaluate(
                "Array.from(document.images).filter(i => !i.complete || i.naturalWidth === 0)"
                ".length"
            )
            count = page.evaluate("document.images.length")
            ARTIFACTS.mkdir(exist_ok=True)
            page.screenshot(path=str(ARTIFACTS / "report.png"), full_page=True)
        finally:
            browser.close()
    assert count >= 5
    assert broken == 0
    assert errors == []
