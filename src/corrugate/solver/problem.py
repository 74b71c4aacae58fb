"""The optimisation problem a spec states, in internal units (DESIGN.md section 5).

A :class:`Problem` is what the solver sees: the moduli variant, the layout, whether the two layers
are identical, the candidate sheets (material and thickness: a discrete variable), the bounds and
optional grid steps of W (mm), alpha (deg) and the integer n, the constraints and the objective.

Every constraint is a bound on one named *quantity* of a design (:data:`QUANTITIES`):

* ``Lx``, ``Ly``: folded extents (mm), Lx = (n1 + 1) W1 sin(alpha1/2), Ly likewise for layer 2;
* ``thickness``: folded thickness t_d = W1 cos(alpha1/2) + W2 cos(alpha2/2) (mm);
* ``flat``: longest flat blank, max over layers of (n + 1) W (mm);
* ``facet``: longest facet, max over layers and facets of L_j (mm);
* ``mass``: g; ``EI@eta`` (N mm^2), ``D@eta`` (N mm), ``K@eta`` (N/mm): stiffness at eta (deg)
  of the panel with free sides (:mod:`corrugate.mechanics.offaxis`); ``EIframe@eta``, ``Dframe@eta``,
  ``Kframe@eta`` the same held in a rigid frame (the paper's rule);
* ``Pb@eta``: lower bound (N) of the compressive load at which the end facets buckle along eta
  (0 or 90 deg; :mod:`corrugate.mechanics.buckling`).
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field, replace
from typing import Literal

import numpy as np
from numpy.typing import NDArray

from corrugate.core.errors import InputError
from corrugate.geometry.layer import crease_layer
from corrugate.geometry.layouts import Layout, make_layout
from corrugate.materials.library import Material, get_material, inline_material
from corrugate.mechanics.moduli import get_model
from corrugate.spec.schema import STIFFNESS_KINDS, MaterialSpec, Spec, SpecError

__all__ = [
    "FEAS_RTOL",
    "QUANTITY_UNITS",
    "Candidate",
    "Constraint",
    "DesignVariable",
    "Objective",
    "Problem",
    "describe",
    "stiffness_key",
]

#: Relative tolerance within which a constraint counts as met (floating-point slack only).
FEAS_RTOL = 1e-9

#: Stiffness quantity prefix for each spec kind (DESIGN.md 3.3).
_PREFIX = {"flexural_rigidity": "EI", "bending_stiffness": "D", "inplane_stiffness": "K"}

QUANTITY_UNITS = {
    "Lx": "mm",
    "Ly": "mm",
    "thickness": "mm",
    "flat": "mm",
    "facet": "mm",
    "mass": "g",
    "EI": "N*mm^2",
    "D": "N*mm",
    "K": "N/mm",
    "EIframe": "N*mm^2",
    "Dframe": "N*mm",
    "Kframe": "N/mm",
    "Pb": "N",
}

Sense = Literal["min", "max"]


_DESCRIPTIONS = {
    "Lx": "folded extent Lx",
    "Ly": "folded extent Ly",
    "thickness": "folded thickness t_d",
    "flat": "flat blank (n + 1) W",
    "facet": "longest facet L_j",
    "mass": "mass",
    "EI": "flexural rigidity EI",
    "D": "bending stiffness D",
    "K": "in-plane stiffness K",
    "EIframe": "flexural rigidity EI in a frame",
    "Dframe": "bending stiffness D in a frame",
    "Kframe": "in-plane stiffness K in a frame",
    "Pb": "buckling load (lower bound)",
}


def describe(quantity: str) -> str:
    """A readable name for a quantity key, e.g. ``EI@0`` -> ``flexural rigidity EI(0 deg)``."""
    kind, _, eta = quantity.partition("@")
    text = _DESCRIPTIONS.get(kind, kind)
    return f"{text}({eta} deg)" if eta else text


def stiffness_key(kind: str, eta_deg: float, support: str = "free") -> str:
    """Quantity key of a stiffness kind (spec name or EI/D/K) at eta (deg) under ``support``,
    e.g. ``EI@0`` (free sides) or ``Kframe@45`` (rigid frame)."""
    prefix = _PREFIX.get(kind, kind)
    if support == "frame" and not prefix.endswith("frame"):
        prefix += "frame"
    return f"{prefix}@{eta_deg:.12g}"


@dataclass(frozen=True, slots=True)
class DesignVariable:
    """A continuous variable on [lo, hi], or the grid lo, lo + step, ... <= hi when step is set."""

    lo: float
    hi: float
    step: float | None = None

    @property
    def gridded(self) -> bool:
        return self.step is not None

    def count(self) -> int:
        """Number of grid values (only for gridded variables)."""
        assert self.step is not None
        return math.floor((self.hi - self.lo) / self.step + 1e-9) + 1

    def values(self) -> NDArray[np.float64]:
        """The grid values (gridded) or the two end points (continuous)."""
        if self.step is None:
            return np.array([self.lo, self.hi])
        return self.lo + self.step * np.arange(self.count(), dtype=np.float64)

    @property
    def top(self) -> float:
        """Largest admissible value (the last grid value for a gridded variable)."""
        return self.hi if self.step is None else float(self.values()[-1])


@dataclass(frozen=True, slots=True)
class Candidate:
    """A candidate sheet: a material at one thickness t (mm)."""

    material: Material
    t: float

    @property
    def label(self) -> str:
        return f"{self.material.id} {self.t:g} mm"


@dataclass(frozen=True, slots=True)
class Constraint:
    """``quantity`` >= ``bound`` (sense ``min``) or <= ``bound`` (sense ``max``).

    ``name`` is the spec path it comes from (e.g. ``constraints.side.min``).
    """

    name: str
    quantity: str
    sense: Sense
    bound: float

    @property
    def unit(self) -> str:
        return QUANTITY_UNITS[self.quantity.split("@")[0]]

    def satisfied(self, value: NDArray[np.float64], rtol: float = FEAS_RTOL) -> NDArray[np.bool_]:
        """Whether ``value`` meets the bound to the relative tolerance ``rtol``."""
        tol = rtol * abs(self.bound)
        if self.sense == "min":
            return np.asarray(value >= self.bound - tol)
        return np.asarray(value <= self.bound + tol)

    def margin(self, value: float) -> float:
        """Signed slack in the quantity's unit: >= 0 when met."""
        return value - self.bound if self.sense == "min" else self.bound - value


@dataclass(frozen=True, slots=True)
class Objective:
    """Minimise or maximise one quantity (mass by default)."""

    quantity: str = "mass"
    sense: Sense = "min"


@dataclass(frozen=True)
class Problem:
    """A design problem in internal units (mm, deg, g, N)."""

    name: str
    model: str
    layout: Layout
    identical: bool
    candidates: tuple[Candidate, ...]
    W: DesignVariable
    alpha: DesignVariable
    n_lo: int
    n_hi: int
    constraints: tuple[Constraint, ...]
    objective: Objective = field(default_factory=Objective)
    support: str = "free"  # the spec's global support condition (reports, tables)

    @property
    def etas(self) -> tuple[float, ...]:
        """Directions (deg) at which some stiffness is needed."""
        keys = [c.quantity for c in self.constraints] + [self.objective.quantity]
        return tuple(sorted({float(k.split("@")[1]) for k in keys if "@" in k}))

    @property
    def gridded(self) -> bool:
        """Whether every variable is discrete (then the optimum is certified with zero gap)."""
        return self.W.gridded and self.alpha.gridded

    def without(self, name: str) -> Problem:
        """The same problem without the constraint called ``name``."""
        return replace(self, constraints=tuple(c for c in self.constraints if c.name != name))

    def with_objective(self, quantity: str, sense: Sense) -> Problem:
        return replace(self, objective=Objective(quantity, sense))

    @classmethod
    def from_spec(cls, spec: Spec) -> Problem:
        """Translate a validated spec (see :mod:`corrugate.spec.schema`)."""
        v = spec.variables
        layout = make_layout(spec.layout.shape, spec.layout.vertices, spec.layout.hole_list())
        mats = [spec.material] if spec.material is not None else list(spec.materials or [])
        cands: list[Candidate] = []
        for i, m in enumerate(mats):
            where = "material" if spec.material is not None else f"materials[{i}]"
            cands.extend(_candidates(where, m))
            try:
                get_model(spec.model).check_nu(cands[-1].material.nu)
            except InputError as exc:
                raise SpecError(f"{where}.nu", exc.value, exc.allowed, reason=exc.reason) from None
        c = spec.constraints
        cons: list[Constraint] = []
        if c.sheet_max is not None:
            cons.append(
                Constraint("constraints.sheet_max (flat blank)", "flat", "max", c.sheet_max)
            )
            cons.append(
                Constraint("constraints.sheet_max (facet length)", "facet", "max", c.sheet_max)
            )
        sizes = {
            "side": ("Lx",),
            "diameter": ("Lx",),
            "side_x": ("Lx",),
            "side_y": ("Ly",),
            "thickness": ("thickness",),
        }
        for key, (qty,) in sizes.items():
            r = getattr(c, key)
            if r is None:
                continue
            if r.min is not None:
                cons.append(Constraint(f"constraints.{key}.min", qty, "min", r.min))
            if r.max is not None:
                cons.append(Constraint(f"constraints.{key}.max", qty, "max", r.max))
        for kind in STIFFNESS_KINDS:
            for i, b in enumerate(getattr(c, kind)):
                key = stiffness_key(kind, b.eta, b.support or spec.support)
                cons.append(Constraint(f"constraints.{kind}[{i}].min", key, "min", b.min))
        for i, bk in enumerate(c.buckling_load):
            if crease_layer(bk.eta) is None:
                raise SpecError(
                    f"constraints.buckling_load[{i}].eta",
                    f"{bk.eta:g} deg",
                    "0 or 90 deg (along a layer's creases)",
                )
            if layout.name not in ("square", "rectangle"):
                raise SpecError(
                    f"constraints.buckling_load[{i}]",
                    f"layout {layout.name}",
                    "a square or rectangle layout",
                    reason="has buckling bounds only for long straight end facets",
                )
            eta = 0.0 if crease_layer(bk.eta) == 0 else 90.0
            cons.append(
                Constraint(f"constraints.buckling_load[{i}].min", f"Pb@{eta:g}", "min", bk.min)
            )
        if c.mass is not None:
            cons.append(Constraint("constraints.mass.max", "mass", "max", c.mass.max))
        o = spec.objective
        objective = (
            Objective()
            if o.maximize is None
            else Objective(stiffness_key(o.maximize, o.eta, o.support or spec.support), "max")
        )
        return cls(
            name=spec.name,
            model=spec.model,
            layout=layout,
            identical=spec.layers == "identical",
            candidates=tuple(cands),
            W=DesignVariable(v.W.min, v.W.max, v.W.step),
            alpha=DesignVariable(v.alpha.min, v.alpha.max, v.alpha.step),
            n_lo=v.n.min,
            n_hi=v.n.max,
            constraints=tuple(cons),
            objective=objective,
            support=spec.support,
        )


def _candidates(where: str, m: MaterialSpec) -> list[Candidate]:
    if m.E is not None:
        assert m.nu is not None
        assert m.density is not None
        ts = m.thickness if isinstance(m.thickness, list) else [m.thickness]
        mat = inline_material(m.E, m.nu, m.density / 1e-3, name=m.name)
        return [Candidate(mat, float(t)) for t in ts if isinstance(t, float)]
    mat = get_material(m.name)
    if m.thickness == "all":
        if not mat.thicknesses:
            raise SpecError(
                f"{where}.thickness",
                "'all'",
                "explicit thicknesses",
                reason=f"lists none for {mat.id}",
            )
        return [Candidate(mat, t) for t in mat.thicknesses]
    if m.thickness is None:
        if mat.default_thickness is None:
            raise SpecError(f"{where}.thickness", None, "a thickness", reason="is missing")
        return [Candidate(mat, mat.default_thickness)]
    ts = m.thickness if isinstance(m.thickness, list) else [m.thickness]
    return [Candidate(mat, float(t)) for t in ts]
