"""The optimisation problem a spec states, in internal units (docs/theory.md section 5).

A :class:`Problem` is what the solver sees: the moduli variant, the layout, whether the two layers
are identical, the candidate sheets (material and thickness: a discrete variable), the bounds and
optional grid steps of W (mm), alpha (deg) and the integer n, the constraints and the objective.

Every constraint is a bound on one *quantity* of a design, a value
(:class:`~corrugate.solver.quantity.Quantity`: its kind, the direction eta, the support condition
and load case of a stiffness), e.g. the folded extent ``Lx``, the mass, ``EI@0`` (free sides),
``Kframe@45`` (in a rigid frame) or the buckling load ``Pb@90``.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field, replace
from functools import cached_property
from typing import Literal

import numpy as np
from numpy.typing import NDArray

from corrugate.core.errors import InputError
from corrugate.core.limits import check_items
from corrugate.geometry.layer import crease_layer
from corrugate.geometry.layouts import Layout, make_layout
from corrugate.geometry.profile import ZIGZAG, ProfileKind
from corrugate.materials.library import Material, get_material, inline_material
from corrugate.mechanics.behaviours import Behaviour, get_load_case, listed, load_cases
from corrugate.mechanics.load_cases import DEFAULT_SAFETY_FACTOR
from corrugate.mechanics.moduli import get_model
from corrugate.names import DEFAULT_MACHINE, DEFAULT_MARGIN_MM, DEFAULT_SUPPORT
from corrugate.solver.quantity import (
    CREASES,
    FACET,
    FLAT,
    LX,
    LY,
    MASS,
    PART_LONG,
    PART_SHORT,
    T_OVER_W,
    THICKNESS,
    W_MIN,
    Quantity,
)
from corrugate.solver.worst_case import NOMINAL, WorstCase
from corrugate.spec.schema import PURE, STIFFNESS_KINDS, MaterialSpec, Spec, SpecError

__all__ = [
    "FEAS_RTOL",
    "HOLDS",
    "Candidate",
    "Constraint",
    "DesignVariable",
    "Objective",
    "Problem",
]

#: Relative tolerance within which a constraint counts as met (floating-point slack only).
FEAS_RTOL = 1e-9

Sense = Literal["min", "max"]


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


#: The suffix of the bound a deflection bound under a load brings with it: the part holds that
#: load at the safety factor (its capacity, docs/load_cases.md 10.6).
HOLDS = ".load (held at the safety factor)"


@dataclass(frozen=True, slots=True)
class Constraint:
    """``quantity`` >= ``bound`` (sense ``min``) or <= ``bound`` (sense ``max``).

    ``name`` is the spec path it comes from (e.g. ``constraints.side.min``). A deflection
    bound (``constraints.deflection[i].max``: delta <= max under ``load``) is P / delta >= load /
    max, with ``load`` kept to report the deflection.
    """

    name: str
    quantity: Quantity
    sense: Sense
    bound: float
    load: float | None = None  # N: a deflection bound's load (the quantity is P / delta)
    # the unit the spec wrote the bound in ("N*m^2"; None: a plain number), what the diagnosis
    # answers in (corrugate.spec.written)
    written: str | None = None

    @property
    def unit(self) -> str:
        return self.quantity.unit

    def deflection(self, value: float) -> float | None:
        """The deflection (mm) under this bound's load at P / delta = ``value`` (N/mm), None
        when it is not a deflection bound."""
        return None if self.load is None else self.load / value

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

    quantity: Quantity = MASS
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
    support: str = DEFAULT_SUPPORT  # the spec's global support condition (reports, tables)
    safety_factor: float = DEFAULT_SAFETY_FACTOR  # of the strength bounds (Pmax quantities)
    joint: str = "none"  # how the layers are joined (mechanics.load_cases.JOINTS)
    # the profile both layers are folded to (geometry.profile; the zig-zag unless the Python API
    # names another designable profile)
    profile_kind: ProfileKind = ZIGZAG
    # "certified": the validated ranges are constraints; "extrapolate": they are ``ranges``,
    # checked on the answer only (corrugate.solver.validity)
    trust: str = "certified"
    ranges: tuple[Constraint, ...] = ()
    # the worst-case tolerances its certificate covers (solver.worst_case, docs/tolerances.md;
    # the spec's [tolerances]: its defaults unless tolerances = "none", or [robust] alone)
    tolerances: WorstCase = NOMINAL

    @property
    def calibrated(self) -> bool:
        """Whether a candidate sheet is a calibrated material: its certificate bounds every
        directional quantity over the measured intervals (:mod:`~.tolerance_box`)."""
        return any(c.material.calibration is not None for c in self.candidates)

    @property
    def E_measured(self) -> bool:
        """Whether every candidate sheet's E is measured (a calibrated entry): its interval
        then replaces the +-dE of ``[tolerances]`` (:mod:`~.tolerance_box`)."""
        return all(
            c.material.calibration is not None and c.material.calibration.E_measured
            for c in self.candidates
        )

    @property
    def tolerance_sentence(self) -> str:
        """What the certificate covers of the tolerances (:meth:`WorstCase.sentence_for`): the
        +-dE is not named when every candidate's E is measured (:attr:`E_measured`)."""
        return self.tolerances.sentence_for(self.E_measured)

    @property
    def calibration_words(self) -> str:
        """``calibrated E ... from my-dura-lar, 2026-12-06, 40 measurements`` for each calibrated
        material of the candidates ('' for none; :meth:`corrugate.materials.calibrated.
        Calibration.words`)."""
        seen: dict[str, str] = {}
        for c in self.candidates:
            cal = c.material.calibration
            if cal is not None and c.material.id not in seen:
                seen[c.material.id] = cal.words(c.material.id)
        return "; ".join(seen.values())

    @cached_property
    def quantities(self) -> tuple[Quantity, ...]:
        """The quantities of the constraints, then the objective's (computed once: the fields
        of a frozen problem do not change; :func:`dataclasses.replace` makes a new one)."""
        return (*(c.quantity for c in self.constraints), self.objective.quantity)

    @cached_property
    def etas(self) -> tuple[float, ...]:
        """Directions (deg) at which some stiffness is needed (computed once)."""
        return tuple(sorted({q.eta for q in self.quantities if q.eta is not None}))

    @property
    def layer_count(self) -> int:
        """The layers of a design (docs/theory.md section 2: two crossed corrugated layers)."""
        return 2

    @property
    def searched_layers(self) -> int:
        """The layers whose variables the search spans: one for identical layers."""
        return 1 if self.identical else self.layer_count

    @property
    def gridded(self) -> bool:
        """Whether every variable is discrete (then the optimum is certified with zero gap)."""
        return self.W.gridded and self.alpha.gridded

    def without(self, name: str) -> Problem:
        """The same problem without the constraint called ``name``."""
        return replace(self, constraints=tuple(c for c in self.constraints if c.name != name))

    def with_objective(self, quantity: Quantity, sense: Sense) -> Problem:
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
            cands.extend(_candidates(where, m, spec.own_materials))
            check_items("thicknesses", "materials", len(cands), "candidate sheets")
            try:
                get_model(spec.model).check_nu(cands[-1].material.nu)
            except InputError as exc:
                raise SpecError(f"{where}.nu", exc.value, exc.allowed, reason=exc.reason) from None
        c = spec.constraints
        cons: list[Constraint] = []
        if c.sheet_max is not None:
            cons.append(Constraint("constraints.sheet_max (flat blank)", FLAT, "max", c.sheet_max))
            cons.append(
                Constraint("constraints.sheet_max (facet length)", FACET, "max", c.sheet_max)
            )
        cons.extend(_making_constraints(spec))
        sizes = {
            "side": (LX,),
            "diameter": (LX,),
            "side_x": (LX,),
            "side_y": (LY,),
            "thickness": (THICKNESS,),
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
                where = f"constraints.{kind}[{i}]"
                q = _stiffness_quantity(where, kind, b.eta, b.support or spec.support, b.test)
                if q.test == "wheel":
                    _check_wheel(where, layout, b.eta, q.support, b.support is None)
                elif q.test is not None:
                    _check_load_case_layout(where, layout, q.test)
                q = _sustained(where, q, b.duration, cands)
                cons.append(Constraint(f"{where}.min", q, "min", b.min))
        for i, d in enumerate(c.deflection):
            where = f"constraints.deflection[{i}]"
            support = d.support or spec.support
            _check_load_case_layout(where, layout, d.test)
            _check_no_span(where, d.test, d.span)
            if get_load_case(d.test).form.own:  # type: ignore[union-attr]
                q = Quantity.stiffness("K", d.eta, support)
            else:
                q = Quantity.load_case("k", d.eta, d.test, support, d.span)
                if d.span is not None:  # the panel must reach the supports (or the clamp)
                    cons.append(
                        Constraint(f"{where}.span", Quantity("length", d.eta), "min", d.span)
                    )
            q = _sustained(where, q, d.duration, cands)
            cons.append(Constraint(f"{where}.max", q, "min", d.load / d.max, load=d.load))
            if crease_layer(d.eta) is not None and not get_load_case(d.test).stiffness_only:
                # a linear deflection past the first failure is no certificate: the part must
                # hold the load at the safety factor (docs/load_cases.md 10.6)
                eta = 0.0 if crease_layer(d.eta) == 0 else 90.0
                held = Quantity.load_case("Pmax", eta, d.test, support, d.span)
                # held for the deflection's duration: buckling at the creep modulus (section 11)
                held = _sustained(where, held, d.duration, cands)
                held = replace(held, bearing=_bearing(where, spec, d.test, eta, d.span, d.bearing))
                cons.append(Constraint(f"{where}{HOLDS}", held, "min", d.load))
        for i, g in enumerate(c.strength):
            where = f"constraints.strength[{i}]"
            _check_load_case_layout(where, layout, g.test)
            if crease_layer(g.eta) is None:
                raise SpecError(
                    f"{where}.eta",
                    f"{g.eta:g} deg",
                    "0 or 90 deg (stresses are modelled along a layer's creases)",
                )
            _check_no_span(where, g.test, g.span)
            for cand in cands:
                if cand.material.yield_strength is None:
                    raise SpecError(
                        "material.yield_strength",
                        None,
                        "a yield strength (MPa) for a strength bound",
                        reason=f"is missing for {cand.material.id}",
                    )
            eta = 0.0 if crease_layer(g.eta) == 0 else 90.0
            q = Quantity.load_case("Pmax", eta, g.test, g.support or spec.support, g.span)
            q = replace(q, bearing=_bearing(where, spec, g.test, eta, g.span, g.bearing))
            if g.span is not None:  # a bending test's (_check_no_span)
                cons.append(Constraint(f"{where}.span", Quantity("length", eta), "min", g.span))
            cons.append(Constraint(f"{where}.load", q, "min", g.load))
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
            where = f"constraints.buckling_load[{i}]"
            q = _sustained(where, Quantity("Pb", eta), bk.duration, cands)
            cons.append(Constraint(f"{where}.min", q, "min", bk.min))
        if c.mass is not None:
            cons.append(Constraint("constraints.mass.max", MASS, "max", c.mass.max))
        from corrugate.solver.validity import validity_constraints

        v_n = (v.n.min, v.n.max)
        W_var = DesignVariable(v.W.min, v.W.max, v.W.step)
        a_var = DesignVariable(v.alpha.min, v.alpha.max, v.alpha.step)
        ranges = validity_constraints(
            cons,
            W_var,
            a_var,
            v_n,
            cands,
            spec.fabrication.max_t_over_W,
            _joint(spec.joint, layout),
            spec.layers == "identical",
        )
        if spec.trust == "certified":
            cons.extend(ranges)
        o = spec.objective
        objective = (
            Objective()
            if o.maximize is None
            else Objective(Quantity.stiffness(o.maximize, o.eta, o.support or spec.support), "max")
        )
        cons = [replace(c, written=spec.unit_written(c.name.split(" ")[0])) for c in cons]
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
            safety_factor=spec.safety_factor,
            joint=_joint(spec.joint, layout),
            trust=spec.trust,
            ranges=tuple(ranges),
            tolerances=WorstCase.of(spec.tolerances),  # the defaults without [tolerances]
        )


def _sustained(where: str, q: Quantity, duration: float | None, cands: list[Candidate]) -> Quantity:
    """``q`` under a load held for ``duration`` (hours; None: ``q`` itself, short-term): every
    candidate sheet must have a creep modulus then (creep data, the duration within its table;
    docs/load_cases.md section 11), else a :class:`SpecError` at ``where.duration``."""
    if duration is None:
        return q
    for cand in cands:
        try:
            cand.material.creep_modulus(duration, f"{where}.duration")
        except InputError as exc:
            raise SpecError(exc.field, exc.value, exc.allowed, reason=exc.reason) from None
    return replace(q, duration=duration)


def _stiffness_quantity(
    where: str, kind: str, eta: float, support: str, test: str | None
) -> Quantity:
    """The quantity a stiffness bound names: ``test`` None, ``pure`` (EI, D) and the in-plane
    test of the support's own K (K: ``platens``, :attr:`TestForm.own`) are the support's own
    stiffness; a bending test on K or an in-plane test on EI or D is refused."""
    q = Quantity.stiffness(kind, eta, support)
    if test is None:
        return q
    inplane = q.kind == "K"
    form = None if test == PURE else get_load_case(test).form
    if (form is None and not inplane) or (form is not None and form.own and inplane):
        return q
    if form is None or (form.kind == "inplane") != inplane:
        allowed = listed(
            ([] if inplane else [repr(PURE)])
            + [
                repr(b.name) + (f" (a {b.layouts[0]})" if len(b.layouts) == 1 else "")
                for b in load_cases()
                if b.form is not None and (b.form.kind == "inplane") == inplane
            ]
        )
        raise SpecError(f"{where}.test", repr(test), allowed, reason=f"is not a test of {kind}")
    return Quantity.load_case(q.kind, eta, test, support)


def _bearing(
    where: str, spec: Spec, test: str, eta: float, span: float | None, bearing: float | None
) -> float | None:
    """A load case's ``bearing`` width (mm; docs/load_cases.md 10.5), checked: a bending test's
    (platens load no line), at most the span and at most the longest panel the size
    constraints allow along ``eta`` (0: side_y or side, 90: side_x or side), else a
    :class:`SpecError` at ``where.bearing``. None: the default."""
    if bearing is None:
        return None
    if get_load_case(test).form.kind == "inplane":  # type: ignore[union-attr]
        raise SpecError(
            f"{where}.bearing",
            f"{bearing:g} mm",
            f"no bearing for {test} (the platens load the panel's whole ends)",
            reason="does not apply",
        )
    c = spec.constraints
    sizes = [c.side, c.side_y if eta == 0.0 else c.side_x, c.diameter]
    longest = min((r.max for r in sizes if r is not None and r.max is not None), default=None)
    for limit, what in ((span, "the span"), (longest, "the panel's longest length")):
        if limit is not None and bearing > limit:
            raise SpecError(
                f"{where}.bearing",
                f"{bearing:g} mm",
                f"> 0 mm and at most {what}, {limit:g} mm",
                reason="is out of range",
            )
    return bearing


def _check_no_span(where: str, test: str, span: float | None) -> None:
    """An in-plane test compresses the panel's whole length along eta: it takes no span."""
    if span is not None and get_load_case(test).form.kind == "inplane":  # type: ignore[union-attr]
        raise SpecError(
            f"{where}.span",
            f"{span:g} mm",
            f"no span for {test} (the panel's length along eta is compressed)",
            reason="does not apply",
        )


def _check_wheel(
    where: str, layout: Layout, eta: float, support: str | None, inherited: bool = False
) -> None:
    """The wheel test (docs/load_cases.md 9) is a disc's: a circle layout, free sides (it holds
    the disc by its axle and ground patch, no frame; ``inherited``: the support is the spec's
    own, named as ``support``), and a direction its FE factor covers."""
    if layout.name != "circle":
        raise SpecError(
            f"{where}.test",
            "'wheel'",
            f"'platens' for a {layout.name} layout ('wheel' is a circle's test)",
            reason=f"is not a test of a {layout.name}",
        )
    if support not in (None, DEFAULT_SUPPORT):
        raise SpecError(
            "support" if inherited else f"{where}.support",
            repr(support),
            f"{DEFAULT_SUPPORT!r} for test 'wheel' (the disc is held by its axle and the ground)",
            reason="does not apply",
        )
    from corrugate.mechanics.wheel import WHEEL_DIRECTIONS, wheel_direction  # a wheel test only

    if wheel_direction(eta) is None:
        raise SpecError(
            f"{where}.eta",
            f"{eta:g} deg",
            f"{WHEEL_DIRECTIONS} for test 'wheel' (the directions its FE factor covers, "
            "`corrugate docs load_cases`, section 9)",
        )


def _joint(joint: str, layout: Layout) -> str:
    """``joint`` when the layout's band has a model (square, rectangle: straight walls)."""
    if joint != "none" and layout.name not in ("square", "rectangle"):
        raise SpecError(
            "joint",
            repr(joint),
            "'none' for a layout other than a square or rectangle",
            reason="has no model for a curved band",
        )
    return joint


def _inplane(b: Behaviour) -> bool:
    return b.form is not None and b.form.kind == "inplane"


def _check_load_case_layout(where: str, layout: Layout, test: str) -> None:
    """A load case applies to its layouts (:attr:`Behaviour.layouts`): the built-in tests need
    straight edges to support, clamp or load, a square or a rectangle."""
    layouts = get_load_case(test).layouts
    if layouts and layout.name not in layouts:
        own = [b for b in load_cases() if layout.name in b.layouts]  # the tests it does take
        instead = "".join(
            f"; a {layout.name} takes "
            + ("an [[constraints.inplane_stiffness]] bound with " if _inplane(b) else "")
            + f'test = "{b.name}": {b.text}'
            for b in own
        )
        raise SpecError(
            f"{where}.test",
            f"layout {layout.name}",
            f"a {' or '.join(layouts)} layout{instead}",
            reason="has no straight edges to support or load",
        )


def _candidates(where: str, m: MaterialSpec, own: dict[str, Material]) -> list[Candidate]:
    if m.E is not None:
        assert m.nu is not None
        assert m.density is not None
        ts = m.thickness if isinstance(m.thickness, list) else [m.thickness]
        mat = inline_material(m.E, m.nu, m.density / 1e-3, name=m.name)
        mat = replace(mat, yield_strength=m.yield_strength)
        k = math.inf if m.crease_stiffness is None else m.crease_stiffness
        if not math.isinf(k) or m.springback:  # stated: models, certificate and verify use them
            from corrugate.materials.calibrated import Calibration

            cal = Calibration.stated(mat.E, k, m.springback or 0.0)
            mat = replace(mat, crease_stiffness=k, calibration=cal)
        return [Candidate(mat, float(t)) for t in ts if isinstance(t, float)]
    mat = get_material(m.name, own)
    if m.yield_strength is not None:
        mat = replace(mat, yield_strength=m.yield_strength)
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


def machine_area(name: str) -> tuple[float, float]:
    """The usable area (mm, shorter side first) of the machine ``name`` in which every cut part
    must fit, turned 90 deg or not: its cut area less the sheet planner's margin on each side
    (:func:`corrugate.fabrication.sheets.plan_sheets`)."""
    from corrugate.core.cutters import get_cutter

    cut = get_cutter(name)
    w, h = cut.width - 2 * DEFAULT_MARGIN_MM, cut.height - 2 * DEFAULT_MARGIN_MM
    return min(w, h), max(w, h)


def _making_constraints(spec: Spec) -> list[Constraint]:
    """The constraints of the spec's ``[fabrication]`` (docs/fabrication.md, "What the solve
    asks of the making"): every cut part fits the machine (the spec's, else the default), no
    facet narrower than ``min_facet``, t / W at most ``max_t_over_W``, at most ``max_creases``."""
    f = spec.fabrication
    out = [
        Constraint("fabrication.min_facet", W_MIN, "min", f.min_facet),
        Constraint("fabrication.max_t_over_W", T_OVER_W, "max", f.max_t_over_W),
    ]
    if f.max_creases is not None:
        out.append(Constraint("fabrication.max_creases", CREASES, "max", float(f.max_creases)))
    machine = f.machine or DEFAULT_MACHINE
    if machine != "none":
        short, long = machine_area(machine)
        out.append(
            Constraint(f"fabrication.machine ({machine}: shorter side)", PART_SHORT, "max", short)
        )
        out.append(
            Constraint(f"fabrication.machine ({machine}: longer side)", PART_LONG, "max", long)
        )
    return out
