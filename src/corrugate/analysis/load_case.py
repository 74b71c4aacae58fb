"""A load case stated on one design (``corrugate analyze --test --load --span``, the web's
``POST /api/analyze`` fields ``test``, ``load`` and ``span``): at each direction of an
:class:`~corrugate.analysis.evaluate.Analysis`, the deflection delta (mm) of the test under the
load P (N) and the test's P / delta (N/mm), from the support's D or K, the layers' shear springs
and the panel's length along eta (docs/load_cases.md).

Errors name the input at fault as ``flag`` spells it: the command line's ``--test`` by default,
the web's ``test``.
"""

from __future__ import annotations

import math
from collections.abc import Callable
from dataclasses import dataclass
from typing import TYPE_CHECKING, Any

from corrugate.core.errors import InputError, UnknownNameError
from corrugate.core.parameters import PARAMETERS
from corrugate.names import LOAD_CASES

if TYPE_CHECKING:
    from corrugate.analysis.evaluate import Analysis
    from corrugate.mechanics.capacity import Capacity

__all__ = [
    "LoadCase",
    "cli_flag",
    "load_case_capacity",
    "load_case_dict",
    "load_case_of",
    "load_case_rows",
]


def cli_flag(name: str) -> str:
    """How the command line spells the parameter ``name`` (``--test``)."""
    return PARAMETERS[name].flag


@dataclass(frozen=True, slots=True)
class LoadCase:
    """A load case of ``analyze``: the test's name, the load (N), the span (mm; None: the
    panel's length along each eta, and always None between platens) and the load and support
    lines' bearing width (mm; None: :data:`corrugate.mechanics.capacity.DEFAULT_BEARING`)."""

    test: str
    load: float
    span: float | None = None
    bearing: float | None = None


def load_case_of(
    test: str | None,
    load: str | None,
    span: str | None,
    flag: Callable[[str], str] = cli_flag,
) -> LoadCase | None:
    """The load case the options ``--test``, ``--load`` and ``--span`` state (None when none is
    given); :class:`InputError` naming the option at fault: a load or a span without a test, a
    test without a load, an unknown test, a load or span that is not > 0, a span between
    platens. ``flag`` names an input in the messages (module docstring)."""
    from corrugate.core.limits import LIMITS, abnormal_reason
    from corrugate.core.units import parse_quantity

    if test is None:
        for name, value in (("load", load), ("span", span)):
            if value is not None:
                raise InputError(
                    flag(name),
                    value,
                    f"only with {flag('test')} ({', '.join(LOAD_CASES)})",
                    reason=f"is given without {flag('test')}",
                )
        return None
    if test not in LOAD_CASES:
        raise UnknownNameError(flag("test"), test, LOAD_CASES)
    if load is None:
        raise InputError(
            flag("load"),
            "not given",
            "a load in N (e.g. 10 or '2 lbf')",
            reason=f"is required with {flag('test')}",
        )

    def positive(name: str, value: str, unit: str, limit: str) -> float:
        x = parse_quantity(value, unit, flag(name))
        hi = LIMITS[limit].hi
        if not 0.0 < x <= hi:
            reason = abnormal_reason(x) or "is out of range"
            raise InputError(
                flag(name), f"{x:g} {unit}", f"> 0 {unit} and <= {hi:g} {unit}", reason=reason
            )
        return x

    P = positive("load", load, "N", "load")
    if span is None:
        return LoadCase(test, P)
    from corrugate.mechanics.behaviours import get_load_case

    if get_load_case(test).form.kind == "inplane":  # type: ignore[union-attr]
        raise InputError(
            flag("span"),
            span,
            f"no span for {test} (the panel's length along eta is compressed)",
            reason="does not apply",
        )
    return LoadCase(test, P, positive("span", span, "mm", "length"))


def load_case_rows(
    r: Analysis, case: LoadCase, flag: Callable[[str], str] = cli_flag
) -> list[dict[str, Any]]:
    """For each direction of ``r``: the span Ls (mm; platens: the length compressed), the
    deflection (mm) of ``case`` under its load and the test's P / delta (N/mm), by
    :func:`corrugate.mechanics.load_cases.load_stiffness` (docs/load_cases.md, sections 1-3):
    the support's D (bending tests, EI = D L over the panel's length L along eta, the layers'
    shear spring V and depth h at eta) or K (platens). :class:`InputError` naming the span
    where it is longer than the panel, and the test for a layout it does not apply to (its
    registry entry's ``layouts``: the built-ins need straight edges)."""
    from corrugate.mechanics.behaviours import get_load_case
    from corrugate.mechanics.load_cases import load_stiffness, shear_and_depth
    from corrugate.mechanics.offaxis import _cs

    layout = r.assembly.layout
    entry = get_load_case(case.test)
    if entry.layouts and layout.name not in entry.layouts:
        raise InputError(
            flag("test"),
            f"{case.test} on layout {layout.name}",
            f"a {' or '.join(entry.layouts)} layout",
            reason="has no straight edges to support or load",
        )
    form = entry.form
    assert form is not None
    rows = []
    for st in r.stiffness:
        if case.span is not None and case.span > st.span:
            raise InputError(
                flag("span"),
                f"{case.span:g} mm",
                f"at most the panel's length along eta = {st.eta_deg:g} deg, {st.span:.6g} mm",
            )
        if form.kind == "inplane":
            k = float(load_stiffness(form, st.K, None, None, st.span, eta_deg=st.eta_deg))
            Ls = st.span
        else:
            V, h = shear_and_depth(r.springs, *_cs(st.eta_deg))
            k = float(load_stiffness(form, st.D, float(V), float(h), st.span, case.span))
            Ls = st.span if case.span is None else case.span
        if not (math.isfinite(k) and k > 0):
            raise InputError("body", f"P/delta = {k}", "a positive stiffness", reason="is not")
        row: dict[str, Any] = {
            "eta_deg": st.eta_deg,
            "span_mm": Ls,
            "deflection_mm": case.load / k,
            "stiffness_N_per_mm": k,
        }
        cap = load_case_capacity(r, case, st.eta_deg)
        if cap is not None:
            row.update(
                {"load_capacity_N": cap.load, "safety_factor": cap.safety_factor, **cap.as_dict()}
            )
            row["holds"] = cap.sentence
        rows.append(row)
    return rows


def load_case_capacity(
    r: Analysis, case: LoadCase, eta_deg: float, safety_factor: float | None = None
) -> Capacity | None:
    """The capacity of the load case ``case`` at ``eta_deg`` (0 or 90 deg: along a layer's
    creases; None elsewhere, and for a test without a capacity, the wheel): every failure mode's
    load (:func:`corrugate.mechanics.capacity.capacity_modes`, the formulas the solver bounds),
    their least over the ``safety_factor`` (default
    :data:`corrugate.mechanics.load_cases.DEFAULT_SAFETY_FACTOR`, the spec's), named
    (docs/load_cases.md 10)."""
    from corrugate.geometry.layer import crease_layer
    from corrugate.mechanics.behaviours import get_load_case
    from corrugate.mechanics.capacity import Band, Capacity, capacity_modes
    from corrugate.mechanics.load_cases import DEFAULT_SAFETY_FACTOR, band_walls

    entry = get_load_case(case.test)
    form = entry.form
    along = crease_layer(eta_deg)
    if form is None or along is None or entry.stiffness_only:
        return None
    st = next(s for s in r.stiffness if s.eta_deg == eta_deg)
    a = r.assembly
    lay = (a.layer1, a.layer2) if along == 0 else (a.layer2, a.layer1)
    sp = r.springs if along == 0 else r.springs[::-1]
    whole = st.K if form.kind == "inplane" else st.D
    layers, band = whole, None
    if r.joint != "none":
        l1 = a.layer1
        depth = float(a.thickness)
        walls = band_walls(l1.material.E, l1.material.nu, l1.t, depth, st.span)
        layers = whole - walls[2 if form.kind == "inplane" else 0]
        band = Band(l1.material.E, l1.material.nu, l1.t, depth, _yield(l1))
    modes = capacity_modes(
        form,
        (sp[0], sp[1]),
        (lay[0].material.E, lay[1].material.E),
        (lay[0].t, lay[1].t),
        lay[0].material.nu,
        lay[0].W,
        lay[0].n,
        layers,
        whole,
        st.span,
        a.Lx if along == 0 else a.Ly,
        case.span,
        (_yield(lay[0]), _yield(lay[1])),
        band,
        r.joint == "none",
        along,
        case.bearing,
    )
    sf = DEFAULT_SAFETY_FACTOR if safety_factor is None else safety_factor
    return Capacity.of({k: float(v) for k, v in modes.items()}, sf, form, along + 1, case.bearing)


def _yield(layer: Any) -> float:
    """A layer's yield strength (MPa), +inf without one (no yield mode)."""
    y = layer.material.yield_strength
    return math.inf if y is None else float(y)


def load_case_dict(case: LoadCase, rows: list[dict[str, Any]]) -> dict[str, object]:
    """The ``load_case`` object of ``analyze --json``."""
    return {
        "test": case.test,
        "load_N": case.load,
        "span_mm": case.span,
        "directions": rows,
    }
