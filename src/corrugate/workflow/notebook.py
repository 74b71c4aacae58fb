"""The two calls of a notebook (the Python boundary of a design request)::

    import corrugate
    result = corrugate.design("examples/blimp_gripper.toml")   # a path, a dict or TOML text
    result                                                      # five lines; HTML in Jupyter
    corrugate.write_files(result, "out/gripper", cutter="maker-12x12")

:func:`design` reads its spec into a :class:`~corrugate.workflow.request.DesignRequest` and runs
it (:func:`corrugate.workflow.steps.run`), as ``corrugate design --json`` does; :func:`write_files`
writes the answer's files as ``corrugate design --out`` does.
"""

from __future__ import annotations

import json
from collections.abc import Mapping
from dataclasses import dataclass
from pathlib import Path
from typing import TYPE_CHECKING, Any

from corrugate.core.errors import InputError
from corrugate.names import DEFAULT_FOLD_STYLE, DEFAULT_PAPER
from corrugate.workflow.files import made_for, output_options, write_design
from corrugate.workflow.request import DesignRequest, resolve_machine
from corrugate.workflow.steps import run

if TYPE_CHECKING:
    from corrugate.solver.solve import Solution
    from corrugate.spec.schema import Spec
    from corrugate.workflow.solve import DesignRun

__all__ = ["DesignResult", "design", "write_files"]


@dataclass(frozen=True)
class DesignResult:
    """The answer to a spec: the certified ``solution`` (:class:`~corrugate.solver.Solution`), the
    JSON object of ``corrugate design --json`` (``payload``), the ``spec`` and its ``text``."""

    run: DesignRun
    spec: Spec
    text: str

    @property
    def solution(self) -> Solution:
        return self.run.solution

    @property
    def payload(self) -> dict[str, Any]:
        return self.run.payload

    def __repr__(self) -> str:
        """Five lines at most: the solution's (:func:`corrugate.solver.display.solution_repr`)."""
        from corrugate.solver.display import solution_repr

        return solution_repr(self.run.solution)

    def _repr_html_(self) -> str:
        from corrugate.solver.display import solution_html

        return solution_html(self.run.solution)


def _read(spec: str | Path | Mapping[str, Any]) -> tuple[Spec, str]:
    from corrugate.spec.schema import load_spec_text, parse_spec, parse_spec_text

    if isinstance(spec, Mapping):
        return parse_spec(spec), json.dumps(spec, indent=2, default=str)
    if isinstance(spec, Path) or ("\n" not in spec and spec.strip().endswith(".toml")):
        return load_spec_text(spec)
    return parse_spec_text(spec), spec


def design(spec: str | Path | Mapping[str, Any], *, budget: float | None = None) -> DesignResult:
    """The certified lightest design that meets ``spec``: a path to a TOML file, the TOML text
    itself, or a dict with the keys of the file (docs/spec.md), within ``budget`` CPU seconds
    (None: the default 60 s; see :func:`~corrugate.workflow.solve.solve_spec`). Bad input raises
    a :class:`~corrugate.core.errors.InputError` naming the key."""
    from corrugate.solver.problem import Problem

    if not isinstance(spec, str | Path | Mapping):
        raise InputError("spec", type(spec).__name__, "a path, TOML text or a dict")
    parsed, text = _read(spec)
    made = made_for(parsed)
    request = DesignRequest(
        made.spec, text, Problem.from_spec(made.spec), resolve_machine(made.cutter), budget
    )
    return DesignResult(run(request).design, parsed, text)


def write_files(
    result: DesignResult,
    out: str | Path,
    *,
    cutter: str | None = None,
    fold_style: str = DEFAULT_FOLD_STYLE,
    cut: str | float | None = None,
    gap: str | float | None = None,
    labels: bool | None = None,
    paper: str = DEFAULT_PAPER,
    mountain: str | None = None,
    valley: str | None = None,
    marks: str | None = None,
) -> list[Path]:
    """Every file of ``result`` into the folder ``out`` (as ``corrugate design --out``: cut files
    for ``cutter``, fold map, FOLD, GLB/STL, assembly steps, report, ``design.json``), committed as
    one set; returns the paths. ``cutter``, ``mountain``, ``valley`` and ``marks`` default to the
    spec's ``[fabrication]`` (the machine the design was solved for,
    :func:`~corrugate.workflow.files.made_for`), as on the command line; a ``cutter`` given here is
    checked but the design is not re-solved for it (its parts may not fit: then an error naming
    the part). Other options as the command line's (lengths in mm or with units)."""
    made = made_for(result.spec, mountain=mountain, valley=valley, marks=marks)
    options = output_options(
        made.cutter if cutter is None else cutter,
        fold_style,
        cut,
        gap,
        labels=labels,
        paper=paper,
        mountain=made.mountain,
        valley=made.valley,
        marks=made.marks,
    )
    return write_design(result.run, out, options, result.text)
