"""An answer solved under a model other than the refined one says whether it meets its bounds
under the refined model (the one that agrees with FE): the shipped case study, which reproduces
the paper with its formulas as printed (tests/data/paper_case_study.toml), fails EI(0) >= 80
mN m^2 there, and the shipped example (examples/blimp_gripper.toml, the same spec under the
default model) is solved under refined itself."""

from __future__ import annotations

import re
from pathlib import Path

import pytest

from corrugate import analyze
from corrugate.solver import Problem, solve
from corrugate.spec.schema import load_spec, parse_spec
from data_files import PAPER_CASE_STUDY

EXAMPLES = Path(__file__).resolve().parents[2] / "examples"


def _warning(sol: object, code: str) -> str | None:
    for w in sol.warnings:  # type: ignore[attr-defined]
        if w["code"] == code:
            return str(w["message"])
    return None


def test_the_case_study_says_it_fails_under_the_refined_model() -> None:
    """Second method: the warning's EI is analyze()'s EI of the same design under refined
    (71.6 mN m^2 for the paper's W 8, n 8, alpha 84), below the 80 mN m^2 bound."""
    sol = solve(Problem.from_spec(load_spec(PAPER_CASE_STUDY)))
    assert sol.assembly is not None
    layer = sol.assembly.layer1
    assert (layer.W, layer.n, layer.alpha_deg) == (8.0, 8, 84.0)  # the paper's answer
    message = _warning(sol, "fails-under-refined")
    assert message is not None and _warning(sol, "holds-under-refined") is None
    assert "constraints.flexural_rigidity[0].min" in message
    EI = analyze(sol.assembly, "refined", [0.0]).stiffness[0].EI
    assert EI < 80_000.0  # N mm^2: 71.6 mN m^2
    shown = float(re.search(r"EI\(0 deg\) = ([0-9.e+]+) N\*mm\^2 < 80000", message)[1])  # type: ignore[index]
    assert shown == pytest.approx(EI, rel=1e-4)


def test_the_shipped_case_study_is_solved_under_refined_and_meets_the_bound() -> None:
    sol = solve(Problem.from_spec(load_spec(EXAMPLES / "blimp_gripper.toml")))
    assert sol.problem.model == "refined"
    assert _warning(sol, "fails-under-refined") is None
    assert _warning(sol, "holds-under-refined") is None
    assert sol.assembly is not None
    assert analyze(sol.assembly, "refined", [0.0]).stiffness[0].EI >= 80_000.0


def test_an_answer_that_also_holds_under_refined_says_so() -> None:
    """A bound low enough for both models: the paper-model answer meets it under refined too."""
    d = {
        "name": "both",
        "model": "paper",
        "material": {"name": "dura-lar", "thickness": "0.125 mm"},
        "variables": {
            "W": {"min": "6 mm", "max": "12 mm", "step": "1 mm"},
            "n": {"min": 6, "max": 12},
            "alpha": {"min": "60 deg", "max": "110 deg", "step": "5 deg"},
        },
        "constraints": {
            "side": {"min": "40 mm", "max": "60 mm"},
            "flexural_rigidity": [{"min": "20 mN*m^2", "eta": "0 deg"}],
        },
    }
    sol = solve(Problem.from_spec(parse_spec(d)))
    assert sol.assembly is not None
    assert analyze(sol.assembly, "refined", [0.0]).stiffness[0].EI >= 20_000.0
    assert _warning(sol, "holds-under-refined") is not None
    assert _warning(sol, "fails-under-refined") is None
