"""Tolerance Monte Carlo against closed-form expectations."""

from __future__ import annotations

import json
import math
from pathlib import Path

import pytest
from scipy.stats import norm

from corrugate import Assembly, Layer, get_material
from corrugate.cli import main
from corrugate.solver import Problem, Solution, solve
from corrugate.solver.tolerance import Tolerances, monte_carlo
from corrugate.spec.schema import load_spec
from data_files import PAPER_CASE_STUDY

EXAMPLES = Path(__file__).resolve().parents[2] / "examples"


@pytest.fixture(scope="module")
def case_study() -> tuple[Problem, Solution]:
    problem = Problem.from_spec(load_spec(PAPER_CASE_STUDY))
    return problem, solve(problem, explain=False)


def test_zero_tolerance_reproduces_the_nominal_design(case_study: tuple[Problem, Solution]) -> None:
    problem, sol = case_study
    r = monte_carlo(problem, sol.assembly, Tolerances(0.0, 0.0, 0.0, 0.0), samples=50)
    for s in r.stats:
        assert s.sd == pytest.approx(0.0, abs=1e-9 * max(1.0, abs(s.nominal)))
        assert s.mean == pytest.approx(s.nominal, rel=1e-12)
    assert r.p_all == 1.0


def test_modulus_scatter_gives_the_normal_probability(case_study: tuple[Problem, Solution]) -> None:
    """Every stiffness is proportional to E, so with only E scattered (sd 10 %),
    P(EI >= bound) = P(1 + 0.1 Z >= bound / EI_nominal) for a standard normal Z."""
    problem, sol = case_study
    N = 20_000
    r = monte_carlo(problem, sol.assembly, Tolerances(0.0, 0.0, 0.0, 0.10), samples=N, seed=3)
    ei = next(s for s in r.stats if s.quantity.key == "EI@0")
    expected = norm.sf((80_000 / ei.nominal - 1) / 0.10)
    got = dict(r.probabilities)["constraints.flexural_rigidity[0].min"]
    se = math.sqrt(expected * (1 - expected) / N)
    assert abs(got - expected) < 4 * se
    assert ei.sd / ei.nominal == pytest.approx(0.10, rel=0.05)
    mass = next(s for s in r.stats if s.quantity.key == "mass")
    assert mass.sd == pytest.approx(0.0, abs=1e-12)  # E does not change the mass


def test_tolerance_cli_json(capsys: pytest.CaptureFixture[str]) -> None:
    with pytest.raises(SystemExit) as info:
        main(
            [
                "tolerance",
                str(PAPER_CASE_STUDY),
                "--samples",
                "500",
                "--json",
                "--alpha-tol",
                "1 deg",
                "--E-tol",
                "5%",
            ]
        )
    assert info.value.code in (0, None)
    d = json.loads(capsys.readouterr().out)
    assert d["samples"] == 500
    assert d["tolerances_1sigma"]["E_rel"] == pytest.approx(0.05)
    assert 0.0 <= d["probability_all_met"] <= 1.0
    assert d["design"]["layers"][0]["n"] == 8


def test_tolerance_cli_rejects_bad_percentage(capsys: pytest.CaptureFixture[str]) -> None:
    with pytest.raises(SystemExit) as info:
        main(["tolerance", str(PAPER_CASE_STUDY), "--E-tol", "lots"])
    assert info.value.code == 2
    assert capsys.readouterr().err.startswith("corrugate: error: --E-tol = ")


def test_robust_design_meets_the_spec_with_the_target_probability(
    case_study: tuple[Problem, Solution], capsys: pytest.CaptureFixture[str]
) -> None:
    with pytest.raises(SystemExit) as info:
        main(["design", str(EXAMPLES / "blimp_gripper_robust.toml"), "--json"])
    assert info.value.code in (0, None)
    d = json.loads(capsys.readouterr().out)
    assert d["certified"] is False  # the robust optimum is not proven
    assert d["robust"]["met"] is True
    assert d["robust"]["certified_lightest_robust"] is False
    target = d["robust"]["target_probability"]
    # independent check: a fresh Monte Carlo of the returned design against the original spec
    problem = Problem.from_spec(load_spec(EXAMPLES / "blimp_gripper_robust.toml"))
    layers = d["design"]["layers"]
    mat = get_material(layers[0]["material"])
    a = Assembly(*(Layer(x["W_mm"], x["n"], x["alpha_deg"], mat, x["t_mm"]) for x in layers))
    N = 20_000
    r = monte_carlo(problem, a, Tolerances(0.1, 2.0, 0.05, 0.10), samples=N, seed=12345)
    se = math.sqrt(target * (1 - target) / N)
    assert r.p_all >= target - 4 * se
    # robustness costs mass: no lighter than the nominal optimum of the same spec
    nominal = solve(problem, explain=False)
    assert d["mass_g"] >= nominal.mass


def test_robust_table_is_validated() -> None:
    from corrugate.spec.schema import SpecError, parse_spec

    with pytest.raises(SpecError) as info:
        parse_spec({"material": {"name": "dura-lar"}, "robust": {"probability": 1.5}})
    assert info.value.field == "robust.probability"
    with pytest.raises(SpecError) as info:
        parse_spec({"material": {"name": "dura-lar"}, "robust": {"E": "150%"}})
    assert info.value.field == "robust.E"
