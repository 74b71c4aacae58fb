"""The orientation trap (:mod:`corrugate.solver.orientation`, issue 36 item 2).

tests/data/diagnosis/orientation_trap.toml is the issue's case: a 150 x 40 mm part (side_x 150-160
mm, side_y 35-40 mm) with a 150 mm cantilever span at the default eta = 0. eta runs from layer 1's
creases, which run along y (docs/models.md, "Layouts and facet lengths"), so the span runs along the 40 mm
side: infeasible. The diagnosis must say so in its first entry and hint the eta edit; the hint is
checked by solving the spec with it (a feasible design, analysed on its own). The limit cases: a
span longer than both sides, where no quarter turn helps (no entry), and a square, where a quarter
turn changes nothing (no re-solve, no entry).
"""

from __future__ import annotations

import tomllib
from dataclasses import replace
from pathlib import Path
from typing import TYPE_CHECKING

import pytest

from corrugate.solver import Problem, solve
from corrugate.solver.orientation import orientation
from corrugate.spec.schema import load_spec, parse_spec

if TYPE_CHECKING:
    from conftest import CliRun

DATA = Path(__file__).resolve().parents[1] / "data" / "diagnosis"
TRAP = DATA / "orientation_trap.toml"


def _trap(**deflection: object) -> Problem:
    raw = tomllib.loads(TRAP.read_text())
    raw["constraints"]["deflection"][0].update(deflection)
    return Problem.from_spec(parse_spec(raw))


def test_the_trap_is_recognised_and_its_hint_is_the_eta_edit() -> None:
    problem = Problem.from_spec(load_spec(TRAP))
    found = orientation(problem)
    assert len(found) == 1
    d = found[0]
    assert d.kind == "orientation"
    assert d.hint == 'constraints.deflection[0].eta = "90 deg"'
    # the words: eta 0 is along y, where side_y allows 40 mm, and the 150 mm span fits side_x
    assert d.message.startswith(
        "constraints.deflection[0]: eta = 0 deg runs along y (side_y: at most 40 mm); "
        "the span of 150 mm fits side_x (at most 160 mm): set "
        'constraints.deflection[0].eta = "90 deg" (or swap side_x and side_y)'
    )
    # the hint holds: the spec with eta = 90 deg has a certified design
    turned = solve(_trap(eta="90 deg"), explain=False)
    assert turned.status == "optimal" and turned.assembly is not None
    assert turned.assembly.Lx >= 150 - 1e-6


def test_no_entry_when_no_quarter_turn_helps_or_none_can() -> None:
    # a 200 mm span fits neither side (side_x at most 160 mm): turning eta changes nothing
    assert orientation(_trap(span="200 mm")) == []
    # a square: Lx = Ly, no quarter turn to suggest
    square = Problem.from_spec(
        load_spec(DATA.parent.parent.parent / "examples" / "infeasible.toml")
    )
    assert square.layout.name == "square" and orientation(square) == []


@pytest.mark.slow
def test_the_first_line_of_the_trap_diagnosis_says_eta_and_the_side_swap(cli: CliRun) -> None:
    """The whole answer, as `corrugate design` prints it (about 7 s of CPU: the diagnosis's
    other entries re-solve the spec per constraint)."""
    code, out, _ = cli(["design", str(TRAP)])
    assert code == 1
    lines = out.splitlines()
    assert "infeasible" in lines[0]
    first = lines[1]
    assert first.startswith("  - constraints.deflection[0]: eta = 0 deg runs along y")
    assert 'set constraints.deflection[0].eta = "90 deg" (or swap side_x and side_y)' in first
    assert lines[-1] == 'hint: constraints.deflection[0].eta = "90 deg"'


def test_only_directions_turn() -> None:
    """The turned problem keeps every bound and turns only the directed quantities (eta + 90 deg
    modulo 180: a bound along 90 deg holds along 0 deg turned)."""
    from corrugate.solver.orientation import _turned

    problem = Problem.from_spec(load_spec(TRAP))
    turned = _turned(problem)
    for a, b in zip(problem.constraints, turned.constraints, strict=True):
        assert (a.name, a.bound, a.sense) == (b.name, b.bound, b.sense)
        if a.quantity.eta is None:
            assert a.quantity == b.quantity
        else:
            assert b.quantity == replace(a.quantity, eta=(a.quantity.eta + 90) % 180)


def test_a_bound_without_a_span_that_misses_its_side_is_not_an_orientation_mistake() -> None:
    """The arm link's stiffness form asks EI(90 deg) along its 150 mm side, on purpose; the same
    EI at 0 deg (along the 40 mm side) is met, but turning eta changes the requirement, and there
    is no span that misses its side to say it was a mistake: no orientation entry (it was the
    first line of that spec's diagnosis)."""
    spec = DATA.parent / "arm_link_stiffness.toml"
    assert orientation(Problem.from_spec(load_spec(spec))) == []
