"""The zig-zag strip pulled along its chord line: CalculiX with crease strips against the hand
derivation (corrugate.calibration.fe_crease; docs/offaxis.md, "Compliant creases").

Dura-Lar 0.125 mm, 9 creases, facets 12 mm at 90 deg, 20 mm wide (the kit's C1 with full end
facets); k in N mm/(rad mm), 1e6 standing for rigid on the strips' mesh (k = inf meshes no
strip, and its rigid end columns, W / along wide, converge at first order).

    PYTHONPATH=src python benchmarks/fea_crease_strip.py [--along 2,4,8,16] [--k 1e6,1,0.1,0.05]
"""

from __future__ import annotations

import argparse

from corrugate.calibration.fe_crease import compliance, crease_strip_compliance, rigid_ends
from corrugate.materials.library import get_material


def main() -> None:
    ap = argparse.ArgumentParser()
    ap.add_argument("--along", default="2,4,8,16")
    ap.add_argument("--k", default="1e6,1,0.1,0.05")
    args = ap.parse_args()
    m = get_material("dura-lar")
    t, b, W, alpha, n = 0.125, 20.0, 12.0, 90.0, 9
    for k in (float(x) for x in args.k.split(",")):
        closed = compliance(k, m.E, m.nu, t, b, W, alpha, n)
        # the FE's end zones (one strip element each) are rigid: the closed form less them
        ends = closed - rigid_ends(m.E, m.nu, t, b, W, alpha)
        for along in (int(x) for x in args.along.split(",")):
            r = crease_strip_compliance(m, k, t, b, W, alpha, n, along)
            print(
                f"k={k:g} along={along} FE C={r.C:.6g} mm/N closed form {closed:.6g} (less the "
                f"rigid ends {ends:.6g}) FE/closed {r.C / closed:.4f} nodes={r.nodes} "
                f"ccx {r.seconds:.1f} s",
                flush=True,
            )


if __name__ == "__main__":
    main()
