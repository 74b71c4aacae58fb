"""FE coupons along eta versus the closed forms' cos^2 rule (docs/fea.md, section 2.5).

    python benchmarks/fea_eta.py            # two designs, eta = 0, 15, ..., 90, 4 elements/facet
    python benchmarks/fea_eta.py converge   # W 10, n 7, alpha 90 at eta = 45: 2, 4, 8 per facet

Prints Markdown tables. Needs ccx and gmsh (the `fea` extra). A few minutes.
"""

from __future__ import annotations

import sys
import time

from corrugate import Assembly, Layer, analyze, get_material
from corrugate.fea.assembly import AssemblyMesh, solve_assembly

DESIGNS = {
    "case study W 8, n 8, alpha 84": Layer(
        W=8.0, n=8, alpha_deg=84.0, material=get_material("dura-lar")
    ),
    "W 10, n 7, alpha 90": Layer(W=10.0, n=7, alpha_deg=90.0, material=get_material("dura-lar")),
}
TESTS = ("platens", "three-point", "four-point")


def table(along: int = 4) -> None:
    for name, layer in DESIGNS.items():
        a = Assembly.identical(layer)
        etas = [0.0, 15.0, 30.0, 45.0, 60.0, 75.0, 90.0]
        cf = analyze(a, "refined", etas).stiffness
        print(f"\n#### {name}, Dura-Lar 0.125 mm, square, {along} elements/facet\n")
        print(
            "| eta | K FE | K refined | K refined/FE | D FE | D4 FE | D refined | D refined/FE | D refined/D4 FE | s |"
        )
        print("|---" * 10 + "|")
        for eta, d in zip(etas, cf, strict=True):
            t0 = time.perf_counter()
            K, D, D4 = (solve_assembly(a, t, AssemblyMesh(along), eta).value() for t in TESTS)
            s = time.perf_counter() - t0
            print(
                f"| {eta:g} | {K:.4g} | {d.K:.4g} | {d.K / K:.3g} | {D:.4g} | {D4:.4g} | "
                f"{d.D:.4g} | {d.D / D:.3g} | {d.D / D4:.3g} | {s:.0f} |",
                flush=True,
            )


def converge() -> None:
    a = Assembly.identical(DESIGNS["W 10, n 7, alpha 90"])
    print("\n| eta | elements/facet | nodes | K FE | D FE | D4 FE | s |")
    print("|---" * 7 + "|")
    for along in (2, 4, 8):
        t0 = time.perf_counter()
        rs = [solve_assembly(a, t, AssemblyMesh(along), 45.0) for t in TESTS]
        s = time.perf_counter() - t0
        K, D, D4 = (r.value() for r in rs)
        print(
            f"| 45 | {along} | {rs[0].nodes} | {K:.4g} | {D:.4g} | {D4:.4g} | {s:.0f} |", flush=True
        )


if __name__ == "__main__":
    converge() if sys.argv[1:] == ["converge"] else table()
