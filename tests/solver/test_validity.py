"""The validated ranges as constraints (corrugate.solver.validity, issue 35 item 1): the arm link
of the issue, trust = "extrapolate", the trust key's bad input, which ranges a spec gets, and the
box bounds of the range quantities."""

from __future__ import annotations

import json
import tomllib
from dataclasses import replace
from pathlib import Path
from typing import TYPE_CHECKING, Any

import numpy as np
import pytest

from corrugate.solver import Problem, solve
from corrugate.solver.points import DesignPoints, LayerPoints
from corrugate.solver.problem import Constraint
from corrugate.solver.quantities import box_bounds, point_values
from corrugate.solver.tables import Tables
from corrugate.solver.validity import VALIDITY
from corrugate.spec.schema import SpecError, parse_spec, parse_spec_text

if TYPE_CHECKING:
    from conftest import CliRun

ROOT = Path(__file__).resolve().parents[2]
ARM = ROOT / "tests" / "data" / "arm_link.toml"
ARM_EI = ROOT / "tests" / "data" / "arm_link_stiffness.toml"
FACETS = "validity.cantilever.facets.min"


def _problem(path: Path, **top: Any) -> Problem:
    d = tomllib.loads(path.read_text())
    d.setdefault("tolerances", "none")  # the ranges' answers, measured nominally
    d.update(top)
    return Problem.from_spec(parse_spec(d))


def _named(p: Problem, key: str) -> str:
    (name,) = [c.name for c in p.constraints if c.name.split(" ")[0] == key]
    return name


@pytest.mark.slow
def test_the_arm_link_has_no_certified_design_below_the_cantilever_range() -> None:
    """The issue's arm link, its deflection bound read as the cantilever's rigidity
    (tests/data/arm_link_stiffness.toml). By default the cantilever's range is a constraint,
    7 facets per layer (docs/validation/load_cases_fe.csv: the fewest, n 6); no design meets it
    with every other bound (certified infeasible), and dropping that range alone finds one with
    a layer of fewer facets: it is the range that binds."""
    p = _problem(ARM_EI)
    name = _named(p, FACETS)
    assert name.endswith(
        "(the cantilever model (local term c = 1.5) is validated for >= 7 facets per layer)"
    )
    (c,) = [c for c in p.constraints if c.name == name]
    assert c.bound == 7 and c.sense == "min"
    sol = solve(p, explain=False)
    assert sol.status == "infeasible" and sol.certified and sol.assembly is None
    without = solve(p.without(name), explain=False)
    assert without.status == "optimal" and without.assembly is not None
    assert min(layer.n + 1 for layer in without.assembly.layers) < 7


@pytest.mark.slow
def test_extrapolate_gives_the_old_answer_marked_extrapolated() -> None:
    """trust = "extrapolate": the ranges are dropped and the answer is the one the issue
    reported (layer 2 at n 2, W 25 mm: 3 facets), marked extrapolated, not certified, naming
    the cantilever's facet range (its t/W, 0.25 / 25 = 0.01, lies inside the sample's
    0.005-0.05 since issue 35's wider sample) in the certificate, --json and its own list; its status stays optimal (exit 0)."""
    p = _problem(ARM_EI, trust="extrapolate")
    assert p.trust == "extrapolate" and not any(
        c.name.startswith("validity.") for c in p.constraints
    )
    assert any(c.name.startswith(FACETS) for c in p.ranges)
    sol = solve(p, explain=False)
    assert sol.status == "optimal" and sol.assembly is not None
    layer2 = sol.assembly.layers[1]
    assert (layer2.n, layer2.W) == (2, 25.0)
    assert not sol.certified
    keys = [x.split(" ")[0] for x in sol.extrapolated]
    assert keys == [FACETS]
    assert sol.certificate.startswith(
        "extrapolated, not certified: optimal under the refined model"
    )
    d = json.loads(json.dumps(sol.to_dict()))
    assert d["trust"] == "extrapolate" and d["certified"] is False
    assert d["extrapolated"] == list(sol.extrapolated)


def test_an_extrapolated_answer_inside_every_range_stays_certified() -> None:
    """The blimp gripper's answer (n 9, W 8, alpha 78) lies inside the springs' range: with
    trust = "extrapolate" it is the same design, certified (it is the default problem's
    optimum too)."""
    p = _problem(ROOT / "examples" / "blimp_gripper.toml", trust="extrapolate")
    sol = solve(p, explain=False)
    base = solve(_problem(ROOT / "examples" / "blimp_gripper.toml"), explain=False)
    assert sol.certified and sol.extrapolated == ()
    assert sol.assembly == base.assembly


def test_the_deflection_arm_link_gets_the_cantilever_range_too() -> None:
    """tests/data/arm_link.toml as the issue wrote it: its deflection bound and the load's
    capacity bound are cantilever quantities, so the spec gets the cantilever's range; the spec
    is infeasible with and without it (since issue 34 a 5 N load exceeds the panel's capacity at
    the safety factor 2 within the 42 mm width: docs/load_cases.md 10.6)."""
    p = _problem(ARM)
    assert _named(p, FACETS)
    assert solve(p, explain=False).status == "infeasible"
    assert solve(_problem(ARM, trust="extrapolate"), explain=False).status == "infeasible"


def _spec(**extra: Any) -> dict[str, Any]:
    d: dict[str, Any] = {
        "name": "x",
        "material": {"name": "dura-lar"},
        "variables": {
            "W": {"min": "5 mm", "max": "20 mm"},
            "n": {"min": 2, "max": 20},
            "alpha": {"min": "30 deg", "max": "150 deg"},
        },
        "constraints": {"side": {"min": "40 mm", "max": "80 mm"}},
    }
    d["constraints"].update(extra)
    return d


def test_a_spec_gets_the_ranges_of_the_models_it_uses_and_that_can_bind() -> None:
    """Sizes only: no model, no range. A pure-bending bound: the springs' facets only. A
    three-point bound: the three-point model's facets, alpha and t/W ends (named by it, the
    test's model first); an end the variable bounds cannot cross is left out (n from 6: no
    facet range)."""
    sizes = Problem.from_spec(parse_spec(_spec()))
    assert not any(c.name.startswith("validity.") for c in sizes.constraints)
    pure = Problem.from_spec(parse_spec(_spec(flexural_rigidity=[{"min": "10 mN*m^2", "eta": 0}])))
    assert [c.name.split(" ")[0] for c in pure.constraints if c.name.startswith("validity.")] == [
        "validity.springs.facets.min"
    ]
    d3 = _spec(flexural_rigidity=[{"min": "10 mN*m^2", "eta": 0, "test": "three-point"}])
    d3["variables"]["W"]["max"] = "30 mm"  # t/W down to 0.125 / 30 = 0.0042 < 0.005
    three = Problem.from_spec(parse_spec(d3))
    keys = [c.name.split(" ")[0] for c in three.constraints if c.name.startswith("validity.")]
    assert keys == [
        "validity.three-point.facets.min",
        "validity.three-point.alpha.min",
        "validity.three-point.alpha.max",
        "validity.three-point.t_over_W.min",
    ]  # t/W max: 0.125 / 5 = 0.025 < 0.05 cannot cross it
    d = _spec(flexural_rigidity=[{"min": "10 mN*m^2", "eta": 0}])
    d["variables"]["n"]["min"] = 6
    assert not any(
        c.name.startswith("validity.") for c in Problem.from_spec(parse_spec(d)).constraints
    )


def _box_problems() -> list[tuple[Problem, int]]:
    """A disc with an axle hole (identical layers: one stored layer) and a rectangle of
    independent layers, each asking every range quantity."""
    disc = _spec()
    disc["layout"] = {"shape": "circle", "holes": [{"diameter": "6 mm"}]}
    disc["constraints"] = {"diameter": {"min": "40 mm", "max": "80 mm"}}
    rect = _spec()
    rect["layers"] = "independent"
    rect["layout"] = {"shape": "rectangle"}
    rect["constraints"] = {"side_x": {"min": "40 mm", "max": "80 mm"}}
    extra = tuple(
        Constraint(f"x{i}", q, "min", 0.0) for i, q in enumerate(sorted(VALIDITY, key=str))
    )
    out = []
    for d, layers in ((disc, 1), (rect, 2)):
        p = Problem.from_spec(parse_spec(d))
        out.append((replace(p, constraints=p.constraints + extra), layers))
    return out


@pytest.mark.parametrize("case", [0, 1])
def test_the_box_bounds_of_the_range_quantities_hold_their_values(case: int) -> None:
    """Every range quantity at 400 random points of each of 50 random boxes lies within the
    box's bounds (the solver prunes with them: a bound that misses a point would prune a valid
    design)."""
    p, layers = _box_problems()[case]
    rng = np.random.default_rng(1 + case)
    cand = p.candidates[0]
    tables = Tables(p)
    for _ in range(50):
        n = np.sort(rng.integers(2, 20, size=(layers, 2)), axis=1).astype(float)
        W = np.sort(rng.uniform(5, 20, size=(layers, 2)), axis=1)
        a = np.sort(rng.uniform(30, 150, size=(layers, 2)), axis=1)
        ids = range(layers)
        lo = DesignPoints.of(*(LayerPoints(n[i, :1], W[i, :1], a[i, :1]) for i in ids))
        hi = DesignPoints.of(*(LayerPoints(n[i, 1:], W[i, 1:], a[i, 1:]) for i in ids))
        bounds = box_bounds(p, cand, cand, lo, hi, tables, set(VALIDITY))
        k = 400
        pts = DesignPoints.of(
            *(
                LayerPoints(
                    rng.integers(n[i, 0], n[i, 1] + 1, size=k).astype(float),
                    rng.uniform(W[i, 0], W[i, 1], size=k),
                    rng.uniform(a[i, 0], a[i, 1], size=k),
                )
                for i in ids
            )
        )
        values = point_values(p, cand, cand, pts, tables)
        for q in VALIDITY:
            b_lo, b_hi = bounds[q]
            assert np.all(values[q] >= b_lo[0] * (1 - 1e-12) - 1e-12), q
            assert np.all(values[q] <= b_hi[0] * (1 + 1e-12) + 1e-12), q
            if q.kind == "hub" and case == 0:  # 6 mm over a 40-80 mm disc (wider boxes too)
                assert np.all(values[q] > 0)


def test_an_unknown_trust_is_one_line_naming_it(cli: CliRun, tmp_path: Path) -> None:
    """trust = "maybe": the parser names `trust`, the value and the two allowed; the CLI exits 2
    with one line and no traceback."""
    with pytest.raises(SpecError) as info:
        parse_spec_text('trust = "maybe"\n[material]\nname = "dura-lar"\n')
    assert info.value.field == "trust"
    text = str(info.value)
    assert "'certified'" in text and "'extrapolate'" in text and "maybe" in text
    spec = tmp_path / "s.toml"
    spec.write_text('trust = "maybe"\n[material]\nname = "dura-lar"\n')
    code, _out, err = cli(["design", str(spec), "--json"])
    assert code == 2
    assert "trust" in err and "Traceback" not in err and len(err.strip().splitlines()) == 1


def test_the_diagnosis_names_a_binding_range_and_hints_extrapolate() -> None:
    """At most 5 creases (6 facets) with a pure-bending bound: only the springs' range (7 facets,
    docs/validation/ranges.md) stands between the spec and a design; the diagnosis names it,
    reaches 6 facets at best, and its hint is trust = "extrapolate"."""
    d = _spec(flexural_rigidity=[{"min": "10 mN*m^2", "eta": 0}])
    d["variables"]["n"] = {"min": 2, "max": 5}
    p = Problem.from_spec(parse_spec(d))
    sol = solve(p)
    assert sol.status == "infeasible" and sol.certified
    (diag,) = [x for x in sol.diagnosis if x.names[0].startswith("validity.springs.facets.min")]
    assert diag.reachable == 6 and diag.bound == 7
    assert diag.hint is not None and diag.hint.startswith('trust = "extrapolate"')
    assert "is validated for >= 7 facets per layer" in diag.message


@pytest.mark.slow
def test_a_binding_range_is_named_in_the_answer() -> None:
    """examples/rectangle_independent.toml allows n from 4: its answer before issue 35 had a
    layer of 5 facets (layer 2 W 10, n 4); now the springs' range holds layer 2 at n 6 and the
    answer's constraint table shows the range binding (relaxing it alone finds a lighter
    design: the old one)."""
    sol = solve(_problem(ROOT / "examples" / "rectangle_independent.toml"))
    assert sol.certified and sol.assembly is not None
    assert min(layer.n for layer in sol.assembly.layers) == 6
    (row,) = [c for c in sol.constraints if c.name.startswith("validity.springs.facets.min")]
    assert row.binding is True and row.value == 7


@pytest.mark.slow
def test_an_extrapolated_answer_is_marked_everywhere(cli: CliRun, tmp_path: Path) -> None:
    """The arm link (stiffness form) with trust = "extrapolate": the CLI's text says
    EXTRAPOLATED, not certified (exit 0: an answer); --json, design.json and report.html carry
    the ranges it leaves."""
    spec = tmp_path / "arm.toml"
    # nominal, as the ranges were measured (tolerances = "none")
    spec.write_text('trust = "extrapolate"\ntolerances = "none"\n' + ARM_EI.read_text())
    code, out, _ = cli(["design", str(spec)])
    assert code == 0
    assert "EXTRAPOLATED, not certified" in out and "extrapolated, not certified" in out
    code, out, _ = cli(["design", str(spec), "--json", "--out", str(tmp_path / "o")])
    assert code == 0
    answer = json.loads(out)
    assert answer["certified"] is False and answer["trust"] == "extrapolate"
    assert answer["extrapolated"][0].startswith(FACETS)
    record = json.loads((tmp_path / "o" / "design.json").read_text())
    assert record["extrapolated"] == answer["extrapolated"] and record["certified"] is False
    assert "EXTRAPOLATED, not certified" in (tmp_path / "o" / "report.html").read_text()


def _band_spec(thickness: str, **top: Any) -> Problem:
    """A 60 x 100 mm plate of polypropylene, the layers joined by the band (band-edges), to hold
    2 N in three-point bending over its length (a deflection bound under a load: the capacity
    Pmax >= 2 N at the safety factor 2 comes with it, docs/load_cases.md 10.6), nominal."""
    d: dict[str, Any] = {
        "name": "band",
        "layers": "independent",
        "joint": "band-edges",
        "tolerances": "none",
        "material": {"name": "polypropylene", "thickness": thickness},
        "layout": {"shape": "rectangle"},
        "variables": {
            "W": {"min": "15 mm", "max": "20 mm", "step": "1 mm"},
            "n": {"min": 6, "max": 14},
            "alpha": {"min": "80 deg", "max": "130 deg", "step": "10 deg"},
        },
        "constraints": {
            "side_x": {"min": "50 mm", "max": "70 mm"},
            "side_y": {"min": "90 mm", "max": "110 mm"},
            "deflection": [{"test": "three-point", "load": "2 N", "max": "5 mm", "eta": "0 deg"}],
        },
    }
    d.update(top)
    return Problem.from_spec(parse_spec(d))


WALLS_T = "validity.band-walls.t.max"


def test_a_capacity_gets_the_capacity_models_ranges() -> None:
    """A load held with the band: the capacity's facet ranges (alpha 40-150, t/W 0.00625-0.05
    of docs/validation/capacity_fe.csv: its alpha max 150 is looser than the three-point
    model's 120, which keeps it) and the walls' t_d / h1 <= 2.089 (the variables reach 1 + 20 cos 40
    / (15 cos 65) = 3.42); the ends no design can cross are left out: t_d / h1 >= 1.221 (at least
    1 + 15 cos 65 / (20 cos 40) = 1.41) and the walls' t on a 0.3 mm sheet (0.125-0.5 mm). On
    a 0.1 mm sheet the walls' t >= 0.125 mm binds, and the capacity's t/W >= 0.00625 (0.1 / 20
    = 0.005 reachable) is kept over the three-point model's looser 0.005, named by it."""
    p = _band_spec("0.3 mm")
    keys = [c.name.split(" ")[0] for c in p.constraints if c.name.startswith("validity.")]
    assert "validity.band-walls.td_over_h1.min" not in keys
    assert "validity.band-walls.td_over_h1.max" in keys
    assert WALLS_T not in keys and "validity.band-walls.t.min" not in keys
    assert "validity.three-point.alpha.max" in keys
    assert not any(k.startswith("validity.capacity.alpha") for k in keys)
    thin = _band_spec("0.1 mm")
    keys = [c.name.split(" ")[0] for c in thin.constraints if c.name.startswith("validity.")]
    assert "validity.band-walls.t.min" in keys and "validity.capacity.t_over_W.min" in keys
    (c,) = [c for c in thin.constraints if c.name.startswith("validity.capacity.t_over_W.min")]
    assert c.bound == 0.00625
    without = Problem.from_spec(
        parse_spec(
            {
                "name": "x",
                "material": {"name": "polypropylene", "thickness": "0.3 mm"},
                "variables": {"W": {"min": "10 mm", "max": "14 mm"}},
                "constraints": {"side": {"min": "40 mm", "max": "80 mm"}},
            }
        )
    )
    assert not any(c.name.startswith("validity.") for c in without.constraints)


@pytest.mark.slow
def test_a_band_capacity_outside_the_walls_range_is_not_certified() -> None:
    """0.75 mm polypropylene with the band: thicker than every sheet the band's walls were
    checked on in FE (0.125-0.5 mm, docs/validation/capacity_fe.csv), so by default no design
    is certified (certified infeasible) and the diagnosis names the walls' range, hinting
    trust = "extrapolate"; with it, the answer is marked extrapolated, not certified, naming
    that range."""
    p = _band_spec("0.75 mm")
    name = _named(p, WALLS_T)
    assert name.endswith(
        "(the band's walls' buckling model is validated for sheet thickness t <= 0.5 mm)"
    )
    sol = solve(p)
    assert sol.status == "infeasible" and sol.certified and sol.assembly is None
    assert any(WALLS_T in " ".join(x.names) for x in sol.diagnosis)
    ext = solve(_band_spec("0.75 mm", trust="extrapolate"), explain=False)
    assert ext.status == "optimal" and ext.assembly is not None and not ext.certified
    assert WALLS_T in [x.split(" ")[0] for x in ext.extrapolated]
    assert ext.certificate.startswith("extrapolated, not certified")
