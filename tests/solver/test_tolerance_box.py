"""Certificates that cover the worst-case tolerances (docs/tolerances.md).

The independent source of each check: the point model (``evaluate``) at the 2^6 corners of the
tolerance box (each layer's W and alpha, the sheet's t and E at their limits), which the
interval bound over the box must enclose; the nominal answer of the paper's case study (W 8,
n 9, alpha 78, examples/blimp_gripper.toml's comment, measured before tolerances existed).
"""

from __future__ import annotations

import itertools
from dataclasses import replace
from pathlib import Path

import numpy as np
import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from corrugate.cli import main
from corrugate.solver import Problem, solve
from corrugate.solver.points import DesignPoints, LayerPoints
from corrugate.solver.problem import Candidate
from corrugate.solver.quantities import Tables, point_values
from corrugate.solver.worst_case import NOMINAL, WorstCase
from corrugate.spec.schema import SpecError, load_spec, parse_spec

ROOT = Path(__file__).resolve().parents[2]
ALPHA150 = ROOT / "tests" / "data" / "tolerances_alpha150.toml"

#: A rectangle with independent layers and every directional kind the bound covers: EI, D and K
#: under free sides and in a frame, a three-point deflection (its P / delta and the capacity it
#: brings), a buckling load, the span's length.
_SPEC = {
    "name": "corners",
    "tolerances": {},  # the defaults (opt-in: docs/tolerances.md)
    "layers": "independent",
    "material": {"name": "dura-lar", "thickness": "0.125 mm", "yield_strength": "50 MPa"},
    "layout": {"shape": "rectangle"},
    "variables": {
        "W": {"min": "4 mm", "max": "14 mm"},
        "n": {"min": 6, "max": 14},
        "alpha": {"min": "50 deg", "max": "150 deg"},
    },
    "constraints": {
        "flexural_rigidity": [{"min": "1 mN*m^2", "eta": "0 deg"}],
        "bending_stiffness": [{"min": "1 N*mm", "eta": "90 deg", "support": "frame"}],
        "inplane_stiffness": [{"min": "1 N/mm", "eta": "30 deg"}],
        "buckling_load": [{"min": "0.1 N", "eta": "90 deg"}],
        "deflection": [
            {"test": "three-point", "load": "0.1 N", "max": "5 mm", "eta": "0 deg", "span": "40 mm"}
        ],
    },
}


def _corners(
    problem: Problem,
    c: Candidate,
    W: tuple[float, float],
    n: tuple[int, int],
    a: tuple[float, float],
) -> DesignPoints:
    """The 64 corners of the tolerance box of the design (W, n, alpha per layer), as points of
    the point model with the sheet's E and t per point."""
    tol = problem.tolerances
    rows = list(itertools.product(*[(-1.0, 1.0)] * 6))
    s = np.array(rows).T
    E = c.material.E * (1 + s[5] * tol.E)
    t = c.t * (1 + s[4] * tol.t)
    layers = [
        LayerPoints(
            np.full(len(rows), float(n[i])),
            W[i] + s[2 * i] * tol.W,
            a[i] + s[2 * i + 1] * tol.alpha,
            E,
            t,
        )
        for i in range(2)
    ]
    return DesignPoints.of(*layers)


@settings(max_examples=25, deadline=None, suppress_health_check=[HealthCheck.too_slow])
@given(
    W1=st.floats(4.0, 14.0),
    W2=st.floats(4.0, 14.0),
    n1=st.integers(6, 14),
    n2=st.integers(6, 14),
    a1=st.floats(50.0, 150.0),
    a2=st.floats(50.0, 150.0),
)
def test_the_bound_over_the_tolerance_box_encloses_every_corner(
    W1: float, W2: float, n1: int, n2: int, a1: float, a2: float
) -> None:
    """Each directional quantity's certified value (its bound over the tolerance box) is at or
    below its point value at every corner of the box: the worst part is covered."""
    problem = Problem.from_spec(parse_spec(_SPEC))
    assert problem.tolerances == WorstCase(3.0, 0.1, 0.05, 0.10)  # the defaults
    c = problem.candidates[0]
    tables = Tables(problem)
    x = DesignPoints.of(
        LayerPoints(np.array([float(n1)]), np.array([W1]), np.array([a1])),
        LayerPoints(np.array([float(n2)]), np.array([W2]), np.array([a2])),
    )
    certified = point_values(problem, c, c, x, tables)
    nominal = replace(problem, tolerances=NOMINAL)
    corners = point_values(
        nominal, c, c, _corners(problem, c, (W1, W2), (n1, n2), (a1, a2)), tables
    )
    at_x = point_values(nominal, c, c, x, tables)
    directional = [q for q in problem.quantities if q.eta is not None]
    assert {q.kind for q in directional} >= {"EI", "D", "K", "Pb", "k", "Pmax", "length"}
    for q in directional:
        worst = float(np.min(corners[q]))
        assert certified[q][0] <= worst * (1 + 1e-12), q.key
        assert certified[q][0] <= at_x[q][0] * (1 + 1e-12), q.key
    # the sizes and mass stay nominal (docs/tolerances.md)
    for q in problem.quantities:
        if q.eta is None:
            assert certified[q][0] == at_x[q][0], q.key


@pytest.mark.slow
def test_the_certified_optimum_meets_every_bound_at_every_corner() -> None:
    """The alpha-150 spec of docs/tolerances.md: its answer with the default tolerances meets
    each behavioural bound at all 64 corners (point model), while the nominal answer of the
    same spec misses one at some corner: the tolerances change the answer for a reason."""
    problem = Problem.from_spec(load_spec(ALPHA150))
    sol = solve(problem, explain=False)
    assert sol.status == "optimal" and sol.certified
    a = sol.assembly
    assert a is not None and a.layers[0].alpha_deg >= 145  # near 150 deg
    assert "for every part within +-3 deg, +-0.1 mm, +-5 % thickness, +-10 % E" in (sol.certificate)
    c = problem.candidates[0]
    nominal = replace(problem, tolerances=NOMINAL)
    tables = Tables(problem)

    def corner_values(asm: object) -> dict[object, np.ndarray]:
        l1, l2 = asm.layers  # type: ignore[attr-defined]
        x = _corners(problem, c, (l1.W, l2.W), (l1.n, l2.n), (l1.alpha_deg, l2.alpha_deg))
        return point_values(nominal, c, c, x, tables)

    behavioural = [k for k in problem.constraints if k.quantity.eta is not None]
    assert behavioural
    vals = corner_values(a)
    for k in behavioural:
        assert bool(np.all(k.satisfied(vals[k.quantity]))), k.name
    plain = solve(nominal, explain=False)
    assert plain.assembly is not None and plain.mass is not None and sol.mass is not None
    assert plain.mass < sol.mass  # the tolerances cost mass
    vals = corner_values(plain.assembly)
    assert not all(bool(np.all(k.satisfied(vals[k.quantity]))) for k in behavioural)


def test_none_is_the_nominal_certificate_of_the_case_study() -> None:
    """``tolerances = "none"``: the case study's nominal answer (W 8, n 9, alpha 78, 2.16 g under
    the refined model, examples/blimp_gripper.toml) and a certificate without tolerance words."""
    spec = load_spec(ROOT / "examples" / "blimp_gripper.toml")
    assert spec.tolerances.nominal
    problem = Problem.from_spec(spec)
    assert problem.tolerances == NOMINAL
    sol = solve(problem, explain=False)
    layer = sol.assembly.layers[0]  # type: ignore[union-attr]
    assert (layer.W, layer.n, layer.alpha_deg) == (8.0, 9, 78.0)
    assert sol.mass == pytest.approx(2.16, abs=0.005)
    assert "within" not in sol.certificate
    assert sol.to_dict()["tolerances"] == {**NOMINAL.as_dict()}


def test_a_robust_spec_without_a_tolerances_table_is_nominal() -> None:
    """[robust] is the probabilistic alternative: without its own [tolerances] the worst-case
    defaults do not apply on top of it; with one they do."""
    base = {"material": {"name": "dura-lar", "thickness": "0.125 mm"}, "robust": {}}
    assert Problem.from_spec(parse_spec(base)).tolerances.nominal
    both = {**base, "tolerances": {"alpha": "2 deg"}}
    assert Problem.from_spec(parse_spec(both)).tolerances == WorstCase(2.0, 0.1, 0.05, 0.10)


@pytest.mark.parametrize(
    ("value", "field"),
    [
        ({"alpha": "-1 deg"}, "tolerances.alpha"),
        ({"alpha": "nan"}, "tolerances.alpha"),
        ({"W": "2 N"}, "tolerances.W"),
        ({"t": 1.5}, "tolerances.t"),
        ({"E": -0.1}, "tolerances.E"),
        ({"fold": "3 deg"}, "tolerances.fold"),
        ("some", "tolerances"),
        (3, "tolerances"),
    ],
)
def test_bad_tolerances_name_the_field(value: object, field: str) -> None:
    with pytest.raises(SpecError) as info:
        parse_spec({"material": {"name": "dura-lar"}, "tolerances": value})
    assert info.value.field == field
    assert "\n" not in str(info.value)


def test_bad_tolerances_on_the_command_line_exit_2(
    tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    spec = tmp_path / "bad.toml"
    spec.write_text('[material]\nname = "dura-lar"\n[tolerances]\nalpha = "40 deg"\n')
    with pytest.raises(SystemExit) as info:
        main(["design", str(spec), "--json"])
    assert info.value.code == 2
    err = capsys.readouterr().err.strip()
    assert "tolerances.alpha" in err and "<= 30 deg" in err and "Traceback" not in err
