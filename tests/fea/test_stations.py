"""Node lines at a fixture's stations on the structured mesh (corrugate.fea.stations): spans
shorter than the panel in three-point, four-point and cantilever bending, with and without the
connector band, checked on the decks' geometry (no CalculiX)."""

from __future__ import annotations

import numpy as np
import pytest

from corrugate import Assembly, Layer, get_material
from corrugate.core.errors import InputError
from corrugate.fea.assembly import AssemblyMesh, assembly_deck
from corrugate.fea.stations import station_map
from corrugate.geometry.layouts import Rectangle

A = Assembly(
    Layer(W=5.0, n=5, alpha_deg=84.0, material=get_material("dura-lar"), t=0.125),
    Layer(W=4.0, n=7, alpha_deg=100.0, material=get_material("dura-lar"), t=0.125),
    Rectangle(),
)


def test_the_map_moves_the_nearest_line_of_the_interval_onto_the_station() -> None:
    """Hand derivation: node lines 0, 1, 2, 3, 4 with creases at 0, 2, 4 and a station at 0.3:
    the interval [0, 2] holds two elements; the station's share 0.15 rounds to no line, so the
    first inner line (1) moves to 0.3 and the map is linear on [0, 1] -> [0, 0.3] and
    [1, 2] -> [0.3, 2]; a station already on a line (3) moves nothing."""
    grid = np.arange(5.0)
    phi = station_map(grid, (0.0, 2.0, 4.0), (0.3, 3.0), 1e-9)
    assert phi(np.array([0.0, 0.5, 1.0, 1.5, 2.0, 3.0, 4.0])) == pytest.approx(
        [0.0, 0.15, 0.3, 1.15, 2.0, 3.0, 4.0]
    )
    # two stations in one interval take two lines, in order; a third does not fit
    phi2 = station_map(np.linspace(0.0, 2.0, 5), (0.0, 2.0), (0.2, 0.3), 1e-9)
    assert phi2(np.array([0.5, 1.0])) == pytest.approx([0.2, 0.3])
    with pytest.raises(InputError, match=r"^mesh.along = 2 .* a finer mesh"):
        station_map(np.array([0.0, 1.0, 2.0]), (0.0, 2.0), (0.2, 0.3), 1e-9, along=2)


def _deck(test: str, eta: float, span: float, connectors: bool) -> tuple[dict, dict, str]:
    deck, info = assembly_deck(A, test, AssemblyMesh(2), eta, span=span, connectors=connectors)
    lines = deck.splitlines()
    nodes: dict[int, np.ndarray] = {}
    i = lines.index("*NODE") + 1
    while not lines[i].startswith("*"):
        n, *xyz = lines[i].split(",")
        nodes[int(n)] = np.array([float(v) for v in xyz])
        i += 1
    sets: dict[str, list[int]] = {}
    for j, line in enumerate(lines):
        if line.startswith("*NSET,NSET="):
            name, members, k = line.split("=")[1], [], j + 1
            while not lines[k].startswith("*"):
                members += [int(v) for v in lines[k].split(",")]
                k += 1
            sets[name] = members
    assert info.span == span
    return nodes, sets, deck


@pytest.mark.parametrize("connectors", [False, True])
@pytest.mark.parametrize("eta", [0.0, 90.0])
@pytest.mark.parametrize("test", ["three-point", "four-point", "cantilever"])
def test_the_fixture_lines_lie_at_the_span_and_the_facets_stay_flat(
    test: str, eta: float, connectors: bool
) -> None:
    """Over a span s = 0.8 L centred on the panel (the cantilever: the clamp up to L - s), every
    supported, loaded and gauged node lies on its station, the stations have nodes of every part,
    every element's corners stay coplanar (a facet stays flat: its nodes lifted back onto the
    zig-zag) and no element turns over."""
    axis = 1 if eta == 0.0 else 0
    L = (A.Lx, A.Ly)[axis]
    s = 0.8 * L
    a0 = (L - s) / 2
    nodes, sets, deck = _deck(test, eta, s, connectors)
    parts = 3 if connectors else 2

    def at(name: str) -> np.ndarray:
        return np.array([nodes[n][axis] for n in sets[name]])

    for k in range(1, parts + 1):
        if test == "cantilever":
            root = at(f"ROOT{k}")
            assert root.max() == pytest.approx(L - s, abs=1e-7)
            assert np.isclose(root, L - s, atol=1e-7).sum() >= 2  # the clamp's edge line
            assert at(f"TIP{k}") == pytest.approx(np.full(len(sets[f"TIP{k}"]), L), abs=1e-7)
            continue
        sup = at(f"SUP{k}")
        assert np.minimum(abs(sup - a0), abs(sup - a0 - s)).max() < 1e-7
        assert sup.min() < L / 2 < sup.max()
        if test == "four-point":
            loads = at(f"LOAD{k}")
            gauges = at(f"GAUGE{k}")
            q1, q3 = a0 + s / 4, a0 + 3 * s / 4
            g1, g3 = a0 + 3 * s / 8, a0 + 5 * s / 8
            assert np.minimum(abs(loads - q1), abs(loads - q3)).max() < 1e-7
            assert np.minimum(abs(gauges - g1), abs(gauges - g3)).max() < 1e-7
            assert loads.min() < L / 2 < loads.max() and gauges.min() < L / 2 < gauges.max()
    # every element: corners coplanar, and its normal keeps the side of the unmoved mesh's
    full, _ = assembly_deck(A, test, AssemblyMesh(2), eta, connectors=connectors)
    old: dict[int, np.ndarray] = {}
    fl = full.splitlines()
    i = fl.index("*NODE") + 1
    while not fl[i].startswith("*"):
        n, *xyz = fl[i].split(",")
        old[int(n)] = np.array([float(v) for v in xyz])
        i += 1
    el: list[str] = []
    dl = deck.splitlines()
    for j, line in enumerate(dl):
        if line.startswith("*ELEMENT,TYPE=S8R"):
            k = j + 1
            while not dl[k].startswith("*"):
                el.append(dl[k])
                k += 1
    assert el
    for line in el:
        ids = [int(v) for v in line.split(",")[1:5]]
        p = np.array([nodes[n] for n in ids])
        normal = np.cross(p[2] - p[0], p[3] - p[1])
        assert abs(np.dot(normal / np.linalg.norm(normal), p[1] - p[0])) < 1e-7
        q = np.array([old[n] for n in ids])
        assert np.dot(normal, np.cross(q[2] - q[0], q[3] - q[1])) > 0


def test_a_span_equal_to_the_panel_length_moves_nothing() -> None:
    """span = L is the panel supported at its ends: the same deck as without a span."""
    for test in ("three-point", "four-point", "cantilever"):
        for connectors in (False, True):
            with_span, _ = assembly_deck(
                A, test, AssemblyMesh(2), 0.0, span=A.Ly, connectors=connectors
            )
            without, _ = assembly_deck(A, test, AssemblyMesh(2), 0.0, connectors=connectors)
            assert with_span == without
