"""The off-axis bending model of docs/load_cases.md 5, the strip bound counting one facet fewer
(D_S c^4 max(0, 1 - |tan theta| - 1 / (n + 1))) times the factor 1 - w(eta) c / sqrt(n),
c = FINITE_PANEL_BENDING, against the FE coupons of docs/validation/load_cases_fe.csv
(independent source: CalculiX 3-point coupons cut along eta at three positions of the cut,
2 / 4 / 8 / 16 elements per facet).

Every coupon whose series the project's convergence rule settles (corrugate.fea.extrapolate.judge,
as `corrugate verify` uses it: four meshes, monotone, shrinking steps, two Richardson estimates
within a quarter of the margin) holds the model: the model's apparent D of the test is at or
below the FE, on more than one coupon, with no exception (the table of docs/load_cases.md 5,
`python benchmarks/offaxis_bending_factor.py`). The coupon that 0.3 / sqrt(n) alone failed
(Dura-Lar 0.175 mm, W 10, n 6, alpha 40 at 30 deg, shift 0: FE 1745.2 / 1691.2 / 1651.2 /
1630.7 N mm, estimate 1609.2, against 1871.6) is among the settled rows that hold."""

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
#: The coupon whose settled series the factor 0.3 / sqrt(n) alone did not bound at 30 deg
#: (docs/load_cases.md 5).
FORMERLY_FAILING = "Dura-Lar 0.175: W 10, n 6, alpha 40"


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
    held: set[tuple[str, float, float]] = set()
    failing = set()
    for (design, eta, shift), s in series.items():
        a = identical_square(design)
        if a is None or not {2, 4, 8, 16} <= set(s):
            continue
        j = judge(s, _model(a, eta), "min")
        if j.verdict == "fails":
            failing.add((design, eta, shift))
        if j.verdict == "holds" and min(eta, 90 - eta) < 45:  # where the strip bound is used
            held.add((design, eta, shift))
    assert not failing, failing  # no settled coupon is below the model
    designs = {d for d, _, _ in held}
    assert len(designs) >= 3, held  # more than one coupon, polypropylene among them
    assert any("polypropylene" in d for d in designs)
    assert {15.0, 30.0} <= {e for _, e, _ in held}
    assert (FORMERLY_FAILING, 30.0, 0.0) in held  # settled now, and above the model
    assert len(held) >= 12, held
