"""Pareto fronts: the gridded front equals the one read off an exhaustive enumeration."""

from __future__ import annotations

import csv
import io
import itertools
from pathlib import Path
from typing import Any

import numpy as np
import pytest

from corrugate import LayerArrays, evaluate, get_material, make_layout
from corrugate.cli import main
from corrugate.solver import Problem
from corrugate.solver.pareto import pareto_front
from corrugate.spec.schema import parse_spec
from data_files import PAPER_CASE_STUDY

EXAMPLES = Path(__file__).resolve().parents[2] / "examples"


def _spec(W_step: float | None, a_step: float | None) -> dict[str, Any]:
    W: dict[str, float] = {"min": 4.0, "max": 14.0}
    A: dict[str, float] = {"min": 50.0, "max": 120.0}
    if W_step is not None:
        W["step"] = W_step
    if a_step is not None:
        A["step"] = a_step
    return {
        "tolerances": "none",  # the nominal model (tolerances: tests/solver/test_tolerance_box.py)
        "model": "refined",
        "material": {"name": "dura-lar", "thickness": "0.125 mm"},
        "variables": {"W": W, "n": {"min": 3, "max": 20}, "alpha": A},
        "constraints": {
            "side": {"min": "40 mm", "max": "60 mm"},
            "thickness": {"min": "8 mm", "max": "14 mm"},
            "flexural_rigidity": [{"min": "60 mN*m^2", "eta": "0 deg"}],  # replaced by the sweep
        },
    }


def _brute_front(W_step: float, a_step: float) -> list[tuple[float, float]]:
    """(stiffness, mass) of every Pareto-optimal design over the full grid, by enumeration."""
    mat = get_material("dura-lar")
    n, W, A = np.meshgrid(
        np.arange(3, 21),
        np.arange(4.0, 14.0 + 1e-9, W_step),
        np.arange(50.0, 120.0 + 1e-9, a_step),
        indexing="ij",
    )
    layer = LayerArrays(mat.E, mat.nu, 0.125, W, n, A, mat.density)
    ev = evaluate(layer, layer, make_layout("square"), "refined", 0.0)
    ok = (ev.Lx >= 40 * (1 - 1e-9)) & (ev.Lx <= 60 * (1 + 1e-9))
    ok &= (ev.thickness >= 8 * (1 - 1e-9)) & (ev.thickness <= 14 * (1 + 1e-9))
    # the springs' validated range: 7 or more facets (docs/validation/ranges.md)
    ok &= n + 1 >= 7
    EI, mass = ev.EI[ok], ev.mass[ok]
    order = np.lexsort((mass, -EI))  # stiffest first, lightest first among equals
    front: list[tuple[float, float]] = []
    best = np.inf
    for k in order:
        if mass[k] < best:
            best = float(mass[k])
            front.append((float(EI[k]), best))
    return front[::-1]


def test_gridded_front_is_exact() -> None:
    problem = Problem.from_spec(parse_spec(_spec(1.0, 5.0)))
    front = pareto_front(problem, "flexural_rigidity", 0.0)
    assert front.exact
    assert not front.truncated
    assert front.certified
    expected = _brute_front(1.0, 5.0)
    got = [(p.stiffness, p.mass) for p in front.points]
    assert len(got) == len(expected)
    for (s, m), (se, me) in zip(got, expected, strict=True):
        assert m == pytest.approx(me, rel=1e-12)
        assert s == pytest.approx(se, rel=1e-12)


def test_continuous_front_is_monotone_and_below_the_grid_front() -> None:
    problem = Problem.from_spec(parse_spec(_spec(None, None)))
    calls: list[tuple[int, int | None]] = []
    front = pareto_front(
        problem, "flexural_rigidity", 0.0, points=8, progress=lambda d, t: calls.append((d, t))
    )
    assert calls == [(k, 8) for k in range(1, 9)]  # one progress report per certified solve
    assert not front.exact
    assert front.certified
    pts = front.points
    assert len(pts) == 8
    assert all(b.mass >= a.mass for a, b in itertools.pairwise(pts))
    assert all(p.stiffness >= p.level * (1 - 1e-12) for p in pts)
    # every grid design is admissible here, so the continuous front lies on or below it
    grid = _brute_front(1.0, 5.0)
    for p in pts:
        heavier_or_equal = [m for s, m in grid if s >= p.level]
        if heavier_or_equal:
            assert p.mass <= min(heavier_or_equal) * (1 + 1e-12)


def test_pareto_cli_writes_csv_and_plot(tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    out = tmp_path / "front"
    with pytest.raises(SystemExit) as info:
        main(
            [
                "pareto",
                str(PAPER_CASE_STUDY),
                "--vs",
                "flexural_rigidity",
                "--out",
                str(out),
            ]
        )
    assert info.value.code in (0, None)
    rows = list(csv.DictReader(io.StringIO((out / "pareto.csv").read_text("utf-8"))))
    assert rows
    # the case study's optimum is the lightest design with EI_0 >= 80 mN m^2
    first_ok = next(r for r in rows if float(r["stiffness_N mm^2"]) >= 80_000)
    assert (first_ok["layer1_W_mm"], first_ok["layer1_n"], first_ok["layer1_alpha_deg"]) == (
        "8.0",
        "8",
        "84.0",
    )
    pytest.importorskip("matplotlib")
    assert (out / "pareto.png").read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"


def test_pareto_cli_rejects_unknown_quantity(capsys: pytest.CaptureFixture[str]) -> None:
    with pytest.raises(SystemExit) as info:
        main(["pareto", str(PAPER_CASE_STUDY), "--vs", "stiffness"])
    assert info.value.code == 2
    assert capsys.readouterr().err.startswith("corrugate: error: --vs = ")
