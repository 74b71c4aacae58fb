"""One FE fixture per test, named as the spec names it, and the analysis step apart from it
(corrugate.fea.fixtures, corrugate.fea.steps; docs/fea.md 2): without CalculiX."""

from __future__ import annotations

import re

import pytest

from corrugate import Assembly, Layer, get_material
from corrugate.core.errors import InputError
from corrugate.fea.assembly import AssemblyMesh, assembly_deck
from corrugate.fea.fixtures import (
    fixture_names,
    fixtures,
    get_fixture,
    register_fixture,
    unregister_fixture,
)
from corrugate.fea.fixtures.three_point import THREE_POINT
from corrugate.fea.steps import STATIC, LinearBuckling
from corrugate.mechanics.behaviours import load_cases, supports

SMALL = Assembly.identical(
    Layer(W=5.0, n=7, alpha_deg=120.0, material=get_material("dura-lar"), t=0.1)
)


def test_every_behaviour_names_a_registered_fixture_by_the_spec_name() -> None:
    """The link from mechanics to the FE is real: each support condition and load case names a
    fixture that the FE registry holds; a load case's fixture is the load case itself (the
    spec's name: no second vocabulary), a support's is the test that measures its K."""
    for b in (*supports(), *load_cases()):
        assert b.fixture in fixture_names(), b.name
    for b in load_cases():
        assert b.fixture == b.name
    assert {b.name: b.fixture for b in supports()} == {"free": "platens", "frame": "frame"}
    with pytest.raises(InputError, match="bending"):  # the former FE names are gone
        assembly_deck(SMALL, "bending", AssemblyMesh(2))


def _sets(deck: str) -> dict[str, list[int]]:
    """The node sets of a deck (name -> node numbers), read back from its *NSET cards."""
    out: dict[str, list[int]] = {}
    name = None
    for line in deck.splitlines():
        if line.startswith("*"):
            m = re.match(r"\*NSET,NSET=(\w+)", line)
            name = m.group(1) if m else None
        elif name:
            out.setdefault(name, []).extend(int(v) for v in line.split(","))
    return out


@pytest.mark.parametrize("name", ["platens", "three-point", "four-point", "cantilever", "frame"])
def test_any_fixture_runs_as_a_static_or_a_buckling_step(name: str) -> None:
    """A deck is mesh + fixture + step. The same fixture written with either step has the same
    mesh and node sets (everything before the step's cards); the static step prescribes the
    driven sets' displacement, the buckling step ties each driven node to one new reference node
    (one two-term *EQUATION per node of the driven sets, counted from the *NSET cards) loaded by
    1 N, and keeps every other boundary line."""
    along = 4 if name == "four-point" else 2
    static, info = assembly_deck(SMALL, name, AssemblyMesh(along), 0.0, step=STATIC)
    buckle, _ = assembly_deck(SMALL, name, AssemblyMesh(along), 0.0, step=LinearBuckling())
    assert "(static)" in static.splitlines()[1] and "(buckle)" in buckle.splitlines()[1]
    body = "\n".join(static.split("*STEP")[0].splitlines()[2:])  # less *HEADING and its title
    assert body in buckle  # the same mesh and fixture sets
    assert "*STATIC" in static and "*BUCKLE" not in static
    assert "*BUCKLE\n3,1.e-6" in buckle and "*STATIC" not in buckle
    sets = _sets(static)
    driven = [n for s in info.sets for n in sets[s]]
    top = max(max(v) for v in sets.values())
    equations = re.findall(r"\n2\n(\d+),(\d),1\.,(\d+),(\d),-1\.", buckle)
    assert sorted(int(e[0]) for e in equations) == sorted(driven)
    ref = {int(e[2]) for e in equations}
    assert len(ref) == 1 and ref.pop() > top  # one reference node, numbered after the mesh
    # every boundary line of the static step but the drives is in the buckling step
    s_bc = static.split("*BOUNDARY\n")[1].split("\n*NODE PRINT")[0].splitlines()
    b_bc = buckle.split("*BOUNDARY\n")[1].split("\n*CLOAD")[0].splitlines()
    drives = [ln for ln in s_bc if ln.split(",")[0] in info.sets and ln.split(",")[3] != "0"]
    assert all(float(ln.split(",")[3]) == pytest.approx(-info.delta, rel=1e-11) for ln in drives)
    assert drives and [ln for ln in s_bc if ln not in drives] == b_bc


def test_a_fixture_registered_by_its_name_is_run_by_the_deck_writer() -> None:
    """The registry is the one place a fixture is known: a toy fixture registered under a new
    name (the three-point fixture's supports under another name) is written by assembly_deck
    without any other change, and a taken name is refused."""
    from dataclasses import replace

    toy = register_fixture(replace(THREE_POINT, name="toy-three-point"))
    try:
        deck, _ = assembly_deck(SMALL, "toy-three-point", AssemblyMesh(2))
        ref, _ = assembly_deck(SMALL, "three-point", AssemblyMesh(2))
        assert deck.replace("toy-three-point", "three-point") == ref
        assert get_fixture("toy-three-point") is toy and toy in fixtures("coupon")
        with pytest.raises(InputError, match="taken"):
            register_fixture(toy)
    finally:
        unregister_fixture("toy-three-point")


def test_outline_fixtures_are_not_coupon_fixtures() -> None:
    """The wheel and corner fixtures load an outline, not the coupon: the deck writer of the
    assembly refuses them, naming the coupon fixtures."""
    assert fixture_names("outline") == ("wheel", "corners", "clamped-corners")
    with pytest.raises(InputError, match="platens"):
        assembly_deck(SMALL, "wheel", AssemblyMesh(2))


def test_a_new_load_case_reaches_verify_and_strength_through_the_registries() -> None:
    """The seam of a new load case on the FE side: a load case registered in the behaviours
    (role ``test``, naming its fixture) and its fixture registered in the FE registry are what
    ``verify`` twins (its fixture, with the test's own Euler coefficient) and what strength's
    bench moment reads (its form's ``moment``), with no table to extend. The toy is the
    three-point test under another name, so its moment and coefficient must be three-point's
    (statics: P Ls / 4; EI = P Ls^3 / (48 delta))."""
    from dataclasses import replace

    from corrugate.fea.verify import Twin, twin_of
    from corrugate.mechanics.behaviours import register, unregister
    from corrugate.mechanics.load_cases import THREE_POINT as THREE_POINT_CASE
    from corrugate.mechanics.strength import bending_moment
    from corrugate.solver.quantity import Quantity

    register(replace(THREE_POINT_CASE, name="toy-bend", fixture="toy-bend", suffix="toy"))
    register_fixture(replace(THREE_POINT, name="toy-bend"))
    try:
        t = twin_of(Quantity("EI", 0.0, None, "toy-bend"), SMALL)
        assert isinstance(t, Twin) and t.test == "toy-bend" and t.read == "EI"
        assert t.a == pytest.approx(1 / 48)
        assert t.label == "3-point bending" and t.step is STATIC
        assert bending_moment("toy-bend", 2.0, 100.0) == pytest.approx(2.0 * 100.0 / 4)
    finally:
        unregister("toy-bend", "test")
        unregister_fixture("toy-bend")


@pytest.mark.parametrize("kind", ["frame", "coupon"])
def test_a_new_support_with_its_own_fixture_gets_its_verify_twin(kind: str) -> None:
    """The seam of a new support condition on the FE side, as a load case's: a support
    registered in the behaviours naming its own fixture, and that fixture registered in the FE
    registry, are what ``verify`` twins its K with (no support named in ``verify``). The toy is
    the frame under another name: held by its own fixture, its bending and a deflection have no
    twin, as the frame's (the words its label gives); a toy of kind ``coupon`` (the platens'
    supports under another name) is run on the coupon, shifted off the creases as every
    coupon is."""
    from dataclasses import replace

    from corrugate.fea.fixtures.frame import FRAME as FRAME_FIXTURE
    from corrugate.fea.fixtures.platens import PLATENS
    from corrugate.fea.verify import Twin, twin_of
    from corrugate.mechanics.behaviours import register, unregister
    from corrugate.mechanics.supports.frame import FRAME
    from corrugate.solver.quantity import Quantity

    base = FRAME_FIXTURE if kind == "frame" else PLATENS
    register(replace(FRAME, name="toy-held", fixture="toy-held", suffix="toyh", label=" toy-held"))
    register_fixture(replace(base, name="toy-held"))
    try:
        for eta in (0.0, 45.0):
            t = twin_of(Quantity("K", eta, "toy-held"), SMALL)
            assert isinstance(t, Twin) and t.test == "toy-held" and t.read == "K"
            assert t.fixture.kind == kind and t.shifted == (kind == "coupon" and eta == 45.0)
        bend = twin_of(Quantity("EI", 0.0, "toy-held"), SMALL)
        assert bend == "no FE twin yet (bending toy-held)"
        deflection = twin_of(Quantity("K", 0.0, "toy-held"), SMALL, load=2.0)
        assert deflection == "no FE twin yet (a deflection toy-held)"
        # the frame's own twins keep their words
        assert twin_of(Quantity("EI", 0.0, "frame"), SMALL) == "no FE twin yet (bending in a frame)"
    finally:
        unregister("toy-held")
        unregister_fixture("toy-held")
