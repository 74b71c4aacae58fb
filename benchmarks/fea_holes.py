"""FE check of the hole model (docs/fea.md, section 2.7).

The case-study square (W 8 mm, n 8, alpha 84 deg, Dura-Lar 0.125 mm) with a circular hole of each
given diameter (mm; 0 = none) at its centre: K at eta = 0 in compression from the model
(``analyze``, refined) and from the assembly FE (CalculiX, staircase hole), and the plan area the
staircase hole removes from layer 1.

    python benchmarks/fea_holes.py ALONG D1 [D2 ...]      # e.g. 8 0 6 12
"""

from __future__ import annotations

import math
import sys
import time

import numpy as np

from corrugate.analysis.evaluate import analyze
from corrugate.fea.assembly import AssemblyMesh, solve_assembly
from corrugate.fea.cuts import cut_holes
from corrugate.fea.shells import Shell, layer_shell
from corrugate.geometry.holes import Hole
from corrugate.geometry.layer import Assembly, Layer
from corrugate.geometry.layouts import make_layout
from corrugate.materials.library import get_material


def plan_area(sh: Shell) -> float:
    """Plan area (mm^2) of a shell's S8R elements (corner nodes)."""
    idx = {int(n): i for i, n in enumerate(sh.ids)}
    total = 0.0
    for e in sh.elements:
        p = sh.xyz[[idx[n] for n in e[:4]], :2]
        total += 0.5 * abs(
            float(np.sum(p[:, 0] * np.roll(p[:, 1], -1) - np.roll(p[:, 0], -1) * p[:, 1]))
        )
    return total


def main(along: int, diameters: list[float]) -> None:
    layer = Layer(8.0, 8, 84.0, get_material("dura-lar"))
    for d in diameters:
        holes = () if d == 0 else (Hole("circle", (0.0, 0.0), d),)
        a = Assembly.identical(layer, make_layout("square", holes=holes))
        model = analyze(a, "refined", (0.0,)).to_dict()["stiffness"][0]["K_N_per_mm"]
        t0 = time.time()
        r = solve_assembly(a, "platens", AssemblyMesh(along), 0.0)
        line = (
            f"d={d:g} mm along={along}: model K={model:.2f} N/mm  FE K={r.K:.2f} N/mm "
            f"(layers {r.layer_values[0]:.2f} + {r.layer_values[1]:.2f}), nodes {r.nodes}, "
            f"elements {r.elements}, {time.time() - t0:.0f} s"
        )
        if d:
            sh = layer_shell(a.layer1, a.Ly, along, 1, 0, 0.0, 2, None)
            removed = plan_area(sh) - plan_area(cut_holes(sh, a))
            line += f"; hole area {removed:.2f} mm^2 (pi r^2 {math.pi * d * d / 4:.2f})"
        print(line, flush=True)


if __name__ == "__main__":
    main(int(sys.argv[1]), [float(x) for x in sys.argv[2:]])
