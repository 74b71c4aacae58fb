"""FE of a design at a tolerance corner (docs/tolerances.md, section 3): verify's twin of EI(0)
(the four-point pure-bending gauge, ``corrugate.fea.verify.verify_design``) on the corner's
Assembly built by hand: two Dura-Lar layers of n creases at (W1, alpha1) and (W2, alpha2) on a
rectangle, the sheet's t and E scaled by TF and EF.

Usage: PYTHONPATH=src python benchmarks/tolerance_corner_fe.py W1 A1 W2 A2 n TF EF BOUND MESHES
[TIMEOUT]
e.g. ... 3.9 152 3.9 146 15 0.95 0.9 1200 2,4,8 (TIMEOUT: seconds per ccx run, default 900)
"""

from __future__ import annotations

import sys
import time
from dataclasses import replace

from corrugate.fea.verify import verify_design
from corrugate.geometry.layer import Assembly, Layer
from corrugate.geometry.layouts import Rectangle
from corrugate.materials.library import get_material


def main(argv: list[str]) -> None:
    W1, a1, W2, a2, n, tf, ef, bound = (float(v) for v in argv[:8])
    meshes = tuple(int(v) for v in argv[8].split(","))
    timeout = float(argv[9]) if len(argv) > 9 else 900.0
    m = get_material("dura-lar")
    m = replace(m, E=m.E * ef)
    t = 0.125 * tf
    a = Assembly(Layer(W1, int(n), a1, m, t), Layer(W2, int(n), a2, m, t), Rectangle())
    entry = {
        "name": "constraints.flexural_rigidity[0].min",
        "quantity": "EI@0",
        "sense": "min",
        "bound": bound,
        "value": float("nan"),
        "unit": "N*mm^2",
    }
    t0 = time.time()
    v = verify_design(
        a,
        [entry],
        meshes=meshes,
        timeout=timeout,
        progress=lambda s: print(f"[{time.time() - t0:7.1f} s] {s}"),
    )
    print(f"wall {time.time() - t0:.1f} s")
    print(v)


if __name__ == "__main__":
    main(sys.argv[1:])
