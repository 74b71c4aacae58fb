"""Benchmark: one vectorised evaluate() call over a million designs against a Python loop.

Run by hand: ``.venv/bin/python benchmarks/sweep.py``. Prints the time per design of each path and
their ratio; the loop is timed on a sample and extrapolated (it would take minutes on 10^6).
"""

from __future__ import annotations

import time

import numpy as np

from corrugate import Assembly, Layer, analyze, get_material
from corrugate.analysis import LayerArrays, evaluate
from corrugate.layouts import Circle, Square

N = 1_000_000
SAMPLE = 2_000


def main() -> None:
    rng = np.random.default_rng(0)
    m = get_material("dura-lar")
    W = rng.uniform(1, 30, N)
    n = rng.integers(1, 200, N)
    alpha = rng.uniform(1, 179, N)
    arr = LayerArrays(m.E, m.nu, 0.125, W, n, alpha, m.density)
    per_design: dict[str, float] = {}
    for layout in (Square(), Circle()):
        times = []
        for _ in range(3):
            t0 = time.perf_counter()
            ev = evaluate(arr, arr, layout, "refined", 0.0)
            times.append(time.perf_counter() - t0)
        vec = min(times)
        per_design[layout.name] = vec / N
        assert ev.EI.shape == (N,)
        print(
            f"{layout.name:8s} vectorised: {N:,} designs in {vec:.3f} s "
            f"({1e9 * vec / N:.0f} ns/design)"
        )
    t0 = time.perf_counter()
    for i in range(SAMPLE):
        layer = Layer(float(W[i]), int(n[i]), float(alpha[i]), m)
        analyze(Assembly.identical(layer, Square()), "refined", [0.0])
    loop = (time.perf_counter() - t0) / SAMPLE
    print(
        f"loop over analyze() (square): {1e6 * loop:.0f} us/design "
        f"(extrapolated {loop * N:.0f} s for {N:,})"
    )
    print(f"ratio loop / vectorised (square): {loop / per_design['square']:.0f}x")


if __name__ == "__main__":
    main()
