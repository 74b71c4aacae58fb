"""The one run of a design request (:func:`run`): solve, verify and refine in FE, write the files,
for ``corrugate design`` (:mod:`corrugate.cli.design`), the web app's design route and its job
(:mod:`corrugate.web.app`, inside a worker process) and the notebook's :func:`corrugate.design`.

The steps, in order: the certified answer of the spec within the request's budget
(:func:`~corrugate.workflow.solve.solve_spec`); with ``fe``, its FE verification and, with
``refine``, the correction loop (:func:`~corrugate.workflow.fe.check_fe`, docs/fea.md section 6);
with ``output``, every file of the answer written as one set
(:func:`~corrugate.workflow.files.prepare_design`: the sheet plan first, then, once the answer
is told to :attr:`Events.answered`, the files) and, after an FE check, ``verify.json``. The
errors of the files step are renamed here, once, to the boundary's names
(:class:`~corrugate.workflow.request.Names`).
"""

from __future__ import annotations

import math
from collections.abc import Callable, Iterator
from contextlib import contextmanager
from dataclasses import dataclass, field, replace
from pathlib import Path
from typing import TYPE_CHECKING, Any

from corrugate.workflow.files import prepare_design
from corrugate.workflow.solve import DesignRun, solve_spec

if TYPE_CHECKING:
    from corrugate.analysis.evaluate import Analysis
    from corrugate.solver.robust import RobustResult
    from corrugate.solver.solve import Solution
    from corrugate.workflow.fe import FeCheck
    from corrugate.workflow.request import DesignRequest, Names

__all__ = ["Events", "Run", "json_safe", "output_errors", "run"]


def _nothing() -> None:
    pass


def _no_line(line: str) -> None:
    pass


def _no_lines() -> Callable[[str], None]:
    return _no_line


def _no_check(analysis: Analysis) -> None:
    pass


def _no_answer(answer: Run) -> None:
    pass


@dataclass(frozen=True)
class Events:
    """What a boundary hears of a run: ``fe_progress``, called when the FE step starts, makes
    what hears its lines (the command line's ``CalculiX run N (s): ...``, seconds from then);
    ``solved``, called once the search is over (the web job's last search event); ``writing``,
    called with the answer's analysis before its files are written (a hook for a boundary's own
    check of the part before its files; none uses it today: the web app answers first and makes
    the files on demand, docs/web.md); ``answered``, called once with the answer (the solution,
    its FE check; no files yet) as soon as it is final, before its files are written (their
    sheet plan made and checked first, so a part too large for the machine is still an error
    before it), so that ``corrugate design`` prints the answer before the slow files (issue
    39)."""

    fe_progress: Callable[[], Callable[[str], None]] = _no_lines
    solved: Callable[[], None] = _nothing
    writing: Callable[[Analysis], None] = _no_check
    answered: Callable[[Run], None] = _no_answer


@dataclass(frozen=True)
class Run:
    """A request's answer: the ``design`` run (solution, ``design --json``'s object, the robust
    search), its FE check (``fe``; None without ``--verify fe`` or without a certified design)
    and the ``files`` written (none without an output folder)."""

    design: DesignRun
    fe: FeCheck | None = None
    files: tuple[Path, ...] = field(default=())

    @property
    def solution(self) -> Solution:
        return self.design.solution

    @property
    def payload(self) -> dict[str, Any]:
        return self.design.payload

    @property
    def robust(self) -> RobustResult | None:
        return self.design.robust


def json_safe(obj: Any) -> Any:
    """``obj`` with every non-finite float replaced by None (JSON has no NaN or infinity)."""
    if isinstance(obj, float):
        return obj if math.isfinite(obj) else None
    if isinstance(obj, dict):
        return {k: json_safe(v) for k, v in obj.items()}
    if isinstance(obj, list | tuple):
        return [json_safe(v) for v in obj]
    return obj


@contextmanager
def output_errors(names: Names, machine: str) -> Iterator[None]:
    """The files step's errors about the output options, named as the boundary ``names`` them
    (``machine``: the machine's name, shown as the value of a part too large for it)."""
    from corrugate.fabrication.linestyle import PerforationError
    from corrugate.fabrication.sheets import PartTooLargeError

    try:
        yield
    except PartTooLargeError as exc:
        if names.machine is None:
            raise
        raise exc.renamed(
            names.machine, repr(machine), f"is too small for {exc.field} ({exc.value})"
        ) from None
    except PerforationError as exc:
        name = names.cut if exc.field.endswith("cut") else names.gap
        if name is None:
            raise
        raise exc.renamed(name) from None


def run(request: DesignRequest, events: Events | None = None) -> Run:
    """Run ``request`` (module docstring): its answer, FE check and files."""
    ev = events or Events()
    design = solve_spec(request.spec, request.problem, budget=request.budget)
    ev.solved()
    checked: FeCheck | None = None
    sol = design.solution
    if request.fe is not None and (sol.certified or sol.extrapolated) and sol.assembly is not None:
        from corrugate.workflow.fe import check_fe  # the FE step only with --verify fe

        progress = ev.fe_progress()
        checked = check_fe(
            design, request.spec, request.problem, request.fe, request.budget, progress
        )
        design = checked.run
    if request.strict_json:
        design = replace(design, payload=json_safe(design.payload))
    out = request.output
    analysis = design.solution.analysis
    if out is None or (analysis is None and not out.record_infeasible):
        answer = Run(design, checked)
        ev.answered(answer)
        return answer
    if analysis is not None:
        ev.writing(analysis)
    with output_errors(request.names, request.machine.name):
        write = prepare_design(design, out.folder, out.options, request.text)
    ev.answered(Run(design, checked))
    with output_errors(request.names, request.machine.name):
        files = write()
    if checked is not None:
        from corrugate.workflow.fe import write_verify

        files.append(write_verify(out.folder, checked))
    return Run(design, checked, tuple(files))
