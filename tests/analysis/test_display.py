"""Short reprs and notebook HTML: what they show is the result's own numbers, in five lines."""

from __future__ import annotations

import tomllib
from html.parser import HTMLParser

from corrugate import Assembly, Layer, analyze, get_material
from corrugate.solver import solve
from corrugate.solver.problem import Problem
from corrugate.spec.examples import example_text
from corrugate.spec.schema import parse_spec
from data_files import PAPER_CASE_STUDY


class _Cells(HTMLParser):
    def __init__(self) -> None:
        super().__init__()
        self.cells: list[str] = []
        self._in = False

    def handle_starttag(self, tag: str, attrs: object) -> None:
        self._in = tag in ("td", "th")

    def handle_data(self, data: str) -> None:
        if self._in:
            self.cells.append(data)
            self._in = False


def case_study() -> Layer:
    return Layer(W=8, n=8, alpha_deg=84, material=get_material("dura-lar"))


def test_analysis_repr_is_short_and_holds_the_numbers() -> None:
    a = analyze(Assembly.identical(case_study()), model="paper", eta_deg=[0, 90, 45])
    text = repr(a)
    assert len(text.splitlines()) <= 5
    assert "W 8 mm, n 8, alpha 84 deg, dura-lar 0.125 mm" in text
    assert f"K {a.stiffness[0].K:.4g} N/mm" in text and "1 more" in text
    assert "Grafix" not in text  # no material source text


def test_analysis_html_table_has_one_row_per_direction() -> None:
    a = analyze(Assembly.identical(case_study()), eta_deg=[0, 30, 90])
    p = _Cells()
    p.feed(a._repr_html_())
    assert p.cells[:4] == ["eta (deg)", "K (N/mm)", "D (N mm)", "EI (N mm^2)"]
    assert p.cells[4:8] == [
        "0",
        f"{a.stiffness[0].K:.4g}",
        f"{a.stiffness[0].D:.4g}",
        f"{a.stiffness[0].EI:.4g}",
    ]
    assert len(p.cells) == 4 * 4


def test_solution_repr_fits_five_lines_and_names_the_binding_constraints() -> None:
    spec = parse_spec(tomllib.loads(PAPER_CASE_STUDY.read_text("utf-8")))
    s = solve(Problem.from_spec(spec))
    text = repr(s)
    assert len(text.splitlines()) <= 5
    assert text.startswith("Solution(optimal, certified=True")
    assert "W 8 mm, n 8, alpha 84 deg" in text  # the paper's case 1
    binding = [c.name for c in s.constraints if c.binding or c.active]
    assert binding and all(name in text for name in binding)
    html = s._repr_html_()
    assert html.count("<tr>") == 1 + len(s.constraints)


def test_infeasible_solution_repr_says_why() -> None:
    spec = parse_spec(tomllib.loads(example_text("infeasible")))
    s = solve(Problem.from_spec(spec))
    text = repr(s)
    assert s.analysis is None and len(text.splitlines()) <= 5
    assert s.status in text and (not s.diagnosis or s.diagnosis[0].message in text)
