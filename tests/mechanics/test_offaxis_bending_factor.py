"""The off-axis bending factor 1 - w(eta) c / sqrt(n), c = FINITE_PANEL_BENDING (docs/load_cases.md
5), against the FE coupons of docs/validation/load_cases_fe.csv (independent source: CalculiX
3-point coupons cut along eta at three positions of the cut, 2 / 4 / 8 / 16 elements per facet).

Every coupon whose series the project's convergence rule settles (corrugate.fea.extrapolate.judge,
as `corrugate verify` uses it: four meshes, monotone, shrinking steps, two Richardson estimates
within a quarter of the margin) holds the model: the model's apparent D of the test is at or
below the FE, on more than one coupon, but one: KNOWN_FAILING at 30 deg, shift 0, which judge
settles as failing (the factor 0.3 is not enough there; docs/load_cases.md 5) (the table of docs/load_cases.md 5, `python
benchmarks/offaxis_bending_factor.py`)."""

from __future__ import annotations

import csv
from pathlib import Path

from corrugate import Assembly, analyze
from corrugate.fea.extrapolate import judge
from corrugate.mechanics.load_cases import THREE_POINT, apparent, load_stiffness, shear_and_depth
from corrugate.mechanics.offaxis import _cs
from fe_rows import identical_square

ROOT = Path(__file__).resolve().parents[2]
DATA = ROOT / "docs" / "validation" / "load_cases_fe.csv"
#: The coupon whose settled series the factor 0.3 / sqrt(n) does not bound at 30 deg
#: (docs/load_cases.md 5): FE 1745.2 / 1691.2 / 1651.2 / 1630.7 N mm, estimate 1609.2, against
#: the model's 1871.6 N mm.
KNOWN_FAILING = "Dura-Lar 0.175: W 10, n 6, alpha 40"


def _model(a: Assembly, eta: float) -> float:
    """The three-point test's apparent D (N mm) of the model at eta over the coupon's length."""
    form = THREE_POINT.form
    assert form is not None
    r = analyze(a, eta_deg=[eta])
    st = r.stiffness[0]
    V, h = shear_and_depth(r.springs, *_cs(eta))
    return float(
        apparent(form, "D", load_stiffness(form, st.D, float(V), float(h), st.span), st.span)
    )


def test_the_bending_factor_holds_every_settled_coupon() -> None:
    series: dict[tuple[str, float, float], dict[int, float]] = {}
    with DATA.open() as f:
        for r in csv.DictReader(line for line in f if not line.startswith("#")):
            eta = float(r["eta_deg"])
            if r["test"] == "bending" and eta % 90 != 0:
                key = (r["design"], eta, float(r["shift"]))
                series.setdefault(key, {})[int(r["along"])] = float(r["value"])
    held: set[tuple[str, float]] = set()
    failing = set()
    for (design, eta, shift), s in series.items():
        a = identical_square(design)
        if a is None or not {2, 4, 8, 16} <= set(s):
            continue
        j = judge(s, _model(a, eta), "min")
        if j.verdict == "fails":
            failing.add((design, eta, shift))
        if j.verdict == "holds" and min(eta, 90 - eta) < 45:  # where the strip bound is used
            held.add((design, eta))
    # the one settled coupon the factor does not bound (docs/load_cases.md 5: it needs c = 0.89;
    # the refit is left to the lead): any other failure, or this one fixed, fails the test
    assert failing == {(KNOWN_FAILING, 30.0, 0.0)}, failing
    designs = {d for d, _ in held}
    assert len(designs) >= 2, held  # more than one coupon, polypropylene among them
    assert any("polypropylene" in d for d in designs)
    assert {15.0, 30.0} <= {e for _, e in held}
