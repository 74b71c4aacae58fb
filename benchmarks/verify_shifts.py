"""Where the off-axis coupon is cut: one FE twin of a design at every coupon shift and mesh.

For ``corrugate verify``'s worst-over-positions rule (docs/fea.md, section 6): runs the test
``TEST`` at ``ETA`` of the design in ``DIR/design.json`` for every shift (fraction of each
layer's pitch, :func:`corrugate.fea.shells.oblique_shells`) and every mesh, printing the value,
the CPU seconds of the ccx child processes, and per shift the Richardson estimate; then whether
the shift that is worst at the second-finest mesh is also the worst estimate (the screen verify
uses to run the finest mesh at one shift only).

    python benchmarks/verify_shifts.py DIR compression 15 --meshes 2,4,8 --shifts 0,0.25,0.5,0.75
"""

from __future__ import annotations

import argparse
import resource
import time

from corrugate.export.record import read_record
from corrugate.fea.assembly import AssemblyMesh, solve_assembly
from corrugate.fea.extrapolate import extrapolate


def _child_cpu() -> float:
    r = resource.getrusage(resource.RUSAGE_CHILDREN)
    return r.ru_utime + r.ru_stime


def main() -> None:
    ap = argparse.ArgumentParser()
    ap.add_argument("folder")
    ap.add_argument("test")
    ap.add_argument("eta", type=float)
    ap.add_argument("--meshes", default="2,4,8")
    ap.add_argument("--shifts", default="0,0.25,0.5,0.75")
    args = ap.parse_args()
    a = read_record(args.folder).assembly()
    meshes = [int(m) for m in args.meshes.split(",")]
    shifts = [float(s) for s in args.shifts.split(",")]
    table: dict[float, dict[int, float]] = {}
    for m in meshes:
        for s in shifts:
            c0, w0 = _child_cpu(), time.monotonic()
            r = solve_assembly(a, args.test, AssemblyMesh(m), args.eta, shift=s)
            v = r.value()  # K (N/mm), D (N mm, the test's own reading), Pb (N)
            table.setdefault(s, {})[m] = v
            print(
                f"mesh {m} shift {s:g}: {v:.6g}  (ccx CPU {_child_cpu() - c0:.1f} s, "
                f"wall {time.monotonic() - w0:.1f} s)",
                flush=True,
            )
    est = {s: extrapolate(series, "min") for s, series in table.items()}  # a minimum's side
    for s, e in est.items():
        value = "-" if e.value is None else f"{e.value:.6g}"
        print(f"shift {s:g}: series {table[s]}, estimate {value} ({e.how})")
    worst_est = min(est, key=lambda s: est[s].value or float("inf"))
    if len(meshes) >= 2:
        screen = min(shifts, key=lambda s: table[s][meshes[-2]])
        print(
            f"worst estimate at shift {worst_est:g}; worst at mesh {meshes[-2]}: shift {screen:g}"
            f" -> screen {'agrees' if screen == worst_est else 'DISAGREES'}"
        )


if __name__ == "__main__":
    main()
