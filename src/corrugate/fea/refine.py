"""``corrugate design --verify fe --refine``: correct the model's bounds by the FE and re-solve.

The certified design meets every bound under the closed-form model; its FE twins
(:mod:`corrugate.fea.verify`) say whether it meets them in the test each bound states. Where
they differ, the model bound of a constraint is corrected by the ratio measured at the design,

    b' = B x model / FE            (a stiffness or load bound, minimum or maximum)
    b' = B x FE / model            (a deflection bound: the solver bounds P / delta >= load / max,
                                    and FE / model of the deflection is model / FE of P / delta)

with B the spec's own bound and model, FE the constraint's values at that design (FE: the
extrapolated mesh series, off the crease directions the worst coupon position), so that a
design whose model/FE ratio is the measured one meets B in FE. The bound is corrected when the
FE misses B (tightened), and, when ``loosen`` is on, when the FE exceeds B by more than
:data:`LOOSEN_ABOVE` (loosened: where the model is very conservative, e.g. off-axis bending of a
free panel, docs/load_cases.md 5); otherwise the bound of the attempt before stays. The spec is
re-solved under the corrected bounds and the new design verified, at most :data:`MAX_RESOLVES`
times; the loop stops earlier when no bound changes, when it would repeat a set of bounds
already solved, or when a re-solve has no certified design. The answer is the best (lightest,
for a mass objective) attempt whose own FE verification holds, every constraint at the worst
coupon position: a ratio that holds at one design but not at the next is never trusted, since
only a verified design is returned. When no attempt verifies, the answer is the first (the
spec's own certified design) with its failed verification.
"""

from __future__ import annotations

import math
from collections.abc import Callable, Iterable, Sequence
from dataclasses import dataclass, replace
from typing import Any, Generic, Protocol, TypeVar

from corrugate.fea.verify import Row, Verification
from corrugate.geometry.layer import Layer
from corrugate.solver.problem import Constraint, Problem
from corrugate.solver.solve import ConstraintReport, Solution

__all__ = [
    "LOOSEN_ABOVE",
    "MAX_RESOLVES",
    "Attempt",
    "Refined",
    "Solved",
    "answer_payload",
    "corrected_bound",
    "next_bounds",
    "refine",
    "spec_reports",
    "statement",
    "with_bounds",
]

#: At most this many re-solves after the first solve (each one a solve and an FE verification).
MAX_RESOLVES = 4
#: With ``loosen``, a bound is loosened when its FE exceeds it by more than this factor.
LOOSEN_ABOVE = 1.05


class Solved(Protocol):
    """What a solve of the loop returns: its ``solution``, and the JSON object ``design --json``
    prints for it (``payload``), which :func:`answer_payload` starts the answer's JSON from, e.g.
    :class:`corrugate.workflow.solve.DesignRun`. The loop itself reads the solution only."""

    @property
    def solution(self) -> Solution: ...

    @property
    def payload(self) -> dict[str, Any]: ...


R = TypeVar("R", bound=Solved)

#: Verifies a solved design in FE: its solution and its constraint reports, each with the spec's
#: bound (:func:`spec_reports`).
VerifyFn = Callable[[Solution, tuple[ConstraintReport, ...]], Verification]


@dataclass(frozen=True)
class Attempt(Generic[R]):
    """One solve of the loop: the model ``bounds`` of the behavioural constraints it was solved
    under (name -> bound, in the solver's units), what the solve returned (``run``: its
    ``solution``), and the FE ``verification`` of its design (None without a certified
    design)."""

    bounds: dict[str, float]
    run: R
    verification: Verification | None

    @property
    def solution(self) -> Solution:
        return self.run.solution

    @property
    def layers(self) -> tuple[Layer, ...]:
        """The layers of its design (none without a design: the JSON's ``design`` is null)."""
        sol = self.solution
        if sol.assembly is None or sol.analysis is None:
            return ()
        return tuple(sol.assembly.layers)

    @property
    def verified(self) -> bool:
        """A certified design whose every constraint with an FE twin holds in FE (a converged
        series; a constraint without a twin, "not checked", rests on the certificate)."""
        return (
            self.solution.certified
            and self.solution.assembly is not None
            and self.verification is not None
            and self.verification.no_failure
        )


@dataclass(frozen=True)
class Refined(Generic[R]):
    """Every attempt of the loop, the index of the chosen one (the best verified; None when no
    attempt verifies) and why the loop ``stopped``."""

    attempts: tuple[Attempt[R], ...]
    chosen: int | None
    stopped: str

    @property
    def resolves(self) -> int:
        """Re-solves after the first solve."""
        return len(self.attempts) - 1

    @property
    def answer(self) -> Attempt[R]:
        """The chosen attempt, or the first one when none verifies."""
        return self.attempts[0 if self.chosen is None else self.chosen]


def corrected_bound(c: Constraint, row: Row) -> float | None:
    """The model bound of ``c`` (the spec's constraint, bound B) that the measured ratio at the
    verified design asks for (module docstring), or None when the row has no usable FE value
    (no twin, no estimate, a value that is not positive and finite)."""
    fe, model = row.fe, row.model
    if fe is None or not (math.isfinite(fe) and math.isfinite(model)) or fe <= 0 or model <= 0:
        return None
    ratio = fe / model if c.load is not None else model / fe
    return c.bound * ratio


def _beyond(row: Row, factor: float, missed: bool = False) -> bool:
    """Whether the row's FE meets its bound with more than ``factor`` to spare (``missed``:
    whether it misses the bound)."""
    if row.fe is None:
        return False
    if missed:
        return row.fe < row.bound if row.sense == "min" else row.fe > row.bound
    return row.fe > factor * row.bound if row.sense == "min" else row.fe * factor < row.bound


def next_bounds(
    spec: Problem, current: dict[str, float], v: Verification, *, loosen: bool
) -> dict[str, float]:
    """The model bounds of the next solve: for each row of ``v`` (the last design's FE), the
    corrected bound (:func:`corrected_bound`) where the FE fails the spec's bound, or where its
    series did not converge and its estimate misses the bound (tightened only: an unconverged
    ratio never loosens), or, with ``loosen``, where a converged FE exceeds it by more than
    :data:`LOOSEN_ABOVE`; elsewhere the ``current`` bound."""
    by_name = {c.name: c for c in spec.constraints}
    out = dict(current)
    for row in v.rows:
        c = by_name.get(row.name)
        if c is None or row.fe is None:
            continue
        if row.verdict == "holds" and not (loosen and _beyond(row, LOOSEN_ABOVE)):
            continue
        if row.verdict == "not converged" and not _beyond(row, 1.0, missed=True):
            continue
        if row.verdict == "not checked":
            continue
        b = corrected_bound(c, row)
        if b is not None:
            out[row.name] = b
    return out


def with_bounds(spec: Problem, bounds: dict[str, float]) -> Problem:
    """``spec`` with the model bounds ``bounds`` (name -> bound) in place of its own."""
    return replace(
        spec,
        constraints=tuple(
            replace(c, bound=bounds[c.name]) if c.name in bounds else c for c in spec.constraints
        ),
    )


def _same(a: dict[str, float], b: dict[str, float]) -> bool:
    return a.keys() == b.keys() and all(math.isclose(a[k], b[k], rel_tol=1e-9) for k in a)


def _better(a: Solution, b: Solution) -> bool:
    """Whether ``a``'s objective is better than ``b``'s."""
    if a.problem.objective.sense == "min":
        return a.objective < b.objective
    return a.objective > b.objective


def refine(
    spec: Problem,
    solve: Callable[[Problem], R],
    verify: VerifyFn,
    *,
    loosen: bool = True,
    cap: int = MAX_RESOLVES,
    progress: Callable[[str], None] = lambda line: None,
    first: R | None = None,
) -> Refined[R]:
    """The loop of the module docstring on the problem ``spec`` (its bounds are the spec's):
    ``solve`` solves a problem (its solution, :class:`Solved`), ``verify`` runs the FE twins of
    a solved design (given its constraint reports with the spec's bounds, :func:`spec_reports`); ``first``: the spec's own solve when already solved. At most
    ``cap`` re-solves."""
    bounds: dict[str, float] = {}
    attempts: list[Attempt[R]] = []
    tried: list[dict[str, float]] = []
    problem = spec
    stopped = f"the cap of {cap} re-solves"
    cached: dict[tuple[tuple[str, float, float, int, float], ...], Verification] = {}
    for k in range(cap + 1):
        if k == 0 and first is not None:
            run = first
        else:
            progress(
                f"refine: re-solve {k} of at most {cap} under the corrected bounds "
                + ", ".join(f"{n} {b:.5g}" for n, b in bounds.items())
            )
            run = solve(problem)
        sol = run.solution
        verification: Verification | None = None
        if sol.certified and sol.assembly is not None:
            key = _design_key(sol.assembly.layers)
            if key not in cached:
                progress(f"refine: FE verification of design {k + 1} ({_design_text(sol)})")
                # the FE is judged against the spec's bounds, never the corrected ones
                checked = spec_reports(sol.constraints, spec, bounds)
                cached[key] = verify(sol, checked)
            verification = cached[key]
            progress(f"refine: design {k + 1}: {_verdict(verification)}")
        if k == 0:
            spec_bounds = {
                r.name: c.bound
                for r in (verification.rows if verification is not None else ())
                for c in spec.constraints
                if c.name == r.name
            }
            bounds = dict(spec_bounds)
        attempts.append(Attempt(dict(bounds), run, verification))
        tried.append(dict(bounds))
        if verification is None:
            stopped = (
                "no certified design"
                if k == 0
                else f"re-solve {k} has no certified design ({sol.status})"
            )
            break
        if k == cap:
            break
        new = next_bounds(spec, bounds, verification, loosen=loosen)
        if _same(new, bounds):
            stopped = "no bound to correct (the corrected bounds are the last attempt's)"
            break
        if any(_same(new, t) for t in tried):
            stopped = "the corrected bounds repeat an attempt's"
            break
        bounds = new
        problem = with_bounds(spec, bounds)
    chosen: int | None = None
    for i, a in enumerate(attempts):
        if a.verified and (chosen is None or _better(a.solution, attempts[chosen].solution)):
            chosen = i
    return Refined(tuple(attempts), chosen, stopped)


def _design_key(layers: Sequence[Layer]) -> tuple[tuple[str, float, float, int, float], ...]:
    """A design by its layers' values (material, t, W, n, alpha), so that a design solved again
    is verified once."""
    return tuple((lay.material.id, lay.t, lay.W, lay.n, lay.alpha_deg) for lay in layers)


def _design_text(sol: Solution) -> str:
    """The design of ``sol`` in one phrase: each distinct layer, then its mass."""
    layers = sol.assembly.layers if sol.assembly is not None else ()
    parts = [
        f"{lay.material.id} {lay.t:g} mm W {lay.W:g} n {lay.n} alpha {lay.alpha_deg:g}"
        for lay in layers
    ]
    mass = sol.mass
    head = "; ".join(dict.fromkeys(parts))  # identical layers once
    return head + (f", {mass:.4g} g" if mass is not None else "")


def statement(v: Verification) -> str:
    """The FE statement of a verified design: the series, then per constraint its test, FE
    estimate against the bound, and the coupon position that counts, e.g. ``verified by FE
    (CalculiX; mesh series 2 / 4 / 8 elements per facet, extrapolated): constraints.x.min in
    3-point bending along eta = 45 deg: FE 61.2 >= 50 N mm (worst of 4 coupon positions: shift
    0.5 pitch)``."""
    head = {
        "holds": "verified by FE",
        "not checked": "verified by FE where it has a twin (the rest not checked)",
        "not converged": "NOT verified by FE (a series did not converge)",
        "fails": "NOT verified by FE",
    }[v.verdict]
    series = " / ".join(map(str, v.meshes))
    parts = []
    for r in v.rows:
        op = ">=" if r.sense == "min" else "<="
        if r.fe is None:
            parts.append(f"{r.name}: {r.note or 'no FE value'}")
            continue
        verdict = {"holds": "", "fails": " (does not hold)"}.get(r.verdict, f" ({r.verdict})")
        where = (
            f" (worst of {len(r.by_shift)} coupon positions: shift {r.shift:g} pitch)"
            if r.shift is not None
            else ""
        )
        parts.append(
            f"{r.name} in {r.test or 'its test'}: FE {r.fe:.5g} {op} {r.bound:.5g} {r.unit}"
            f"{verdict}{where}".rstrip()
        )
    if not parts:
        parts.append("no behavioural constraint to check")
    return (
        f"{head} (CalculiX; mesh series {series} elements per facet, extrapolated): "
        + "; ".join(parts)
    )


def spec_reports(
    reports: Iterable[ConstraintReport], spec: Problem, names: Iterable[str]
) -> tuple[ConstraintReport, ...]:
    """A solution's constraint ``reports`` with the spec's bound again for each name in
    ``names`` (solved under a corrected bound), their ``margin`` against it (negative where the
    model value is below it); the others as they are. A deflection report's bounds are
    deflections (mm): the spec's is load / (its P / delta bound)."""
    wanted = set(names)
    by_name = {c.name: c for c in spec.constraints}
    out = []
    for r in reports:
        con = by_name.get(r.name)
        if con is not None and con.name in wanted:
            bound = con.bound if con.load is None else con.load / con.bound
            margin = r.value - bound if r.sense == "min" else bound - r.value
            r = replace(r, bound=bound, margin=margin)
        out.append(r)
    return tuple(out)


def _attempt_json(a: Attempt[Any], spec_bounds: dict[str, float]) -> dict[str, Any]:
    """The attempt ``a`` as ``refine.attempts[]`` of the answer's JSON."""
    sol = a.solution
    v = a.verification
    return {
        "status": sol.status,
        "certified": sol.certified,
        "mass_g": sol.mass,
        "objective": None if math.isnan(sol.objective) else sol.objective,
        "layers": [
            {
                "material": lay.material.id,
                "t_mm": lay.t,
                "W_mm": lay.W,
                "n": lay.n,
                "alpha_deg": lay.alpha_deg,
            }
            for lay in a.layers
        ],
        "model_bounds": {k: {"spec": spec_bounds[k], "model": b} for k, b in a.bounds.items()},
        "fe_holds": None if v is None else v.holds,
        "fe_verdict": None if v is None else v.verdict,
        "fe": None if v is None else {r.name: r.as_json()["fe"] for r in v.rows},
    }


def answer_payload(refined: Refined[Any], spec: Problem) -> dict[str, Any]:
    """The JSON object of ``design --verify fe --refine``: the chosen attempt's payload (its
    ``certificate``: certified under the model, for the corrected bounds), with each corrected
    constraint's ``bound`` the spec's again and its ``model_bound`` the one solved under (margin
    against the spec's bound), ``verification`` (the FE table and statement of that design) and
    ``refine`` (every attempt, the number of re-solves, the cap, why the loop stopped)."""
    a = refined.answer
    sol = a.solution
    out = dict(a.run.payload)
    spec_bounds = refined.attempts[0].bounds
    corrected = {k: b for k, b in a.bounds.items() if not math.isclose(b, spec_bounds[k])}
    if corrected:
        # a corrected report's model_bound: the bound it was solved under
        out["constraints"] = [
            r.as_dict() if r is solved else {**r.as_dict(), "model_bound": solved.bound}
            for r, solved in zip(
                spec_reports(sol.constraints, spec, corrected), sol.constraints, strict=True
            )
        ]
        out["certificate"] = (
            sol.certificate
            + "; for the model bounds corrected by FE: "
            + ", ".join(f"{k} {spec_bounds[k]:.5g} -> {b:.5g}" for k, b in corrected.items())
        )
    v = a.verification
    if v is not None:
        out["verification"] = {"method": "fe", **v.as_json(), "statement": statement(v)}
    out["refine"] = {
        "resolves": refined.resolves,
        "cap": MAX_RESOLVES,
        "loosen_above": LOOSEN_ABOVE,
        "stopped": refined.stopped,
        "chosen": refined.chosen,
        "verified": refined.chosen is not None,
        "attempts": [_attempt_json(t, spec_bounds) for t in refined.attempts],
    }
    return out


def _verdict(v: Verification) -> str:
    """One line: each row's FE estimate against its bound."""
    parts = [
        f"{r.name} FE {'-' if r.fe is None else f'{r.fe:.5g}'} "
        f"{'>=' if r.sense == 'min' else '<='} {r.bound:.5g}"
        + ("" if r.shift is None else f" (worst shift {r.shift:g})")
        for r in v.rows
    ]
    head = {"holds": "holds in FE", "fails": "does not hold in FE"}.get(v.verdict, v.verdict)
    return f"{head}: " + "; ".join(parts)
