"""The free panel's K(eta) with compliant creases: the model against the FE with the same crease.

One small design (Dura-Lar 0.125 mm, W 8 mm, n 4, alpha 84 deg, identical layers on a square),
frictionless platens, at eta = 45 and 90 deg, for rigid creases and two crease stiffnesses k
(N mm/(rad mm)) spanning what the kit's fit measures (docs/calibration.md section 4): 1.0 (stiff)
and 0.05 (soft, about the k = D / 12 mm the kit is sized for). The FE's creases are compliant
strips (corrugate.fea.shells.crease_strip); each row is a mesh series at 2 / 4 / 8 elements per
facet, judged by corrugate.fea.extrapolate. At eta = 90 deg layer 1 is pulled along its chords
(K_C, the accordion) and layer 2 along its creases (K_S); both layers' shares are printed.

    PYTHONPATH=src python benchmarks/fea_crease_offaxis.py [--along 2,4,8] [--eta 45,90] [--k inf,1,0.05]

docs/offaxis.md, "Compliant creases", shows its table.
"""

from __future__ import annotations

import argparse
import time
from dataclasses import replace

from corrugate.analysis.evaluate import analyze
from corrugate.fea.assembly import AssemblyMesh, solve_assembly
from corrugate.geometry.layer import Assembly, Layer
from corrugate.materials.library import get_material


def main() -> None:
    ap = argparse.ArgumentParser()
    ap.add_argument("--along", default="2,4,8")
    ap.add_argument("--eta", default="45,90")
    ap.add_argument("--k", default="inf,1,0.05")
    ap.add_argument("--W", type=float, default=8.0)
    ap.add_argument("--n", type=int, default=4)
    ap.add_argument("--alpha", type=float, default=84.0)
    args = ap.parse_args()
    base = get_material("dura-lar")
    for k in (float(x) for x in args.k.split(",")):
        m = replace(base, crease_stiffness=k)
        a = Assembly.identical(Layer(W=args.W, n=args.n, alpha_deg=args.alpha, material=m, t=0.125))
        for eta in (float(x) for x in args.eta.split(",")):
            r = analyze(a, eta_deg=[eta], support="free")
            s1 = r.springs[0]
            print(
                f"k={k:g} eta={eta:g} model K={r.stiffness[0].K:.6g} N/mm (layer 1 K_C="
                f"{float(s1.K_C):.6g}, K_S={float(s1.K_S):.6g})",
                flush=True,
            )
            for along in (int(x) for x in args.along.split(",")):
                t0 = time.time()
                fe = solve_assembly(a, "platens", AssemblyMesh(along=along), eta)
                print(
                    f"k={k:g} eta={eta:g} along={along} FE K={fe.K:.6g} N/mm layers="
                    f"{fe.layer_values[0]:.6g},{fe.layer_values[1]:.6g} nodes={fe.nodes} "
                    f"wall={time.time() - t0:.1f}s",
                    flush=True,
                )


if __name__ == "__main__":
    main()
