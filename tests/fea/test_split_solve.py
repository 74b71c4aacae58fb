"""The memory-saving solver options of corrugate.fea.assembly (docs/fea.md 2.9): each layer in a
ccx run of its own (``split``) and meshes coarser along the creases (``AssemblyMesh.aspect``)."""

from __future__ import annotations

import math
import re

import numpy as np
import pytest

from corrugate import Assembly, Layer, get_material
from corrugate.core.errors import InputError
from corrugate.fea.assembly import AssemblyMesh, _decks, solve_assembly
from corrugate.fea.shells import oblique_shells
from corrugate.fea.steps import LinearBuckling


@pytest.fixture(scope="module")
def small() -> Assembly:
    layer = Layer(W=5.0, n=7, alpha_deg=120.0, material=get_material("dura-lar"), t=0.1)
    return Assembly.identical(layer)


def _node_count(deck: str) -> int:
    """Node lines of a deck's *NODE blocks, read back from its text."""
    count, inside = 0, False
    for line in deck.splitlines():
        if line.startswith("*"):
            inside = line.upper().startswith("*NODE") and "PRINT" not in line.upper()
        elif inside:
            count += 1
    return count


def test_split_decks_hold_one_layer_each_with_its_own_fixtures(small: Assembly) -> None:
    """Read back: the split decks' nodes add up to the one deck's, and each names the sets,
    elements and material of its own layer only (no node or set shared: the system is
    block-diagonal, so the split is the same solve)."""
    for test, eta in (("three-point", 0.0), ("platens", 30.0)):
        ((whole, info),) = _decks(small, test, AssemblyMesh(2), eta)
        parts = _decks(small, test, AssemblyMesh(2), eta, split=True)
        assert len(parts) == 2
        assert sum(_node_count(d) for d, _ in parts) == _node_count(whole) == info.nodes
        ids = [set(re.findall(r"^(\d+),", d.split("*ELEMENT")[0], re.M)) for d, _ in parts]
        assert not ids[0] & ids[1]
        for k, (deck, part_info) in enumerate(parts, start=1):
            other = 3 - k
            assert f"ELSET=L{k}" in deck and f"ELSET=L{other}" not in deck
            assert all(name.endswith(str(k)) for name in part_info.sets)
            assert not re.search(rf"NSET=\w+{other}\b", deck)


@pytest.mark.fea
@pytest.mark.slow
def test_split_solve_equals_the_one_run_direct_solve(ccx: str, small: Assembly) -> None:
    """Second method: the one-run direct solve of the whole deck. The split solves the same
    block-diagonal system in two runs, so the values agree to the solver's round-off
    (measured 1e-9 to 1e-12, docs/fea.md 2.9): bound 1e-7 on the total, and on each layer's part
    1e-7 of the total (the soft layer bent across its creases, 1e-3 of the total, carries the
    joint solve's round-off: 1.7e-9 of the total for the cantilever here),
    for the structured mesh (3-point, 4-point, cantilever, frame) and a gmsh coupon (compression
    and 3-point at 30 deg)."""
    cases = [
        ("three-point", 0.0, AssemblyMesh(2)),
        ("four-point", 0.0, AssemblyMesh(4)),
        ("cantilever", 0.0, AssemblyMesh(2)),
        ("frame", 0.0, AssemblyMesh(2)),
        ("platens", 30.0, AssemblyMesh(2)),
        ("three-point", 30.0, AssemblyMesh(2)),
    ]
    for test, eta, mesh in cases:
        one = solve_assembly(small, test, mesh, eta, split=False)  # type: ignore[arg-type]
        two = solve_assembly(small, test, mesh, eta, split=True)  # type: ignore[arg-type]
        assert two.value() == pytest.approx(one.value(), rel=1e-7), test
        for a, b in zip(two.layer_values, one.layer_values, strict=True):
            assert a == pytest.approx(b, rel=1e-7, abs=1e-7 * abs(one.value())), test
        assert two.nodes == one.nodes
        if test == "frame":
            assert two.side_force == pytest.approx(one.side_force, rel=1e-7)


def test_split_is_refused_where_the_parts_are_coupled(small: Assembly) -> None:
    """The band joins the layers and the buckling platen ties them: no split there (one line)."""
    with pytest.raises(InputError, match="split"):
        solve_assembly(small, "platens", AssemblyMesh(2), connectors=True, split=True)
    with pytest.raises(InputError, match="split"):
        solve_assembly(small, "platens", AssemblyMesh(2), split=True, step=LinearBuckling())
    with pytest.raises(InputError, match="split"):
        solve_assembly(small, "three-point", AssemblyMesh(2), stresses=True, split=True)


@pytest.mark.parametrize("bad", [0.5, 9.0, math.nan, True])
def test_aspect_out_of_range_is_refused(bad: float) -> None:
    with pytest.raises(InputError, match=r"mesh\.aspect"):
        AssemblyMesh(2, bad)


def test_aspect_stretches_coupon_elements_along_the_creases_only(small: Assembly) -> None:
    """Geometry of the gmsh coupon at 30 deg with aspect 3: the S8R elements' extent along the
    crease direction is about 3 times their extent across (1 with aspect 1), every node still on
    the folded surface (heights between the layer's valleys and ridges, the crease heights
    reproduced), and under half the nodes (0.45 on this small coupon: the creases and edges are embedded)."""
    eta = math.radians(30.0)
    crease = np.array([-math.sin(eta), math.cos(eta)])  # layer 1's creases in the test frame
    chord = np.array([math.cos(eta), math.sin(eta)])
    ratios = []
    counts = []
    for aspect in (1.0, 3.0):
        sh = oblique_shells(small, 30.0, 4, (), aspect=aspect)[0]
        xy = sh.xyz[:, :2]
        index = {int(n): i for i, n in enumerate(sh.ids)}
        along, across = [], []
        for e in sh.elements:
            p = xy[[index[n] for n in e[:4]]]
            along.append(np.ptp(p @ crease))
            across.append(np.ptp(p @ chord))
        ratios.append(float(np.median(along) / np.median(across)))
        counts.append(len(sh.ids))
        h = small.layer1.height
        assert sh.xyz[:, 2].min() == pytest.approx(0.0, abs=1e-9)
        assert sh.xyz[:, 2].max() == pytest.approx(h, rel=1e-9)
    assert ratios[0] == pytest.approx(1.0, rel=0.3)
    assert ratios[1] == pytest.approx(3.0, rel=0.3)
    assert 0.25 < counts[1] / counts[0] < 0.5


@pytest.mark.fea
def test_aspect_keeps_the_membrane_stiffness_along_the_creases(ccx: str, small: Assembly) -> None:
    """K(0) is membrane stretching of layer 1 along its creases, a field that S8R elements of any
    aspect represent exactly (K_S = E t (n + 1) W L_y / L, plus K_C2 below 0.5 %): elements 4 times
    longer along the creases give K within 0.1 % of square elements, on a quarter of the nodes."""
    square = solve_assembly(small, "platens", AssemblyMesh(2), 0.0)
    long = solve_assembly(small, "platens", AssemblyMesh(2, 4.0), 0.0)
    assert long.value() == pytest.approx(square.value(), rel=1e-3)
    assert long.nodes < 0.4 * square.nodes
