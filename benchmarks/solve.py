"""Benchmark the certified solver against an exhaustive fine grid and differential evolution.

Run by hand (about a minute; the exhaustive grid dominates)::

    .venv/bin/python benchmarks/solve.py [--repeats 21] [--de-runs 5] [--skip-grid]
    .venv/bin/python benchmarks/solve.py --offaxis-only   # eta 45 (free sides) against eta 0
    .venv/bin/python benchmarks/solve.py --headline-only  # the case study's ratios only
    .venv/bin/python benchmarks/solve.py --chassis-only   # issue 24's chassis spec, examples
    .venv/bin/python benchmarks/solve.py --examples-against /tmp/main  # examples, before/after

``--chassis-only`` (issue 24, "Must show"): the chassis spec (benchmarks/specs/
chassis_independent.toml: 6 variables, independent layers) as fresh processes of the installed
package with compiled bytecode, interleaved: the certified solve (``solve(problem,
explain=False)``), the explained answer (``corrugate design SPEC --json``) and a vectorised numpy
exhaustive search of the same grid that decomposes by layer (``chassis_exhaustive``); the CPU
time (user + system of the child, ``os.wait4``) median of ``--chassis-repeats``, peak RSS, the
ratios; the same three in this process (imports done), with the must-show ratio (exhaustive /
certified solve, CPU, >= 10x) and which path the certified solve took; then ``design --json`` of every shipped example (examples/*.toml), CPU median and peak.

First (``headline``), the case study's certified solve against the broadcast numpy exhaustive
search of the spec's own grid and scipy's vectorised differential evolution, interleaved in one
run, with ratios of medians and the masses each found.

For the case study (``examples/blimp_gripper.toml``: W on 1 mm, alpha on 1 deg) and its continuous
variant (``examples/blimp_gripper_continuous.toml``) it prints the median wall-clock (and CPU)
time of the certified solve (``solve(problem, explain=False)``: the optimum and its certificate,
without the explanation), of an exhaustive search over W at 0.1 mm x alpha at 0.1 deg x every n,
and of scipy's ``differential_evolution`` (penalty for infeasibility, n integer; on the case study
W and alpha are integer grid indices, i.e. the same problem), the ratios, and the mass each found.

The fine grid is a *different* problem for the case study (a finer grid than the spec's), so it
may find a lighter design there; on the continuous variant every fine-grid point is admissible,
so the certified optimum can be no heavier.
"""

from __future__ import annotations

import argparse
import compileall
import math
import os
import statistics
import subprocess
import sys
import sysconfig
import time
from collections.abc import Callable
from pathlib import Path
from typing import Any

import numpy as np
from numpy.typing import NDArray

from corrugate import LayerArrays, evaluate, get_material, make_layout
from corrugate.solver import Problem, solve
from corrugate.solver.separable import applies
from corrugate.spec.schema import Spec, load_spec

ROOT = Path(__file__).resolve().parents[1]
EXAMPLES = ROOT / "examples"
CHASSIS = ROOT / "benchmarks" / "specs" / "chassis_independent.toml"
Arr = NDArray[np.float64]


def _timed(fn: Callable[[], Any], repeats: int) -> tuple[float, float, Any]:
    """Median wall and CPU seconds of ``fn`` over ``repeats`` runs, and its last result."""
    wall, cpu = [], []
    result = None
    for _ in range(repeats):
        t0, c0 = time.perf_counter(), time.process_time()
        result = fn()
        wall.append(time.perf_counter() - t0)
        cpu.append(time.process_time() - c0)
    return statistics.median(wall), statistics.median(cpu), result


class Case:
    """The spec's constraints written out directly (square layout, identical layers)."""

    def __init__(self, spec: Spec) -> None:
        assert spec.material is not None
        self.spec = spec
        self.mat = get_material(spec.material.name)
        t = spec.material.thickness
        assert isinstance(t, float)
        self.t = t
        self.layout = make_layout("square")
        c = spec.constraints
        assert c.side is not None
        assert c.thickness is not None
        self.c = c

    def mass_and_violation(self, n: Arr, W: Arr, A: Arr) -> tuple[Arr, Arr]:
        """Mass (g) and the summed relative violation of the constraints (0 when feasible).

        One ``evaluate`` call per distinct (eta, support) of the stiffness bounds (the first
        also gives the geometry and the mass): what a careful user of the package writes.
        Inputs may broadcast (e.g. n (k, 1, 1), W (1, m, 1), A (1, 1, j))."""
        m = self.mat
        layer = LayerArrays(m.E, m.nu, self.t, W, n, A, m.density)
        sup = self.spec.support
        c = self.c
        cases = [(b.eta, b.support or sup) for b in c.flexural_rigidity]
        cases += [(k.eta, k.support or sup) for k in c.inplane_stiffness]
        evs = {
            key: evaluate(layer, layer, self.layout, self.spec.model, key[0], support=key[1])
            for key in dict.fromkeys(cases or [(0.0, sup)])
        }
        ev = next(iter(evs.values()))
        assert c.side is not None
        assert c.thickness is not None

        def above(x: Arr, lo: float | None) -> Arr:
            return np.zeros(np.shape(x)) if lo is None else np.maximum(0.0, (lo - x) / lo)

        def below(x: Arr, hi: float | None) -> Arr:
            return np.zeros(np.shape(x)) if hi is None else np.maximum(0.0, (x - hi) / hi)

        viol: Arr = above(ev.Lx, c.side.min) + below(ev.Lx, c.side.max)
        viol += above(ev.thickness, c.thickness.min) + below(ev.thickness, c.thickness.max)
        if c.sheet_max is not None:
            viol += below((n + 1) * W, c.sheet_max) + below(ev.Lx, c.sheet_max)
        for b in c.flexural_rigidity:
            viol = viol + above(evs[(b.eta, b.support or sup)].EI, b.min)
        for k in c.inplane_stiffness:
            viol = viol + above(evs[(k.eta, k.support or sup)].K, k.min)
        return np.asarray(ev.mass), np.asarray(viol)

    def mass_if_feasible(self, n: Arr, W: Arr, A: Arr) -> Arr:
        """Mass (g) where every constraint holds exactly, +inf elsewhere."""
        mass, viol = self.mass_and_violation(n, W, A)
        return np.asarray(np.where(viol == 0, mass, np.inf))


def exhaustive(case: Case, dW: float = 0.1, dA: float = 0.1) -> float:
    """Lightest design over W x alpha at (dW, dA) and every n, one n at a time."""
    v = case.spec.variables
    Ws = np.arange(round((v.W.max - v.W.min) / dW) + 1) * dW + v.W.min
    As = np.arange(round((v.alpha.max - v.alpha.min) / dA) + 1) * dA + v.alpha.min
    W, A = np.meshgrid(Ws, As, indexing="ij")
    best = math.inf
    for n in range(v.n.min, v.n.max + 1):
        best = min(best, float(case.mass_if_feasible(np.full(W.shape, n), W, A).min()))
    return best


def de(case: Case, seed: int, vectorized: bool = True) -> float:
    """Lightest feasible mass differential evolution finds (inf if none). ``vectorized``: the
    population is evaluated in one ``evaluate`` call per generation (fast); otherwise one
    Python call per design, scipy's default way of calling the objective."""
    from scipy.optimize import differential_evolution  # (not in the exhaustive's child)

    v = case.spec.variables
    gridded = v.W.step is not None and v.alpha.step is not None

    def decode(x: Arr) -> tuple[Arr, Arr, Arr]:
        n = np.round(x[0])
        if gridded:
            assert v.W.step is not None
            assert v.alpha.step is not None
            return (
                n,
                v.W.min + v.W.step * np.round(x[1]),
                v.alpha.min + v.alpha.step * np.round(x[2]),
            )
        return n, x[1], x[2]

    def f(x: Arr) -> Arr:  # infeasible points rank after every feasible one, by violation
        n, W, A = decode(x)
        mass, viol = case.mass_and_violation(n, W, A)
        return np.asarray(np.where(viol == 0, mass, 1e3 * (1 + viol)))

    if gridded:
        assert v.W.step is not None
        assert v.alpha.step is not None
        bounds = [
            (v.n.min, v.n.max),
            (0, round((v.W.max - v.W.min) / v.W.step)),
            (0, round((v.alpha.max - v.alpha.min) / v.alpha.step)),
        ]
        integrality = [True, True, True]
    else:
        bounds = [(v.n.min, v.n.max), (v.W.min, v.W.max), (v.alpha.min, v.alpha.max)]
        integrality = [True, False, False]

    def f_scalar(x: Arr) -> float:
        return float(f(np.asarray(x)[:, None])[0])

    res = differential_evolution(
        f if vectorized else f_scalar,
        bounds,
        integrality=integrality,
        vectorized=vectorized,
        updating="deferred" if vectorized else "immediate",
        seed=seed,
        maxiter=1000,
        popsize=40,
        tol=1e-12,
        polish=False,
    )
    return float(res.fun) if res.fun < 1e3 else math.inf


def exhaustive_spec_grid(case: Case) -> float:
    """Lightest design over the spec's own W and alpha grids and every n: one vectorised
    evaluation of the whole grid, its axes broadcast (n (k, 1, 1), W (1, m, 1), alpha (1, 1, j)),
    so the trigonometry and the moduli run on the small axes only: the fastest plain-numpy
    exhaustive search (see ``sweep_spec_grid`` for the package's chunked sweep)."""
    v = case.spec.variables
    assert v.W.step is not None
    assert v.alpha.step is not None
    Ws = np.arange(round((v.W.max - v.W.min) / v.W.step) + 1) * v.W.step + v.W.min
    As = np.arange(round((v.alpha.max - v.alpha.min) / v.alpha.step) + 1) * v.alpha.step
    ns = np.arange(v.n.min, v.n.max + 1, dtype=np.float64)
    n, W, A = ns[:, None, None], Ws[None, :, None], (As + v.alpha.min)[None, None, :]
    return float(case.mass_if_feasible(n, W, A).min())


def headline(repeats: int, de_runs: int) -> None:
    """The case study (examples/blimp_gripper.toml: W on 1 mm, alpha on 1 deg, n 1-200): the
    certified solve (explain=False) against the two strongest alternatives on the same grid, all
    timed interleaved in one run (the machine is shared): the broadcast numpy exhaustive search
    (``exhaustive_spec_grid``) and scipy's vectorised differential evolution (``de``, penalty,
    integer grid indices). Prints medians (wall and CPU), the ratios and the masses found."""
    spec = load_spec(EXAMPLES / "blimp_gripper.toml")
    problem = Problem.from_spec(spec)
    case = Case(spec)
    sol = solve(problem, explain=False)  # warm-up (imports, caches)
    exhaustive_spec_grid(case)
    t_sol: list[tuple[float, float]] = []
    t_grid: list[tuple[float, float]] = []
    t_de: list[tuple[float, float]] = []
    grid_mass = math.nan
    de_masses: list[float] = []
    rounds = max(de_runs, 1)
    per_round = max(repeats // rounds, 1)
    for r in range(rounds):
        for _ in range(per_round):
            w, c, sol = _timed(lambda: solve(problem, explain=False), 1)
            t_sol.append((w, c))
            w, c, grid_mass = _timed(lambda: exhaustive_spec_grid(case), 1)
            t_grid.append((w, c))
        w, c, m = _timed(lambda s=r: de(case, s, True), 1)
        t_de.append((w, c))
        de_masses.append(m)

    def med(ts: list[tuple[float, float]]) -> tuple[float, float]:
        return statistics.median(t[0] for t in ts), statistics.median(t[1] for t in ts)

    (ws, cs), (wg, cg), (wd, cd) = med(t_sol), med(t_grid), med(t_de)
    lay = sol.assembly.layer1
    print("== case study (blimp_gripper.toml, spec grid 1 mm x 1 deg x n 1-200), interleaved")
    print(
        f"certified solve (explain=False): median {1e3 * ws:7.2f} ms wall, {1e3 * cs:7.2f} ms CPU "
        f"over {len(t_sol)} runs; mass {sol.mass:.12f} g (W={lay.W:g} n={lay.n} "
        f"alpha={lay.alpha_deg:g}), certified={sol.certified}, gap={sol.gap:g}"
    )
    print(
        f"numpy exhaustive (broadcast grid): median {1e3 * wg:7.2f} ms wall, {1e3 * cg:7.2f} ms "
        f"CPU; mass {grid_mass:.12f} g; ratio {wg / ws:.1f}x wall, {cg / cs:.1f}x CPU; "
        f"same mass: {abs(grid_mass - sol.mass) <= 1e-12 * grid_mass}"
    )
    print(
        f"vectorised DE (scipy, popsize 40): median {1e3 * wd:9.1f} ms wall, {1e3 * cd:9.1f} ms "
        f"CPU over {len(t_de)} seeds; masses best {min(de_masses):.12f} / worst "
        f"{max(de_masses):.12f} g; ratio {wd / ws:.0f}x wall, {cd / cs:.0f}x CPU; "
        f"seeds reaching the certified mass: "
        f"{sum(abs(m - sol.mass) <= 1e-12 * sol.mass for m in de_masses)}/{len(de_masses)}"
    )


def offaxis(repeats: int) -> None:
    """The case study with an in-plane stiffness bound at eta = 45 deg (free sides) next to the
    same bound at eta = 0: certified solve and a vectorised exhaustive search of the spec's grid,
    timed interleaved."""
    base = load_spec(EXAMPLES / "blimp_gripper.toml").model_dump()
    print(
        "\n== case study + inplane_stiffness >= 0.4 N/mm (free sides; model paper; binds at 45), eta 0 against eta 45"
    )
    cases = {}
    for eta in (0.0, 45.0):
        d = dict(base)
        d["constraints"] = dict(base["constraints"])
        d["constraints"]["inplane_stiffness"] = [{"min": "0.4 N/mm", "eta": eta}]
        spec = Spec.model_validate(d)
        cases[eta] = (Problem.from_spec(spec), Case(spec))
        solve(cases[eta][0], explain=False)  # warm-up
    results: dict[float, list[tuple[float, float]]] = {0.0: [], 45.0: []}
    sols = {}
    for _ in range(repeats):  # interleaved: the machine is shared and noisy
        for eta, (problem, case) in cases.items():
            t0 = time.perf_counter()
            sols[eta] = solve(problem, explain=False)
            t1 = time.perf_counter()
            grid = exhaustive_spec_grid(case)
            t2 = time.perf_counter()
            results[eta].append((t1 - t0, t2 - t1))
            assert sols[eta].mass <= grid * (1 + 1e-9), (eta, sols[eta].mass, grid)
    for eta, rs in results.items():
        ts = statistics.median(r[0] for r in rs)
        tg = statistics.median(r[1] for r in rs)
        sol = sols[eta]
        lay = sol.assembly.layer1
        print(
            f"eta {eta:4.0f}: certified {1e3 * ts:7.2f} ms (mass {sol.mass:.6f} g, W={lay.W:g} "
            f"n={lay.n} alpha={lay.alpha_deg:g}, certified={sol.certified}); exhaustive numpy on "
            f"the spec's grid {1e3 * tg:7.2f} ms; ratio {tg / ts:.1f}x"
        )


def chassis_exhaustive(path: Path) -> tuple[float, dict[str, float]]:
    """The lightest design of an independent-layer rectangle spec over its whole grid, by a
    vectorised numpy exhaustive search that decomposes by layer (what a capable user writes):

    1. each layer's grid (n x W x alpha, 410 k designs for the chassis) at once: its extent
       (n + 1) W sin(alpha/2) (Lx for layer 1, Ly for layer 2: a rectangle's extents) and
       depth W cos(alpha/2); the constraints of one layer alone (its side range, min_facet,
       max_t_over_W) keep a few hundred of each;
    2. the pairs whose thickness W1 c1 + W2 c2 (a sum of layer terms) meets its bound;
    3. every constraint of the spec and the mass at each remaining pair, exactly, with the
       package's vectorised point evaluation (``corrugate.solver.quantities.point_values``:
       ``evaluate`` and the fabrication sizes), in chunks; the lightest feasible pair.

    The layer filters keep every design within a relative 1e-9 of a bound; step 3 decides."""
    from corrugate.solver.points import DesignPoints, LayerPoints
    from corrugate.solver.problem import FEAS_RTOL
    from corrugate.solver.quantities import Tables, point_values
    from corrugate.solver.quantity import LX, LY, T_OVER_W, THICKNESS, W_MIN

    problem = Problem.from_spec(load_spec(path))
    assert not problem.identical and problem.layout.name == "rectangle" and problem.gridded
    tables = Tables(problem)
    ns = np.arange(problem.n_lo, problem.n_hi + 1, dtype=np.float64)
    n, W, a = (
        v.reshape(-1)
        for v in np.meshgrid(ns, problem.W.values(), problem.alpha.values(), indexing="ij")
    )
    half = np.radians(a) / 2
    extent, depth = (n + 1) * W * np.sin(half), W * np.cos(half)
    slack = 1e-9

    def layer_ok(extent_q: Any) -> Any:
        ok = np.ones(len(n), dtype=bool)
        for c in problem.constraints:
            q = c.quantity
            v = extent if q == extent_q else W if q == W_MIN else None
            if q == T_OVER_W:
                v = problem.candidates[0].t / W
            if v is None:
                continue
            ok &= v >= c.bound * (1 - slack) if c.sense == "min" else v <= c.bound * (1 + slack)
        return ok

    one, two = np.flatnonzero(layer_ok(LX)), np.flatnonzero(layer_ok(LY))
    t_max = min(
        (c.bound for c in problem.constraints if c.quantity == THICKNESS and c.sense == "max"),
        default=math.inf,
    )
    i, j = np.nonzero(depth[one][:, None] + depth[two][None, :] <= t_max * (1 + slack))
    i, j = one[i], two[j]
    best, best_at = math.inf, {}
    cand = problem.candidates[0]
    chunk = 100_000
    for k in range(0, len(i), chunk):
        a_, b_ = i[k : k + chunk], j[k : k + chunk]
        x = {"n1": n[a_], "W1": W[a_], "a1": a[a_], "n2": n[b_], "W2": W[b_], "a2": a[b_]}
        pts = DesignPoints.of(LayerPoints(n[a_], W[a_], a[a_]), LayerPoints(n[b_], W[b_], a[b_]))
        vals = point_values(problem, cand, cand, pts, tables)
        ok = np.ones(len(a_), dtype=bool)
        for c in problem.constraints:
            ok &= c.satisfied(vals[c.quantity], rtol=FEAS_RTOL)
        mass = np.where(ok, vals[problem.objective.quantity], np.inf)
        m = int(np.argmin(mass))
        if mass[m] < best:
            best, best_at = float(mass[m]), {key: float(v[m]) for key, v in x.items()}
    best_at["pairs"] = float(len(i))
    best_at["layer1"], best_at["layer2"] = float(len(one)), float(len(two))
    return best, best_at


def _child(argv: list[str], env: dict[str, str]) -> tuple[float, float]:
    """Run ``argv`` to its end: its user + system CPU seconds and peak RSS (MB)."""
    proc = subprocess.Popen(argv, env=env, stdout=subprocess.DEVNULL, stderr=subprocess.PIPE)
    assert proc.stderr is not None
    err = proc.stderr.read()
    _, status, usage = os.wait4(proc.pid, 0)
    proc.returncode = os.waitstatus_to_exitcode(status)
    if proc.returncode not in (0, 1):  # design exits 1 for an infeasible spec
        raise RuntimeError(f"{argv} exited {proc.returncode}: {err.decode()[-2000:]}")
    return usage.ru_utime + usage.ru_stime, usage.ru_maxrss / 1024


def chassis(repeats: int) -> None:
    """Issue 24's must-show: the chassis spec as fresh processes (module docstring)."""
    env = {k: v for k, v in os.environ.items() if k != "PYTHONDONTWRITEBYTECODE"}
    for tree in (ROOT / "src", Path(sysconfig.get_paths()["purelib"])):
        compileall.compile_dir(str(tree), quiet=1, workers=1)  # bytecode, as an install has it
    py = sys.executable
    solve_code = (
        "import sys; from corrugate.spec.schema import load_spec; "
        "from corrugate.solver import Problem, solve; "
        "s = solve(Problem.from_spec(load_spec(sys.argv[1])), explain=False); "
        "assert s.certified, s.status"
    )
    floor_code = "import numpy, pydantic, corrugate.solver.solve, corrugate.spec.schema"
    cmds = {
        "python: import numpy, pydantic, the solver (floor)": [py, "-c", floor_code],
        "certified solve (explain=False)": [py, "-c", solve_code, str(CHASSIS)],
        "corrugate design SPEC --json (explained)": [
            *(py, "-m", "corrugate", "design", str(CHASSIS), "--json"),
        ],
        "numpy exhaustive by layer": [py, __file__, "--chassis-exhaustive", str(CHASSIS)],
    }
    runs: dict[str, list[tuple[float, float]]] = {k: [] for k in cmds}
    for _ in range(repeats):  # interleaved: the machine is shared
        for label, argv in cmds.items():
            runs[label].append(_child(argv, env))
    best, at = chassis_exhaustive(CHASSIS)
    sol = solve(Problem.from_spec(load_spec(CHASSIS)), explain=False)
    a = sol.assembly
    print(
        f"\n== issue 24 chassis spec ({CHASSIS.relative_to(ROOT)}), fresh processes, median of {repeats}"
    )
    med = {k: statistics.median(c for c, _ in v) for k, v in runs.items()}
    for label, v in runs.items():
        print(
            f"{label:44s} CPU {med[label]:6.2f} s (min {min(c for c, _ in v):.2f}, max "
            f"{max(c for c, _ in v):.2f}); peak RSS {max(r for _, r in v):6.0f} MB"
        )
    brute = med["numpy exhaustive by layer"]
    solved = med["certified solve (explain=False)"]
    floor_label = "python: import numpy, pydantic, the solver (floor)"
    floor = med[floor_label]
    spread = max(c for c, _ in runs[floor_label]) - min(c for c, _ in runs[floor_label])

    def above_floor() -> str:
        """The ratio of the CPU above the import floor, unless the solve is inside its spread."""
        if solved - floor <= spread:
            return (
                f"the certified solve's process is inside the floor's spread ({solved - floor:+.2f}"
                f" s vs {spread:.2f} s): no ratio above the floor"
            )
        return f"{(brute - floor) / (solved - floor):.1f}x above the import floor"

    print(
        f"certified solve vs exhaustive: {brute / solved:.1f}x (whole processes); {above_floor()}"
    )
    print(
        f"solver: mass {sol.mass:.12f} g, certified={sol.certified}, layer 1 W={a.layer1.W:g} "
        f"n={a.layer1.n} alpha={a.layer1.alpha_deg:g}, layer 2 W={a.layer2.W:g} "
        f"n={a.layer2.n} alpha={a.layer2.alpha_deg:g}; exhaustive: mass {best:.12f} g over "
        f"{at['pairs']:.0f} pairs ({at['layer1']:.0f} x {at['layer2']:.0f} layers); same: "
        f"{abs(best - sol.mass) <= 1e-12 * best}"
    )
    problem = Problem.from_spec(load_spec(CHASSIS))
    warm: dict[str, list[float]] = {"solve": [], "explained": [], "exhaustive": []}
    for _ in range(repeats):  # in this process, imports done, interleaved
        for key, fn in (
            ("solve", lambda: solve(problem, explain=False)),
            ("explained", lambda: solve(problem)),
            ("exhaustive", lambda: chassis_exhaustive(CHASSIS)),
        ):
            c0 = time.process_time()
            fn()
            warm[key].append(time.process_time() - c0)
    w = {k: statistics.median(v) for k, v in warm.items()}
    print(
        f"in this process (imports done), median of {repeats}: certified solve {w['solve']:.4f} s "
        f"CPU, explained solve {w['explained']:.3f} s, exhaustive {w['exhaustive']:.3f} s; "
        f"exhaustive / certified solve {w['exhaustive'] / w['solve']:.2f}x"
    )
    ratio = w["exhaustive"] / w["solve"]
    path = "layer by layer (solver.separable)" if applies(problem) else "branch and bound"
    print(
        f"must-show (certified solve >= 10x faster than the exhaustive by layer, CPU): in this "
        f"process {ratio:.1f}x ({'met' if ratio >= 10 else 'NOT met'}); whole processes "
        f"{brute / solved:.2f}x ({above_floor()}); the certified solve's path: {path}"
    )
    print("\n== corrugate design EXAMPLE --json, every shipped example, fresh processes")
    ex = sorted(EXAMPLES.glob("*.toml"))
    per: dict[str, list[tuple[float, float]]] = {p.name: [] for p in ex}
    for _ in range(repeats):
        for p in ex:
            per[p.name].append(_child([py, "-m", "corrugate", "design", str(p), "--json"], env))
    for name, v in per.items():
        m = statistics.median(c for c, _ in v)
        print(
            f"{name:36s} CPU {m:6.2f} s (above the floor {m - floor:5.2f} s); peak RSS "
            f"{max(r for _, r in v):5.0f} MB; <= 1 s: {m <= 1.0}"
        )


def examples_against(other: Path, repeats: int) -> None:
    """``design --json`` of every shipped example, as fresh processes with compiled bytecode,
    interleaved with the same command run on the package of another source tree ``other`` (a
    checkout of main, e.g. ``git archive main | tar -x -C /tmp/main``; its ``src`` first on
    PYTHONPATH, same interpreter and libraries), each pair in turns of both orders: CPU medians
    of ``repeats``, the import floor of both, and the ratio (before / after, on this tree's
    examples/*.toml)."""
    trees = {"other": other.resolve() / "src", "this": ROOT / "src"}
    for tree in (*trees.values(), Path(sysconfig.get_paths()["purelib"])):
        compileall.compile_dir(str(tree), quiet=1, workers=1)
    base = {k: v for k, v in os.environ.items() if k != "PYTHONDONTWRITEBYTECODE"}
    envs = {k: {**base, "PYTHONPATH": str(src)} for k, src in trees.items()}
    py = sys.executable
    floor = [py, "-c", "import numpy, pydantic, corrugate.solver.solve, corrugate.spec.schema"]
    cases = {"(import floor)": floor}
    for p in sorted(EXAMPLES.glob("*.toml")):
        cases[p.name] = [py, "-m", "corrugate", "design", str(p), "--json"]
    runs: dict[tuple[str, str], list[float]] = {(c, t): [] for c in cases for t in trees}
    for r in range(repeats):  # interleaved (the machine is shared), the order swapped each round
        for case, argv in cases.items():
            for tree in list(trees)[:: 1 if r % 2 == 0 else -1]:
                runs[(case, tree)].append(_child(argv, envs[tree])[0])
    print(
        f"\n== design EXAMPLE --json, {trees['other']} (before) against {trees['this']} (after), "
        f"fresh processes interleaved, CPU median of {repeats}"
    )
    for case in cases:
        a, b = (statistics.median(runs[(case, t)]) for t in trees)
        print(
            f"{case:34s} before {a:5.2f} s  after {b:5.2f} s  ratio {a / b:4.2f}x  <= 1 s: {b <= 1.0}"
        )


def main() -> None:
    if len(sys.argv) == 3 and sys.argv[1] == "--chassis-exhaustive":  # one child process
        chassis_exhaustive(Path(sys.argv[2]))
        return
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--repeats", type=int, default=21, help="runs of the certified solver")
    ap.add_argument("--de-runs", type=int, default=5, help="runs (seeds) of differential_evolution")
    ap.add_argument("--skip-grid", action="store_true", help="skip the exhaustive 0.1 grid")
    ap.add_argument("--offaxis-only", action="store_true", help="only the off-axis comparison")
    ap.add_argument(
        "--headline-only", action="store_true", help="only the case study's ratios (headline)"
    )
    ap.add_argument("--chassis-only", action="store_true", help="only issue 24's chassis spec")
    ap.add_argument("--chassis-repeats", type=int, default=5, help="runs of each child (median)")
    ap.add_argument(
        "--examples-against",
        type=Path,
        metavar="DIR",
        help="only design --json of the examples, interleaved with another source tree's package",
    )
    args = ap.parse_args()
    if args.examples_against is not None:
        examples_against(args.examples_against, args.chassis_repeats)
        return
    if args.chassis_only:
        chassis(args.chassis_repeats)
        return
    if not args.offaxis_only:
        headline(args.repeats, args.de_runs)
        if args.headline_only:
            return
    offaxis(args.repeats)
    if args.offaxis_only:
        return
    for name in ("blimp_gripper", "blimp_gripper_continuous"):
        spec = load_spec(EXAMPLES / f"{name}.toml")
        problem = Problem.from_spec(spec)
        case = Case(spec)
        solve(problem, explain=False)  # warm-up (imports, caches)
        t_sol, c_sol, sol = _timed(lambda p=problem: solve(p, explain=False), args.repeats)
        lay = sol.assembly.layer1
        print(
            f"\n== {name} (model {spec.model}; {'gridded' if problem.gridded else 'continuous'}"
            f" W and alpha)"
        )
        print(
            f"certified solver : median {1e3 * t_sol:8.2f} ms wall ({1e3 * c_sol:.2f} ms CPU), "
            f"mass {sol.mass:.9f} g, certified={sol.certified}, gap={sol.gap:.1e}, "
            f"W={lay.W:.6g} mm n={lay.n} alpha={lay.alpha_deg:.6g} deg"
        )
        for vectorized in (True, False):
            de_masses: list[float] = []
            de_wall: list[float] = []
            de_cpu: list[float] = []
            for seed in range(args.de_runs):
                w, c, m = _timed(lambda s=seed, k=case, v=vectorized: de(k, s, v), 1)
                de_wall.append(w)
                de_cpu.append(c)
                de_masses.append(m)
            t_de, c_de = statistics.median(de_wall), statistics.median(de_cpu)
            label = "vectorised" if vectorized else "scalar    "
            worse = max((sol.mass - m) / m for m in de_masses)
            print(
                f"DE {label}    : median {t_de:8.3f} s  wall ({c_de:.3f} s CPU) over "
                f"{args.de_runs} seeds, masses best {min(de_masses):.9f} / median "
                f"{statistics.median(de_masses):.9f} / worst {max(de_masses):.9f} g; "
                f"ratio {t_de / t_sol:,.0f}x (CPU {c_de / c_sol:,.0f}x); certified heavier than "
                f"the best DE by {max(worse, 0.0):.1e} (relative; proven gap {sol.gap:.0e})"
            )
        if not args.skip_grid:
            t_grid, c_grid, grid_mass = _timed(lambda k=case: exhaustive(k), 1)
            print(
                f"exhaustive 0.1mm/0.1deg : {t_grid:8.2f} s wall ({c_grid:.2f} s CPU), "
                f"mass {grid_mass:.9f} g; ratio {t_grid / t_sol:,.0f}x "
                f"(CPU {c_grid / c_sol:,.0f}x); certified <= grid: {sol.mass <= grid_mass}"
                + (
                    " (the 0.1 grid is finer than the spec's grid: a different, larger problem)"
                    if problem.gridded
                    else ""
                )
            )


if __name__ == "__main__":
    main()
