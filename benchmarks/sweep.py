"""Benchmark: the vectorised evaluator and the chunked sweep against their ceilings.

Run by hand (about a minute; the machine should be otherwise idle for absolute numbers, the
ratios are measured interleaved in one run)::

    .venv/bin/python benchmarks/sweep.py [--repeats 5] [--skip-rss] [--skip-dask] [--skip-loop]

Prints, for identical square layers of Dura-Lar 0.125 mm (model ``refined``, eta 0, free sides):

1. designs per CPU-second of ``sweep()`` over a W x n x alpha grid (the case study's bounds as
   reductions: lightest feasible design, count, min/max of the mass), of one ``evaluate()`` call
   on 10^6 random designs given as full arrays, and of the memory-bound ceiling ``W * n + alpha``
   on those same arrays (three passes over 8 MB arrays: no evaluator can beat it), with ratios;
2. the peak resident memory (``resource.getrusage`` maxrss and /proc VmHWM, in a subprocess
   started before this process allocates anything: a child's maxrss includes its parent's size
   at the fork) of a 10^8 design sweep, next to that of a subprocess that only imports;
3. the same sweep on a ``distributed.LocalCluster`` (2 worker processes, 1 thread each) and in
   process, with the check that both results are equal;
4. the Python loop over ``analyze()`` it all replaces (sampled, extrapolated).
"""

from __future__ import annotations

import argparse
import json
import subprocess
import sys
import time
from collections.abc import Callable
from typing import Any

import numpy as np

from corrugate import Assembly, Layer, analyze, get_material
from corrugate.analysis.evaluate import LayerArrays, evaluate
from corrugate.analysis.sweep import sweep
from corrugate.geometry.layouts import Square

N = 1_000_000
SAMPLE = 2_000
MAT = get_material("dura-lar")
BOUNDS = {"Lx": (48.0, 60.0), "thickness": (10.0, 12.5), "flat": (None, 250.0), "EI": (8e4, None)}


def grid(total: float) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """A W x n x alpha grid of about ``total`` designs (n 1-200, alpha 1-179 deg, W 1-30 mm)."""
    n = np.arange(1, 201)
    A = np.linspace(1.0, 179.0, 500)
    W = np.linspace(1.0, 30.0, max(1, round(total / (n.size * A.size))))
    return W, n, A


def run_sweep(total: float, **kw: Any) -> Any:
    W, n, A = grid(total)
    return sweep(W, n, A, MAT, 0.125, bounds=BOUNDS, fields=("mass",), **kw)


def cpu(fn: Callable[[], Any]) -> tuple[float, Any]:
    t0 = time.process_time()
    out = fn()
    return time.process_time() - t0, out


def rss_child(total: float, do_sweep: bool) -> None:
    """Subprocess body: one sweep of ``total`` designs (or none); prints maxrss (KiB) as JSON."""
    import resource

    result = None
    if do_sweep:
        r = run_sweep(total)
        result = {"count": r.count, "feasible": r.feasible, "best": r.best}
    rss = resource.getrusage(resource.RUSAGE_SELF).ru_maxrss
    hwm = None  # VmHWM: the peak of this process's own memory (reset by exec, unlike maxrss)
    with open("/proc/self/status") as f:
        for line in f:
            if line.startswith("VmHWM:"):
                hwm = int(line.split()[1])
    print(json.dumps({"maxrss_kib": rss, "vmhwm_kib": hwm, "result": result}))


def peak_rss(total: float, do_sweep: bool) -> dict[str, Any]:
    out = subprocess.run(
        [sys.executable, __file__, "--rss-child", str(total), "1" if do_sweep else "0"],
        check=True,
        capture_output=True,
        text=True,
    )
    return dict(json.loads(out.stdout.strip().splitlines()[-1]))


def throughput(repeats: int) -> None:
    rng = np.random.default_rng(0)
    W = rng.uniform(1, 30, N)
    n = rng.integers(1, 200, N)
    A = rng.uniform(1, 179, N)
    nf = n.astype(np.float64)
    arr = LayerArrays(MAT.E, MAT.nu, 0.125, W, n, A, MAT.density)
    total = 1e7
    size = int(np.prod([x.size for x in grid(total)]))
    best: dict[str, float] = {"sweep": np.inf, "evaluate": np.inf, "ceiling": np.inf}
    run_sweep(1e5)  # warm-up
    for _ in range(repeats):  # interleaved: the machine is shared
        t, r = cpu(lambda: run_sweep(total))
        best["sweep"] = min(best["sweep"], t / size)
        t, _ = cpu(lambda: evaluate(arr, arr, Square(), "refined", 0.0))
        best["evaluate"] = min(best["evaluate"], t / N)
        t, _ = cpu(lambda: W * nf + A)
        best["ceiling"] = min(best["ceiling"], t / N)
    rate = {k: 1.0 / v for k, v in best.items()}
    print(f"== throughput (best of {repeats}, CPU time, identical square layers, refined, eta 0)")
    print(
        f"sweep() over a {size:,}-design grid with reductions: {rate['sweep'] / 1e6:7.1f} M "
        f"designs/s ({1e9 * best['sweep']:.1f} ns/design); lightest feasible "
        f"W={r.best['W']:.4g} n={r.best['n']:g} alpha={r.best['alpha']:.4g}, {r.feasible:,} feasible"
    )
    print(
        f"evaluate() on {N:,} random designs (full arrays): {rate['evaluate'] / 1e6:7.1f} M "
        f"designs/s ({1e9 * best['evaluate']:.1f} ns/design)"
    )
    print(
        f"ceiling W * n + alpha on the same {N:,} arrays: {rate['ceiling'] / 1e6:7.1f} M "
        f"designs/s ({1e9 * best['ceiling']:.2f} ns/design)"
    )
    print(
        f"ratios: sweep / ceiling = {rate['sweep'] / rate['ceiling']:.3f}, "
        f"evaluate / ceiling = {rate['evaluate'] / rate['ceiling']:.3f}, "
        f"sweep / evaluate = {rate['sweep'] / rate['evaluate']:.1f}x"
    )


def memory() -> None:
    base = peak_rss(0, False)
    t0 = time.perf_counter()
    big = peak_rss(1e8, True)
    wall = time.perf_counter() - t0
    res = big["result"]
    print("== peak resident memory (subprocess, resource.getrusage maxrss)")
    print(
        f"import corrugate only: maxrss {base['maxrss_kib'] / 1024:8.1f} MiB, VmHWM "
        f"{(base['vmhwm_kib'] or 0) / 1024:8.1f} MiB"
    )
    print(
        f"sweep of {res['count']:,} designs: maxrss {big['maxrss_kib'] / 1024:8.1f} MiB "
        f"({big['maxrss_kib'] / 2**20:.3f} GiB; limit 1 GiB), VmHWM "
        f"{(big['vmhwm_kib'] or 0) / 1024:8.1f} MiB, {wall:.1f} s wall incl. start-up; "
        f"{res['feasible']:,} feasible, best W={res['best']['W']:.4g} n={res['best']['n']:g} "
        f"alpha={res['best']['alpha']:.4g}"
    )


def dask() -> None:
    try:
        from distributed import Client, LocalCluster
    except ImportError:
        print("== dask: distributed is not installed (pip install corrugate[dist]); skipped")
        return
    total = 2e7
    with (
        LocalCluster(n_workers=2, threads_per_worker=1, processes=True) as cluster,
        Client(cluster) as client,
    ):
        run_sweep(1e5, scheduler=client)  # warm-up: workers import corrugate
        t0 = time.perf_counter()
        remote = run_sweep(total, scheduler=client)
        t_remote = time.perf_counter() - t0
    t0 = time.perf_counter()
    local = run_sweep(total)
    t_local = time.perf_counter() - t0
    same = (
        remote.best_index == local.best_index
        and remote.best == local.best
        and (remote.count, remote.feasible) == (local.count, local.feasible)
        and remote.minimum == local.minimum
        and remote.maximum == local.maximum
    )
    print("== dask (distributed.LocalCluster, 2 worker processes x 1 thread)")
    print(
        f"{remote.count:,} designs: cluster {t_remote:.2f} s wall, in process {t_local:.2f} s "
        f"wall; results equal: {same} (best index {remote.best_index}, {remote.feasible:,} "
        f"feasible)"
    )


def loop(repeats: int) -> None:
    rng = np.random.default_rng(0)
    W = rng.uniform(1, 30, SAMPLE)
    n = rng.integers(1, 200, SAMPLE)
    A = rng.uniform(1, 179, SAMPLE)
    t0 = time.process_time()
    for i in range(SAMPLE):
        layer = Layer(float(W[i]), int(n[i]), float(A[i]), MAT)
        analyze(Assembly.identical(layer, Square()), "refined", [0.0])
    per = (time.process_time() - t0) / SAMPLE
    print(f"== loop over analyze(): {1e6 * per:.0f} us/design (CPU, {SAMPLE:,} sampled)")


def main() -> None:
    if len(sys.argv) == 4 and sys.argv[1] == "--rss-child":
        rss_child(float(sys.argv[2]), sys.argv[3] == "1")
        return
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--repeats", type=int, default=5)
    ap.add_argument("--skip-rss", action="store_true")
    ap.add_argument("--skip-dask", action="store_true")
    ap.add_argument("--skip-loop", action="store_true")
    args = ap.parse_args()
    if not args.skip_rss:  # first: a child's maxrss starts at its parent's size (fork)
        memory()
    throughput(args.repeats)
    if not args.skip_dask:
        dask()
    if not args.skip_loop:
        loop(args.repeats)


if __name__ == "__main__":
    main()
