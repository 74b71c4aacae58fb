"""Which FE fixture checks which constraint (corrugate.fea.verify.twin_of), without CalculiX."""

from __future__ import annotations

from dataclasses import replace

import pytest

from corrugate import Assembly, Layer, get_material
from corrugate.fea.verify import Twin, behavioural, twin_of
from corrugate.geometry.layouts import Rectangle
from corrugate.mechanics.load_cases import CANTILEVER, FOUR_POINT, THREE_POINT
from corrugate.solver.quantity import Quantity

A = Assembly.identical(
    Layer(W=5.0, n=5, alpha_deg=84.0, material=get_material("dura-lar"), t=0.125)
)


@pytest.mark.parametrize(
    ("key", "test", "read", "a"),
    [
        ("K@0", "platens", "K", 0.0),
        ("Kplat@90", "platens", "K", 0.0),
        ("Kframe@45", "frame", "K", 0.0),
        ("EI@0", "four-point", "pure-EI", 0.0),
        ("D@90", "four-point", "pure-D", 0.0),
        ("D@30", "four-point", "pure-D", 0.0),
        ("EI3pt@0", "three-point", "EI", THREE_POINT.form.a),  # type: ignore[union-attr]
        ("k4pt@0", "four-point", "k", FOUR_POINT.form.a),  # type: ignore[union-attr]
        ("Dcant@90", "cantilever", "D", CANTILEVER.form.a),  # type: ignore[union-attr]
        ("D3pt@30", "three-point", "D", THREE_POINT.form.a),  # type: ignore[union-attr]
        ("Pb@0", "platens", "Pb", 0.0),
        ("Pmax3pt@0", "three-point", "Pmax", 0.0),
        ("Pmaxcant@90", "cantilever", "Pmax", 0.0),
    ],
)
def test_each_constraint_has_the_fixture_of_its_test(
    key: str, test: str, read: str, a: float
) -> None:
    t = twin_of(Quantity.parse(key), A)
    assert isinstance(t, Twin), t
    assert (t.test, t.read, t.a) == (test, read, a)
    # the buckling load is the platens run as a linear buckling step, every other a static one
    assert t.step.name == ("buckle" if key.startswith(("Pb", "Pmax")) else "static")
    assert t.eta == Quantity.parse(key).eta
    coupon = t.test != "frame" and t.eta not in (0.0, 90.0)  # the frame: the whole panel
    assert t.shifted == coupon  # a coupon off the creases runs at several positions


@pytest.mark.parametrize(
    ("key", "why"),
    [
        ("Dcant@30/L=15", "span 15 mm: the FE takes a span up to the panel's length"),
        ("k3pt@0/L=25", "span 25 mm"),  # longer than the 20.07 mm panel
        ("EIframe@0", "bending in a frame"),
        ("EI@45", "EI off the crease directions"),
        ("k3pt@45", "off the crease directions"),
        ("Pmax3pt@30", "a load capacity off the crease directions"),
        ("Pmax3pt@0/L=25", "span 25 mm"),
        ("Pb@45", "buckling off the crease directions"),
    ],
)
def test_what_has_no_twin_says_why(key: str, why: str) -> None:
    t = twin_of(Quantity.parse(key), A)
    assert isinstance(t, str) and t.startswith("no FE twin yet"), t
    assert why in t


def test_a_span_equal_to_the_panel_length_has_its_twin_and_the_band_joint_only_on_axis() -> None:
    L = A.Ly
    assert isinstance(twin_of(Quantity.parse(f"k3pt@0/L={L:.12g}"), A), Twin)
    r = Assembly(A.layer1, A.layer2, Rectangle())
    assert isinstance(twin_of(Quantity.parse("K@0"), r, "band-edges"), Twin)
    assert isinstance(twin_of(Quantity.parse("K@30"), r, "band-edges"), str)
    t = twin_of(Quantity.parse("k3pt@0"), A, load=2.0)
    assert isinstance(t, Twin) and t.load == 2.0


@pytest.mark.parametrize(
    ("key", "test"),
    [
        ("k3pt@0/L=15", "three-point"),
        ("k4pt@0/L=15", "four-point"),
        ("kcant@90/L=15", "cantilever"),
        ("D4pt@90/L=12.5", "four-point"),
        ("Pmax4pt@0/L=15", "four-point"),
        ("Pmaxcant@0/L=15", "cantilever"),
    ],
)
def test_a_span_shorter_than_the_panel_is_its_twin_span(key: str, test: str) -> None:
    """Every bending test over a span shorter than the 20.07 mm panel along a crease direction
    has its twin over that span (issue 35 item 4: no "no FE twin yet" for such a span)."""
    q = Quantity.parse(key)
    t = twin_of(q, A, load=1.0)
    assert isinstance(t, Twin) and t.test == test and t.span == q.span
    assert not t.shifted


def test_the_three_point_deck_supports_a_shorter_span_inside_the_panel() -> None:
    """The deck's support sets lie on the lines (L - s) / 2 and (L + s) / 2, the load line at
    L / 2, and the span the result is read over is s; spans the fixture cannot take are
    refused."""
    import numpy as np

    from corrugate.core.errors import InputError
    from corrugate.fea.assembly import AssemblyMesh, assembly_deck

    L, s = A.Ly, 15.0
    deck, info = assembly_deck(A, "three-point", AssemblyMesh(2), 0.0, span=s)
    assert info.span == s
    lines = deck.splitlines()
    nodes: dict[int, tuple[float, ...]] = {}
    i = lines.index("*NODE") + 1
    while not lines[i].startswith("*"):
        n, *xyz = lines[i].split(",")
        nodes[int(n)] = tuple(float(v) for v in xyz)
        i += 1

    def members(name: str) -> list[int]:
        j = lines.index(f"*NSET,NSET={name}") + 1
        out: list[int] = []
        while not lines[j].startswith("*"):
            out += [int(v) for v in lines[j].split(",")]
            j += 1
        return out

    for k in (1, 2):
        ys = np.array([nodes[n][info.axis] for n in members(f"SUP{k}")])
        near = np.minimum(np.abs(ys - (L - s) / 2), np.abs(ys - (L + s) / 2))
        assert near.max() < 1e-7 and ys.min() < L / 2 < ys.max()  # both lines, nothing else
        mid = np.array([nodes[n][info.axis] for n in members(f"MID{k}")])
        assert np.allclose(mid, L / 2, atol=1e-7)
    for test, span in (("three-point", L + 1.0), ("three-point", 0.0), ("platens", 10.0)):
        with pytest.raises(InputError, match="span"):
            assembly_deck(A, test, AssemblyMesh(2), 0.0, span=span)  # type: ignore[arg-type]


def test_only_behavioural_constraints_are_checked() -> None:
    rows = [
        {"name": "side", "quantity": "Lx"},
        {"name": "len", "quantity": "length@0"},
        {"name": "ei", "quantity": "EI@0"},
        {"name": "d", "quantity": "k3pt@0/L=120"},
    ]
    assert [c["name"] for c, _ in behavioural(rows)] == ["ei", "d"]


def test_a_failed_run_at_any_coupon_position_leaves_the_row_unproven(
    monkeypatch: pytest.MonkeyPatch,
) -> None:
    """Off the crease directions a position whose run fails (e.g. a ccx time-out) could hide the
    worst value: the row is not converged (not "holds") and names the failure, though every
    value that was computed meets the bound (a stand-in for CalculiX: K = 2 + 8 / mesh^2 N/mm,
    an exact series of order 2 whose limit 2 is above the bound 1); without the failure the
    same series holds at 2 / 4 / 8 / 16 (both extrapolations exactly 2)."""
    from types import SimpleNamespace

    from corrugate.fea import verify
    from corrugate.fea.ccx import SolverError

    fail = [True]

    def fake(assembly, test, mesh, eta, *, shift=0.0, **kw):  # type: ignore[no-untyped-def]
        if fail[0] and shift == 0.0 and mesh.along == 4:
            raise SolverError("ccx timed out after 900 s")
        return SimpleNamespace(K=2.0 + 8.0 / mesh.along**2)

    monkeypatch.setattr(verify, "solve_assembly", fake)
    c = [{"name": "k", "quantity": "K@15", "sense": "min", "bound": 1.0, "value": 3.0}]
    for screen in (True, False):
        v = verify.verify_design(A, c, meshes=(2, 4, 8, 16), shifts=(0.0, 0.5), screen=screen)
        [row] = v.rows
        assert not row.holds and row.verdict == "not converged" and v.exit_code == 5
        assert "shift 0: 4/facet not run: ccx timed out" in row.note
        assert "not proven" in row.note
    fail[0] = False
    ok = verify.verify_design(A, c, meshes=(2, 4, 8, 16), shifts=(0.0, 0.5))
    assert ok.holds and ok.verdict == "holds" and ok.exit_code == 0
    assert ok.rows[0].fe == pytest.approx(2.0, rel=1e-12)


def test_the_k45_series_runs_on_to_16_per_facet_and_is_not_converged_there(
    monkeypatch: pytest.MonkeyPatch,
) -> None:
    """A stand-in for CalculiX returning the K(45) series of docs/fea.md 6 (2.073 / 1.312 /
    1.117 / 1.035 N/mm at 2 / 4 / 8 / 16 per facet; the coupon at shift 0.5 0.1 stiffer, screened
    out at 4 per facet, more than 5 % above). From 2 / 4 / 8 the series is one extrapolation
    short, so the worst position (shift 0) runs at 16; by hand d = 0.761, 0.195, 0.082: R1 =
    1.117 - 0.195 / (0.761 / 0.195 - 1) = 1.0498, R2 = 1.035 - 0.082 / (0.195 / 0.082 - 1) =
    0.9755. They differ by 0.074, three times the margin 0.0245: at the cap of 16 the row is
    "not converged" (exit 5), not "holds" and not "fails"; capped at 8 it is not converged
    without running on."""
    from types import SimpleNamespace

    from corrugate.fea import verify

    values = {2: 2.073, 4: 1.312, 8: 1.117, 16: 1.035}
    calls: list[tuple[int, float]] = []

    def fake(assembly, test, mesh, eta, *, shift=0.0, **kw):  # type: ignore[no-untyped-def]
        calls.append((mesh.along, shift))
        return SimpleNamespace(K=values[mesh.along] + (0.1 if shift else 0.0))

    monkeypatch.setattr(verify, "solve_assembly", fake)
    lines: list[str] = []
    c = [{"name": "k45", "quantity": "K@45", "sense": "min", "bound": 1.0, "value": 1.0027}]
    v = verify.verify_design(A, c, shifts=(0.0, 0.5), progress=lines.append)
    [row] = v.rows
    assert (16, 0.0) in calls and (16, 0.5) not in calls
    d2, d3 = 1.312 - 1.117, 1.117 - 1.035
    assert row.fe == pytest.approx(1.035 - d3 / (d2 / d3 - 1), rel=1e-12)
    assert row.fe == pytest.approx(0.9755, abs=1e-4)
    assert row.fe_series[16] == pytest.approx(1.035) and row.shift == 0.0
    assert row.verdict == "not converged" and v.verdict == "not converged"
    assert not row.holds and v.exit_code == 5
    assert "extended to 16 per facet at shift 0" in row.extended
    assert "four meshes" in row.extended and row.extended in row.note
    assert "not converged at shift 0 at 16 per facet" in row.note and "1.0498" in row.note
    assert row.as_json()["verdict"] == "not converged"
    assert v.as_json()["verdict"] == "not converged"
    assert any("extending" in x and "~8 GB" in x for x in lines)
    calls.clear()
    capped = verify.verify_design(A, c, shifts=(0.0, 0.5), max_mesh=8)
    assert max(a for a, _ in calls) == 8
    assert capped.verdict == "not converged" and capped.rows[0].extended == ""
    assert capped.rows[0].fe == pytest.approx(1.0498, abs=1e-4)  # its best estimate, not 1.117


def test_a_series_is_refined_until_it_settles_and_every_position_counts(
    monkeypatch: pytest.MonkeyPatch,
) -> None:
    """Two coupon positions, both exact series c + A / mesh (order 1; 2 / 4 / 8 are one
    extrapolation short): each position runs on to 16 and holds or fails by its own limit c.
    Limits 1.2 and 1.5 against a minimum of 1: holds (exit 0), the worst (1.2, shift 0.5)
    counts. Limits 0.8 and 1.5: shift 0 reads 1.1 / 0.95 / 0.875, already below the bound and
    softening, so it fails from 2 / 4 / 8 (exit 1; its estimate the exact limit 0.8) and no
    position runs on."""
    from types import SimpleNamespace

    from corrugate.fea import verify

    limits = {0.0: 1.5, 0.5: 1.2}
    calls: list[tuple[int, float]] = []

    def fake(assembly, test, mesh, eta, *, shift=0.0, **kw):  # type: ignore[no-untyped-def]
        calls.append((mesh.along, shift))
        return SimpleNamespace(K=limits[shift] + 0.6 / mesh.along)

    monkeypatch.setattr(verify, "solve_assembly", fake)
    c = [{"name": "k", "quantity": "K@30", "sense": "min", "bound": 1.0, "value": 1.1}]
    v = verify.verify_design(A, c, shifts=(0.0, 0.5), screen=False)
    [row] = v.rows
    assert {(16, 0.0), (16, 0.5)} <= set(calls)
    assert row.verdict == "holds" and v.exit_code == 0
    assert row.shift == 0.5 and row.fe == pytest.approx(1.2, rel=1e-12)
    limits[0.0] = 0.8
    calls.clear()
    v = verify.verify_design(A, c, shifts=(0.0, 0.5), screen=False)
    [row] = v.rows
    assert row.verdict == "fails" and v.exit_code == 1
    assert row.shift == 0.0 and row.fe == pytest.approx(0.8, rel=1e-12)
    assert max(a for a, _ in calls) == 8 and "moves away" in row.how


def test_a_constraint_without_a_twin_is_not_checked_not_failed() -> None:
    """A constraint with no FE twin (EI off the crease directions) is its own verdict, "not
    checked" (exit 6 when nothing worse), never "fails"; a design whose every row has no twin
    is not checked; a row's verdict sets its holds."""
    from corrugate.fea import verify
    from corrugate.fea.verify import Row, Verification

    c = [{"name": "ei", "quantity": "EI@30", "sense": "min", "bound": 1.0, "value": 2.0}]
    v = verify.verify_design(A, c)
    [row] = v.rows
    assert row.verdict == "not checked" and not row.holds and "no FE twin" in row.note
    assert v.verdict == "not checked" and v.exit_code == 6 and v.no_failure
    held = Row("a", "EI@0", "min", "", 1.0, 2.0, {2: 2.0}, 2.0, holds=True)
    failed = Row("b", "EI@0", "min", "", 1.0, 2.0, {2: 0.5}, 0.5)
    open_ = replace(failed, verdict="not converged")
    assert failed.verdict == "fails" and held.verdict == "holds" and not open_.holds
    assert Verification((held, row), (2,)).exit_code == 6
    assert Verification((held, row, open_), (2,)).exit_code == 5
    assert Verification((open_, failed, row), (2,)).exit_code == 1
    assert Verification((held,), (2,)).exit_code == 0 and Verification((), (2,)).exit_code == 0
    with pytest.raises(ValueError, match="verdict must be one of"):
        Row("c", "EI@0", "min", "", 1.0, 2.0, verdict="maybe")


def test_a_solutions_reports_are_checked_as_its_design_json_entries() -> None:
    """``verify`` of a run reads the solution's constraint reports, ``corrugate verify`` of its
    folder design.json's entries: both give the same checked constraints (name, quantity,
    sense, unit, bound, model value and a deflection's load), and only the behavioural ones
    (EI, a deflection's P / delta; not the sizes)."""
    import json

    from corrugate.fea.verify import Checked
    from corrugate.solver import Problem, solve
    from corrugate.spec.schema import parse_spec_text

    spec = parse_spec_text(
        """
name = "checked"
tolerances = "none"  # nominal: verify checks the nominal part here (docs/tolerances.md)
joint = "band-edges"  # free outermost facets cannot hold 1 N at the safety factor
[material]
name = "dura-lar"
thickness = "0.125 mm"
[variables]
W = { min = "4 mm", max = "8 mm", step = "1 mm" }
n = { min = 3, max = 6 }
alpha = { min = "60 deg", max = "120 deg", step = "2 deg" }
[constraints]
side = { min = "20 mm", max = "30 mm" }
flexural_rigidity = [{ min = "5 mN*m^2", eta = "0 deg" }]
[[constraints.deflection]]
test = "three-point"
load = "1 N"  # 2 N: no design since the band's composite walls (docs/load_cases.md 10.5)
max = "0.5 mm"
eta = "0 deg"
[objective]
minimize = "mass"
"""
    )
    sol = solve(Problem.from_spec(spec))
    entries = json.loads(json.dumps(sol.to_dict()))["constraints"]  # as design.json holds them
    typed = [c for c in map(Checked.of, sol.constraints) if c is not None]
    read = [c for c in map(Checked.of, entries) if c is not None]
    assert typed == read
    assert [(c.quantity.key, c.unit, c.load) for c in typed] == [
        ("EI@0", "N*mm^2", None),
        ("k3pt@0", "mm", 1.0),  # a deflection: its bound in mm under its load
        ("Pmax3pt@0", "N", None),  # and that load held at the safety factor (its capacity)
    ]
    assert typed[1].bound == pytest.approx(0.5)


def test_a_load_capacity_is_the_first_buckling_load_over_its_safety_factor(
    monkeypatch: pytest.MonkeyPatch,
) -> None:
    """A load capacity (Pmax: a deflection's load held at the safety factor) in design.json
    carries the capacity at the safety factor (``value``) and the model's failure loads
    (``failure_loads_N``): the safety factor is their least over the value, 1.2 / 0.6 = 2 here.
    Its FE twin is the three-point fixture as a linear buckling run (a stand-in for CalculiX:
    3 / 2.5 / 2.4 / 2.38 N at 2 / 4 / 8 / 16 per facet, 2.375 + 0.625 (2 / mesh)^p with p =
    log2 5: both extrapolations 2.375 N) over that factor, 1.1875 N, against the bound 1 N: it
    holds; at a bound of 1.3 N it fails. Without failure loads there is no factor and no twin:
    not checked."""
    from types import SimpleNamespace
    from typing import Any

    from corrugate.fea import verify

    loads = {2: 3.0, 4: 2.5, 8: 2.4, 16: 2.38}
    steps: list[str] = []

    def fake(assembly: Any, test: str, mesh: Any, eta: float, **kw: Any) -> Any:
        steps.append(kw["step"].name)
        return SimpleNamespace(value=lambda: loads[mesh.along])

    monkeypatch.setattr(verify, "solve_assembly", fake)
    c = {
        "name": "cap",
        "quantity": "Pmax3pt@0",
        "sense": "min",
        "bound": 1.0,
        "value": 0.6,
        "unit": "N",
        "failure_loads_N": {"yield": 5.0, "edge-facet-buckling": 1.2},
    }
    assert verify.safety_factor(c) == pytest.approx(2.0)
    [row] = verify.verify_design(A, [c]).rows
    assert row.fe == pytest.approx(2.375 / 2.0, rel=1e-12) and row.holds
    assert row.fe_series == {2: 1.5, 4: 1.25, 8: 1.2, 16: 1.19} and set(steps) == {"buckle"}
    assert "over the safety factor 2" in row.note and "buckling" in row.test
    [tight] = verify.verify_design(A, [{**c, "bound": 1.3}]).rows
    assert not tight.holds and tight.verdict == "fails"
    [none] = verify.verify_design(A, [{k: v for k, v in c.items() if k != "failure_loads_N"}]).rows
    assert none.verdict == "not checked" and "safety factor" in none.note and not none.fe_series


def test_a_capacity_under_tolerances_is_judged_at_its_stated_safety_factor(
    monkeypatch: pytest.MonkeyPatch,
) -> None:
    """Under tolerances (docs/tolerances.md) the capacity is the worst part's, below the nominal
    first failure over the factor: the chassis plate's design.json of 2026-12-07 had 56.92 N nominal
    (yield) and a capacity of 15.258 N at safety factor 2, whose quotient 3.73 verify took as the
    factor before issue 35. design.json now states the factor; verify reads it: the stand-in's
    2.375 N extrapolated over 2 is 1.1875 N (over the quotient 1.2 / 0.3 = 4 it would be 0.594 N,
    below the bound of 1 N). A design.json without it (written before) still infers the
    quotient; a factor that is not a positive number is refused by design.json's schema."""
    from types import SimpleNamespace
    from typing import Any

    from corrugate.fea import verify

    loads = {2: 3.0, 4: 2.5, 8: 2.4, 16: 2.38}

    def fake(assembly: Any, test: str, mesh: Any, eta: float, **kw: Any) -> Any:
        return SimpleNamespace(value=lambda: loads[mesh.along])

    monkeypatch.setattr(verify, "solve_assembly", fake)
    c = {
        "name": "cap",
        "quantity": "Pmax3pt@0",
        "sense": "min",
        "bound": 1.0,
        "value": 0.3,  # the worst part's capacity at the factor: below 1.2 / 2
        "unit": "N",
        "failure_loads_N": {"yield": 5.0, "edge-facet-buckling": 1.2},
        "safety_factor": 2.0,
    }
    assert verify.safety_factor(c) == 2.0
    [row] = verify.verify_design(A, [c]).rows
    assert row.fe == pytest.approx(2.375 / 2.0, rel=1e-12) and row.holds
    assert "over the safety factor 2" in row.note
    old = {k: v for k, v in c.items() if k != "safety_factor"}
    assert verify.safety_factor(old) == pytest.approx(4.0)
    from pydantic import ValidationError

    from corrugate.export.record_schema import _Constraint

    assert _Constraint.model_validate(c).safety_factor == 2.0
    for bad in (-2.0, 0.0, float("nan"), "2"):
        with pytest.raises(ValidationError, match="safety_factor"):
            _Constraint.model_validate({**c, "safety_factor": bad})
