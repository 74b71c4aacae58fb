"""The plate bounds of corrugate.mechanics.buckling against the FE first buckling load, on the paper's
bench designs (docs/fea.md, section 2.6): is the lower bound, which the solver's
``buckling_load`` constraints use, below the FE for every design?

    python benchmarks/buckling_table.py            # 2 and 4 elements/facet; 8 for two designs
    python benchmarks/buckling_table.py 2 4 8      # these meshes for every design

The paper's validation sweep (``corrugate validate --sweep paper``, corrugate.fea.series) has 12
cases, 10 distinct designs (W = 10, n = 11, alpha = 90 is in each set); each distinct design is
run once. Compression along eta = 0 (layer 1's creases), no connector band. Prints a Markdown
table. Needs ccx. About 15 min on 2 shared cores (the 8-per-facet runs dominate: 3-4 min each).
"""

from __future__ import annotations

import sys
import time

from corrugate.analysis.evaluate import facet_buckling_load
from corrugate.fea.assembly import AssemblyMesh, solve_assembly
from corrugate.fea.series import paper_cases
from corrugate.fea.steps import LinearBuckling

#: Designs also run at 8 elements per facet: the deepest fold and the widest facet.
SERIES = ("W=10 n=11 alpha=40", "W=14 n=11 alpha=90")


def main(meshes: tuple[int, ...], series: tuple[int, ...]) -> None:
    cols = ["set", "design", "low N (k 0.425)", "high N (k 1.277)"]
    cols += [f"FE {m}/facet N" for m in (*meshes, *series)]
    cols += ["low/FE (finest)", "FE finest / high", "s"]
    print("| " + " | ".join(cols) + " |")
    print("|---" * len(cols) + "|")
    done: dict[str, dict[int, float]] = {}
    for case in paper_cases(unit_cell=False):
        a = case.assembly
        b = facet_buckling_load(a, 0.0)
        t0 = time.perf_counter()
        if case.label not in done:
            runs = meshes + (series if case.label in SERIES else ())
            done[case.label] = {
                m: solve_assembly(a, "platens", AssemblyMesh(m), 0.0, step=LinearBuckling()).value()
                for m in runs
            }
        s = time.perf_counter() - t0
        fe = done[case.label]
        cells = [f"{fe[m]:.4g}" if m in fe else "" for m in (*meshes, *series)]
        finest = fe[max(fe)]
        print(
            f"| {case.group} | {case.label} | {b.low:.4g} | {b.high:.4g} | "
            + " | ".join(cells)
            + f" | {b.low / finest:.3f} | {finest / b.high:.3f} | {s:.0f} |",
            flush=True,
        )


if __name__ == "__main__":
    if len(sys.argv) > 1:
        main(tuple(int(v) for v in sys.argv[1:]), ())
    else:
        main((2, 4), (8,))
