"""Monte Carlo over manufacturing and material tolerances of a design.

Each sample perturbs the design with independent normal errors (the tolerances are one standard
deviation): the facet width W (mm) and fold angle alpha (deg) of each layer separately (the
cutter and the folding), the sheet thickness t and Young's modulus E by relative errors (one draw
per sheet: identical layers share it). n is exact. Every sample is evaluated with
:func:`corrugate.analysis.evaluate.evaluate` (the same model as the design), giving the distribution of
every constrained quantity, the probability that each constraint holds and that all hold.

Under tolerances the two layers of a square or circle no longer have exactly equal extents; the
size constraints are checked on Lx (layer 1), as in the solver, and Ly is reported beside it.
"""

from __future__ import annotations

from dataclasses import dataclass, field, replace

import numpy as np

from corrugate.geometry.layer import Assembly
from corrugate.solver.points import DesignPoints, LayerPoints
from corrugate.solver.problem import FEAS_RTOL, Candidate, Problem
from corrugate.solver.quantities import Tables, point_values
from corrugate.solver.quantity import LX, LY, MASS, THICKNESS, Quantity
from corrugate.solver.worst_case import NOMINAL

__all__ = ["QuantityStats", "ToleranceReport", "Tolerances", "monte_carlo"]


@dataclass(frozen=True, slots=True)
class Tolerances:
    """One-sigma errors: W (mm), alpha (deg), t and E relative (0.05 = 5 %)."""

    W: float = 0.1
    alpha: float = 2.0
    t_rel: float = 0.05
    E_rel: float = 0.10

    def as_dict(self) -> dict[str, float]:
        return {"W_mm": self.W, "alpha_deg": self.alpha, "t_rel": self.t_rel, "E_rel": self.E_rel}


@dataclass(frozen=True, slots=True)
class QuantityStats:
    """Distribution of one quantity over the samples (unit of the quantity)."""

    quantity: Quantity
    unit: str
    nominal: float
    mean: float
    sd: float
    q05: float
    q50: float
    q95: float

    def as_dict(self) -> dict[str, object]:
        return {
            "quantity": self.quantity.key,
            "description": self.quantity.description,
            "unit": self.unit,
            "nominal": self.nominal,
            "mean": self.mean,
            "sd": self.sd,
            "q05": self.q05,
            "q50": self.q50,
            "q95": self.q95,
        }


@dataclass(frozen=True)
class ToleranceReport:
    """Monte Carlo result: quantity distributions and the odds that the spec holds."""

    samples: int
    seed: int
    tolerances: Tolerances
    stats: tuple[QuantityStats, ...]
    probabilities: tuple[tuple[str, float], ...]
    p_all: float
    #: Every quantity of every sample (not in :meth:`as_dict`).
    values: dict[Quantity, np.ndarray] = field(default_factory=dict, repr=False, compare=False)

    def as_dict(self) -> dict[str, object]:
        return {
            "samples": self.samples,
            "seed": self.seed,
            "tolerances_1sigma": self.tolerances.as_dict(),
            "quantities": [s.as_dict() for s in self.stats],
            "constraints": [{"name": n, "probability_met": p} for n, p in self.probabilities],
            "probability_all_met": self.p_all,
        }


def monte_carlo(
    problem: Problem, design: Assembly, tol: Tolerances, samples: int = 10_000, seed: int = 0
) -> ToleranceReport:
    """Sample ``samples`` perturbed copies of ``design`` (see the module docstring) and check
    them against ``problem``'s constraints."""
    a = design
    # each sample is one part, evaluated at its own point: its nominal values (a certificate's
    # worst case over the tolerance box is not this, solver.tolerance_box)
    problem = replace(problem, tolerances=NOMINAL)
    rng = np.random.default_rng(seed)
    N = samples
    c1, c2 = (Candidate(layer.material, layer.t) for layer in a.layers)
    same_sheet = c1 == c2
    drawn: list[LayerPoints] = []
    for layer in a.layers:
        n = np.full(N, float(layer.n))
        W = np.maximum(layer.W + tol.W * rng.standard_normal(N), 1e-6)
        alpha = np.clip(layer.alpha_deg + tol.alpha * rng.standard_normal(N), 0.1, 179.9)
        drawn.append(LayerPoints(n, W, alpha))
    t_err = rng.standard_normal((2, N)) * tol.t_rel
    E_err = rng.standard_normal((2, N)) * tol.E_rel
    if same_sheet:
        t_err[1], E_err[1] = t_err[0], E_err[0]
    for i, layer in enumerate(a.layers):
        t = np.maximum(layer.t * (1 + t_err[i]), 1e-9)
        E = np.maximum(layer.material.E * (1 + E_err[i]), 1e-9)
        drawn[i] = replace(drawn[i], E=E, t=t)
    x = DesignPoints.of(*drawn)
    tables = Tables(problem)
    vals = point_values(problem, c1, c2, x, tables)
    nominal_x = DesignPoints.of(
        *(
            LayerPoints(np.array([layer.n]), np.array([layer.W]), np.array([layer.alpha_deg]))
            for layer in a.layers
        )
    )
    nominal = point_values(problem, c1, c2, nominal_x, tables)
    keys = [MASS, LX, LY, THICKNESS]
    keys += sorted({c.quantity for c in problem.constraints} - set(keys), key=lambda q: q.key)
    stats = []
    for k in keys:
        v = vals[k]
        q05, q50, q95 = np.quantile(v, [0.05, 0.5, 0.95])
        stats.append(
            QuantityStats(
                k,
                k.unit,
                float(nominal[k][0]),
                float(v.mean()),
                float(v.std(ddof=1)),
                float(q05),
                float(q50),
                float(q95),
            )
        )
    ok_all = np.ones(N, dtype=bool)
    probs = []
    for c in problem.constraints:
        ok = c.satisfied(vals[c.quantity], rtol=FEAS_RTOL)
        ok_all &= ok
        probs.append((c.name, float(ok.mean())))
    return ToleranceReport(N, seed, tol, tuple(stats), tuple(probs), float(ok_all.mean()), vals)
