"""The two calls of a notebook: :func:`design` a spec, :func:`write_files` of the answer.

``corrugate.design(spec)`` is this module's :func:`design` (the ``corrugate.design`` subpackage,
which holds the solver, is callable for that), ``corrugate.write_files`` is :func:`write_files`::

    import corrugate
    result = corrugate.design("examples/blimp_gripper.toml")   # a path, a dict or TOML text
    result                                                      # five lines; HTML in Jupyter
    corrugate.write_files(result, "out/gripper", cutter="maker-12x12")

Both run the very chain of ``corrugate design`` (:mod:`corrugate.pipeline`).
"""

from __future__ import annotations

import json
from collections.abc import Mapping
from dataclasses import dataclass
from pathlib import Path
from typing import TYPE_CHECKING, Any

from .errors import InputError

if TYPE_CHECKING:
    from .design.run import DesignRun
    from .design.solve import Solution
    from .spec import Spec

__all__ = ["DesignResult", "design", "write_files"]


@dataclass(frozen=True)
class DesignResult:
    """The answer to a spec: the certified ``solution`` (:class:`~corrugate.design.Solution`), the
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
        """Five lines at most: the solution's (:func:`corrugate.display.solution_repr`)."""
        from .display import solution_repr

        return solution_repr(self.run.solution)

    def _repr_html_(self) -> str:
        from .display import solution_html

        return solution_html(self.run.solution)


def _read(spec: str | Path | Mapping[str, Any]) -> tuple[Spec, str]:
    from .spec import load_spec_text, parse_spec, parse_spec_text

    if isinstance(spec, Mapping):
        return parse_spec(spec), json.dumps(spec, indent=2, default=str)
    if isinstance(spec, Path) or ("\n" not in spec and spec.strip().endswith(".toml")):
        return load_spec_text(spec)
    return parse_spec_text(spec), spec


def design(spec: str | Path | Mapping[str, Any]) -> DesignResult:
    """The certified lightest design that meets ``spec``: a path to a TOML file, the TOML text
    itself, or a dict with the keys of the file (docs/spec.md). Bad input raises a
    :class:`~corrugate.errors.InputError` naming the key."""
    from .pipeline import solve_spec

    if not isinstance(spec, str | Path | Mapping):
        raise InputError("spec", type(spec).__name__, "a path, TOML text or a dict")
    parsed, text = _read(spec)
    return DesignResult(solve_spec(parsed), parsed, text)


def write_files(
    result: DesignResult,
    out: str | Path,
    *,
    cutter: str = "cameo4-12x12",
    fold_style: str = "solid",
    cut: str | float | None = None,
    gap: str | float | None = None,
    labels: bool | None = None,
    paper: str = "mat",
) -> list[Path]:
    """Every file of ``result`` into the folder ``out`` (as ``corrugate design --out``: cut files
    for ``cutter``, fold map, FOLD, GLB/STL, assembly steps, report, ``design.json``), committed as
    one set; returns the paths. Options as the command line's (lengths in mm or with units)."""
    from .pipeline import output_options, write_design

    options = output_options(cutter, fold_style, cut, gap, labels=labels, paper=paper)
    return write_design(result.run, out, options, result.text)
