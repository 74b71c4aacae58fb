"""Off-axis FE coupons with mesh series, for docs/validation/off_axis.md (issue: free panel).

    python benchmarks/fea_offaxis.py run [ALONG ...] [--etas 15,45] [--design NAME] [--tests compression]
                                                       # FE series -> off_axis_fe.csv
    python benchmarks/fea_offaxis.py table             # model vs FE -> off_axis.md and polar plots

``run`` appends one CSV row per (design, eta, test, elements per facet) as soon as ccx returns,
and skips rows already in the file, so an interrupted run resumes where it stopped. Needs ccx
and gmsh (the ``fea`` extra). About 15 minutes for 2, 4, 8 elements per facet on 2 cores.
"""

from __future__ import annotations

import math
import sys
import time
from pathlib import Path

from corrugate import Assembly, Layer, get_material, make_layout
from resumable_csv import appender, done_keys  # type: ignore[import-not-found]
from stored_names import FIXTURE_OF  # type: ignore[import-not-found]

OUT = Path(__file__).resolve().parents[1] / "docs" / "validation"
CSV = OUT / "off_axis_fe.csv"
ETAS = (0.0, 15.0, 30.0, 45.0, 60.0, 75.0, 90.0)
TESTS = ("compression", "bending")
FIELDS = ("design", "eta_deg", "test", "along", "nodes", "value", "seconds")


def designs() -> dict[str, Assembly]:
    """The designs of the validation: three squares (the case study, one at alpha = 40 deg, and
    one with differing layers, layer 2's alpha solved so that both span the case study's side)
    and a rectangle twice as long as it is wide (the case study's layer 1 across, 18 of its
    facets along: 48.2 x 96.4 mm), whose coupon has the rectangle's proportions
    (:func:`corrugate.fea.shells.specimen`)."""
    dl = get_material("dura-lar")
    case = Layer(W=8.0, n=8, alpha_deg=84.0, material=dl)
    deep = Layer(W=10.0, n=10, alpha_deg=40.0, material=dl)
    side = case.chord_extent
    a2 = 2 * math.degrees(math.asin(side / (7 * 10.0)))
    other = Layer(W=10.0, n=6, alpha_deg=a2, material=dl)
    long = Layer(W=8.0, n=17, alpha_deg=84.0, material=dl)
    return {
        "case study W 8, n 8, alpha 84": Assembly.identical(case),
        "W 10, n 10, alpha 40": Assembly.identical(deep),
        f"layer 1 W 8, n 8, alpha 84; layer 2 W 10, n 6, alpha {a2:.4f}": Assembly(case, other),
        "rectangle 48.2 x 96.4: layer 1 W 8, n 8, alpha 84; layer 2 W 8, n 17": Assembly(
            case, long, layout=make_layout("rectangle")
        ),
    }


def run(
    alongs: tuple[int, ...],
    etas: tuple[float, ...] = ETAS,
    only: str = "",
    tests: tuple[str, ...] = TESTS,
) -> None:
    """FE rows for each mesh of ``alongs`` and each eta of ``etas``, for the designs whose name
    contains ``only`` and the load cases ``tests``."""
    from corrugate.fea.assembly import AssemblyMesh, solve_assembly

    done = done_keys(CSV, ("design", "eta_deg", "test", "along"))
    with appender(CSV, FIELDS) as write:
        for along in alongs:
            for name, a in designs().items():
                if only not in name:
                    continue
                for eta in etas:
                    if eta not in ETAS or (eta > 45 and a.layer1 == a.layer2 and along > 4):
                        continue  # identical layers: eta and 90 - eta are mirror images
                    for test in tests:
                        key = (name, f"{eta:g}", test, str(along))
                        if key in done:
                            continue
                        t0 = time.perf_counter()
                        r = solve_assembly(a, FIXTURE_OF[test], AssemblyMesh(along), eta)
                        s = time.perf_counter() - t0
                        write((*key[:3], along, r.nodes, f"{r.value():.8g}", f"{s:.1f}"))
                        print(*key, f"{r.value():.5g}", f"{s:.0f} s", flush=True)


if __name__ == "__main__":
    if sys.argv[1:2] == ["run"]:
        args = sys.argv[2:]
        opts = {"--etas": ",".join(f"{e:g}" for e in ETAS), "--design": "", "--tests": ""}
        for flag in opts:
            if flag in args:
                i = args.index(flag)
                opts[flag] = args[i + 1]
                args = args[:i] + args[i + 2 :]
        run(
            tuple(int(v) for v in args) or (2, 4, 8),
            tuple(float(v) for v in opts["--etas"].split(",")),
            opts["--design"],
            tuple(opts["--tests"].split(",")) if opts["--tests"] else TESTS,
        )
    elif sys.argv[1:2] == ["table"]:
        from offaxis_table import table  # type: ignore[import-not-found]

        table()
    else:
        sys.exit(__doc__)
