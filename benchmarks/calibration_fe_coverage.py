"""The calibration's virtual experiment with the flat strips' readings from the FE, not the
elastica (issue 38's must-show; docs/calibration.md section 7).

    PYTHONPATH=src python benchmarks/calibration_fe_coverage.py [--trials 100] [--seed 2026]
                                                               [--meshes 16,32,64]

The kit of benchmarks/calibration_coverage.py (Dura-Lar 0.125 mm on a 12 x 12 in mat; truth E
3100 MPa along, 2900 MPa across, k = 0.1 N mm/(rad mm), folded to 84 deg). Each flat set-up's
true sag is the FE's (corrugate.calibration.fe_strip: S8R shells, NLGEOM, clamped at the table
edge, its weight and the coin), the Richardson estimate of a mesh series along the strip (2
elements across); the crease strip's readings stay the zig-zag model's. Each trial adds an
error uniform in +-1 mm to five repeats of every reading and fits them
(corrugate.calibration.fit); printed: the FE series, how often each 90 % interval holds the
true E, the median fitted E over the truth, and each set-up's mean residual (a bias between the
fit's model and the FE shows as residuals of one sign and an E off the truth by more than its
interval).
"""

from __future__ import annotations

import argparse
import time
from dataclasses import replace
from itertools import pairwise

import numpy as np

from corrugate.calibration.coupons import design_kit
from corrugate.calibration.fe_strip import strip_sag
from corrugate.calibration.fit import fit_measurements
from corrugate.calibration.virtual import virtual_measurements
from corrugate.fea.extrapolate import richardson
from corrugate.materials.library import get_material

TRUTH = {"along": 3100.0, "across": 2900.0, "k": 0.1, "angle": 84.0}
#: The strips' longest length on a 12 x 12 in mat (as benchmarks/calibration_coverage.py).
USABLE = 11.5 * 25.4 - 2 * 5.0 - 2 * 25.0


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--trials", type=int, default=100)
    ap.add_argument("--seed", type=int, default=2026)
    ap.add_argument("--meshes", default="16,32,64")
    args = ap.parse_args()
    mat = get_material("dura-lar")
    kit = design_kit(mat, 0.125, USABLE)
    meshes = [int(x) for x in args.meshes.split(",")]
    fe: dict[tuple[str, float, float], float] = {}
    for f in kit.flat:
        E = TRUTH[f.direction]
        for L, tip in ((f.overhang, 0.0), (f.coin_overhang, f.coins * f.coin_g)):
            series: dict[int, float] = {}
            for nx in meshes:
                r = strip_sag(mat, E, kit.t, f.width, L, tip, nx, 2)
                series[nx] = r.sag
                print(
                    f"{f.direction} free {L:g} mm tip {tip:g} g: {nx} x 2 sag {r.sag:.4f} mm "
                    f"({r.seconds:.1f} s)",
                    flush=True,
                )
            steps = [b - a for a, b in pairwise(series.values())]
            # the limit of the three finest meshes (fea.extrapolate); the finest where the
            # series is not asymptotic
            limit = richardson(series)
            fe[(f.direction, L, tip)] = series[meshes[-1]] if limit is None else limit[0]
            print(
                f"  steps {', '.join(f'{s:+.4f}' for s in steps)}; estimate "
                f"{fe[(f.direction, L, tip)]:.4f} mm",
                flush=True,
            )
    rng = np.random.default_rng(args.seed)
    hits = {"along": 0, "across": 0}
    ratios: dict[str, list[float]] = {"along": [], "across": []}
    residuals: dict[tuple[str, float, float], list[float]] = {key: [] for key in fe}
    t0 = time.process_time()
    for _ in range(args.trials):
        m = virtual_measurements(
            kit, TRUTH["along"], TRUTH["k"], TRUTH["angle"], rng, E_across=TRUTH["across"]
        )
        flat = tuple(
            replace(
                t,
                sags=tuple(
                    float(max(fe[(t.direction, t.overhang, t.tip_g)] + rng.uniform(-1, 1), 0.0))
                    for _ in t.sags
                ),
            )
            for t in m.flat
        )
        fit = fit_measurements(replace(m, flat=flat), seed=int(rng.integers(1 << 31)))
        for mod in fit.moduli:
            true = TRUTH[mod.direction]
            hits[mod.direction] += mod.lo <= true <= mod.hi
            ratios[mod.direction].append(mod.E / true)
            at = 0
            for t in mod.tests:  # its residuals in reading order, test by test
                res = mod.residuals[at : at + len(t.sags)]
                at += len(t.sags)
                residuals[(t.direction, t.overhang, t.tip_g)].append(float(np.mean(res)))
    cpu = time.process_time() - t0
    print(f"{args.trials} trials, seed {args.seed}, {cpu:.0f} s of CPU")
    for key, n in hits.items():
        med = float(np.median(ratios[key]))
        print(
            f"E {key}: truth {TRUTH[key]:g} MPa, the 90 % interval holds it {n} of "
            f"{args.trials}; median fitted E / truth {med:.4f}"
        )
    for (direction, L, tip), rs in residuals.items():
        print(
            f"residual {direction} free {L:g} mm tip {tip:g} g: mean {np.mean(rs):+.3f} mm "
            f"(read - fitted)"
        )


if __name__ == "__main__":
    main()
