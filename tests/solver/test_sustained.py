"""Quantities under a sustained load (``corrugate.solver.sustained``): the creep modulus in
place of E, checked against a second method, the model evaluated with E replaced (an inline
sheet of modulus E_c(t)), and against the linearity in E of docs/load_cases.md section 11."""

from __future__ import annotations

import copy
from dataclasses import replace
from typing import Any

import numpy as np
import pytest

from corrugate.materials.library import get_material
from corrugate.solver import Problem, solve
from corrugate.solver.context import AtPoints
from corrugate.solver.points import DesignPoints, LayerPoints
from corrugate.solver.quantities import box_bounds, point_values
from corrugate.solver.quantity import Quantity
from corrugate.solver.tables import Tables
from corrugate.spec.schema import parse_spec

WEEK = 168.0
SPEC: dict[str, Any] = {
    "name": "held",
    "tolerances": "none",  # the nominal model (tolerances: tests/solver/test_tolerance_box.py)
    "joint": "band-edges",  # free outermost facets cannot hold 10 N at the safety factor
    "material": {"name": "polycarbonate", "thickness": "0.25 mm"},
    "layout": {"shape": "square"},
    "variables": {
        "W": {"min": "4 mm", "max": "20 mm", "step": "1 mm"},
        "n": {"min": 2, "max": 40},
        "alpha": {"min": "30 deg", "max": "150 deg", "step": "5 deg"},
    },
    "constraints": {
        "side": {"min": "100 mm", "max": "120 mm"},
        "deflection": [{"test": "three-point", "load": "10 N", "max": "1 mm", "span": "100 mm"}],
        "flexural_rigidity": [{"min": "1 mN*m^2", "eta": "90 deg"}],
        "inplane_stiffness": [{"min": "1 N/mm", "eta": "0 deg"}],
        "buckling_load": [{"min": "0.1 N", "eta": "0 deg"}],
    },
}


def spec(duration: str | None, material: dict[str, Any] | None = None) -> dict[str, Any]:
    """SPEC with every bound's load held ``duration`` (None: short-term)."""
    d = copy.deepcopy(SPEC)
    if material is not None:
        d["material"] = material
    if duration is not None:
        for key in ("deflection", "flexural_rigidity", "inplane_stiffness", "buckling_load"):
            for b in d["constraints"][key]:
                b["duration"] = duration
    return d


def spec_without_duration(d: dict[str, Any]) -> dict[str, Any]:
    out = copy.deepcopy(d)
    for b in out["constraints"]["deflection"]:
        b.pop("duration", None)
    return out


def points(k: int = 25, seed: int = 1) -> DesignPoints:
    rng = np.random.default_rng(seed)
    n = rng.integers(2, 40, k).astype(float)
    W = rng.uniform(4, 20, k)
    alpha = rng.uniform(30, 150, k)
    return DesignPoints.of(LayerPoints(n, W, alpha))


def values(problem: Problem, x: DesignPoints) -> dict[Quantity, np.ndarray]:
    (c,) = problem.candidates
    return point_values(problem, c, c, x, Tables(problem))


def test_keys_gain_the_duration_and_short_term_keys_stay() -> None:
    held = Problem.from_spec(parse_spec(spec("1 week")))
    short = Problem.from_spec(parse_spec(spec(None)))
    assert [c.quantity.key for c in short.constraints if c.quantity.directional] == [
        "EI@90",
        "K@0",
        "length@0",
        "k3pt@0/L=100",
        "Pmax3pt@0/L=100",  # the deflection's load held at the safety factor
        "Pb@0",
    ]
    assert [c.quantity.key for c in held.constraints if c.quantity.directional] == [
        "EI@90/t=168h",
        "K@0/t=168h",
        "length@0",
        "k3pt@0/L=100/t=168h",
        "Pmax3pt@0/L=100/t=168h",  # held as long: its buckling at the creep modulus
        "Pb@0/t=168h",
    ]
    for c in held.constraints:
        assert Quantity.parse(c.quantity.key) == c.quantity


def test_a_sustained_quantity_is_the_model_with_e_replaced() -> None:
    """Second method: the short-term problem on an inline sheet whose E is E_c(1 week) (the same
    nu and density), and the linearity in E: r(t) = E_c / E times the short-term value."""
    pc = get_material("polycarbonate")
    Ec = pc.creep_modulus(WEEK)
    r = Ec / pc.E
    inline = {
        "name": "pc-at-one-week",
        "E": f"{Ec!r} MPa",
        "nu": pc.nu,
        "density": f"{pc.density_g_cm3!r} g/cm^3",
        "yield_strength": f"{pc.yield_strength!r} MPa",
        "thickness": "0.25 mm",
    }
    held = Problem.from_spec(parse_spec(spec("1 week")))
    short = Problem.from_spec(parse_spec(spec(None)))
    replaced = Problem.from_spec(parse_spec(spec(None, inline)))
    x = points()
    vh, vs, vr = values(held, x), values(short, x), values(replaced, x)
    for c_held, c_short in zip(held.constraints, short.constraints, strict=True):
        q, q0 = c_held.quantity, c_short.quantity
        if q.duration is None:
            continue
        assert q == replace(q0, duration=WEEK)
        np.testing.assert_allclose(vh[q], vr[q0], rtol=1e-12)  # E replaced
        if q.kind != "Pmax":  # a capacity's yield mode is a stress: not linear in E
            np.testing.assert_allclose(vh[q], r * vs[q0], rtol=1e-9)  # linear in E


def test_box_bounds_of_a_sustained_quantity_hold_every_point_inside() -> None:
    held = Problem.from_spec(parse_spec(spec("1 week")))
    (c,) = held.candidates
    tables = Tables(held)
    lo = DesignPoints.of(LayerPoints(np.array([5.0]), np.array([8.0]), np.array([60.0])))
    hi = DesignPoints.of(LayerPoints(np.array([9.0]), np.array([12.0]), np.array([100.0])))
    asked = {con.quantity for con in held.constraints if con.quantity.duration is not None}
    bounds = box_bounds(held, c, c, lo, hi, tables, asked)
    rng = np.random.default_rng(3)
    k = 200
    inside = DesignPoints.of(
        LayerPoints(
            rng.integers(5, 10, k).astype(float), rng.uniform(8, 12, k), rng.uniform(60, 100, k)
        )
    )
    v = point_values(held, c, c, inside, tables)
    for q in asked:
        low, high = bounds[q]
        assert np.all(v[q] >= low[0] * (1 - 1e-9)) and np.all(v[q] <= high[0] * (1 + 1e-9)), q


def test_a_sustained_answer_differs_by_the_creep_modulus_and_prints_its_source() -> None:
    """The deflection of the held answer's design is its short-term deflection times E / E_c,
    and the certificate names the creep modulus and its source."""
    d = copy.deepcopy(SPEC)
    d["constraints"] = {
        "side": SPEC["constraints"]["side"],
        "deflection": [
            {
                "test": "three-point",
                "load": "2 N",  # light enough that the deflection binds, not the capacity
                "max": "0.1 mm",
                "span": "100 mm",
                "duration": "1 week",
            }
        ],
    }
    held = Problem.from_spec(parse_spec(d))
    sol = solve(held)
    assert sol.certified and sol.assembly is not None
    pc = get_material("polycarbonate")
    Ec = pc.creep_modulus(WEEK)
    (con,) = [
        c for c in sol.constraints if c.quantity.duration is not None and c.quantity.kind == "k"
    ]
    lay = sol.assembly.layers[0]
    x = DesignPoints.of(
        LayerPoints(np.array([lay.n]), np.array([lay.W]), np.array([lay.alpha_deg]))
    )
    (c,) = held.candidates
    at = AtPoints(held, c, c, x, Tables(held))
    k_short = at.value(replace(con.quantity, duration=None))
    k_held = at.value(con.quantity)
    assert k_held[0] == pytest.approx(k_short[0] * Ec / pc.E, rel=1e-9)
    assert con.value == pytest.approx(2.0 / k_held[0], rel=1e-9)  # the deflection, mm
    # the short-term answer's design sags past the bound when held: the answers differ
    short = solve(Problem.from_spec(parse_spec(spec_without_duration(d))))
    (con0,) = [c for c in short.constraints if c.name == con.name]
    assert con0.value * pc.E / Ec > 0.1 >= con.value - 1e-9
    assert sol.objective > short.objective  # heavier: the price of a week under load
    text = sol.certificate
    assert "the load held 1 week" in text and f"E_c = {Ec:.4g} MPa" in text
    assert "Makrolon" in text and "ISO 899-1" in text
