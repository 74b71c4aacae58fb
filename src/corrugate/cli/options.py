"""The command-line options that describe a design and its files, made from the one table of
parameters (:data:`corrugate.core.parameters.PARAMETERS`: flags, metavar, help text), for every
command that takes them (``analyze``, ``pattern``, ``validate``, ``design``): typer reads each
``Annotated`` alias below as the option it declares; the commands' signatures give the defaults
(the constants of :mod:`corrugate.names`). :func:`corrugate.spec.inputs.assembly_from_namespace`
turns their values into an :class:`~corrugate.geometry.layer.Assembly`.
"""

from __future__ import annotations

from collections.abc import Callable
from typing import Annotated, Any

import typer

from corrugate.core.parameters import PARAMETERS, choices_metavar
from corrugate.names import FOLD_STYLES as FOLD_STYLE_NAMES
from corrugate.names import (
    LASER_PREFIX,
    LAYOUT_SHAPES,
    LOAD_CASES,
    MACHINE_NAMES,
    MODEL_NAMES,
    SUPPORTS,
)

__all__ = [
    "ANGLE",
    "DEFAULT_MARGIN",
    "DEFAULT_SPACING",
    "DEFAULT_TAB_DEPTH",
    "FOLD_STYLES",
    "LAYOUTS",
    "LENGTH",
    "MODEL_CHOICES",
    "N2",
    "W2",
    "Alpha",
    "Alpha2",
    "Cut",
    "Density",
    "FoldStyle",
    "Gap",
    "Holes",
    "Labels",
    "Layout",
    "LoadOpt",
    "Machine",
    "Margin",
    "Marks",
    "Material",
    "Material2",
    "Model",
    "Mountain",
    "N",
    "Nu",
    "OptionalAlpha",
    "OptionalN",
    "OptionalW",
    "Paper",
    "Quiet",
    "SolverBudget",
    "Spacing",
    "SpanOpt",
    "SupportOpt",
    "TabDepth",
    "TestOpt",
    "Thickness",
    "Thickness2",
    "Valley",
    "Vertices",
    "W",
    "YoungsModulus",
    "option",
]

Opt = typer.Option


def complete_materials(incomplete: str) -> list[str]:
    """Shell completion of a material option: the library's ids."""
    from corrugate.materials.library import library

    return [m for m in library() if m.startswith(incomplete)]


def complete_models(incomplete: str) -> list[str]:
    """Shell completion of ``--model``: the moduli variants."""
    return [m for m in MODEL_NAMES if m.startswith(incomplete)]


def complete_layouts(incomplete: str) -> list[str]:
    """Shell completion of ``--layout``."""
    return [m for m in LAYOUT_SHAPES if m.startswith(incomplete)]


def complete_machines(incomplete: str) -> list[str]:
    """Shell completion of ``--machine``/``--cutter`` (a laser takes its bed: ``laser:WxH``)."""
    return [m for m in (*MACHINE_NAMES, LASER_PREFIX) if m.startswith(incomplete)]


def complete_supports(incomplete: str) -> list[str]:
    """Shell completion of ``--support``."""
    return [m for m in SUPPORTS if m.startswith(incomplete)]


def complete_tests(incomplete: str) -> list[str]:
    """Shell completion of ``--test``: the load cases."""
    return [m for m in LOAD_CASES if m.startswith(incomplete)]


#: The shell completion of the parameters that have one.
_COMPLETION: dict[str, Callable[[str], list[str]]] = {
    "material": complete_materials,
    "material2": complete_materials,
    "layout": complete_layouts,
    "model": complete_models,
    "support": complete_supports,
    "test": complete_tests,
    "cutter": complete_machines,
}


def option(name: str, **overrides: Any) -> Any:
    """The typer option of the parameter ``name`` (:data:`~corrugate.core.parameters.PARAMETERS`):
    its flags, metavar, help text and shell completion; ``overrides`` replace any of those keyword
    arguments of :func:`typer.Option` (a command that takes only some of the choices)."""
    p = PARAMETERS[name]
    kwargs: dict[str, Any] = {
        "metavar": p.metavar,
        "autocompletion": _COMPLETION.get(name),
        "help": p.help,
    }
    if p.kind == "flag":
        kwargs["show_default"] = False  # its default (None) is "not given", said in the help
    return Opt(*p.flags, **(kwargs | overrides))


W = Annotated[str, option("W")]
N = Annotated[str, option("n")]
Alpha = Annotated[str, option("alpha")]
#: ``validate`` takes the design from ``--design`` instead, so W, n and alpha may be left out.
OptionalW = Annotated[str | None, option("W")]
OptionalN = Annotated[str | None, option("n")]
OptionalAlpha = Annotated[str | None, option("alpha")]
Material = Annotated[str | None, option("material")]
Thickness = Annotated[str | None, option("thickness")]
YoungsModulus = Annotated[str | None, option("E")]
Nu = Annotated[str | None, option("nu")]
Density = Annotated[str | None, option("density")]
W2 = Annotated[str | None, option("W2")]
N2 = Annotated[str | None, option("n2")]
Alpha2 = Annotated[str | None, option("alpha2")]
Material2 = Annotated[str | None, option("material2")]
Thickness2 = Annotated[str | None, option("thickness2")]
Layout = Annotated[str, option("layout")]
Vertices = Annotated[str | None, option("vertices")]
Holes = Annotated[str | None, option("holes")]
Model = Annotated[str, option("model")]
SupportOpt = Annotated[str, option("support")]
#: ``analyze``'s load case (docs/load_cases.md).
TestOpt = Annotated[str | None, option("test")]
LoadOpt = Annotated[str | None, option("load")]
SpanOpt = Annotated[str | None, option("span")]

Machine = Annotated[str, option("cutter")]
#: ``design``'s machine: given, it overrides the spec's ``[fabrication] machine``; not given,
#: the spec's or the default.
DesignMachine = Annotated[str | None, option("cutter")]
Labels = Annotated[bool | None, option("labels")]
FoldStyle = Annotated[str, option("fold_style")]
Mountain = Annotated[str | None, option("mountain")]
Valley = Annotated[str | None, option("valley")]
Marks = Annotated[str | None, option("marks")]
Cut = Annotated[str | None, option("cut")]
Gap = Annotated[str | None, option("gap")]
Spacing = Annotated[str, option("spacing")]
Margin = Annotated[str, option("margin")]
TabDepth = Annotated[str, option("tab_depth")]
#: Output option of ``pattern`` and ``design``: the 1:1 tiles of the sheets for office paper.
Paper = Annotated[str, option("paper")]


def _text_default(name: str) -> str:
    """The default of the parameter ``name`` as the command line takes it (a string)."""
    default = PARAMETERS[name].default
    assert default is not None, name
    return default


#: The defaults of the length options as ``--help`` shows them (plain numbers in mm).
DEFAULT_SPACING = _text_default("spacing")
DEFAULT_MARGIN = _text_default("margin")
DEFAULT_TAB_DEPTH = _text_default("tab_depth")

#: ``--quiet`` of the commands that print (design, analyze, pattern, validate, pareto, tolerance).
Quiet = Annotated[
    bool,
    Opt(
        "--quiet",
        "-q",
        help="Print nothing but errors (on stderr); files are still written, --json still "
        "printed, exit codes unchanged.",
    ),
]

#: ``--budget`` of ``design``, ``pareto`` and ``tolerance``: CPU seconds for the whole solve (None: the default).
SolverBudget = Annotated[
    float | None,
    Opt(
        "--budget",
        metavar="SECONDS",
        help="Work budget: CPU seconds for the whole solve, explanation included (default 60; "
        "0.01 to 86400). When it runs out: the best design found so far, not certified, and "
        "exit code 4.",
    ),
]

#: Metavars shown in ``--help`` for options read as a quantity with an optional unit.
LENGTH = "LENGTH"  # '8', '8mm', '0.3 in'
ANGLE = "ANGLE"  # '84', '84deg', '1.47 rad'
LAYOUTS = choices_metavar(LAYOUT_SHAPES)
MODEL_CHOICES = choices_metavar(MODEL_NAMES)
FOLD_STYLES = choices_metavar(FOLD_STYLE_NAMES)
