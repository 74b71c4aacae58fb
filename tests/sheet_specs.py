"""A spec shared by the solver's explanation tests: examples/rectangle_independent.toml on a small
grid with six candidate sheets (tests/solver/test_explain_tree.py, test_joint_checks.py)."""

from __future__ import annotations

from pathlib import Path

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
