"""Coupon-size series of the off-axis compression coupon (docs/offaxis.md, "Open").

    python benchmarks/fea_offaxis_size.py [--eta 15] [--n 4,8,16] [--along 4,8] [--csv FILE]

The case study's layers (W 8, alpha 84, Dura-Lar 0.125 mm) with n = 4, 8, 16 cells, so coupons of
about 0.5, 1 and 2 times the case study's side, compressed between frictionless platens at eta
(docs/fea.md 2.1), at each number of shell elements per facet. Prints (and appends to the CSV,
resuming where a killed run stopped) K in N/mm beside the free model's K, which does not depend on
the coupon's size: whether the model is the large-coupon limit shows in how K(n) moves with n.
Needs ccx and gmsh. Slow: minutes per run at 8 elements per facet for n = 16.
"""

from __future__ import annotations

import argparse
import time
from pathlib import Path

from corrugate import Assembly, Layer, analyze, get_material
from resumable_csv import appender, done_keys  # type: ignore[import-not-found]

FIELDS = ("n", "eta_deg", "along", "nodes", "K_FE", "K_model", "seconds")


def main() -> None:
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("--eta", type=float, default=15.0)
    p.add_argument("--n", default="4,8,16")
    p.add_argument("--along", default="4,8")
    p.add_argument("--csv", type=Path, default=Path("offaxis_size.csv"))
    a = p.parse_args()
    from corrugate.fea.assembly import AssemblyMesh, solve_assembly

    dl = get_material("dura-lar")
    done = done_keys(a.csv, ("n", "eta_deg", "along"))
    with appender(a.csv, FIELDS) as write:
        for along in (int(v) for v in a.along.split(",")):
            for n in (int(v) for v in a.n.split(",")):
                if (str(n), f"{a.eta:g}", str(along)) in done:
                    continue
                asm = Assembly.identical(Layer(W=8.0, n=n, alpha_deg=84.0, material=dl))
                model = float(analyze(asm, eta_deg=(a.eta,)).stiffness[0].K)
                t0 = time.perf_counter()
                r = solve_assembly(asm, "platens", AssemblyMesh(along), a.eta)
                s = time.perf_counter() - t0
                row = (
                    n,
                    f"{a.eta:g}",
                    along,
                    r.nodes,
                    f"{r.value():.6g}",
                    f"{model:.6g}",
                    f"{s:.0f}",
                )
                write(row)
                print(*row, flush=True)


if __name__ == "__main__":
    main()
