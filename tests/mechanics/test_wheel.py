"""The wheel test (docs/load_cases.md 9): a disc's radial stiffness between a ground patch and its
axle, c(eta) x the model's K, with c from the FE sweep of docs/validation/wheel_fe.csv."""

from __future__ import annotations

import csv
import math
from pathlib import Path
from typing import Any

import numpy as np
import pytest

from corrugate import Assembly, Layer, analyze, get_material
from corrugate.analysis.warnings import wheel_warnings
from corrugate.geometry.holes import Hole
from corrugate.geometry.layouts import Circle
from corrugate.mechanics.wheel import (
    VALIDATED_WHEEL,
    WHEEL_FACTOR,
    WHEEL_LOWER_RATIO,
    wheel_direction,
    wheel_factor,
)
from corrugate.solver import Problem
from corrugate.solver.points import DesignPoints, LayerPoints
from corrugate.solver.quantities import Tables, box_bounds, point_values
from corrugate.solver.quantity import Quantity
from corrugate.spec.schema import SpecError, parse_spec
from fe_rows import SETTLED_WHEELS, settled_wheel_rows
from spec_units import with_units

ROOT = Path(__file__).resolve().parents[2]
DATA = ROOT / "docs" / "validation" / "wheel_fe.csv"
PP = get_material("polypropylene")


def _rows(every: bool = False) -> list[dict[str, str]]:
    """The rows of the first sweep, which c(eta) comes from; with ``every``, the issue-35 discs
    too (named ``s-...``: the staircase mesh, not settled; ``d-...``: the mesh conforming to the
    rim and the hole, whose settled series make the validated range; docs/load_cases.md 9)."""
    with DATA.open() as f:
        rows = list(csv.DictReader(line for line in f if not line.startswith("#")))
    return rows if every else [r for r in rows if not r["design"].startswith(("s-", "d-"))]


def _series(every: bool = False) -> dict[tuple[str, float], dict[int, float]]:
    """FE K (N/mm) by (design, eta) and elements per facet, the runs that ran."""
    out: dict[tuple[str, float], dict[int, float]] = {}
    for r in _rows(every):
        if r["K_FE"] != "failed":
            out.setdefault((r["design"], float(r["eta_deg"])), {})[int(r["along"])] = float(
                r["K_FE"]
            )
    return out


def _model(every: bool = False) -> dict[tuple[str, float], float]:
    return {(r["design"], float(r["eta_deg"])): float(r["K_model"]) for r in _rows(every)}


def _lower_ratios() -> dict[float, dict[str, float]]:
    """Each design's lower ratio by eta (0, 45), written out from docs/load_cases.md 9: its FE
    K at 8 per facet less its last step |K8 - K4|, or its 16-per-facet K if that is lower, over
    the model's K."""
    fe, model = _series(), _model()
    out: dict[float, dict[str, float]] = {0.0: {}, 45.0: {}}
    for (d, eta), s in fe.items():
        if eta not in out:
            continue
        low = s[8] - abs(s[8] - s[4])
        if 16 in s:
            low = min(low, s[16])
        out[eta][d] = low / model[d, eta]
    return out


def test_the_factor_is_the_sweeps_least_lower_ratio() -> None:
    """c(eta) recomputed from the data file: at least 8 designs at each of eta 0 and 45, every
    one run at 4 and 8 per facet; c is the least lower ratio rounded down, at or below every
    design's FE at 4, 8 (and 16) per facet over its model."""
    fe, model = _series(), _model()
    lower = _lower_ratios()
    for eta in (0.0, 45.0):
        assert len(lower[eta]) >= 8
        assert WHEEL_LOWER_RATIO[eta] == pytest.approx(min(lower[eta].values()), rel=1e-5)
        c = WHEEL_FACTOR[eta]
        assert c == math.floor(1000 * min(lower[eta].values())) / 1000
        for d in lower[eta]:
            assert all(c * model[d, eta] <= k for m, k in fe[d, eta].items() if m >= 4), d


def test_the_factor_holds_every_disc_whose_series_counts() -> None:
    """Every disc of wheel_fe.csv, the issue-35 discs (2 / 4 / 8 / 16 per facet) among them,
    against c(eta) x the model as `corrugate verify` judges a series
    (corrugate.fea.extrapolate.judge: the four finest meshes each twice the one before, monotone
    with shrinking steps, two Richardson estimates within a quarter of the margin): none fails,
    every settled one holds, and every disc's FE at its finest mesh is above the bound. On the
    staircase mesh one series settles (polypropylene 0.5 mm W 10, n 6, alpha 150 at 45 deg;
    docs/load_cases.md 9: the staircase hub and patch make the others turn); on the mesh
    conforming to the rim and the hole (discs ``d-...``) both directions of six discs settle
    and hold, and the validated range is theirs (the test below)."""
    from corrugate.fea.extrapolate import judge

    fe, model = _series(every=True), _model(every=True)
    four = 0
    for (d, eta), s in fe.items():
        if eta not in WHEEL_FACTOR:
            continue
        bound = WHEEL_FACTOR[eta] * model[d, eta]
        j = judge(s, bound, "min")
        assert j.verdict != "fails", (d, eta, s, j.how)
        if j.verdict == "holds":
            assert j.value is not None and j.value >= bound
        assert s[max(s)] >= bound, (d, eta, s)
        four += {2, 4, 8, 16} <= set(s)
    assert four >= 10  # the issue-35 discs at eta 0 and 45


def test_the_validated_range_is_the_settled_discs() -> None:
    """Issue 35: the range is the span of the discs whose series at 0 and 45 deg settle, all on
    the mesh conforming to the rim and the hole (docs/load_cases.md 9): polypropylene 0.3 mm and
    Dura-Lar 0.175 mm, n 6-7, W 8-12 mm, alpha 120-150 deg, a 6 mm hole in 55.4-77.8 mm; each
    holds c(eta) x the
    model (the test above)."""
    rows = settled_wheel_rows(_rows(every=True))
    settled = {r["design"] for r in rows}
    assert settled == SETTLED_WHEELS
    assert all(d.startswith("d-") for d in settled)
    n = [float(r["n"]) for r in rows]
    alpha = [float(r["alpha_deg"]) for r in rows]
    W = [float(r["W_mm"]) for r in rows]
    tw = [float(r["t_mm"]) / float(r["W_mm"]) for r in rows]
    hole = [float(r["hole_mm"]) / float(r["diameter_mm"]) for r in rows]
    for name, values in (
        ("n", n),
        ("alpha", alpha),
        ("W", W),
        ("t/W", tw),
        ("hole/diameter", hole),
    ):
        lo, hi = VALIDATED_WHEEL[name]
        assert lo == pytest.approx(min(values), rel=1e-5), name
        assert hi == pytest.approx(max(values), rel=1e-5), name


def test_the_symmetric_directions_read_as_the_sweeps() -> None:
    """eta 90 and 135 read as 0 and 45 (identical layers, a mirror-symmetric disc); where the
    sweep ran them (4 per facet) the FE agrees with its mirror to 2 %."""
    assert [wheel_direction(e) for e in (0, 45, 90, 135, 180, -45, 30)] == [
        0.0,
        45.0,
        0.0,
        45.0,
        0.0,
        45.0,
        None,
    ]
    assert wheel_factor(90) == WHEEL_FACTOR[0.0] and wheel_factor(135) == WHEEL_FACTOR[45.0]
    fe = _series()
    checked = 0
    for (d, eta), s in fe.items():
        if eta in (90.0, 135.0) and 4 in s:
            mirror = fe[d, 0.0 if eta == 90.0 else 45.0][4]
            assert s[4] == pytest.approx(mirror, rel=0.02), (d, eta)
            checked += 1
    assert checked >= 2


def _spec(layout: dict[str, Any], **constraints: Any) -> dict[str, Any]:
    return {
        "name": "wheel",
        "tolerances": "none",  # nominal: the test checks the model, not the tolerances (docs/tolerances.md)
        "material": {"name": "polypropylene", "thickness": 0.3},
        "layout": layout,
        "variables": {
            "W": {"min": 6, "max": 12, "step": 0.5},
            "n": {"min": 6, "max": 12},
            "alpha": {"min": 90, "max": 150, "step": 2},
        },
        "constraints": {
            ("diameter" if layout["shape"] == "circle" else "side"): {"min": 60, "max": 80},
            **constraints,
        },
    }


CIRCLE = {"shape": "circle", "holes": [{"shape": "circle", "diameter": 6, "center": [0, 0]}]}


def _problem(layout: dict[str, Any] = CIRCLE, **constraints: Any) -> Problem:
    return Problem.from_spec(parse_spec(with_units(_spec(layout, **constraints))))


def test_the_wheel_bound_is_the_factor_times_the_models_k() -> None:
    """The solver's wheel-test K at a design is c(eta) (from the data file, as above) times
    analyze's K of the same disc (free sides), at 0, 45 and 90 deg; the box bounds hold it."""
    c = {eta: math.floor(1000 * min(r.values())) / 1000 for eta, r in _lower_ratios().items()}
    p = _problem(inplane_stiffness=[{"min": 1, "eta": e, "test": "wheel"} for e in (0, 45, 90)])
    cand = p.candidates[0]
    W, n, a = 8.5, 8, 132.0
    x = DesignPoints.of(LayerPoints(np.array([float(n)]), np.array([W]), np.array([a])))
    values = point_values(p, cand, cand, x, Tables(p))
    disc = Assembly.identical(
        Layer(W=W, n=n, alpha_deg=a, material=PP, t=0.3),
        Circle(holes=(Hole("circle", (0.0, 0.0), 6.0),)),
    )
    r = analyze(disc, "refined", [0.0, 45.0, 90.0])
    for st in r.stiffness:
        q = Quantity.load_case("K", st.eta_deg, "wheel", "free")
        want = c[0.0 if st.eta_deg != 45.0 else 45.0] * st.K
        assert values[q][0] == pytest.approx(want, rel=1e-9), st.eta_deg
    one = x.layer(0)
    lo = DesignPoints.of(LayerPoints(one.n, one.W - 0.5, one.alpha - 2.0))
    hi = DesignPoints.of(LayerPoints(one.n + 1, one.W + 0.5, one.alpha + 2.0))
    qs = {cn.quantity for cn in p.constraints if cn.quantity.test == "wheel"}
    b = box_bounds(p, cand, cand, lo, hi, Tables(p), qs)
    for q in qs:
        assert b[q][0][0] <= values[q][0] <= b[q][1][0], q


@pytest.mark.parametrize(
    ("layout", "entry", "field", "words"),
    [
        ({"shape": "square"}, {"test": "wheel"}, "constraints.inplane_stiffness[0].test", "square"),
        (CIRCLE, {"test": "wheel", "eta": 30}, "constraints.inplane_stiffness[0].eta", "45"),
        (
            CIRCLE,
            {"test": "wheel", "support": "frame"},
            "constraints.inplane_stiffness[0].support",
            "'free'",
        ),
        (CIRCLE, {"test": "wheels"}, "constraints.inplane_stiffness[0].test", "'wheel'"),
    ],
)
def test_bad_wheel_bounds_name_their_field(
    layout: dict[str, Any], entry: dict[str, Any], field: str, words: str
) -> None:
    with pytest.raises(SpecError) as info:
        _problem(layout, inplane_stiffness=[{"min": 1, **entry}])
    assert info.value.field == field
    assert words in str(info.value) and "\n" not in str(info.value)


def test_a_frame_for_the_whole_spec_names_support() -> None:
    spec = _spec(CIRCLE, inplane_stiffness=[{"min": 1, "test": "wheel"}])
    with pytest.raises(SpecError) as info:
        Problem.from_spec(parse_spec(with_units({**spec, "support": "frame"})))
    assert info.value.field == "support" and "'free'" in str(info.value)


def test_wheel_is_a_test_of_k_only() -> None:
    with pytest.raises(SpecError) as info:
        _problem(bending_stiffness=[{"min": 1, "test": "wheel"}])
    assert info.value.field == "constraints.bending_stiffness[0].test"


def test_a_wheel_bound_on_a_square_exits_2_with_one_line(cli: Any, tmp_path: Path) -> None:
    path = tmp_path / "bad.toml"
    path.write_text(
        'name = "bad"\n'
        'material = { name = "polypropylene", thickness = "0.3 mm" }\n'
        'layout = { shape = "square" }\n'
        "[variables]\n"
        'W = { min = "6 mm", max = "12 mm", step = "0.5 mm" }\n'
        "n = { min = 6, max = 12 }\n"
        'alpha = { min = "90 deg", max = "150 deg" }\n'
        "[constraints]\n"
        'side = { min = "60 mm", max = "80 mm" }\n'
        'inplane_stiffness = [{ min = "100 N/mm", eta = "0 deg", test = "wheel" }]\n'
    )
    out_dir = tmp_path / "out"
    code, _out, err = cli(["design", str(path), "--out", str(out_dir)])
    assert code == 2, err
    lines = err.strip().splitlines()
    assert len(lines) == 1 and "constraints.inplane_stiffness[0].test = 'wheel'" in lines[0]
    assert "'platens'" in lines[0] and not out_dir.exists()


def test_a_disc_outside_the_sweep_is_warned() -> None:
    """wheel_warnings names each quantity outside VALIDATED_WHEEL, and none inside it (the
    wheel example's answer, a settled disc: polypropylene 0.3 mm W 10.5, n 6, alpha 146.8, a
    6 mm hole); the wheel example's old design (n 8) is outside it."""
    _n_lo, n_hi = VALIDATED_WHEEL["n"]
    inside = Assembly.identical(
        Layer(W=10.5, n=6, alpha_deg=146.8, material=PP, t=0.3),
        Circle(holes=(Hole("circle", (0.0, 0.0), 6.0),)),
    )
    assert wheel_warnings(inside) == []
    example = Assembly.identical(
        Layer(W=8.5, n=8, alpha_deg=132.42, material=PP, t=0.3),
        Circle(holes=(Hole("circle", (0.0, 0.0), 6.0),)),
    )
    assert {w.code for w in wheel_warnings(example)} == {"wheel-outside-validated-range"}
    many = Assembly.identical(
        Layer(W=3.0, n=int(n_hi) + 10, alpha_deg=132.42, material=PP, t=0.3),
        Circle(holes=(Hole("circle", (0.0, 0.0), 6.0),)),
    )
    text = " ".join(w.message for w in wheel_warnings(many))
    assert "n = " in text and "W = 3 mm" in text
    assert {w.code for w in wheel_warnings(many)} == {"wheel-outside-validated-range"}
    none = Assembly.identical(Layer(W=8.5, n=8, alpha_deg=132.42, material=PP, t=0.3), Circle())
    assert "no" in wheel_warnings(none)[0].message


def test_a_wheel_outside_the_sweep_is_not_certified() -> None:
    """A 2 mm axle hole in a 60-80 mm disc (hole / diameter at most 2/60 = 0.033, below the
    sweep's 0.043, docs/validation/wheel_fe.csv): by default (issue 35) no design is certified
    and the diagnosis names the wheel's range; with trust = "extrapolate" the answer is marked
    extrapolated, not certified, naming it. The same spec with a 6 mm hole is certified inside
    the span of the settled discs (n 6-7, W 8-12 mm, alpha 120-150 deg:
    docs/load_cases.md 9)."""
    from dataclasses import replace

    from corrugate.solver import solve

    small = {"shape": "circle", "holes": [{"shape": "circle", "diameter": 2, "center": [0, 0]}]}
    bounds = [{"min": 20, "eta": e, "test": "wheel"} for e in (0, 45)]
    p = _problem(small, inplane_stiffness=bounds)
    hub = [c.name for c in p.constraints if c.name.startswith("validity.wheel.hub.min")]
    assert len(hub) == 1
    sol = solve(p)
    assert sol.status == "infeasible" and sol.certified
    assert any(hub[0] in d.names for d in sol.diagnosis)
    loose = replace(p, constraints=tuple(c for c in p.constraints if c not in p.ranges))
    loose = replace(loose, trust="extrapolate")
    out = solve(loose)
    assert out.assembly is not None and not out.certified
    assert hub[0] in out.extrapolated
    assert out.certificate.startswith("extrapolated, not certified")
    assert any("hole/diameter" in w.message for w in wheel_warnings(out.assembly))
    six = solve(_problem(CIRCLE, inplane_stiffness=bounds))
    assert six.status == "optimal" and six.certified and six.assembly is not None
    for layer in six.assembly.layers:  # certified inside the settled discs' span
        assert VALIDATED_WHEEL["W"][0] <= layer.W <= VALIDATED_WHEEL["W"][1]
        lo, hi = VALIDATED_WHEEL["alpha"]
        assert lo - 1e-9 <= layer.alpha_deg <= hi + 1e-9
        assert VALIDATED_WHEEL["n"][0] <= layer.n <= VALIDATED_WHEEL["n"][1]


def test_the_wheel_bound_takes_a_compliant_crease_through_k() -> None:
    """A crease spring (docs/offaxis.md, "Compliant creases") reaches the wheel's bound through
    K(eta): the solver's value is c(eta) times analyze's K of the disc with the same crease,
    and below the rigid disc's."""
    from dataclasses import replace

    p = _problem(inplane_stiffness=[{"min": 1, "eta": e, "test": "wheel"} for e in (0, 45)])
    soft = replace(PP, crease_stiffness=0.05)
    cand = replace(p.candidates[0], material=soft)
    p = replace(p, candidates=(cand,))
    W, n, a = 8.5, 8, 132.0
    x = DesignPoints.of(LayerPoints(np.array([float(n)]), np.array([W]), np.array([a])))
    values = point_values(p, cand, cand, x, Tables(p))
    hole = Circle(holes=(Hole("circle", (0.0, 0.0), 6.0),))
    for mat in (soft, PP):
        disc = Assembly.identical(Layer(W=W, n=n, alpha_deg=a, material=mat, t=0.3), hole)
        r = analyze(disc, "refined", [0.0, 45.0])
        for st in r.stiffness:
            q = Quantity.load_case("K", st.eta_deg, "wheel", "free")
            want = wheel_factor(st.eta_deg) * st.K
            if mat is soft:
                assert values[q][0] == pytest.approx(want, rel=1e-9), st.eta_deg
            else:
                assert values[q][0] < want, st.eta_deg
