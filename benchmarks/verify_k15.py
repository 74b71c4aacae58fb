"""The certified K(15) design's verify row under the convergence rule of docs/fea.md 6: the
design "k15" of ``benchmarks/fea_certified.py`` (Dura-Lar 0.125 mm, W 5, n 12, alpha 104, two
identical layers on the square; certified K(15) >= 75 N/mm, model 75.30), its K(15) constraint
alone through :func:`corrugate.fea.verify.verify_design` at one coupon position, meshes 2 / 4 /
8, extended as the rule asks up to ``--max-mesh`` (default 16) elements per facet.

    flock /tmp/fe-big.lock prlimit --as=17000000000 python benchmarks/verify_k15.py [SHIFT] [MAX]

Prints each CalculiX run with its wall time (s) on stderr, then the row as JSON. The 16-per-facet
run needs about 7.5 GiB per layer's ccx run (docs/fea.md 2.9).
"""

from __future__ import annotations

import json
import sys
import time

from corrugate import Assembly, Layer, get_material
from corrugate.fea.verify import verify_design

K15 = {
    "name": "constraints.inplane_stiffness[0]",
    "quantity": "K@15",
    "sense": "min",
    "bound": 75.0,
    "value": 75.30,
    "unit": "N/mm",
}


def main() -> None:
    shift = float(sys.argv[1]) if len(sys.argv) > 1 else 0.0
    cap = int(sys.argv[2]) if len(sys.argv) > 2 else 16
    a = Assembly.identical(Layer(W=5.0, n=12, alpha_deg=104.0, material=get_material("dura-lar")))
    t0 = [time.perf_counter()]
    last = [""]

    def progress(line: str) -> None:
        now = time.perf_counter()
        if last[0]:
            print(f"  done in {now - t0[0]:.0f} s wall", file=sys.stderr, flush=True)
        print(time.strftime("%H:%M:%S"), line, file=sys.stderr, flush=True)
        t0[0], last[0] = now, line

    v = verify_design(a, [K15], shifts=(shift,), progress=progress, timeout=7200.0, max_mesh=cap)
    print(f"  done in {time.perf_counter() - t0[0]:.0f} s wall", file=sys.stderr, flush=True)
    print(json.dumps({"verdict": v.verdict, "exit_code": v.exit_code, **v.as_json()}, indent=2))


if __name__ == "__main__":
    main()
