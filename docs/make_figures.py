"""Regenerate the figures under docs/img from the paper's case study (run by hand):

    .venv/bin/python docs/make_figures.py

They are the report's own figures (corrugate.report) and the fabrication figures of the paper's
case 1 (W 8, n 8, alpha 84: tests/data/paper_case_study.toml, the case study under the paper's
printed model), so docs/design.md shows exactly what `corrugate design
tests/data/paper_case_study.toml --out DIR` produces.
"""

from __future__ import annotations

from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt

from corrugate.export.pdf import sheet_figure
from corrugate.fabrication.build import build_pattern
from corrugate.fabrication.instructions import instructions_figure
from corrugate.fabrication.sheets import plan_sheets
from corrugate.report import design_space_figure, mass_by_n_figure, polar_figure
from corrugate.solver import Problem, solve
from corrugate.spec.schema import load_spec

ROOT = Path(__file__).resolve().parents[1]
IMG = ROOT / "docs" / "img"


def main() -> None:
    IMG.mkdir(parents=True, exist_ok=True)
    sol = solve(Problem.from_spec(load_spec(ROOT / "tests" / "data" / "paper_case_study.toml")))
    assert sol.analysis is not None
    a = sol.analysis
    pattern = build_pattern(a.assembly)
    figures = {
        "design_space.png": design_space_figure(sol.problem, a),
        "mass_by_n.png": mass_by_n_figure(sol.problem, a),
        "polar.png": polar_figure(a),
        "case1_sheet.png": sheet_figure(plan_sheets(pattern, "cameo4-12x12"), 1),
        "case1_assembly.png": instructions_figure(a.assembly, pattern),
    }
    for name, fig in figures.items():
        fig.savefig(IMG / name, dpi=80 if name == "case1_sheet.png" else 90)
        plt.close(fig)
        print(f"wrote {IMG / name}")


if __name__ == "__main__":
    main()
