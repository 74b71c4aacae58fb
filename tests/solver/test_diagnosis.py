"""Diagnoses of infeasible specs give numbers, causes and hints (corrugate.solver.diagnosis).

The three specs of issue 21 (tests/data/diagnosis/): stiff in every direction with free sides,
one bound at 45 deg, a rectangle with identical layers. Every number the diagnosis gives is
checked against a direct evaluation of the model over the whole grid of the spec
(:func:`corrugate.evaluate`, no solver), and every "this would make it feasible" against a design
that meets the spec when analysed on its own (:func:`corrugate.analyze`).
"""

from __future__ import annotations

import re
from pathlib import Path
from typing import Any

import numpy as np
import pytest

from conftest import CliRun
from corrugate import LayerArrays, analyze, evaluate, get_material, make_layout
from corrugate.solver import Budget, Problem, solve
from corrugate.solver.diagnosis import NOT_CERTIFIED, best_hint, shown
from corrugate.spec.schema import load_spec

DATA = Path(__file__).resolve().parents[1] / "data" / "diagnosis"
RTOL = 1e-9  # the solver's feasibility slack


def _solve(name: str) -> Any:
    sol = solve(Problem.from_spec(load_spec(DATA / f"{name}.toml")))
    assert sol.status == "infeasible" and sol.certified
    return sol


def _by_kind(sol: Any, kind: str) -> list[Any]:
    return [d for d in sol.diagnosis if d.kind == kind]


def _number(text: str, after: str) -> float:
    """The number printed right after ``after`` in ``text``."""
    m = re.search(re.escape(after) + r"\s*([-+0-9.e]+)", text)
    assert m, (after, text)
    return float(m.group(1))


class SquareGrid:
    """Every identical-layer design of the square fixtures (Dura-Lar 0.125 mm, W 1-30 mm step 1,
    n 6-200, alpha 40-120 deg step 1), evaluated with the refined model."""

    def __init__(self) -> None:
        mat = get_material("dura-lar")
        n, W, A = np.meshgrid(
            np.arange(6, 201), np.arange(1.0, 31.0), np.arange(40.0, 121.0), indexing="ij"
        )
        self.layer = LayerArrays(mat.E, mat.nu, 0.125, W, n, A, mat.density)
        self.flat = (n + 1) * W
        self.lay = make_layout("square")
        self.cache: dict[tuple[float, str], Any] = {}

    def at(self, eta: float, support: str = "free") -> Any:
        key = (eta, support)
        if key not in self.cache:
            self.cache[key] = evaluate(
                self.layer, self.layer, self.lay, "refined", eta, support=support
            )
        return self.cache[key]

    def sizes(self) -> Any:
        """sheet_max 250 mm (flat blank; a square's facets are its side, <= 60 mm), side 48-60
        mm, thickness 10-12.5 mm."""
        e = self.at(0.0)
        ok = self.flat <= 250 * (1 + RTOL)
        ok &= (e.Lx >= 48 * (1 - RTOL)) & (e.Lx <= 60 * (1 + RTOL))
        ok &= (e.thickness >= 10 * (1 - RTOL)) & (e.thickness <= 12.5 * (1 + RTOL))
        return ok


@pytest.fixture(scope="module")
def grid() -> SquareGrid:
    return SquareGrid()


def test_stiff_in_every_direction_says_why_and_what_would(grid: SquareGrid) -> None:
    sol = _solve("every_direction")
    [sup] = _by_kind(sol, "support")
    # the cause, and the three ways out the issue names
    assert "no facet runs from edge to edge at 45 deg" in sup.message
    assert "docs/offaxis.md" in sup.message
    assert 'support = "frame"' in sup.message and "along the creases" in sup.message
    assert "face sheet" in sup.message
    assert set(sup.names) == {
        "constraints.flexural_rigidity[1].min",
        "constraints.inplane_stiffness[1].min",
    }
    # the numbers: each off-axis bound's best with every on-axis bound held, by the grid
    ok = grid.sizes()
    for eta in (0.0, 90.0):
        ok &= grid.at(eta).EI >= 80_000 * (1 - RTOL)
        ok &= grid.at(eta).K >= 100 * (1 - RTOL)
    ei45, k45 = grid.at(45.0).EI, grid.at(45.0).K
    best_ei, best_k = float(ei45[ok].max()), float(k45[ok].max())
    assert sup.reachable == pytest.approx(best_ei, rel=1e-9)
    assert best_ei < 0.002 * 80_000 and best_k < 0.01 * 100  # far beyond any free panel
    assert f"at most {shown(best_k, 'N/mm')}" in sup.message
    # in a frame the spec is feasible: its lightest design, by the grid with the frame's rule
    fr = ok & (grid.at(45.0, "frame").EI >= 80_000 * (1 - RTOL))
    fr &= grid.at(45.0, "frame").K >= 100 * (1 - RTOL)
    frame_mass = float(grid.at(0.0).mass[fr].min())
    assert _number(sup.message, "then the spec is feasible, best") == pytest.approx(
        frame_mass, rel=1e-3
    )
    # along the creases the same constraints allow much more EI
    assert _number(sup.message, "allow EI up to") * 1000 == pytest.approx(
        max(float(grid.at(0.0).EI[ok].max()), float(grid.at(90.0).EI[ok].max())), rel=1e-3
    )
    # the two bind only together: each one's best with the other dropped, and together
    [pair] = _by_kind(sol, "pair")
    assert pair.names == sup.names
    assert "bind only together" in pair.message
    assert pair.reachable == pytest.approx(best_ei, rel=1e-9)
    together = float(ei45[ok & (k45 >= best_k * (1 - RTOL))].max())
    assert pair.alone == pytest.approx(together, rel=1e-9)
    assert together < best_ei  # they do compete
    # one edit per off-axis bound, at its own table's key (pasted into the spec as it reads)
    assert best_hint(sol.diagnosis) == (
        'constraints.flexural_rigidity[1].support = "frame" and '
        'constraints.inplane_stiffness[1].support = "frame"'
    )


def test_one_bound_at_45_deg_gives_numbers_and_the_frame_not_a_999_percent_cut(
    grid: SquareGrid,
) -> None:
    sol = _solve("offaxis_45")
    [single] = _by_kind(sol, "single")
    ok = grid.sizes()
    ei45 = grid.at(45.0).EI
    best = float(ei45[ok].max())
    assert single.reachable == pytest.approx(best, rel=1e-9)
    assert single.bound == pytest.approx(80_000, rel=1e-12)
    # the constraints it binds together with, each dropped in turn, by the grid
    e0 = grid.at(0.0)
    no_side_max = (
        (grid.flat <= 250 * (1 + RTOL))
        & (e0.Lx >= 48 * (1 - RTOL))
        & (e0.thickness >= 10 * (1 - RTOL))
        & (e0.thickness <= 12.5 * (1 + RTOL))
    )
    assert _number(single.message, "constraints.side.max (without it:") * 1000 == pytest.approx(
        float(ei45[no_side_max].max()), rel=1e-3
    )
    # alone, in the variable bounds only, a free panel still falls short of 80 mN m^2
    assert single.alone == pytest.approx(float(ei45.max()), rel=1e-9)
    assert single.alone < 80_000
    [sup] = _by_kind(sol, "support")
    fr = ok & (grid.at(45.0, "frame").EI >= 80_000 * (1 - RTOL))
    assert _number(sup.message, "then the spec is feasible, best") == pytest.approx(
        float(e0.mass[fr].min()), rel=1e-3
    )
    hint = best_hint(sol.diagnosis)
    assert hint == 'constraints.flexural_rigidity[0].support = "frame"'  # a TOML edit at its key
    assert "99.9" not in hint


def test_a_rectangle_with_identical_layers_is_told_to_make_them_independent() -> None:
    sol = _solve("rectangle_identical")
    [lay] = _by_kind(sol, "layers")
    assert "Lx = Ly" in lay.message and "78-82 mm" in lay.message and "118-122 mm" in lay.message
    assert lay.hint is not None and lay.hint.startswith('layers = "independent"')
    assert best_hint(sol.diagnosis) == lay.hint
    # the claim: with independent layers a design of that mass meets every constraint
    spec = load_spec(DATA / "rectangle_identical.toml").model_copy(update={"layers": "independent"})
    free = solve(Problem.from_spec(spec), explain=False)
    assert free.assembly is not None
    a = analyze(free.assembly, "refined", [0.0])
    assert lay.reachable == pytest.approx(a.mass.total, rel=1e-9)
    asm = free.assembly
    assert 78 * (1 - RTOL) <= asm.Lx <= 82 * (1 + RTOL)
    assert 118 * (1 - RTOL) <= asm.Ly <= 122 * (1 + RTOL)
    assert asm.thickness <= 15 * (1 + RTOL)
    assert a.stiffness[0].EI >= 20_000 * (1 - RTOL)
    # the size numbers: identical layers give Ly = Lx, so side_y reaches the largest Lx that
    # side_x and the rest allow; by the grid of the spec (polypropylene 0.25 mm)
    mat = get_material("polypropylene")
    n, W, A = np.meshgrid(
        np.arange(6, 41), np.arange(5.0, 31.0), np.arange(40.0, 121.0, 5.0), indexing="ij"
    )
    layer = LayerArrays(mat.E, mat.nu, 0.25, W, n, A, mat.density)
    e = evaluate(layer, layer, make_layout("rectangle"), "refined", 0.0)
    assert np.array_equal(e.Lx, e.Ly)
    ok = ((n + 1) * W <= 280) & (e.thickness <= 15 * (1 + RTOL)) & (e.EI >= 20_000 * (1 - RTOL))
    ok_x = ok & (e.Lx >= 78 * (1 - RTOL)) & (e.Lx <= 82 * (1 + RTOL))
    [ymin] = [d for d in sol.diagnosis if d.names == ("constraints.side_y.min",)]
    assert ymin.reachable == pytest.approx(float(e.Ly[ok_x & (e.Ly <= 122)].max()), rel=1e-9)


@pytest.mark.parametrize(
    ("name", "hint"),
    [
        ("every_direction", 'hint: constraints.flexural_rigidity[1].support = "frame" and '),
        ("offaxis_45", 'hint: constraints.flexural_rigidity[0].support = "frame"'),
        ("rectangle_identical", 'hint: layers = "independent"'),
    ],
)
def test_the_cli_ends_with_the_hint(name: str, hint: str, cli: CliRun) -> None:
    code, out, _ = cli(["design", str(DATA / f"{name}.toml")])
    assert code == 1
    lines = out.strip().splitlines()
    assert lines[-1].startswith(hint)
    assert all(line.startswith("  - ") for line in lines[1:-1])


def test_a_small_edit_is_the_hint_before_a_frame() -> None:
    """K(45) >= 1 N/mm with the case study's bounds (tests/fea/test_certified_offaxis.py): a frame
    would do, but side.max 60 -> 60.19 mm (0.3 %) is the smaller change, so it is the hint."""
    text = (DATA / "offaxis_45.toml").read_text("utf-8")
    text = text.replace(
        'flexural_rigidity = [{ min = "80 mN*m^2", eta = "45 deg" }]',
        'flexural_rigidity = [{ min = "80 mN*m^2", eta = "0 deg" }]\n'
        'inplane_stiffness = [{ min = "1 N/mm", eta = "45 deg" }]',
    )
    text = text.replace('W = { min = "1 mm", max = "30 mm"', 'W = { min = "4 mm", max = "16 mm"')
    text = text.replace("n = { min = 6, max = 200 }", "n = { min = 4, max = 30 }")
    from corrugate.spec.schema import parse_spec_text

    sol = solve(Problem.from_spec(parse_spec_text(text)))
    assert sol.status == "infeasible"
    assert _by_kind(sol, "support")  # the frame is named
    [side] = [d for d in sol.diagnosis if d.names == ("constraints.side.max",)]
    assert side.relative is not None and side.relative < 0.01
    hint = best_hint(sol.diagnosis)
    assert hint.startswith('the smallest single change is constraints.side.max = "')


def test_the_reach_of_a_bound_reads_in_its_own_direction() -> None:
    """A pair diagnosis says how far each bound can go: a `max` bound (side.max <= 10 mm) "at
    least" its smallest value, a `min` bound "at most" its largest, a deflection bound (stored as
    P / delta >= load / max) "at least" its smallest deflection (issue 36 item 5: a side.max read
    "reaches at most 18.19 mm")."""
    from corrugate.solver.diagnosis import _reach, _value
    from corrugate.solver.problem import Constraint
    from corrugate.solver.quantity import LX

    side = Constraint("constraints.side.max", LX, "max", 10.0)
    assert _reach(side) == "at least"
    assert _reach(Constraint("constraints.side.min", LX, "min", 10.0)) == "at most"
    deflection = Constraint("constraints.deflection[0].max", LX, "min", 5.0, load=10.0)
    assert _reach(deflection) == "at least"
    assert _value(deflection, 4.0) == "2.5 mm"  # the deflection 10 N / 4 N/mm, not P / delta


def test_a_hint_for_a_plain_number_is_a_toml_number() -> None:
    """A unitless key's hint is a bare number that TOML reads as one (issue 36 item 5: the hint
    was `fabrication.max_t_over_W = "0.08334 "`, a quoted string with a trailing space); a key
    with a unit stays a quoted quantity; both round towards the safe side."""
    import tomllib

    from corrugate.solver.diagnosis import _rounded

    plain = tomllib.loads(f"x = {_rounded(0.0833412, '', down=True)}")["x"]
    assert plain == 0.08334 and isinstance(plain, float)
    assert tomllib.loads(f"x = {_rounded(0.0833412, '', down=False)}")["x"] == 0.08335
    assert tomllib.loads(f"x = {_rounded(12.3456, 'mm', down=False)}")["x"] == "12.35 mm"


def test_a_diagnosis_out_of_memory_keeps_its_entries_and_says_partial(
    monkeypatch: pytest.MonkeyPatch,
) -> None:
    """The rectangle with identical layers (its first entry: make them independent) with the
    machine's memory made to run out at the first constraint's re-solve: the answer is still
    "infeasible" (proven), the entry found before stays, and the last entry says "partial
    diagnosis (memory cap)" instead of the error ending the run."""
    from corrugate.solver import diagnosis

    def short_of_memory(*args: object, **kw: object) -> None:
        raise MemoryError

    monkeypatch.setattr(diagnosis, "_single", short_of_memory)
    sol = solve(Problem.from_spec(load_spec(DATA / "rectangle_identical.toml")))
    assert sol.status == "infeasible" and sol.certified
    assert sol.diagnosis[0].kind == "layers"
    assert sol.diagnosis[-1].message.startswith("partial diagnosis (memory cap)")
    assert len(sol.diagnosis) == 2


_IMPOSSIBLE = ("no design meets the rest", "does not make the spec feasible")


@pytest.mark.parametrize(
    "spec",
    [
        DATA / "offaxis_45.toml",
        DATA / "rectangle_identical.toml",
        Path(__file__).resolve().parents[2] / "examples" / "infeasible.toml",
    ],
    ids=lambda p: p.stem,
)
def test_a_diagnosis_cut_by_its_budget_claims_only_what_its_searches_proved(spec: Path) -> None:
    """Second method: the same spec's diagnosis with the whole budget. Cut at box budgets across
    its run, a diagnosis (1) ends saying partial whenever the budget ran out in it (also inside
    the last entry's searches, where it once ended without saying so: the arm link's 60 s run);
    (2) gives each single's reach as the full run does, or says its value is not certified (a
    design reaching it was found, not that none goes further); (3) gives a bound's reach alone
    only as the full run does; (4) says no design exists, or a frame does not help, only where
    the full run says so too."""
    problem = Problem.from_spec(load_spec(spec))
    budget = Budget()
    full = solve(problem, budget=budget)
    assert full.status == "infeasible" and budget.stopped is None
    by_names = {d.names: d for d in full.diagnosis}
    said = " ".join(d.message for d in full.diagnosis)
    flagged = 0
    for boxes in np.linspace(150, budget.used_boxes - 1, 25).astype(int):
        cut_budget = Budget(boxes=int(boxes))
        cut = solve(problem, budget=cut_budget)
        if cut.status != "infeasible":  # cut before the infeasibility was proven: no diagnosis
            assert not cut.diagnosis
            continue
        assert cut_budget.stopped == "boxes"
        assert "ran out during the diagnosis" in cut.diagnosis[-1].message
        for d in cut.diagnosis[:-1]:
            flagged += NOT_CERTIFIED in d.message
            if d.kind == "single":
                whole = by_names[d.names]
                assert d.reachable == whole.reachable or NOT_CERTIFIED in d.message
                assert d.alone is None or d.alone == whole.alone
            for claim in _IMPOSSIBLE:
                assert claim not in d.message or claim in said
    assert flagged  # the not-certified wording was exercised on this spec
