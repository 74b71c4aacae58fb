"""Specs and helpers shared by the solver's tests: examples/rectangle_independent.toml on a small
grid with six candidate sheets (tests/solver/test_explain_tree.py, test_joint_checks.py), a
two-sheet continuous spec and designs drawn in pairs of cells (test_cells.py, test_cell_checks.py,
test_polish.py)."""

from __future__ import annotations

from pathlib import Path
from typing import Any

import numpy as np
from numpy.typing import NDArray

from corrugate.solver.points import DesignPoints, LayerPoints

EXAMPLES = Path(__file__).resolve().parents[1] / "examples"


def sheet_choices_spec(tmp: Path) -> Path:
    """examples/rectangle_independent.toml on a small grid (per layer n 4-14, W 4-12 mm, alpha
    50-140 deg step 10) with six candidate sheets (dura-lar 0.05, 0.075, 0.125 mm; mylar 0.023,
    0.05, 0.075 mm: 36 sheet pairs) and nominal tolerances, so that a plain search of each
    relaxed problem goes layer by layer (:mod:`corrugate.solver.separable`), written to ``tmp``."""
    text = (EXAMPLES / "rectangle_independent.toml").read_text("utf-8")
    head, rest = text.split("[variables]", 1)
    grid = (
        '[variables]\nW = { min = "4 mm", max = "12 mm", step = "1 mm" }\n'
        'n = { min = 4, max = 14 }\nalpha = { min = "50 deg", max = "140 deg", step = "10 deg" }\n'
    )
    text = head + grid + rest.split("\n\n", 1)[1]
    sheet = '[material]\nname = "dura-lar"\nthickness = "0.125 mm"\n'
    assert sheet in text
    text = text.replace(
        sheet,
        '[[materials]]\nname = "dura-lar"\nthickness = ["0.05 mm", "0.075 mm", "0.125 mm"]\n\n'
        '[[materials]]\nname = "mylar"\nthickness = ["0.023 mm", "0.05 mm", "0.075 mm"]\n',
    )
    text = text.replace('layers = "independent"\n', 'layers = "independent"\ntolerances = "none"\n')
    path = tmp / "sheet_choices.toml"
    path.write_text(text, "utf-8")
    return path


def continuous_two_sheets(tolerances: bool, wide: bool = False, extra: tuple[str, ...] = ()) -> str:
    """The TOML of two dura-lar sheets (0.075 and 0.125 mm: four sheet pairs), continuous W and
    alpha, independent layers on a rectangle (examples/rectangle_independent.toml's kind, ranges
    narrow enough for the plain per-pair branch and bound to be a quick second method): W 7-11
    mm, n 5-7, alpha 70-100 deg; ``wide``: W 5-12 mm, n 4-9, alpha 50-120 deg, so that the
    sides' and the thickness' upper bounds drop cells without binding. EI bounds in mN*m^2,
    lower under the default tolerances (``tolerances``; else none is met) than nominally;
    ``extra``: more lines of [constraints] (tests/solver/test_cells.py, test_cell_checks.py,
    test_polish.py)."""
    ei0, ei90 = (90, 30) if tolerances else (120, 40)
    W, n, alpha = ((5, 12), (4, 9), (50, 120)) if wide else ((7, 11), (5, 7), (70, 100))
    lines = [
        'name = "cells"',
        'model = "refined"',
        'layers = "independent"',
        *([] if tolerances else ['tolerances = "none"']),
        "[[materials]]",
        'name = "dura-lar"',
        'thickness = ["0.075 mm", "0.125 mm"]',
        "[layout]",
        'shape = "rectangle"',
        "[variables]",
        f'W = {{ min = "{W[0]} mm", max = "{W[1]} mm" }}',
        f"n = {{ min = {n[0]}, max = {n[1]} }}",
        f'alpha = {{ min = "{alpha[0]} deg", max = "{alpha[1]} deg" }}',
        "[constraints]",
        'side_x = { min = "60 mm", max = "80 mm" }',
        'side_y = { min = "40 mm", max = "60 mm" }',
        'thickness = { min = "8 mm", max = "16 mm" }',
        *extra,
        f'flexural_rigidity = [{{ min = "{ei0} mN*m^2", eta = "0 deg" }}, '
        f'{{ min = "{ei90} mN*m^2", eta = "90 deg" }}]',
    ]
    return "\n".join(lines)


def designs_in_cells(
    L1: Any, L2: Any, i: NDArray[np.int64], u: NDArray[np.float64]
) -> DesignPoints:
    """One design in each pair of cells (``L1`` row i, ``L2`` row i; cells of
    :mod:`corrugate.solver.cells`, n and the intervals of W in mm and alpha in deg): W and alpha
    of each layer at the fractions ``u`` (4 x len(i), in [0, 1]) of their intervals."""
    return DesignPoints.of(
        LayerPoints(
            L1.n[i],
            L1.W0[i] + u[0] * (L1.W1[i] - L1.W0[i]),
            L1.a0[i] + u[1] * (L1.a1[i] - L1.a0[i]),
        ),
        LayerPoints(
            L2.n[i],
            L2.W0[i] + u[2] * (L2.W1[i] - L2.W0[i]),
            L2.a0[i] + u[3] * (L2.a1[i] - L2.a0[i]),
        ),
    )
