"""The FE step of a design request (``design --verify fe [--refine]``, docs/fea.md section 6):
the answer's design verified by the FE twin of every behavioural bound
(:func:`corrugate.fea.verify.verify_design`) and, with ``refine``, the correction loop of
:func:`corrugate.fea.refine.refine` (every re-solve within the request's budget), and the
``verify.json`` it leaves beside the design's files. The FE package is imported when a request
asks for it.
"""

from __future__ import annotations

import json
from collections.abc import Callable
from dataclasses import dataclass
from pathlib import Path
from typing import TYPE_CHECKING

from corrugate.workflow.solve import DesignRun, solve_spec

if TYPE_CHECKING:
    from corrugate.fea.refine import Refined
    from corrugate.fea.verify import Verification
    from corrugate.solver.problem import Problem
    from corrugate.solver.solve import ConstraintReport, Solution
    from corrugate.spec.schema import Spec
    from corrugate.workflow.request import FeOptions

__all__ = ["FeCheck", "check_fe", "write_verify"]


@dataclass(frozen=True)
class FeCheck:
    """The answer after ``--verify fe`` (``run``, with ``verification`` and, with ``--refine``,
    ``refine`` in its payload), the verification of its design and the loop (None without
    ``--refine``)."""

    run: DesignRun
    verification: Verification
    refined: Refined[DesignRun] | None

    @property
    def holds(self) -> bool:
        """Whether every behavioural bound holds in FE at the answer's design."""
        return self.verification.holds

    @property
    def statement(self) -> str:
        """The FE statement of the answer's design (:func:`corrugate.fea.refine.statement`)."""
        from corrugate.fea.refine import statement

        return statement(self.verification)


def check_fe(
    run: DesignRun,
    spec: Spec,
    problem: Problem,
    fe: FeOptions,
    budget: float | None,
    progress: Callable[[str], None],
) -> FeCheck:
    """Verify the answer's design of ``run`` in FE and, with ``fe.refine``, run the correction
    loop (:func:`corrugate.fea.refine.refine`): each re-solve is :func:`solve_spec` of ``spec``
    under the corrected bounds within ``budget`` CPU seconds; the answer is the loop's chosen
    attempt's run."""
    from corrugate.fea.refine import answer_payload, refine, statement
    from corrugate.fea.verify import verify_design

    def verify(sol: Solution, reports: tuple[ConstraintReport, ...]) -> Verification:
        assert sol.assembly is not None
        return verify_design(
            sol.assembly,
            reports,
            problem.joint,
            fe.meshes,
            shifts=fe.shifts,
            progress=progress,
            max_mesh=fe.max_mesh,
        )

    if not fe.refine:
        v = verify(run.solution, run.solution.constraints)
        payload = {
            **run.payload,
            "verification": {"method": "fe", **v.as_json(), "statement": statement(v)},
        }
        return FeCheck(DesignRun(run.solution, payload, run.robust), v, None)

    def solve(p: Problem) -> DesignRun:
        return solve_spec(spec, p, budget=budget)

    refined = refine(problem, solve, verify, progress=progress, first=run)
    answer = refined.answer
    assert answer.verification is not None
    payload = answer_payload(refined, problem)
    chosen = answer.run
    return FeCheck(DesignRun(chosen.solution, payload, chosen.robust), answer.verification, refined)


def write_verify(out: Path, checked: FeCheck) -> Path:
    """``out/verify.json`` (the set ``corrugate verify`` writes) of the answer's design, named by
    the SHA-256 of the design.json just committed there (the design set's manifest entry) and
    committed as a set that requires it (:mod:`corrugate.core.fileio`): refused
    (:class:`~corrugate.core.errors.StaleSetError`) if another design was written there since."""
    from corrugate.core.errors import StaleSetError
    from corrugate.core.fileio import read_manifest, write_set
    from corrugate.export.record import RECORD_NAME, VERIFY_KIND, VERIFY_NAME, design_label

    sol = checked.run.solution
    assert sol.assembly is not None
    listed = read_manifest(out).get("design", {}).get("files", {})
    digest = listed.get(RECORD_NAME) if isinstance(listed, dict) else None
    if not isinstance(digest, str):
        raise StaleSetError("--out", str(out), RECORD_NAME)
    data = {
        "design": design_label(sol.assembly),
        "design_sha256": digest,
        **checked.verification.as_json(),
    }
    text = json.dumps(data, indent=2, allow_nan=False)
    write_set(
        out,
        {VERIFY_NAME: text + "\n"},
        field="--out",
        kind=VERIFY_KIND,
        requires={RECORD_NAME: digest},
    )
    return out / VERIFY_NAME
