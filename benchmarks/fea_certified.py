"""FE mesh series of certified off-axis designs: does the certificate hold in the FE coupon?

    python benchmarks/fea_certified.py [ALONG ...]

For each design (the certified answers of the two off-axis specs of the load-case work, found
with `corrugate design SPEC`; the specs are in the module's SPECS text) the compression coupon
of `corrugate.fea.assembly` at the spec's eta, at each mesh (default 2 4 8 elements per
facet), printed with the certified model value and the Richardson estimate of
benchmarks/offaxis_table.py `estimate()`. One ccx run at a time.
"""

from __future__ import annotations

import sys
import time

from corrugate import Assembly, Layer, analyze, get_material
from corrugate.fea.assembly import AssemblyMesh, solve_assembly
from offaxis_table import estimate

#: (label, W mm, n, alpha deg, eta deg, bound N/mm): the certified designs (Dura-Lar 0.125 mm,
#: square, identical layers) of
#: * "k15": side 48-60 mm, buckling_load >= 5 N at 0 deg, K(15) >= 75 N/mm, W 5-16 mm step 1,
#:   n 4-30, alpha 40-105 deg step 1 (with K(15) >= 85 N/mm the spec is infeasible under the
#:   corrected model: the largest certified K(15) is 78.1 N/mm);
#: * "k45": the case study's square (side 48-61 mm, thickness 10-12.5 mm), EI(0) >= 80 mN m^2,
#:   K(45) >= 1 N/mm, W 4-16 step 1, n 4-30, alpha 40-120 step 1 (with side <= 60 mm it is
#:   infeasible: the largest certified K(45) is 0.994 N/mm).
DESIGNS = (
    ("k15: W 5, n 12, alpha 104", 5.0, 12, 104.0, 15.0, 75.0),
    ("k45: W 9, n 8, alpha 96", 9.0, 8, 96.0, 45.0, 1.0),
)


def main(alongs: tuple[int, ...]) -> None:
    dl = get_material("dura-lar")
    for label, W, n, alpha, eta, bound in DESIGNS:
        a = Assembly.identical(Layer(W=W, n=n, alpha_deg=alpha, material=dl))
        model = analyze(a, eta_deg=[eta]).stiffness[0].K
        series: dict[int, float] = {}
        for along in alongs:
            t0 = time.perf_counter()
            r = solve_assembly(a, "platens", AssemblyMesh(along), eta, timeout=3600.0)
            series[along] = r.value()
            print(
                f"{label} eta {eta:g}: {along}/facet K = {r.value():.5g} N/mm "
                f"({r.nodes} nodes, {time.perf_counter() - t0:.0f} s)",
                flush=True,
            )
        fe, how = estimate(series)
        print(
            f"{label}: bound {bound:g}, certified model {model:.5g}, FE {fe:.5g} ({how}), "
            f"FE >= bound: {fe >= bound}",
            flush=True,
        )


if __name__ == "__main__":
    main(tuple(int(a) for a in sys.argv[1:]) or (2, 4, 8))
