"""report.html: self-contained, every figure present, every constraint reported; opens cleanly in
Chromium (no missing image, no console error)."""

from __future__ import annotations

import base64
import os
import re
import tomllib
import xml.etree.ElementTree as ET
from html import escape
from html.parser import HTMLParser
from pathlib import Path

import pytest

from corrugate.report import report_html
from corrugate.solver import Problem, Solution, solve
from corrugate.spec.schema import load_spec, parse_spec
from data_files import PAPER_CASE_STUDY
from plan_readers import Tables, sheet_rows, svg_parts

ROOT = Path(__file__).resolve().parents[2]
# the case study under the paper's printed model: its answer is the paper's case 1 (W 8, n 8, alpha 84)
BLIMP = PAPER_CASE_STUDY
CHROMIUM = Path("/usr/bin/chromium")
ARTIFACTS = ROOT / "test-artifacts"


@pytest.mark.slow
def test_report_draws_the_sheet_plan_the_files_are_written_from(
    solution: Solution, tmp_path: Path
) -> None:
    """Non-default cutter, fold style and tab depth: the report beside the files shows their sheets
    (the same parts at the same places, the fold maps themselves), not a plan rebuilt with
    defaults."""
    from corrugate.export.machines import get_machine
    from corrugate.export.plan import CutPlan, OutputOptions
    from corrugate.fabrication.linestyle import line_style
    from corrugate.geometry.fabrication_options import FabricationOptions
    from corrugate.workflow import write_design_files

    assert solution.analysis is not None
    spec_text = BLIMP.read_text()
    options = OutputOptions(
        machine=get_machine("laser:130x80"),
        style=line_style("perforated", cut=1.5, gap=1.0),
        fabrication=FabricationOptions(tab_depth=7.0),
    )
    seen: list[CutPlan] = []

    def make_report(cut: CutPlan) -> str:
        seen.append(cut)
        return report_html(solution, spec_text, cut)

    out = tmp_path / "out"
    write_design_files(solution.analysis, out, options, report=make_report)
    (cut,) = seen
    text = (out / "report.html").read_text(encoding="utf-8")
    in_files, sizes = svg_parts(out)
    assert len(sizes) == len(cut.plan.sheets) > 1
    assert all(size == pytest.approx((130.0, 80.0)) for size in sizes)
    rows = sheet_rows(text)
    assert sorted((r[0], r[1]) for r in rows) == [(s, n) for s, n, _, _ in in_files]
    for (s, n, x, y), (s2, n2, x2, y2) in zip(sorted(rows), in_files, strict=True):
        assert (s, n) == (s2, n2)
        assert x == pytest.approx(x2, abs=0.01) and y == pytest.approx(y2, abs=0.01)
    # the report's sheet figures are the fold maps written beside it, at the sheet's proportions
    parsed = Tables()
    parsed.feed(text)
    figures = [src for alt, src in parsed.images if alt.startswith("sheet ")]
    assert len(figures) == len(cut.plan.sheets)
    for k, src in enumerate(figures, start=1):
        assert src.startswith("data:image/svg+xml;base64,")
        svg = base64.b64decode(src.split(",", 1)[1])
        assert svg == (out / f"sheet-{k}.svg").read_bytes()
        width, height = (float(v) for v in ET.fromstring(svg).attrib["data-sheet-mm"].split())
        assert width / height == pytest.approx(130.0 / 80.0, rel=0.01)
    assert "perforated (1.5 mm cut, 1 mm gap)" in text
    # a report made with the default options would show another plan than these files
    default_rows = sheet_rows(report_html(solution, spec_text))
    assert sorted((r[0], r[1], round(r[2], 2), round(r[3], 2)) for r in default_rows) != sorted(
        (s, n, round(x, 2), round(y, 2)) for s, n, x, y in in_files
    )


@pytest.mark.slow
def test_each_figure_is_drawn_once(
    solution: Solution, tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    """The report beside the files shows the figures the files step drew: each sheet figure (of
    ``pattern.pdf``) and the assembly figure is built once, ``assembly.png`` is embedded byte for
    byte, and pyplot is never used (figures on their own canvases, so threads can draw in
    parallel)."""
    import sys

    from corrugate import workflow
    from corrugate.export import pdf
    from corrugate.export.machines import get_machine
    from corrugate.export.plan import OutputOptions
    from corrugate.fabrication import instructions

    assert solution.analysis is not None
    calls = {"sheet": 0, "assembly": 0}
    sheet_figure, instructions_figure = pdf.sheet_figure, instructions.instructions_figure

    def count_sheet(*args: object, **kwargs: object) -> object:
        calls["sheet"] += 1
        return sheet_figure(*args, **kwargs)  # type: ignore[arg-type]

    def count_assembly(*args: object, **kwargs: object) -> object:
        calls["assembly"] += 1
        return instructions_figure(*args, **kwargs)  # type: ignore[arg-type]

    monkeypatch.setattr(pdf, "sheet_figure", count_sheet)
    monkeypatch.setattr(instructions, "instructions_figure", count_assembly)
    spec_text = BLIMP.read_text()
    out = tmp_path / "out"
    options = OutputOptions(machine=get_machine("laser:130x80"))
    workflow.write_design_files(
        solution.analysis, out, options, report=lambda cut: report_html(solution, spec_text, cut)
    )
    sheets = len(list(out.glob("sheet-*.svg")))
    assert sheets > 1
    assert calls == {"sheet": sheets, "assembly": 1}
    parsed = Tables()
    parsed.feed((out / "report.html").read_text(encoding="utf-8"))
    (folded,) = [src for alt, src in parsed.images if alt.startswith("the folded assembly")]
    assert base64.b64decode(folded.split(",", 1)[1]) == (out / "assembly.png").read_bytes()
    assert "matplotlib.pyplot" not in sys.modules or not any(
        getattr(sys.modules["matplotlib.pyplot"], "get_fignums", list)()
    )


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
def solution() -> Solution:
    return solve(Problem.from_spec(load_spec(BLIMP)))


@pytest.fixture(scope="module")
def report(solution: Solution, tmp_path_factory: pytest.TempPathFactory) -> Path:
    path = tmp_path_factory.mktemp("report") / "report.html"
    path.write_text(report_html(solution, BLIMP.read_text()), encoding="utf-8")
    return path


@pytest.mark.slow
def test_report_is_self_contained_and_complete(report: Path) -> None:
    text = report.read_text(encoding="utf-8")
    parsed = _Collect()
    parsed.feed(text)
    assert parsed.scripts == 0
    assert parsed.links == []  # nothing fetched from anywhere
    assert len(parsed.images) >= 5  # design space, mass by n, polar, sheet(s), folded part
    for img in parsed.images:
        src = str(img["src"])
        data = base64.b64decode(src.split(",", 1)[1])
        if img.get("alt") == "the folded assembly, step by step":  # assembly.png
            assert src.startswith("data:image/png;base64,")
            assert data[:8] == b"\x89PNG\r\n\x1a\n"
        else:
            # the fold map sheet-N.svg, the directions (corrugate.report.orientation), the plots
            assert src.startswith("data:image/svg+xml;base64,")
            assert ET.fromstring(data).tag == "{http://www.w3.org/2000/svg}svg"
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
        "Directions",
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
    from corrugate.analysis.evaluate import facet_buckling_load

    b = facet_buckling_load(
        Assembly.identical(Layer(8.0, 8, 84.0, get_material("dura-lar"))), 0.0, "paper"
    )
    assert f"buckle at {b.low:.3g}-{b.high:.3g} N" in text


@pytest.mark.browser
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


#: For each table cell but the first of its row: the number of lines its text is drawn on.
_CELL_LINES = """() => Array.from(document.querySelectorAll('td:not(:first-child)')).map(td => {
  const range = document.createRange(); range.selectNodeContents(td);
  return [td.textContent, new Set(Array.from(range.getClientRects(), r => Math.round(r.top))).size];
})"""


@pytest.mark.browser
def test_report_fits_a_phone_and_keeps_each_value_on_one_line(report: Path) -> None:
    """report.html in Chromium as a 390 px wide phone (a mobile viewport, which lays a page
    without a viewport declaration out 980 px wide and shrinks it) and a 1280 px wide window:
    the page never scrolls sideways (a table wider than the screen scrolls in its own box) and
    no value cell is broken over lines (the case study's bounds printed "<=" over "250")."""
    if not CHROMIUM.exists():
        pytest.skip(f"{CHROMIUM} not found: run `make system-deps` as root")
    from playwright.sync_api import sync_playwright

    with sync_playwright() as p:
        browser = p.chromium.launch(
            executable_path=str(CHROMIUM), headless=True, args=["--no-sandbox", "--disable-gpu"]
        )
        try:
            phone = browser.new_page(
                viewport={"width": 390, "height": 844}, is_mobile=True, device_scale_factor=2
            )
            phone.goto(report.as_uri())
            phone_width = phone.evaluate(
                "[document.documentElement.scrollWidth, window.innerWidth]"
            )
            phone_cells = phone.evaluate(_CELL_LINES)
            wide = browser.new_page(viewport={"width": 1280, "height": 1000})
            wide.goto(report.as_uri())
            wide_cells = wide.evaluate(_CELL_LINES)
        finally:
            browser.close()
    assert phone_width == [390, 390]
    for cells in (phone_cells, wide_cells):
        assert any("<= 250" in text for text, _ in cells)  # the bounds are read
        assert [(text, lines) for text, lines in cells if lines > 1] == []


@pytest.mark.slow
def test_a_load_case_has_its_figure_and_its_deflection(tmp_path: Path) -> None:
    """A spec with a deflection bound (examples/chassis_plate.toml) gets a 'Load cases' section
    with one figure, titled with the certified deflection under the load, and the report's
    constraint table shows the deflection (mm), not P / delta, and says what the part holds;
    a spec without one has none."""
    spec = ROOT / "examples" / "chassis_plate.toml"
    # its nominal form (the example's comment: the band's walls fail first); the report's
    # load-case section is the point, not the tolerances
    d = tomllib.loads(spec.read_text())
    d["tolerances"] = "none"
    sol = solve(Problem.from_spec(parse_spec(d)))
    text = report_html(sol, spec.read_text())
    parsed = _Collect()
    parsed.feed(text)
    assert "Load cases" in parsed.headings
    [c] = [c for c in sol.constraints if c.load is not None]
    assert c.unit == "mm" and c.value <= c.bound == pytest.approx(1.0)
    assert "constraints.deflection[0].max" in text
    # what it holds and its first failure (docs/load_cases.md 10): the least of the modes the
    # answer lists, over the safety factor, in the answer's words
    assert c.capacity is not None
    assert c.capacity.load == pytest.approx(min(c.capacity.modes.values()) / 2.0)
    assert escape(f"(three-point, 10 N): {c.capacity.sentence}.") in text
    # the band's walls (docs/load_cases.md 10.5) fail first on this design
    assert escape("(first failure: buckling of the connector band's walls at mid-span)") in text
    blimp = report_html(solve(Problem.from_spec(load_spec(BLIMP))), BLIMP.read_text())
    assert "<h2>Load cases</h2>" not in blimp


@pytest.mark.slow
def test_report_plots_are_vector_with_their_labels_as_text(report: Path) -> None:
    """The plots are SVG whose axis labels and titles are text a reader can search and copy
    (``svg.fonttype`` none), not glyphs drawn as paths or pixels, and they carry no date: the
    same design gives the same report (issue 39)."""
    parsed = _Collect()
    parsed.feed(report.read_text(encoding="utf-8"))
    plots = {
        str(img["alt"]): base64.b64decode(str(img["src"]).split(",", 1)[1]).decode("utf-8")
        for img in parsed.images
        if str(img.get("alt")).startswith(("design space", "lightest mass", "polar"))
    }
    assert len(plots) == 3
    ns = "{http://www.w3.org/2000/svg}"
    texts = {
        alt: {"".join(t.itertext()).strip() for t in ET.fromstring(svg).iter(f"{ns}text")}
        for alt, svg in plots.items()
    }
    assert "facet width W (mm)" in texts["design space map: W against alpha"]
    assert "fold angle alpha (deg)" in texts["design space map: W against alpha"]
    assert any(t.startswith("in-plane K(eta)") for t in texts["polar plots of K and D"])
    for svg in plots.values():
        assert "<dc:date>" not in svg
        assert "<image" not in svg  # nothing rasterised inside


class _Key(HTMLParser):
    """The entries (colour, text) of the report's figure keys (``<ul class="key">``)."""

    def __init__(self) -> None:
        super().__init__()
        self.entries: list[tuple[str, str]] = []
        self._in: int = 0

    def handle_starttag(self, tag: str, attrs: list[tuple[str, str | None]]) -> None:
        a = dict(attrs)
        if tag == "ul" and a.get("class") == "key":
            self._in = 1
        elif self._in and tag == "li":
            self.entries.append(("", ""))
        elif self._in and tag == "span" and a.get("class") == "mark":
            style = str(a.get("style"))
            self.entries[-1] = (style.removeprefix("color:"), self.entries[-1][1])

    def handle_endtag(self, tag: str) -> None:
        if tag == "ul":
            self._in = 0

    def handle_data(self, data: str) -> None:
        if (
            self._in
            and self.entries
            and data.strip()
            and not data.strip().startswith(("━", "╍", "★", "■"))
        ):
            colour, text = self.entries[-1]
            self.entries[-1] = (colour, text + data.strip())


@pytest.mark.slow
def test_design_space_key_is_text_naming_each_curve_in_its_colour(
    report: Path, solution: Solution
) -> None:
    """The design-space figure's key is printed under it as text, not drawn into it: every
    binding constraint (its boundary passes through the optimum, so it crosses the plotted
    plane) is in the key, each constraint entry's colour is the stroke of a curve in the figure,
    and the figure itself holds no legend (its texts are the curve labels, axes and title)."""
    text = report.read_text(encoding="utf-8")
    key = _Key()
    key.feed(text)
    names = [t.split(" (", 1)[0] for _, t in key.entries]
    binding = [c.name for c in solution.constraints if c.binding]
    assert binding and set(binding) <= set(names)
    assert names[-2].startswith("optimum: W ") and names[-1] == "feasible"
    parsed = _Collect()
    parsed.feed(text)
    (src,) = [
        str(i["src"]) for i in parsed.images if i.get("alt") == "design space map: W against alpha"
    ]
    svg = base64.b64decode(src.split(",", 1)[1]).decode("utf-8")
    for colour, entry in key.entries[:-2]:
        assert f"stroke: {colour}" in svg, entry
    texts = {
        "".join(t.itertext()) for t in ET.fromstring(svg).iter("{http://www.w3.org/2000/svg}text")
    }
    assert not any(t.startswith("optimum: W ") or t == "feasible" for t in texts)


@pytest.mark.slow
def test_warnings_show_commands_as_code_not_backticks(report: Path, solution: Solution) -> None:
    """A warning's text names commands and spec keys between backticks, the command line's way
    (``corrugate docs fea``); the report printed the backticks as they are. Each backtick span is
    now a ``<code>`` element, and no backtick is left in the warnings' text."""
    text = report.read_text(encoding="utf-8")
    section = text.split("<h2>Warnings</h2>", 1)[1].split("<h2>", 1)[0]
    items = re.findall(r"<li class='warn'>(.*?)</li>", section)
    messages = [w["message"] for w in solution.warnings]
    assert len(items) == len(messages) >= 1
    quoted = [m for m in messages if "`" in m]
    assert quoted  # the case study's shear warning names `corrugate docs fea`
    for item, message in zip(items, messages, strict=True):
        assert "`" not in item
        for span in re.findall(r"`([^`]+)`", message):
            assert f"<code>{escape(span, quote=False)}</code>" in item
