"""The nonlinear ramp of ``verify --nonlinear`` (corrugate.fea.nonlinear, issue 34 item 4): the
knee and peak finders on constructed curves, the imperfection added to a deck's nodes, the
step's cards, the capacity's comparison, and one ramp in CalculiX against a column's hand
derivation and the linear static run of the same deck."""

from __future__ import annotations

import json
import math

import pytest

from corrugate.fea.assembly import AssemblyMesh
from corrugate.fea.nonlinear import (
    NonlinearCase,
    NonlinearResult,
    knee,
    nonlinear_case,
    peak,
    perturb,
)
from corrugate.fea.steps import Drive, Nonlinear


def test_knee_of_a_bilinear_curve_is_where_the_slope_changes() -> None:
    """100 N/mm up to 10 N, then 30 N/mm (30 % of the initial): the first segment below 50 % is
    the one starting at 10 N, index 5 (the origin is index 0)."""
    loads = [2.0, 4.0, 6.0, 8.0, 10.0, 11.5, 13.0]
    travels = [0.02, 0.04, 0.06, 0.08, 0.10, 0.15, 0.20]
    i = knee(loads, travels)
    assert i == 5
    assert [0.0, *loads][i] == 10.0
    # 60 % of the initial is not below 50 %; it is below 70 %
    soft = [2.0, 4.0, 6.0, 8.0, 10.0, 13.0, 16.0]
    assert knee(soft, travels) is None
    assert knee(soft, travels, fraction=0.7) == 5


def test_no_knee_on_a_straight_or_stiffening_curve_and_a_turn_back_counts() -> None:
    loads = [1.0, 2.0, 3.0, 4.0]
    assert knee(loads, [0.01, 0.02, 0.03, 0.04]) is None
    assert knee(loads, [0.01, 0.019, 0.027, 0.034]) is None  # stiffening
    assert knee(loads, [0.01, 0.02, 0.03, 0.029]) == 3  # the travel turns back
    assert knee([1.0], [0.01]) is None  # one point: no tangent to compare


def test_peak_is_a_maximum_followed_by_a_lower_load_or_a_limit() -> None:
    assert peak([1.0, 2.0, 2.5, 2.4, 2.2]) == 2
    assert peak([1.0, 2.0, 2.5]) is None  # still rising
    assert peak([1.0, 2.0, 2.5], limit=True) == 2  # ccx stopped converging there
    assert peak([]) is None


DECK = """*HEADING
test
*NODE
1,0,0,0
2,1,0,0
3,1,1,0.5
*ELEMENT,TYPE=S8R,ELSET=L1
1,1,2,3
*NODE
9,5,5,5
*STEP
"""


def test_perturb_moves_the_mesh_nodes_only() -> None:
    """Node 3 moved by 0.1 x (0, 0, 2) = +0.2 in z; node 1 has no shape and stays; the second
    ``*NODE`` card (a reference node) is not the mesh's and stays."""
    import numpy as np

    out = perturb(DECK, {2: np.array([1.0, 0, 0]), 3: np.array([0, 0, 2.0]), 9: np.ones(3)}, 0.1)
    lines = out.split("\n")
    assert lines[3] == "1,0,0,0"
    assert lines[4] == "2,1.1,0,0"
    assert lines[5] == "3,1,1,0.7"
    assert "9,5,5,5" in lines


def test_the_step_ramps_a_dead_load_on_the_tied_reference_node() -> None:
    step = Nonlinear(2.5, 0.1, watch=(7,))
    bc = ["SUP1,3,3,0", Drive("MID1", 3, (4, 5))]
    lines = step.lines(bc, 99, (0.0, 1.0, 2.0))
    assert lines[:2] == ["*NODE", "99,0,1,2"]
    assert "4,3,1.,99,3,-1." in lines and "5,3,1.,99,3,-1." in lines  # u3(drive) = u3(ref)
    i = lines.index("*STATIC")
    assert lines[i - 1] == "*STEP,NLGEOM,INC=10000"
    assert lines[i + 1] == "1.e-1,1.,1.e-3,1.e-1"  # initial, period, minimum, maximum
    assert lines[lines.index("*CLOAD") + 1] == "99,3,-2.5"  # towards the part, as the drive
    assert "SUP1,3,3,0" in lines
    assert lines[lines.index(f"*NSET,NSET={Nonlinear.PRINTED}") + 1] == "99,7"
    assert lines[-3:] == [f"*NODE PRINT,NSET={Nonlinear.PRINTED}", "U", "*END STEP"]
    assert step.ties_parts


def _result(loads: list[float], travels: list[float], model: float | None, ended: str):
    case = NonlinearCase("three-point", 0.0, None, ("c",), model, 2.0 if model else None)
    return NonlinearResult(
        case,
        AssemblyMesh(2),
        1.0,
        100.0,
        0.01,
        "layer 1",
        1.5,
        tuple(loads),
        tuple(travels),
        tuple(0.0 for _ in loads),
        ended,
    )


def test_the_capacity_is_compared_with_the_knee_or_the_end_of_the_ramp() -> None:
    bilinear = ([0.2, 0.4, 0.6, 0.7], [0.002, 0.004, 0.006, 0.016])  # knee at 0.6 N
    r = _result(*bilinear, 0.5, "target")
    assert r.knee_load == 0.6 and r.compared_with == "knee" and r.model_holds is True
    assert _result(*bilinear, 0.65, "target").model_holds is False
    straight = ([0.5, 1.0, 1.5], [0.005, 0.010, 0.015])
    r = _result(*straight, 1.2, "target")
    assert r.knee_load is None and r.compared_with.startswith("end of the ramp")
    assert r.model_holds is True  # the FE held 1.5 N without a knee
    assert _result(*straight, 2.0, "target").model_holds is None  # beyond what was run
    assert _result(*straight, None, "target").model_holds is None
    # a limit: the ramp stopped converging after the knee, its last load the peak
    assert _result(*bilinear, 0.5, "not converged").peak_load == 0.7
    block = json.loads(json.dumps(r.as_json(), allow_nan=False))
    assert block["curve"][1] == {"load_N": 1.0, "displacement_mm": 0.010, "mode_mm": 0.0}
    assert block["knee_N"] is None and block["model_first_failure_N"] == 1.2


def test_the_case_is_the_load_capacity_s_fixture() -> None:
    """A design.json with a pure-bending bound first and a load capacity in three-point: the
    ramp runs in three-point, the model's first failure is the least of its failure loads."""
    from corrugate import Assembly, Layer, get_material

    a = Assembly.identical(Layer(8.0, 6, 84.0, get_material("dura-lar"), 0.125))
    constraints = [
        {"name": "EI", "quantity": "EI@0", "sense": "min", "bound": 1.0, "value": 2.0},
        {
            "name": "cap",
            "quantity": "Pmax3pt@0",
            "sense": "min",
            "bound": 0.1,
            "value": 0.5,
            "failure_loads_N": {"yield": 3.0, "edge-facet-buckling": 1.0},
        },
    ]
    case = nonlinear_case(a, constraints)
    assert case is not None
    assert case.test == "three-point" and case.eta == 0.0
    assert case.constraints == ("cap",)
    assert case.model == 1.0 and case.safety_factor == pytest.approx(2.0)
    assert nonlinear_case(a, constraints[:1]).test == "four-point"  # type: ignore[union-attr]
    assert nonlinear_case(a, []) is None


@pytest.mark.fea
def test_a_column_between_the_platens_softens_at_its_euler_load(ccx: str) -> None:
    """The long column of tests/fea/test_buckling_step.py (layer 1: Dura-Lar W 5, t 0.5, n 3,
    alpha 90 deg, L = 106.07 mm along the load; P_cr = 24.91 N at 2 per facet, the Euler load of
    its clamped-guided column 24.92 N) ramped to 1.5 P_cr in tenths, its first mode an
    imperfection of W / 200 = 0.025 mm.

    * Small loads: the first point's secant equals the linear static run of the same mesh (the
      ``platens`` fixture's K, :func:`solve_assembly`, a second method: prescribed platen travel,
      reactions summed), within 1 % (the imperfection lowers it by the bowing's share only).
    * The knee: a hand derivation for the imperfect column (Timoshenko and Gere 1.11): the sway
      grows as w = w0 / (1 - p), p = P / P_cr, and shortens the column by c (w^2 - w0^2) with
      c = pi^2 / (16 L) for the clamped-guided mode w0 (1 - cos(pi y / L)) / 2, so
      d delta / dP = 1 / k + 2 c w0^2 / (P_cr (1 - p)^3): the tangent is half the initial at
      (1 - p)^3 = 2 c k w0^2 / P_cr, p = 0.958 with k = 256 N/mm (or 0.933 for a half-sine
      shape, c four times larger). So the knee lies at or below P_cr and above 0.85 P_cr; a knee
      missed (None) or a ramp that ignored the imperfection (no softening below P_cr) fails.
    * The peak: the elastica's post-buckling path is nearly flat (P / P_cr = 1.006 at a sway of
      7 % of L), so the dead load stops converging within 1 % of P_cr."""
    from corrugate import Assembly, Layer, get_material
    from corrugate.fea.assembly import solve_assembly
    from corrugate.fea.nonlinear import ramp
    from corrugate.geometry.layouts import Rectangle

    dl = get_material("dura-lar")
    column = Layer(W=5.0, n=3, alpha_deg=90.0, material=dl, t=0.5)
    a = Assembly(column, Layer(W=10.0, n=14, alpha_deg=90.0, material=dl, t=0.5), Rectangle())
    mesh = AssemblyMesh(2)
    static = solve_assembly(a, "platens", mesh, 0.0)
    assert static.K is not None
    r = ramp(a, NonlinearCase("platens", 0.0, None, ("column",)), mesh, increment=0.1)
    assert r.amplitude == pytest.approx(5.0 / 200)
    assert r.mode_at == "layer 1"
    # the buckling run's base state: the platen tied to a reference node against prescribed
    # platen nodes, which ccx applies to its expanded shells in its own ways (docs/fea.md 6):
    # 255.92 against 256.12 N/mm, 0.08 %
    assert r.k0 == pytest.approx(static.K, rel=2e-3)
    assert r.loads[0] / r.travels[0] == pytest.approx(static.K, rel=0.01)
    assert r.target == pytest.approx(1.5 * r.buckling_load)
    k = r.knee_load
    assert k is not None
    assert 0.85 * r.buckling_load <= k <= r.buckling_load
    assert r.ended == "not converged"
    p = r.peak_load
    assert p is not None and 0.95 * r.buckling_load <= p <= 1.01 * r.buckling_load
    assert math.isfinite(r.seconds)
