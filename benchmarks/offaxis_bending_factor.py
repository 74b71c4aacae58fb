"""The off-axis bending factor against the FE coupons: the c each coupon needs (docs/load_cases.md 5).

    python benchmarks/offaxis_bending_factor.py

Each layer's share of the free panel's D off the crease directions (its strip bound counting
one facet fewer than the homogenised share, :func:`corrugate.mechanics.offaxis.free_bending`) is
multiplied by 1 - w(eta) c / sqrt(n) (:data:`corrugate.mechanics.offaxis.FINITE_PANEL_BENDING`
= c, w of docs/load_cases.md 4, n the layer's creases). For every 3-point coupon of
docs/validation/load_cases_fe.csv off the creases (design, eta, shift of the coupon's cut) the
model's apparent D of the test (`model_value` of benchmarks/load_case_table.py, the formula of
`corrugate.mechanics.load_cases` over the coupon's length) at the c used is the bound its FE
series is judged against, as `corrugate verify` judges one (:func:`corrugate.fea.extrapolate.
judge`, sense ``min``): a series counts only on four meshes k, 2k, 4k, 8k, monotone with
shrinking steps, its two Richardson estimates within a quarter of the margin. A coupon judge
does not settle ("open": fewer than four meshes, not monotone, or the two estimates too far
apart for the margin) is "not converged" and excluded. For the others, "FE estimate" is judge's
value (the extrapolation from the three finest meshes), "c needed" the least c >= 0 at which the
model is at or below it (bisection: the model falls as c grows; 0 when the model without the
factor, c = 0, already is) and the margin the FE estimate over the model at the c used.
"""

from __future__ import annotations

import csv
import itertools
import math
from collections import defaultdict
from collections.abc import Iterator
from contextlib import contextmanager
from dataclasses import dataclass
from pathlib import Path

from corrugate import Assembly
from corrugate.fea.extrapolate import judge, richardson
from corrugate.mechanics import offaxis
from corrugate.mechanics.offaxis import FINITE_PANEL_BENDING, finite_panel_weight
from fea_load_cases import designs  # type: ignore[import-not-found]
from load_case_table import model_value  # type: ignore[import-not-found]

CSV = Path(__file__).resolve().parents[1] / "docs" / "validation" / "load_cases_fe.csv"
Series = dict[int, float]


@contextmanager
def bending_constant(c: float) -> Iterator[None]:
    """The model with FINITE_PANEL_BENDING = ``c`` (the share of K's deficit it scales)."""
    old = offaxis._B
    offaxis._B = c / offaxis.FINITE_PANEL_DEFICIT
    try:
        yield
    finally:
        offaxis._B = old


def model_at(a: Assembly, eta: float, c: float) -> float:
    """The 3-point model's apparent D (N mm) at ``eta`` with the constant ``c``."""
    with bending_constant(c):
        return model_value(a, "bending", eta)


def four_meshes(series: Series) -> bool:
    """Whether the series has four meshes each twice the one before (what judge needs)."""
    alongs = sorted(series)[-4:]
    return len(alongs) == 4 and all(b == 2 * x for x, b in itertools.pairwise(alongs))


def needed(a: Assembly, eta: float, fe: float) -> float:
    """The least c >= 0 at which the model is at or below ``fe`` (N mm); inf when even a
    factor of 0 is not."""
    if model_at(a, eta, 0.0) <= fe:
        return 0.0
    n = min(a.layer1.n, a.layer2.n)
    hi = math.sqrt(n) / finite_panel_weight(eta)  # the factor 0 on the layer of fewest creases
    if model_at(a, eta, hi) > fe:
        return math.inf
    lo = 0.0
    for _ in range(50):
        mid = 0.5 * (lo + hi)
        if model_at(a, eta, mid) <= fe:
            hi = mid
        else:
            lo = mid
    return hi


@dataclass(frozen=True)
class Row:
    design: str
    n: str
    alpha: str
    eta: float
    shift: float
    series: Series
    verdict: str  # judge's at the c used: holds, fails or open (not converged)
    needed: float | None  # None: not converged
    fe: float | None  # judge's estimate at the c used
    model: float  # at the c used
    model0: float  # at c = 0: the homogenised model
    how: str


def load() -> dict[tuple[str, float, float], Series]:
    out: dict[tuple[str, float, float], Series] = defaultdict(dict)
    with CSV.open() as f:
        for r in csv.DictReader(line for line in f if not line.startswith("#")):
            eta = float(r["eta_deg"])
            if r["test"] == "bending" and eta % 90 != 0:
                out[(r["design"], eta, float(r["shift"]))][int(r["along"])] = float(r["value"])
    return out


def rows() -> list[Row]:
    ds = designs()
    out = []
    for (name, eta, shift), s in sorted(load().items()):
        a = ds[name]
        if not four_meshes(s):
            continue
        model = model_at(a, eta, FINITE_PANEL_BENDING)
        j = judge(s, model, "min")
        c = needed(a, eta, j.value) if j.verdict != "open" and j.value is not None else None
        ls = (a.layer1, a.layer2)
        n = "/".join(sorted({str(x.n) for x in ls}))
        alpha = "/".join(sorted({f"{x.alpha_deg:g}" for x in ls}))
        how = j.why if j.verdict == "open" else j.how
        model0 = model_at(a, eta, 0.0)
        out.append(Row(name, n, alpha, eta, shift, s, j.verdict, c, j.value, model, model0, how))
    return out


def excluded() -> list[tuple[str, float, float, Series]]:
    """The coupons with fewer than four meshes (2 / 4 / 8): not shown asymptotic."""
    return [(k[0], k[1], k[2], s) for k, s in sorted(load().items()) if not four_meshes(s)]


def verdict(r: Row) -> str:
    """judge's word: holds / fails, or not converged with what it has not shown."""
    if r.verdict != "open":
        return r.verdict
    return f"not converged: {r.how}"


def main() -> None:
    c_used = FINITE_PANEL_BENDING
    print(
        "| coupon | n | alpha deg | eta deg | shift | FE D 2 / 4 / 8 / 16 N mm | FE estimate N mm "
        "| model N mm (c used) | judge | c needed | c used | margin FE / model | FE / model at c = 0 |"
    )
    print("|---|---|---|---|---|---|---|---|---|---|---|---|---|")
    worst = -math.inf
    for r in rows():
        ser = " / ".join(f"{r.series[k]:.5g}" for k in sorted(r.series))
        if r.needed is None:
            what, fe, margin, m0 = "excluded", "-", "-", "-"
        else:
            worst = max(worst, r.needed)
            what = f"{r.needed:.3f}"
            fe = f"{r.fe:.5g}" if r.fe is not None else "-"
            margin = f"{r.fe / r.model:.3f}" if r.fe is not None else "-"
            m0 = f"{r.fe / r.model0:.3f}" if r.fe is not None else "-"
        print(
            f"| {r.design} | {r.n} | {r.alpha} | {r.eta:g} | {r.shift:g} | {ser} | {fe} | "
            f"{r.model:.5g} | {verdict(r)} | {what} | {c_used:g} | {margin} | {m0} |"
        )
    print(f"\nlargest c needed over the converged coupons: {worst:.4f} (c used {c_used:g})")
    ex = excluded()
    print(f"\nexcluded (fewer than four meshes, not shown asymptotic): {len(ex)} series")
    print("for information, the c each would need at its 2 / 4 / 8 Richardson estimate")
    print("(or its finest value when not monotone), eta below 45 deg from a crease:")
    ds = designs()
    info = -math.inf
    for name, eta, shift, s in ex:
        if min(eta, 90 - eta) >= 45 or len(s) < 3:
            continue
        r = richardson(s)
        fe = r[0] if r is not None else s[max(s)]
        c = needed(ds[name], eta, fe)
        info = max(info, c)
        ser = " / ".join(f"{s[k]:.5g}" for k in sorted(s))
        print(f"  {name} eta {eta:g} shift {shift:g}: {ser} -> {fe:.5g}, c needed {c:.3f}")
    print(f"largest: {info:.4f}")


if __name__ == "__main__":
    main()
