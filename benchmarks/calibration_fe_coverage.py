"""The calibration's virtual experiment with the readings from the FE of the kit's coupons, not
from the fit's own models (issue 38's must-show; docs/calibration.md section 7).

    PYTHONPATH=src python benchmarks/calibration_fe_coverage.py [--trials 100] [--seed 2026]
        [--meshes 16,32,64] [--across 8] [--crease-meshes 4,8,16]

The kit of benchmarks/calibration_coverage.py (Dura-Lar 0.125 mm on a 12 x 12 in mat; truth E
3100 MPa along, 2900 MPa across, k = 0.1 N mm/(rad mm), folded to 84 deg). Each flat set-up's
true sag is the FE's (corrugate.calibration.fe_strip: S8R shells, NLGEOM, clamped at the table
edge, its weight and the coin), the Richardson estimate of a mesh series along the strip with
``--across`` elements across its width (the anticlastic boundary layers at the free edges need
about 8: section 7 shows the series across). The crease strip's compliance is its FE's
(corrugate.calibration.fe_crease: the kit's strip with full end facets, crease strips of the true
k, at the true E along and angle; the Richardson estimate of ``--crease-meshes`` per facet), less
the closed-form difference between that strip and the kit's (half end facets, free tabs); its
length at rest is the geometry's at the true angle. Each trial adds an error uniform in +-1 mm to
five repeats of every reading and fits them (corrugate.calibration.fit); printed: the FE series,
how often each 90 % interval holds the true value, the median fitted value over the truth, and
each flat set-up's mean residual (a bias between the fit's model and the FE shows as residuals of
one sign and a value off the truth by more than its interval). ``--fe-json PATH`` keeps the FE
estimates (read when present, so a second run needs no ccx); ``--example PATH`` writes one
measurements file of such readings instead (the walk-through's, docs/calibration.md section 8).
"""

from __future__ import annotations

import argparse
import datetime
import json
import time
from dataclasses import replace
from itertools import pairwise
from pathlib import Path

import numpy as np

from corrugate.calibration.coupons import GRAVITY, Kit, design_kit
from corrugate.calibration.crease import compliance as kit_compliance
from corrugate.calibration.fe_crease import compliance as strip_compliance
from corrugate.calibration.fe_crease import crease_strip_compliance, rigid_ends
from corrugate.calibration.fe_strip import strip_sag
from corrugate.calibration.fit import fit_measurements
from corrugate.calibration.measurements import Measurements
from corrugate.calibration.virtual import measurements_toml, virtual_measurements
from corrugate.fea.extrapolate import richardson
from corrugate.materials.library import Material, get_material

TRUTH = {"along": 3100.0, "across": 2900.0, "k": 0.1, "angle": 84.0}
#: The strips' longest length on a 12 x 12 in mat (as benchmarks/calibration_coverage.py).
USABLE = 11.5 * 25.4 - 2 * 5.0 - 2 * 25.0


def fe_truth(
    mat: Material, kit: Kit, meshes: list[int], across: int, crease_meshes: list[int]
) -> dict[str, float]:
    """The FE's estimates: each flat set-up's sag (mm, key "direction/L/tip") and the kit crease
    strip's compliance (mm/N, key "C")."""
    fe: dict[str, float] = {}
    for f in kit.flat:
        E = TRUTH[f.direction]
        for L, tip in ((f.overhang, 0.0), (f.coin_overhang, f.coins * f.coin_g)):
            series: dict[int, float] = {}
            for nx in meshes:
                r = strip_sag(mat, E, kit.t, f.width, L, tip, nx, across)
                series[nx] = r.sag
                print(
                    f"{f.direction} free {L:g} mm tip {tip:g} g: {nx} x {across} sag "
                    f"{r.sag:.4f} mm ({r.seconds:.1f} s)",
                    flush=True,
                )
            steps = [b - a for a, b in pairwise(series.values())]
            # the limit of the three finest meshes (fea.extrapolate); the finest where the
            # series is not asymptotic
            limit = richardson(series)
            key = f"{f.direction}/{L:g}/{tip:g}"
            fe[key] = series[meshes[-1]] if limit is None else limit[0]
            print(
                f"  steps {', '.join(f'{s:+.4f}' for s in steps)}; estimate {fe[key]:.4f} mm",
                flush=True,
            )
    c = kit.crease
    E, k, angle = TRUTH["along"], TRUTH["k"], TRUTH["angle"]
    crease_series: dict[int, float] = {}
    for along in crease_meshes:
        sheet = replace(mat, E=E)  # the FE strip at the true E along (the strip is cut along x)
        r = crease_strip_compliance(sheet, k, kit.t, c.width, c.facet, angle, c.creases, along)
        crease_series[along] = r.C
        print(f"crease strip {along} per facet: C {r.C:.5f} mm/N ({r.seconds:.1f} s)", flush=True)
    limit = richardson(crease_series)
    C_fe = list(crease_series.values())[-1] if limit is None else limit[0]
    # the FE strip has full end facets, whose end zones are rigid; the kit's strip half facets
    fe_closed = strip_compliance(k, E, mat.nu, kit.t, c.width, c.facet, angle, c.creases)
    fe_closed -= rigid_ends(E, mat.nu, kit.t, c.width, c.facet, angle)
    kit_closed = kit_compliance(k, E, kit.t, c.width, c.facet, angle, c.creases, mat.nu)
    fe["C"] = C_fe - (fe_closed - kit_closed)
    print(
        f"  estimate {C_fe:.5f} mm/N; its closed form {fe_closed:.5f} (FE / closed "
        f"{C_fe / fe_closed:.4f}); the kit's strip {fe['C']:.5f} mm/N (its model "
        f"{kit_closed:.5f})",
        flush=True,
    )
    return fe


def fe_readings(kit: Kit, fe: dict[str, float], rng: np.random.Generator) -> Measurements:
    """One set of readings: the virtual experiment's (its lengths at rest, the geometry's at the
    true angle), with every sag and extension the FE's plus a ruler's error in +-1 mm."""
    m = virtual_measurements(
        kit, TRUTH["along"], TRUTH["k"], TRUTH["angle"], rng, E_across=TRUTH["across"]
    )

    def read(true: float) -> float:
        return float(max(true + rng.uniform(-1, 1), 0.0))

    flat = tuple(
        replace(
            t, sags=tuple(read(fe[f"{t.direction}/{t.overhang:g}/{t.tip_g:g}"]) for _ in t.sags)
        )
        for t in m.flat
    )
    assert m.crease is not None
    crease = replace(
        m.crease,
        extensions=tuple(
            tuple(read(fe["C"] * g * GRAVITY) for _ in ext)
            for g, ext in zip(m.crease.masses, m.crease.extensions, strict=True)
        ),
    )
    return replace(m, flat=flat, crease=crease)


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--trials", type=int, default=100)
    ap.add_argument("--seed", type=int, default=2026)
    ap.add_argument("--meshes", default="16,32,64")
    ap.add_argument("--across", type=int, default=8)
    ap.add_argument("--crease-meshes", default="4,8,16")
    ap.add_argument("--fe-json", type=Path, default=None)
    ap.add_argument("--example", type=Path, default=None)
    args = ap.parse_args()
    mat = get_material("dura-lar")
    kit = design_kit(mat, 0.125, USABLE)
    if args.fe_json is not None and args.fe_json.exists():
        fe = json.loads(args.fe_json.read_text())
        print(f"FE estimates read from {args.fe_json}: {fe}")
    else:
        fe = fe_truth(
            mat,
            kit,
            [int(x) for x in args.meshes.split(",")],
            args.across,
            [int(x) for x in args.crease_meshes.split(",")],
        )
        if args.fe_json is not None:
            args.fe_json.write_text(json.dumps(fe, indent=1))
    rng = np.random.default_rng(args.seed)
    if args.example is not None:
        today = datetime.date.today().isoformat()
        m = replace(fe_readings(kit, fe, rng), name="my-dura-lar", date=today)
        args.example.write_text(measurements_toml(m))
        print(f"wrote {args.example}")
        return
    hits = {"along": 0, "across": 0, "k": 0, "angle": 0}
    ratios: dict[str, list[float]] = {key: [] for key in hits}
    residuals: dict[str, list[float]] = {key: [] for key in fe if key != "C"}
    t0 = time.process_time()
    for _ in range(args.trials):
        fit = fit_measurements(fe_readings(kit, fe, rng), seed=int(rng.integers(1 << 31)))
        if fit.crease is not None:
            cf = fit.crease
            hits["k"] += cf.k_lo <= TRUTH["k"] <= cf.k_hi
            ratios["k"].append(cf.k / TRUTH["k"])
            hits["angle"] += cf.angle_lo <= TRUTH["angle"] <= cf.angle_hi
            ratios["angle"].append(cf.angle / TRUTH["angle"])
        for mod in fit.moduli:
            true = TRUTH[mod.direction]
            hits[mod.direction] += mod.lo <= true <= mod.hi
            ratios[mod.direction].append(mod.E / true)
            at = 0
            for t in mod.tests:  # its residuals in reading order, test by test
                res = mod.residuals[at : at + len(t.sags)]
                at += len(t.sags)
                residuals[f"{t.direction}/{t.overhang:g}/{t.tip_g:g}"].append(float(np.mean(res)))
    cpu = time.process_time() - t0
    print(f"{args.trials} trials, seed {args.seed}, {cpu:.0f} s of CPU")
    for key, n in hits.items():
        med = float(np.median(ratios[key]))
        print(
            f"{key}: truth {TRUTH[key]:g}, the 90 % interval holds it {n} of "
            f"{args.trials}; median fitted / truth {med:.4f}"
        )
    for key, rs in residuals.items():
        print(
            f"residual {key} (direction/free mm/tip g): mean {np.mean(rs):+.3f} mm (read - fitted)"
        )


if __name__ == "__main__":
    main()
