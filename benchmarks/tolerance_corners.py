"""A design's certified value over its tolerance box against the point model at the box's 64
corners (docs/tolerances.md, section 2 and 3).

Usage: PYTHONPATH=src python benchmarks/tolerance_corners.py SPEC W n alpha [TOL]

SPEC's first directional constraint, at identical layers (W mm, n, alpha deg) on its first
sheet; TOL ("da,dW,dt,dE") replaces the spec's tolerances. Prints the nominal value, the
certified one (the interval bound over the box), the least and greatest of the corners and the
corner of the least (dW1, da1, dW2, da2, dt, dE as -1/+1).
"""

from __future__ import annotations

import itertools
import sys
from dataclasses import replace

import numpy as np

from corrugate.solver.points import DesignPoints, LayerPoints
from corrugate.solver.problem import Problem
from corrugate.solver.quantities import Tables, point_values
from corrugate.solver.worst_case import NOMINAL, WorstCase
from corrugate.spec.schema import load_spec


def main(argv: list[str]) -> None:
    p = Problem.from_spec(load_spec(argv[0]))
    if len(argv) > 4:
        p = replace(p, tolerances=WorstCase(*map(float, argv[4].split(","))))
    W, n, a = (float(v) for v in argv[1:4])
    c = p.candidates[0]
    tab = Tables(p)
    q = next(k.quantity for k in p.constraints if k.quantity.eta is not None)
    x = DesignPoints.of(LayerPoints(np.array([n]), np.array([W]), np.array([a])))
    certified = point_values(p, c, c, x, tab)[q][0]
    plain = replace(p, tolerances=NOMINAL, identical=False)
    nominal = point_values(replace(p, tolerances=NOMINAL), c, c, x, tab)[q][0]
    tol = p.tolerances
    combos = list(itertools.product(*[(-1, 1)] * 6))
    vals = []
    for dW1, da1, dW2, da2, dt, dE in combos:
        E = np.array([c.material.E * (1 + dE * tol.E)])
        t = np.array([c.t * (1 + dt * tol.t)])
        l1 = LayerPoints(
            np.array([n]), np.array([W + dW1 * tol.W]), np.array([a + da1 * tol.alpha]), E, t
        )
        l2 = replace(l1, W=np.array([W + dW2 * tol.W]), alpha=np.array([a + da2 * tol.alpha]))
        vals.append(point_values(plain, c, c, DesignPoints.of(l1, l2), tab)[q][0])
    i = int(np.argmin(vals))
    print(
        f"{q.key}: nominal {nominal:.6g}, certified {certified:.6g} ({certified / nominal - 1:+.1%}), "
        f"corners {min(vals):.6g} ({min(vals) / nominal - 1:+.1%}) to {max(vals):.6g}; "
        f"least at {combos[i]}"
    )


if __name__ == "__main__":
    main(sys.argv[1:])
