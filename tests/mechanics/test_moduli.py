"""Closed-form moduli against periodic unit-cell FE (``docs/data/unitcell_fe.csv``).

The FE model has solid (mitred) creases, so its Ecx and Ebx sit slightly above the zero-thickness
crease theory; the file's header puts the gap at about t/W at alpha = 90 deg, growing for sharper folds
(9 % at t/W = 0.02, alpha = 45 deg). The allowance used below, (t/W)(90/alpha)^2 plus 0.5 %, is that
statement written as a bound (corrugate.analysis.warnings.crease_error_estimate); the 0.5 % covers the "about":
at t/W = 0.01, alpha = 90 deg the file's Ecx is 1.27 % above the theory, not 1 %.
"""

from __future__ import annotations

import csv
from pathlib import Path

import pytest

from corrugate import moduli
from corrugate.analysis.warnings import crease_error_estimate


def _rows(reference: Path) -> list[dict[str, float]]:
    with open(reference / "unitcell_fe.csv") as fh:
        lines = [line for line in fh if not line.startswith("#")]
    out = []
    for row in csv.DictReader(lines):
        out.append({k: float(v) for k, v in row.items() if k != "mesh"})
    assert len(out) >= 4
    return out


def _model(row: dict[str, float], name: str) -> dict[str, float]:
    m = moduli(1.0, row["nu"], row["t"], row["W"], row["alpha_deg"], name)
    return m.as_dict()


def test_refined_matches_fe(reference: Path) -> None:
    for row in _rows(reference):
        m = _model(row, "refined")
        assert m["Ecy"] == pytest.approx(row["Ecy"], rel=1e-3)
        assert m["Eby"] == pytest.approx(row["Eby"], rel=1e-2)
        allowance = crease_error_estimate(row["t"], row["W"], row["alpha_deg"]) + 5e-3
        for key in ("Ecx", "Ebx"):
            ratio = m[key] / row[key]
            # the theory's crease is thinner, so it may only sit below FE, by at most the allowance
            assert 1 - allowance <= ratio <= 1 + 2e-3, (key, row, ratio)


def test_xia_overstates_spanwise_bending(reference: Path) -> None:
    """Xia's Eby carries 1/(1 - nu^2): 10 % too stiff at nu = 0.3, more at higher nu (docs/theory.md 3.1)."""
    for row in _rows(reference):
        ratio = _model(row, "xia")["Eby"] / row["Eby"]
        expected = 1 / (1 - row["nu"] ** 2)
        # the refined form itself is within 1 % of FE (test above), hence the 2 % here
        assert ratio == pytest.approx(expected, rel=0.02)
        assert ratio > 1.09


def test_paper_variant_is_off_as_documented(reference: Path) -> None:
    """Records the finding of docs/theory.md 3.1 so it stays true: the printed Ecx is far too low
    (here 70-88 % below FE), the printed Ecy is off by -4 % to +16 % depending on nu only."""
    for row in _rows(reference):
        p = _model(row, "paper")
        assert 0.10 < p["Ecx"] / row["Ecx"] < 0.35
        ecy = p["Ecy"] / row["Ecy"]
        nu = row["nu"]
        assert ecy == pytest.approx((nu**2 - 2 * nu - 3) / (4 * (nu**2 - 1)), rel=1e-5)
        assert 0.96 < ecy < 1.16
        assert abs(ecy - 1) > 0.03
