"""Spec -> answer -> files: one design request, one run, behind ``corrugate design``,
``corrugate pattern``, ``POST /api/design`` (and its job) and the notebook's two calls.

* :mod:`~corrugate.workflow.request`: :class:`DesignRequest`, the typed request each boundary
  reads once (spec, problem, machine profile, budget, output, FE options, its names of the
  options);
* :mod:`~corrugate.workflow.steps`: :func:`run`, the one entry that solves, verifies and refines
  in FE and writes the files of a request, renaming the errors in one place (:class:`Run`);
* :mod:`~corrugate.workflow.solve`: :func:`solve_spec`, the certified answer of a spec (robust
  specs included) and the JSON object ``corrugate design --json`` prints (:class:`DesignRun`);
* :mod:`~corrugate.workflow.fe`: the FE step (``--verify fe``, ``--refine``: :class:`FeCheck`);
* :mod:`~corrugate.workflow.files`: :func:`output_options`, :func:`made_for`,
  :func:`write_design_files` and :func:`write_design`, every file of a design as one set;
* :mod:`~corrugate.workflow.notebook`: :func:`design` and :func:`write_files`.

The heavy modules (the solver, the FE, the writers, the report) are imported when a function
runs, so the command line starts without them.
"""

from typing import TYPE_CHECKING as _TYPE_CHECKING

from corrugate.core.lazy import lazy_names as _lazy_names

if _TYPE_CHECKING:
    from corrugate.workflow.fe import FeCheck
    from corrugate.workflow.files import (
        MadeFor,
        made_for,
        output_options,
        write_design,
        write_design_files,
    )
    from corrugate.workflow.notebook import DesignResult, design, write_files
    from corrugate.workflow.request import (
        DesignRequest,
        FeOptions,
        Names,
        Output,
        resolve_machine,
    )
    from corrugate.workflow.solve import DesignRun, solve_spec
    from corrugate.workflow.steps import Events, Run, json_safe, output_errors, run

#: The module of each public name, imported when the name is first used (PEP 562): the command
#: line's ``from corrugate.workflow import run`` loads the request, the run and the solve, not
#: the FE step nor the notebook's calls (issue 39: ``corrugate design`` never calls them; their
#: own import took 1.2 ms, ``python -X importtime``, least of 7 runs). No public name is also a
#: submodule's name, so the import system's binding of a loaded submodule never hides one.
_WHERE: dict[str, str] = {
    "FeCheck": "fe",
    **dict.fromkeys(
        ("MadeFor", "made_for", "output_options", "write_design", "write_design_files"), "files"
    ),
    **dict.fromkeys(("DesignResult", "design", "write_files"), "notebook"),
    **dict.fromkeys(
        ("DesignRequest", "FeOptions", "Names", "Output", "resolve_machine"), "request"
    ),
    **dict.fromkeys(("DesignRun", "solve_spec"), "solve"),
    **dict.fromkeys(("Events", "Run", "json_safe", "output_errors", "run"), "steps"),
}


__getattr__ = _lazy_names(__name__, {k: f".{v}" for k, v in _WHERE.items()}, globals())


def __dir__() -> list[str]:
    """The module's names, the public API (:data:`__all__`) included before its first use."""
    return sorted({*globals(), *__all__})


__all__ = [
    "DesignRequest",
    "DesignResult",
    "DesignRun",
    "Events",
    "FeCheck",
    "FeOptions",
    "MadeFor",
    "Names",
    "Output",
    "Run",
    "design",
    "json_safe",
    "made_for",
    "output_errors",
    "output_options",
    "resolve_machine",
    "run",
    "solve_spec",
    "write_design",
    "write_design_files",
    "write_files",
]
