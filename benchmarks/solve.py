"""Benchmark the certified solver against an exhaustive fine grid and differential evolution.

Run by hand (about a minute; the exhaustive grid dominates)::

    .venv/bin/python benchmarks/solve.py [--repeats 21] [--de-runs 5] [--skip-grid]
    .venv/bin/python benchmarks/solve.py --offaxis-only   # eta 45 (free sides) against eta 0

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
import math
import statistics
import time
from collections.abc import Callable
from pathlib import Path
from typing import Any

import numpy as np
from numpy.typing import NDArray
from scipy.optimize import differential_evolution

from corrugate import LayerArrays, evaluate, get_material, make_layout
from corrugate.design import Problem, solve
from corrugate.spec import Spec, load_spec

EXAMPLES = Path(__file__).resolve().parents[1] / "examples"
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
        """Mass (g) and the summed relative violation of the constraints (0 when feasible)."""
        m = self.mat
        layer = LayerArrays(m.E, m.nu, self.t, W, n, A, m.density)
        ev = evaluate(layer, layer, self.layout, self.spec.model, 0.0)
        c = self.c
        assert c.side is not None
        assert c.thickness is not None

        def above(x: Arr, lo: float | None) -> Arr:
            return np.zeros(np.shape(x)) if lo is None else np.maximum(0.0, (lo - x) / lo)

        def below(x: Arr, hi: float | None) -> Arr:
            return np.zeros(np.shape(x)) if hi is None else np.maximum(0.0, (x - hi) / hi)

        viol = above(ev.Lx, c.side.min) + below(ev.Lx, c.side.max)
        viol += above(ev.thickness, c.thickness.min) + below(ev.thickness, c.thickness.max)
        if c.sheet_max is not None:
            viol += below((n + 1) * W, c.sheet_max) + below(ev.Lx, c.sheet_max)
        sup = self.spec.support
        for b in c.flexural_rigidity:
            e = evaluate(
                layer, layer, self.layout, self.spec.model, b.eta, support=b.support or sup
            )
            viol += above(e.EI, b.min)
        for k in c.inplane_stiffness:
            e = evaluate(
                layer, layer, self.layout, self.spec.model, k.eta, support=k.support or sup
            )
            viol += above(e.K, k.min)
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
    """Lightest design over the spec's own W and alpha grids and every n, in one numpy call."""
    v = case.spec.variables
    assert v.W.step is not None
    assert v.alpha.step is not None
    Ws = np.arange(round((v.W.max - v.W.min) / v.W.step) + 1) * v.W.step + v.W.min
    As = np.arange(round((v.alpha.max - v.alpha.min) / v.alpha.step) + 1) * v.alpha.step
    ns = np.arange(v.n.min, v.n.max + 1)
    n, W, A = np.meshgrid(ns, Ws, As + v.alpha.min, indexing="ij")
    return float(case.mass_if_feasible(n.astype(float), W, A).min())


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
        d["constraints"]["inplane_stiffness"] = [{"min": 0.4, "eta": eta}]
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


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--repeats", type=int, default=21, help="runs of the certified solver")
    ap.add_argument("--de-runs", type=int, default=5, help="runs (seeds) of differential_evolution")
    ap.add_argument("--skip-grid", action="store_true", help="skip the exhaustive 0.1 grid")
    ap.add_argument("--offaxis-only", action="store_true", help="only the off-axis comparison")
    args = ap.parse_args()
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
