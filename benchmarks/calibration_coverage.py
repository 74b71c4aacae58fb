"""The calibration's virtual experiment, the full study (docs/calibration.md section 7).

    python benchmarks/calibration_coverage.py [--trials 100] [--seed 2026]
    python benchmarks/calibration_coverage.py --example kit/measurements.toml

For the kit of Dura-Lar 0.125 mm on a 12 x 12 in mat (corrugate.calibration.coupons), readings
are generated from a known sheet (E 3100 MPa along, 2900 MPa across, creases k = 0.1 N mm/(rad
mm) folded to 84 deg, five repeats each, every reading off by an error uniform in +-1 mm:
corrugate.calibration.virtual) and fitted back (corrugate.calibration.fit); printed: how often
each 90 % interval holds the true value in ``--trials`` trials, and the median error of each
fitted value. ``--example PATH`` writes one such measurements file instead (the walk-through's).
"""

from __future__ import annotations

import argparse
import math
import time
from dataclasses import replace
from pathlib import Path

import numpy as np

from corrugate.calibration.coupons import design_kit
from corrugate.calibration.fit import fit_measurements
from corrugate.calibration.measurements import Measurements
from corrugate.calibration.virtual import measurements_toml, virtual_measurements
from corrugate.materials.library import get_material

TRUTH = {"along": 3100.0, "across": 2900.0, "k": 0.1, "angle": 84.0}
#: The strips' longest length on a 12 x 12 in mat (corrugate.calibration.kit.write_kit).
USABLE = 11.5 * 25.4 - 2 * 5.0 - 2 * 25.0


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--trials", type=int, default=100)
    ap.add_argument("--seed", type=int, default=2026)
    ap.add_argument("--example", type=Path, default=None)
    args = ap.parse_args()
    kit = design_kit(get_material("dura-lar"), 0.125, USABLE)
    rng = np.random.default_rng(args.seed)

    def measure() -> Measurements:
        return virtual_measurements(
            kit, TRUTH["along"], TRUTH["k"], TRUTH["angle"], rng, E_across=TRUTH["across"]
        )

    if args.example is not None:
        m = replace(measure(), name="my-dura-lar", date="2026-12-06")
        args.example.write_text(measurements_toml(m))
        print(f"wrote {args.example}")
        return
    hits = {"along": 0, "across": 0, "k": 0, "angle": 0}
    errors: dict[str, list[float]] = {key: [] for key in hits}
    t0 = time.process_time()
    for _ in range(args.trials):
        fit = fit_measurements(measure(), seed=int(rng.integers(1 << 31)))
        for mod in fit.moduli:
            true = TRUTH[mod.direction]
            hits[mod.direction] += mod.lo <= true <= mod.hi
            errors[mod.direction].append(mod.E / true - 1)
        c = fit.crease
        assert c is not None
        hits["k"] += c.k_lo <= TRUTH["k"] <= c.k_hi
        errors["k"].append((c.k if math.isfinite(c.k) else math.inf) / TRUTH["k"] - 1)
        hits["angle"] += c.angle_lo <= TRUTH["angle"] <= c.angle_hi
        errors["angle"].append(c.angle - TRUTH["angle"])
    cpu = time.process_time() - t0
    print(f"{args.trials} trials, seed {args.seed}, {cpu:.0f} s of CPU")
    print("value    truth        90 % interval holds it   median |error|")
    for key, n in hits.items():
        unit = " deg" if key == "angle" else " (relative)"
        med = float(np.median(np.abs(errors[key])))
        shown = f"{med:.2f}{unit}" if key == "angle" else f"{100 * med:.1f} %"
        print(f"{key:<8} {TRUTH[key]:<12g} {n:>3} of {args.trials}              {shown}")


if __name__ == "__main__":
    main()
