"""The elastica against CalculiX on a kit's flat strip: the mesh series (docs/calibration.md
section 7).

    python benchmarks/calibration_fe_strip.py

Dura-Lar 0.125 mm, 20 mm wide, E 3100 MPa (nu 0.43): its own weight at 75 mm free, and a 5 g
coin at 40 mm free (the kit's set-ups, corrugate.calibration.coupons), S8R shells, NLGEOM
(corrugate.calibration.fe_strip). Prints each mesh's sag and ccx wall time, the ratio of
successive differences and the Richardson estimate, beside the elastica with the plate rigidity
E b t^3 / (12 (1 - nu^2)) (what the fit uses) and with the beam rigidity E b t^3 / 12.
"""

from __future__ import annotations

from itertools import pairwise

from corrugate.calibration.elastica import drop_ratio
from corrugate.calibration.fe_strip import strip_sag
from corrugate.materials.library import get_material

MAT = get_material("dura-lar")
E, T, B = 3100.0, 0.125, 20.0


def elastica(L: float, tip_g: float, rigidity: float) -> float:
    q = MAT.density * B * T * 9.80665e-3
    return L * drop_ratio(q * L**3 / rigidity, tip_g * 9.80665e-3 * L**2 / rigidity)


def main() -> None:
    plate = E * B * T**3 / (12 * (1 - MAT.nu**2))
    beam = E * B * T**3 / 12
    for L, tip in ((75.0, 0.0), (40.0, 5.0)):
        print(
            f"free {L:g} mm, tip {tip:g} g: elastica plate {elastica(L, tip, plate):.3f} mm, "
            f"beam {elastica(L, tip, beam):.3f} mm"
        )
        sags = []
        for nx, ny in ((8, 2), (16, 2), (32, 2), (64, 2), (32, 4)):
            r = strip_sag(MAT, E, T, B, L, tip, nx, ny)
            print(f"  {nx:3d} x {ny} elements: sag {r.sag:.3f} mm, ccx {r.seconds:.1f} s wall")
            if ny == 2:
                sags.append(r.sag)
        d = [b - a for a, b in pairwise(sags)]
        ratios = [d[i] / d[i + 1] for i in range(len(d) - 1) if d[i + 1] != 0]
        print(
            "  differences "
            + ", ".join(f"{x:+.3f}" for x in d)
            + "; ratios "
            + ", ".join(f"{x:.2f}" for x in ratios)
        )
        if ratios and ratios[-1] > 1:
            rich = sags[-1] + d[-1] / (ratios[-1] - 1)
            print(f"  Richardson (observed order): {rich:.3f} mm")


if __name__ == "__main__":
    main()
