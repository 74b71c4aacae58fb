"""A load case registered by a test (role ``test``, with its TestForm) is offered everywhere the
built-in ones are: the spec parser takes it in a deflection, strength or stiffness bound and the
solver certifies an answer, the spec reference and its JSON Schema list it, the report's
load-case figure draws and titles it, and the web page's data (``GET /api/load-cases``) names
it; unregistered, everything is as before.

The toy ``clamped-ends`` is a beam clamped at both ends with the load P at mid-span. Independent
source, a hand derivation (Timoshenko, Roark's Table 8.1 case 1d/1e): the bending deflection is
P Ls^3 / (192 EI) against P Ls^3 / (48 EI) simply supported, the shear deflection is the same
(each half carries P / 2 over Ls / 2: P Ls / (4 S)), and the largest moment is P Ls / 8 (at the
ends and at mid-span) against P Ls / 4. So, with the same local term,

    1 / k_cc = 1 / k_3pt - (1/48 - 1/192) Ls^3 / EI,

which the tests check against the three-point value and EI the solver reports for the same
designs (the three-point formula itself is checked against a hand formula in
test_load_cases.py).
"""

from __future__ import annotations

import copy
from collections.abc import Iterator
from dataclasses import replace
from typing import Any

import numpy as np
import pytest

from corrugate.mechanics.behaviours import (
    Behaviour,
    deflection_tests,
    load_cases,
    register,
    unregister,
)
from corrugate.mechanics.behaviours import TestForm as Form
from corrugate.mechanics.load_cases import LOCAL, THREE_POINT
from corrugate.names import RECTANGULAR_LAYOUTS
from corrugate.solver import Problem, solve
from corrugate.solver.points import DesignPoints, LayerPoints
from corrugate.solver.quantities import Tables, point_values
from corrugate.solver.quantity import LY, MASS, Quantity
from corrugate.spec.reference import json_schema, reference_markdown
from corrugate.spec.schema import SpecError, parse_spec
from spec_units import with_units


def _fixed_fixed_shape(x: Any) -> Any:
    """A beam clamped at both ends under a mid-span load: w ~ u^2 (3 - 4u), u from the nearer
    end (Roark, Table 8.1 case 1e with a = l / 2)."""
    u = np.minimum(x, 1 - x)
    return u**2 * (3 - 4 * u)


CLAMPED_ENDS = replace(
    THREE_POINT,
    name="clamped-ends",
    form=Form(
        "bending",
        1.0 / 192.0,
        0.25,
        LOCAL,
        1.0 / 8.0,
        loads=(0.5,),
        shape=_fixed_fixed_shape,
    ),
    label=" with clamped ends",
    suffix="cc",
    text="a toy: clamped at both ends, the load at mid-span",
    curve="clamped-ends",
    choice="clamped ends",
    note="a toy",
    layouts=RECTANGULAR_LAYOUTS,
)


@pytest.fixture
def clamped_ends() -> Iterator[Behaviour]:
    """``clamped-ends`` registered for one test, unregistered after it."""
    register(CLAMPED_ENDS)
    try:
        yield CLAMPED_ENDS
    finally:
        unregister("clamped-ends", "test")
    assert "clamped-ends" not in [b.name for b in load_cases()]


SPEC: dict[str, Any] = {
    "name": "toy",
    "tolerances": "none",  # nominal: the test checks the model, not the tolerances (docs/tolerances.md)
    "material": {"name": "dura-lar", "thickness": 0.125},
    "layout": {"shape": "square"},
    "variables": {
        "W": {"min": 6, "max": 14, "step": 1},
        "n": {"min": 7, "max": 13},
        "alpha": {"min": 40, "max": 115, "step": 5},
    },
    "constraints": {"side": {"min": 40, "max": 80}},
}


def _spec(**constraints: Any) -> dict[str, Any]:
    d = copy.deepcopy(SPEC)
    d["constraints"].update(constraints)
    return with_units(d)


def _points(n: np.ndarray, W: np.ndarray, a: np.ndarray) -> DesignPoints:
    """Identical layers at the points (n, W, a), as the solver's point_values reads them."""
    return DesignPoints.of(LayerPoints(n, W, a))


def _grid() -> tuple[np.ndarray, Any]:
    """The whole grid of :data:`SPEC` (n 7-13, W 6-14 step 1, alpha 40-115 step 5) as rows and
    as the points of identical layers."""
    grid = np.array(
        [(n, W, a) for n in range(7, 14) for W in range(6, 15) for a in range(40, 116, 5)],
        dtype=float,
    )
    return grid, _points(grid[:, 0], grid[:, 1], grid[:, 2])


def _by_hand(x: Any) -> np.ndarray:
    """P / delta (N/mm) of the toy at eta = 0 over the panel's length Ly along eta, from the
    three-point value and EI the solver gives at the same points (module docstring)."""
    probe = Problem.from_spec(
        parse_spec(
            _spec(
                deflection=[{"test": "three-point", "load": 1, "max": 1000}],
                flexural_rigidity=[{"min": "1 N*mm^2"}],
            )
        )
    )
    cand = probe.candidates[0]
    v = point_values(probe, cand, cand, x, Tables(probe))
    k3 = v[Quantity.load_case("k", 0.0, "three-point")]
    EI, L = v[Quantity.stiffness("EI", 0.0)], v[LY]
    return 1.0 / (1.0 / k3 - (1.0 / 48.0 - 1.0 / 192.0) * L**3 / EI)


def test_the_spec_takes_the_registered_load_case_and_the_solver_certifies_it(
    clamped_ends: Behaviour,
) -> None:
    """A deflection bound in 'clamped-ends' parses to the toy's quantity (key kcc@0); the
    certified optimum is the lightest grid point whose hand-derived P / delta meets the bound,
    and the deflection reported there is the load over that hand value."""
    _, x = _grid()
    k_all = _by_hand(x)
    # 0.01 N (a load the toy's grid holds at the safety factor: the deflection bound brings
    # that capacity bound with it, docs/load_cases.md 10.6): a bound some grid points meet
    load = 0.01
    most = load / (0.4 * float(np.max(k_all)))
    p = Problem.from_spec(
        parse_spec(_spec(deflection=[{"test": "clamped-ends", "load": load, "max": most}]))
    )
    [c] = [c for c in p.constraints if c.load is not None]
    assert c.quantity.key == "kcc@0" and c.quantity.test == "clamped-ends"
    assert c.quantity.description.endswith("(0 deg) with clamped ends")
    sol = solve(p)
    assert sol.status == "optimal" and sol.certified
    cand = p.candidates[0]
    vals = point_values(p, cand, cand, x, Tables(p))
    np.testing.assert_allclose(vals[c.quantity], k_all, rtol=1e-12)
    ok = k_all >= load / most
    for other in p.constraints:
        if other is not c:
            ok &= other.satisfied(vals[other.quantity])
    assert sol.mass == pytest.approx(float(np.min(vals[MASS][ok])), rel=1e-9)
    layer = sol.assembly.layer1
    at = _points(np.array([float(layer.n)]), np.array([layer.W]), np.array([layer.alpha_deg]))
    [report] = [r for r in sol.constraints if r.load is not None]
    assert report.value == pytest.approx(load / float(_by_hand(at)[0]), rel=1e-9)
    assert report.value <= most * (1 + 1e-12)


def test_strength_and_stiffness_bounds_take_it_too(clamped_ends: Behaviour) -> None:
    """A strength bound and an EI bound may name the toy: its largest moment P Ls / 8 is half
    the three-point one (P Ls / 4), so at every point of the grid its load capacity is twice
    the three-point one (every peak stress is proportional to the moment). A K bound may not
    name it (a bending test), nor an EI bound platens; the errors list the toy where it fits."""
    p = Problem.from_spec(
        parse_spec(
            _spec(
                strength=[{"test": "clamped-ends", "load": 1}, {"test": "three-point", "load": 1}],
                flexural_rigidity=[{"min": "1 N*mm^2", "test": "clamped-ends"}],
            )
            | {
                "material": {
                    "name": "dura-lar",
                    "thickness": "0.125 mm",
                    "yield_strength": "50 MPa",
                }
            }
        )
    )
    keys = {c.quantity.key: c.quantity for c in p.constraints}
    assert {"Pmaxcc@0", "Pmax3pt@0", "EIcc@0"} <= set(keys)
    _, x = _grid()
    cand = p.candidates[0]
    v = point_values(p, cand, cand, x, Tables(p))
    np.testing.assert_allclose(v[keys["Pmaxcc@0"]], 2.0 * v[keys["Pmax3pt@0"]], rtol=1e-12)
    with pytest.raises(SpecError) as info:
        Problem.from_spec(
            parse_spec(_spec(inplane_stiffness=[{"min": "1 N/mm", "test": "clamped-ends"}]))
        )
    assert info.value.field == "constraints.inplane_stiffness[0].test"
    assert info.value.allowed == "'platens' or 'wheel' (a circle)"
    with pytest.raises(SpecError) as info:
        Problem.from_spec(
            parse_spec(_spec(flexural_rigidity=[{"min": "1 N*mm^2", "test": "platens"}]))
        )
    assert info.value.allowed == (
        "'pure', 'three-point', 'four-point', 'cantilever' or 'clamped-ends'"
    )


def test_the_spec_refuses_it_once_unregistered() -> None:
    """Without the toy, the parser refuses it and names the built-in load cases."""
    with pytest.raises(SpecError) as info:
        parse_spec(_spec(deflection=[{"test": "clamped-ends", "load": 1, "max": 1}]))
    assert info.value.field == "constraints.deflection[0].test"
    assert info.value.allowed == "'three-point', 'four-point', 'cantilever' or 'platens'"


def test_the_reference_and_the_schema_list_it(clamped_ends: Behaviour) -> None:
    """The reference's test rows name the toy with its note, the JSON Schema's test enums hold
    it, and unregistering it gives the reference and schema back unchanged."""
    md = reference_markdown()
    rows = {
        line.split("`")[1]: line
        for line in md.splitlines()
        if line.startswith("| `constraints.") and "[].test`" in line
    }
    assert rows["constraints.deflection[].test"].endswith(
        "'cantilever', 'platens' (in-plane compression) or 'clamped-ends' (a toy). |"
    )
    assert rows["constraints.strength[].test"] == rows["constraints.deflection[].test"].replace(
        "deflection", "strength"
    )
    for k in ("flexural_rigidity", "bending_stiffness"):
        assert (
            "'cantilever' or 'clamped-ends' (a toy) (what that test reads"
            in rows[f"constraints.{k}[].test"]
        )
    assert "clamped-ends" not in rows["constraints.inplane_stiffness[].test"]
    schema = json_schema()
    for name in ("DeflectionSpec", "StrengthSpec"):
        enum = schema["$defs"][name]["properties"]["test"]["enum"]
        assert enum == ["three-point", "four-point", "cantilever", "platens", "clamped-ends"]
    enum = schema["$defs"]["RigiditySpec"]["properties"]["test"]["anyOf"][0]["enum"]
    assert enum == [
        "pure",
        "three-point",
        "four-point",
        "cantilever",
        "platens",
        "wheel",
        "clamped-ends",
    ]
    assert [b.name for b in deflection_tests()][-1] == "clamped-ends"


def test_unregistering_gives_the_reference_back() -> None:
    md, schema = reference_markdown(), json_schema()
    register(CLAMPED_ENDS)
    try:
        assert reference_markdown() != md and json_schema() != schema
    finally:
        unregister("clamped-ends", "test")
    assert reference_markdown() == md and json_schema() == schema


def test_the_report_figure_draws_and_titles_it(clamped_ends: Behaviour) -> None:
    """The load-case figure titles the toy's panel with its name and span and draws its own
    sketch: supports at both ends (not a cantilever's clamp), one load arrow at mid-span and
    its deflected shape, deepest at mid-span and flat at the clamped ends."""
    from corrugate.report.figures import load_case_figure

    p = Problem.from_spec(
        parse_spec(_spec(deflection=[{"test": "clamped-ends", "load": 0.01, "max": 0.5}]))
    )
    sol = solve(p)
    fig = load_case_figure(sol.constraints, (sol.assembly.Lx, sol.assembly.Ly))
    [ax] = fig.axes
    title = ax.get_title()
    assert title.startswith(f"clamped-ends, span {sol.assembly.Ly:.4g} mm\n")
    assert not ax.collections  # no cantilever's clamp
    ends = [ln.get_xdata()[0] for ln in ax.lines if ln.get_marker() == "^"]
    assert ends == [0.0, 1.0]
    [shape] = [ln for ln in ax.lines if ln.get_label() == "deflected (not to scale)"]
    xs, ys = shape.get_data()
    assert xs[int(np.argmin(ys))] == pytest.approx(0.5)
    # zero slope at a clamped end: the first step is second order in x (Roark 1e)
    assert abs(ys[1] - ys[0]) < 0.01 * abs(ys[50] - ys[0])
    arrows = [a.xy[0] for a in ax.texts]
    assert arrows == [0.5]


def test_the_pages_data_names_it(clamped_ends: Behaviour) -> None:
    """GET /api/load-cases (what the page builds its test menus from) lists the toy after the
    built-ins, with its label, kind and layouts."""
    pytest.importorskip("fastapi")
    from fastapi.testclient import TestClient

    from corrugate.web import create_app

    r = TestClient(create_app()).get("/api/load-cases")  # no lifespan: no worker is started
    assert r.status_code == 200
    cases = r.json()
    assert [c["name"] for c in cases] == [
        "three-point",
        "four-point",
        "cantilever",
        "platens",
        "wheel",
        "clamped-ends",
    ]
    toy = cases[-1]
    assert toy == {
        "name": "clamped-ends",
        "label": "clamped ends",
        "kind": "bending",
        "own": False,
        "deflection": True,
        "layouts": ["square", "rectangle"],
        "text": "a toy: clamped at both ends, the load at mid-span",
    }
    assert [c["name"] for c in cases if c["own"]] == ["platens"]
    assert [c["name"] for c in cases if not c["deflection"]] == ["wheel"]
