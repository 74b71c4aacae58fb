"""The validated ranges (corrugate.mechanics.validity, data/validity.toml) are the ranges of the
validation tables they cite: each is recomputed here from docs/validation/*.csv (the designs'
parameters read from the tables' design names and columns), and the shipped docs page that lists
them (docs/validation/ranges.md) shows the same numbers."""

from __future__ import annotations

import csv
import math
import re
from dataclasses import replace
from pathlib import Path
from typing import NamedTuple

import pytest

from corrugate.mechanics.validity import VARIABLES, model_range, model_ranges
from corrugate.mechanics.wheel import VALIDATED_WHEEL
from fe_rows import SETTLED_WHEELS, settled_wheel_rows

ROOT = Path(__file__).resolve().parents[2]
VALIDATION = ROOT / "docs" / "validation"

Layer = tuple[float, int, float, float]  # W mm, n, alpha deg, t mm


def _rows(name: str) -> list[dict[str, str]]:
    lines = [x for x in (VALIDATION / name).read_text().splitlines() if not x.startswith("#")]
    return list(csv.DictReader(lines))


def _layers(design: str) -> list[Layer]:
    """The two layers of a design of load_cases_fe.csv from its name: 'W 10, n 10, alpha 40'
    (identical layers), 'layer 1 W 8, n 8, alpha 84; layer 2 W 10, n 6, alpha 86.9833'; a
    layer without its alpha takes layer 1's (the rectangle 48.2 x 96.4: 18 x 8 sin 42 deg =
    96.4); Dura-Lar 0.125 mm unless the name says 'polypropylene 0.25' (docs/validation/
    load_cases.md); the wider sample of the local term names its sheet before the colon,
    'thin Dura-Lar 0.05: W 10, n 7, alpha 50', 'thick polypropylene 0.5: ...' (mm)."""
    sheet = re.search(r"(?:Dura-Lar|polypropylene) (\d+(?:\.\d+)?)", design.split(":", 1)[0])
    t = float(sheet[1]) if sheet and ":" in design else 0.125
    tail = design.split(":", 1)[1] if ":" in design else design
    out: list[Layer] = []
    for m in re.finditer(r"W (\d+(?:\.\d+)?), n (\d+)(?:, alpha (\d+(?:\.\d+)?))?", tail):
        alpha = float(m[3]) if m[3] else out[0][2]
        out.append((float(m[1]), int(m[2]), alpha, t))
    assert out, design
    return out * 2 if len(out) == 1 else out


def _sweep_layers() -> list[Layer]:
    """The ten designs of sweep_paper.csv ('W=8 n=11 alpha=90'; Dura-Lar 0.125 mm, identical
    layers)."""
    out = []
    for case in {r["case"] for r in _rows("sweep_paper.csv")}:
        m = re.fullmatch(r"W=(\S+) n=(\d+) alpha=(\S+)", case)
        assert m, case
        out += [(float(m[1]), int(m[2]), float(m[3]), 0.125)] * 2
    return out


def _ranges(layers: list[Layer]) -> dict[str, tuple[float, float]]:
    def span(values: list[float]) -> tuple[float, float]:
        return min(values), max(values)

    return {
        "facets": span([n + 1.0 for _, n, _, _ in layers]),
        "W": span([W for W, _, _, _ in layers]),
        "alpha": span([a for _, _, a, _ in layers]),
        "t_over_W": span([t / W for W, _, _, t in layers]),
    }


def _load_case_layers(test: str, off_axis: bool | None = None) -> list[Layer]:
    designs = {
        r["design"]
        for r in _rows("load_cases_fe.csv")
        if r["test"] == test and (off_axis is None or (float(r["eta_deg"]) % 90 != 0) == off_axis)
    }
    assert designs
    return [layer for d in sorted(designs) for layer in _layers(d)]


def _check(name: str, layers: list[Layer]) -> None:
    stated = model_range(name).ranges
    for variable, (lo, hi) in _ranges(layers).items():
        assert stated[variable] == pytest.approx((lo, hi), rel=1e-12), (name, variable)


def test_the_springs_range_is_the_load_case_and_sweep_designs() -> None:
    """Six designs of load_cases_fe.csv (compression and bending rows) and ten of the sweep."""
    layers = _load_case_layers("compression") + _load_case_layers("bending") + _sweep_layers()
    _check("springs", layers)
    assert len({d for d in _load_case_layers("compression")}) >= 6


def test_the_bending_tests_ranges_are_their_rows() -> None:
    """The three-point local term: the bending rows and the sweep's three-point designs; the
    four-point: the bending4-load rows (the test read at its load points, what the four-point
    load case certifies) and the sweep's."""
    _check("three-point", _load_case_layers("bending") + _sweep_layers())
    _check("four-point", _load_case_layers("bending4-load") + _sweep_layers())


def test_the_cantilever_range_is_its_rows() -> None:
    """The cantilever's c = 1.25 was fitted on its cantilever rows only: t/W from 0.05 / 10 =
    0.005 (thin Dura-Lar, issue 35's wider sample) to 0.25 / 5 = 0.05 (the chassis plate's layer
    2) and 0.5 / 10 (thick polypropylene), at least 7 facets (n 6: the chassis plate's layer 1 and
    the layered design's layer 2)."""
    _check("cantilever", _load_case_layers("cantilever"))
    assert model_range("cantilever").ranges["facets"][0] == 7
    assert model_range("cantilever").ranges["t_over_W"][0] == pytest.approx(0.05 / 10)


def test_the_off_axis_range_is_the_rows_off_the_creases() -> None:
    layers = _load_case_layers("compression", True) + _load_case_layers("bending", True)
    _check("off-axis", layers)


def test_the_wheel_range_is_the_settled_discs() -> None:
    """wheel_fe.csv's discs whose series at 0 and 45 deg judge settles (issue 35: the discs on
    the mesh conforming to the rim and the hole, docs/load_cases.md 9): n, W, alpha, t / W and
    hole / diameter (the hub ratio to 6 significant digits, rounded outwards)."""
    rows = settled_wheel_rows(_rows("wheel_fe.csv"))
    assert {r["design"] for r in rows} == SETTLED_WHEELS
    stated = model_range("wheel").ranges
    ns = [int(r["n"]) for r in rows]
    assert stated["facets"] == (min(ns) + 1.0, max(ns) + 1.0)
    for variable, column in (("W", "W_mm"), ("alpha", "alpha_deg")):
        values = [float(r[column]) for r in rows]
        assert stated[variable] == pytest.approx((min(values), max(values)), rel=1e-12)
    tw = [float(r["t_mm"]) / float(r["W_mm"]) for r in rows]
    assert stated["t_over_W"] == pytest.approx((min(tw), max(tw)), rel=1e-12)
    hub = [float(r["hole_mm"]) / float(r["diameter_mm"]) for r in rows]
    lo, hi = stated["hub"]
    assert lo <= min(hub) and max(hub) <= hi
    assert min(hub) - lo <= 1e-6 and hi - max(hub) <= 1e-6  # rounded outwards
    assert VALIDATED_WHEEL["n"] == (min(ns), max(ns))
    assert VALIDATED_WHEEL["hole/diameter"] == stated["hub"]


def test_every_enforced_end_is_a_stated_range_and_the_docs_page_lists_them() -> None:
    """Each model's enforced ends name a variable it states; docs/validation/ranges.md has a row
    per model with its ranges, as the data file gives them."""
    page = (VALIDATION / "ranges.md").read_text()
    for m in model_ranges().values():
        assert m.enforce and m.source and m.label
        for variable, _end in m.enforce:
            assert variable in m.ranges and variable in VARIABLES
        assert f"| `{m.name}` |" in page, m.name
        for variable, (lo, hi) in m.ranges.items():
            assert f"{variable} {lo:.4g}-{hi:.4g}" in page, (m.name, variable)


#: The spans (mm) of capacity_fe.csv's designs that are not their panel's length: the chassis
#: example's 120 mm (docs/validation/capacity.md, "The designs"); the others span the panel.
_CAPACITY_SPANS = {"chassis, joint none": 120.0, "chassis plate": 120.0}
_SHEETS = {"dura-lar": "dura-lar", "pp": "polypropylene", "pc": "polycarbonate"}


class _CapacityDesign(NamedTuple):
    """A design of capacity_fe.csv as its name states it: the sheet's library name, the two
    layers, whether the band joins them, its Young's modulus over the library's (a tolerance
    corner's 'E x 0.9') and the test's direction eta (deg; 'eta 90' before the colon)."""

    sheet: str
    layers: list[Layer]
    bonded: bool
    E_factor: float
    eta: float


def _capacity_designs() -> dict[str, _CapacityDesign]:
    """capacity_fe.csv's designs from their names ('chassis, joint band-edges: pp 0.25, W 16 n
    6 a 90 / W 5 n 27 a 120', 'pc 0.25, W 10 n 13 a 120': one layer named, both alike; 'blimp
    cantilever worst corner, joint band-edges: dura-lar 0.16625 E x 0.9, W 7.9 n 7 a 101 / ...':
    the sheet's modulus scaled; 'eta 90, joint none: ...': the test along layer 2's creases)."""
    out = {}
    for name in {r["design"] for r in _rows("capacity_fe.csv")}:
        head, _, tail = name.rpartition(":")
        sheet = re.search(r"(dura-lar|pp|pc) (\d+(?:\.\d+)?)", tail or name)
        assert sheet, name
        t = float(sheet[2])
        found = re.findall(r"W (\d+(?:\.\d+)?) n (\d+) a (\d+(?:\.\d+)?)", tail or name)
        layers = [(float(W), int(n), float(a), t) for W, n, a in found]
        assert layers, name
        scale = re.search(r"E x (\d+(?:\.\d+)?)", tail or name)
        eta = re.search(r"eta (\d+)", head)
        out[name] = _CapacityDesign(
            _SHEETS[sheet[1]],
            layers * 2 if len(layers) == 1 else layers,
            "band" in head,
            float(scale[1]) if scale else 1.0,
            float(eta[1]) if eta else 0.0,
        )
    return out


def _depth(layer: Layer) -> float:
    W, _, alpha, _ = layer
    return W * math.cos(math.radians(alpha) / 2.0)


def test_the_capacity_ranges_are_its_fe_rows() -> None:
    """The capacity model's facet modes: every design of capacity_fe.csv; the band's walls: the
    designs with the band bonded along the edges, their sheet t and t_d / h1 (t_d = h1 + h2)."""
    designs = _capacity_designs()
    assert len(designs) >= 13
    # the model states a capacity along either layer's creases only (eta 0 and 90 deg,
    # corrugate.analysis.load_case.load_case_capacity): both directions have rows, with and
    # without the band
    for bonded in (False, True):
        assert {d.eta for d in designs.values() if d.bonded == bonded} == {0.0, 90.0}
    _check("capacity", [layer for d in designs.values() for layer in d.layers])
    band = [d.layers for d in designs.values() if d.bonded]
    stated = model_range("band-walls").ranges
    ts = [layers[0][3] for layers in band]
    assert stated["t"] == (min(ts), max(ts)) == (0.125, 0.5)
    td = [1.0 + _depth(layers[1]) / _depth(layers[0]) for layers in band]
    assert stated["td_over_h1"] == pytest.approx((min(td), max(td)), rel=1e-12)


def test_the_capacity_model_is_at_or_below_every_fe_row() -> None:
    """A certificate may not exceed the part (issue 34, docs/validation/capacity.md): the
    model's first failure (no safety factor; the walls composite with layer 1, docs/
    load_cases.md 10.5) is at or below the FE's first buckling of every design of
    capacity_fe.csv: the lower of its dead and held series' estimates (Richardson where the
    three finest meshes are asymptotic; a series that still falls, without an estimate: 0.9 of
    its finest value), and, where a series is settled
    by :func:`corrugate.fea.extrapolate.judge`, that verdict is holds."""
    import corrugate
    from corrugate import Assembly, get_material
    from corrugate.analysis.evaluate import analyze
    from corrugate.analysis.load_case import LoadCase, load_case_capacity
    from corrugate.fea.extrapolate import extrapolate, judge
    from corrugate.geometry.layouts import Rectangle

    rows = _rows("capacity_fe.csv")
    for name, d in _capacity_designs().items():
        mine = [r for r in rows if r["design"] == name]
        test = mine[0]["test"]
        m = get_material(d.sheet)
        m = replace(m, E=m.E * d.E_factor)
        (W1, n1, a1, t), (W2, n2, a2, _) = d.layers
        a = Assembly(
            corrugate.Layer(W1, n1, a1, m, t), corrugate.Layer(W2, n2, a2, m, t), Rectangle()
        )
        span = next((s for k, s in _CAPACITY_SPANS.items() if name.startswith(k)), None)
        joint = "band-edges" if d.bonded else "none"
        r = analyze(a, "refined", eta_deg=[d.eta], joint=joint)
        cap = load_case_capacity(r, LoadCase(test, 1.0, span=span), d.eta, safety_factor=1.0)
        assert cap is not None, name
        fe = []
        for step in ("dead", "held"):
            series = {int(x["along"]): float(x["load_N"]) for x in mine if x["step"] == step}
            if not series:
                continue
            e = extrapolate(series, "min")
            # no estimate (a series still falling): its finest value, with a tenth kept back
            fe.append(e.value if e.value is not None else 0.9 * series[max(series)])
            verdict = judge(series, cap.load, "min")
            assert verdict.verdict != "fails", (name, step, verdict)
        assert fe and cap.load <= min(fe), (name, cap.load, fe)


@pytest.mark.slow
def test_the_blimp_cantilevers_printed_capacity_holds_at_its_worst_tolerance_corners() -> None:
    """examples/blimp_gripper_cantilever.toml prints "holds X N at safety factor 2 ... for every
    part within" the default tolerances (docs/tolerances.md): X times the factor is at or below
    the FE's first buckling at its two worst corners in capacity_fe.csv (docs/validation/
    capacity.md, "The worst tolerance corner of a printed guarantee"; each series' value as the
    other capacity rows take it: Richardson where asymptotic, else 0.9 of its still falling
    finest value), and at or below the model's first failure at each corner (the certified
    value is an interval bound over the box that holds them)."""
    import corrugate
    from corrugate import Assembly, get_material
    from corrugate.analysis.evaluate import analyze
    from corrugate.analysis.load_case import LoadCase, load_case_capacity
    from corrugate.fea.extrapolate import extrapolate
    from corrugate.geometry.layouts import Rectangle
    from corrugate.solver import Problem, solve
    from corrugate.spec.schema import load_spec

    p = Problem.from_spec(load_spec(ROOT / "examples" / "blimp_gripper_cantilever.toml"))
    sol = solve(p)  # explained: its constraints' reports
    assert sol.assembly is not None and sol.assembly.layer1.t == 0.175
    (held,) = [c for c in sol.constraints if c.name.endswith("(held at the safety factor)")]
    assert held.capacity is not None
    claim = held.value * held.capacity.safety_factor  # N: the load at the first failure
    rows = _rows("capacity_fe.csv")
    corners = {n: d for n, d in _capacity_designs().items() if "corner" in n}
    assert len(corners) == 2
    for name, d in corners.items():
        series = {
            int(x["along"]): float(x["load_N"])
            for x in rows
            if x["design"] == name and x["step"] == "dead"
        }
        e = extrapolate(series, "min")
        fe = e.value if e.value is not None else 0.9 * series[max(series)]
        assert claim <= fe, (name, claim, fe)
        m = get_material(d.sheet)
        m = replace(m, E=m.E * d.E_factor)
        (W1, n1, a1, t), (W2, n2, a2, _) = d.layers
        a = Assembly(
            corrugate.Layer(W1, n1, a1, m, t), corrugate.Layer(W2, n2, a2, m, t), Rectangle()
        )
        r = analyze(a, "refined", eta_deg=[0.0], joint="band-edges")
        cap = load_case_capacity(r, LoadCase("cantilever", 1.0), 0.0, safety_factor=1.0)
        assert cap is not None and claim <= cap.load, (name, claim, cap.load)
