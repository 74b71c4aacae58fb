"""Four-point bending along layer 1's creases (eta 0) with and without crease strips, as the
span grows (docs/calibration.md 10): layer 1's EI (its D share times the span, N mm^2) of the
walk-through's design (W 9 mm, n 7, alpha 93 deg, Dura-Lar 0.125 mm at E 2818 MPa) with no
strips, strips at k = 1e6 and at k = 0.0987 N mm/(rad mm), the span being layer 2's extent
(n2 + 1) p on a rectangle.

    PYTHONPATH=src python benchmarks/fea_crease_span.py 7:2,4,8 15:2,4 31:2,4

(each argument: layer 2's n, then the meshes in elements per facet).
"""

import sys
import time
from dataclasses import replace

from corrugate.fea.assembly import AssemblyMesh, solve_assembly
from corrugate.geometry.layer import Assembly, Layer
from corrugate.geometry.layouts import Rectangle
from corrugate.materials.library import get_material

m = replace(get_material("dura-lar"), E=2818.0)
lay = Layer(W=9, n=7, alpha_deg=93, material=m, t=0.125)
for spec in sys.argv[1:]:
    n2, alongs = spec.split(":")
    n2 = int(n2)
    a = Assembly(layer1=lay, layer2=replace(lay, n=n2), layout=Rectangle())
    for along in [int(x) for x in alongs.split(",")]:
        row = []
        for k in (None, 1e6, 0.0987):
            t0 = time.time()
            r = solve_assembly(a, "four-point", AssemblyMesh(along=along), 0.0, crease_stiffness=k)
            row.append(f"k {k}: EI1 {r.layer_values[0] * a.Ly:.0f} ({time.time() - t0:.0f} s)")
        print(f"n2 {n2} span {a.Ly:.1f} mm, {along}/facet: " + "; ".join(row), flush=True)
