"""First buckling load of the assembly in compression: FE mesh convergence against the plate
bounds of corrugate.mechanics.buckling (docs/fea.md, section 2.6).

    python benchmarks/fea_buckling.py

Prints a Markdown table. Needs ccx. A few minutes (the band at 8 elements per facet dominates).
"""

from __future__ import annotations

import time

from corrugate import Assembly, Layer, get_material
from corrugate.analysis.evaluate import facet_buckling_load
from corrugate.fea.assembly import AssemblyMesh, solve_assembly
from corrugate.fea.steps import LinearBuckling

DESIGNS = {
    "test assembly: W 5, n 7, alpha 120, t 0.1": Layer(
        W=5.0, n=7, alpha_deg=120.0, material=get_material("dura-lar"), t=0.1
    ),
    "case study: W 8, n 8, alpha 84, t 0.125": Layer(
        W=8.0, n=8, alpha_deg=84.0, material=get_material("dura-lar")
    ),
}

if __name__ == "__main__":
    print("| design | band | elements/facet | nodes | P_cr FE (N) | plate bounds (N) | s |")
    print("|---" * 7 + "|")
    for name, layer in DESIGNS.items():
        a = Assembly.identical(layer)
        b = facet_buckling_load(a, 0.0)
        for band in (False, True):
            for along in (2, 4, 8):
                t0 = time.perf_counter()
                r = solve_assembly(
                    a, "platens", AssemblyMesh(along), 0.0, connectors=band, step=LinearBuckling()
                )
                s = time.perf_counter() - t0
                print(
                    f"| {name} | {'yes' if band else 'no'} | {along} | {r.nodes} | "
                    f"{r.value():.4g} | {b.low:.3g}-{b.high:.3g} | {s:.0f} |",
                    flush=True,
                )
