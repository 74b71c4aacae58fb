"""The command-line options that describe a design and its files, made from the one table of
parameters (:data:`corrugate.core.parameters.PARAMETERS`: flags, metavar, help text, default),
for every command that takes them (``analyze``, ``pattern``, ``validate``, ``design``).

:func:`table_options` is the one declaration: a command names the table's parameters it takes
(in the order ``--help`` lists them, its own options among them) and gets their values as one
:class:`TableValues` argument; typer reads the options it declares from the table (type,
default, flags, metavar, help text, shell completion).
:func:`corrugate.spec.inputs.assembly_from_namespace` turns the values into an
:class:`~corrugate.geometry.layer.Assembly`. :func:`option` is one entry's typer option.
"""

from __future__ import annotations

import inspect
from collections.abc import Callable, Iterator, Mapping
from dataclasses import dataclass
from typing import Annotated, Any

import typer

from corrugate.core.limits import MAX_INT_DIGITS
from corrugate.core.parameters import (
    DESIGN_PARAMETERS,
    LOAD_CASE_PARAMETERS,
    OUTPUT_PARAMETERS,
    PARAMETERS,
)
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
    "ASCII_FLOAT",
    "ASCII_INT",
    "DESIGN",
    "LENGTH",
    "LOAD_CASE",
    "OUTPUT",
    "Quiet",
    "SolverBudget",
    "TableValues",
    "option",
    "table_options",
]

Opt = typer.Option


def _ascii(number: type[int] | type[float]) -> Callable[[Any], Any]:
    """A typer ``parser`` reading an int or a float written in the digits 0-9 only: click's
    INT and FLOAT call ``int`` and ``float``, which read full-width and other scripts' digits
    (``int("８")`` is 8); those are refused as an invalid value of the option (exit 2), as the
    table's options and the spec refuse them (:func:`corrugate.core.text.foreign_digits`). A
    value that is no number is shown cut short (an integer of 5000 digits, beyond ``int()``,
    by its first 60 and its length), without control characters."""

    def parse(value: Any) -> Any:
        if isinstance(value, int | float) and not isinstance(value, bool):
            return number(value)
        from corrugate.core.text import clipped, foreign_digits, printable

        text = str(value)
        shown = clipped(printable(text))  # click would echo a ValueError's value whole
        if foreign_digits(text):
            raise typer.BadParameter(f"{shown!r} has digits other than 0-9: write it in 0-9")
        try:
            return number(text)
        except ValueError:
            digits = text.strip().lstrip("+-")
            if digits.isascii() and digits.isdigit():  # more than 4300 digits: beyond int()
                raise typer.BadParameter(
                    f"an integer of {len(digits)} digits is too long: at most {MAX_INT_DIGITS}"
                ) from None
            what = "an integer" if number is int else "a number"
            raise typer.BadParameter(f"{shown} is not {what} written in 0-9") from None

    parse.__name__ = number.__name__  # what --help shows: <int>, <float>
    return parse


#: The typer ``parser`` of an int and a float option (:func:`_ascii`).
ASCII_INT = _ascii(int)
ASCII_FLOAT = _ascii(float)


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
        parser=ASCII_FLOAT,
        metavar="SECONDS",
        help="Work budget: CPU seconds for the whole solve, explanation included (default 60; "
        "0.01 to 86400). When it runs out: the best design found so far, not certified, and "
        "exit code 4.",
    ),
]

#: Metavars shown in ``--help`` for options read as a quantity with an optional unit.
LENGTH = "LENGTH"  # '8', '8mm', '0.3 in'
ANGLE = "ANGLE"  # '84', '84deg', '1.47 rad'


#: The names of the table's design, output and load-case parameters, in the table's order.
DESIGN = tuple(p.name for p in DESIGN_PARAMETERS)
OUTPUT = tuple(p.name for p in OUTPUT_PARAMETERS)
LOAD_CASE = tuple(p.name for p in LOAD_CASE_PARAMETERS)

#: The name of the parameter of a command that receives its :class:`TableValues`.
TABLE = "table"


@dataclass(frozen=True)
class TableValues(Mapping[str, Any]):
    """The values of a command's options made by :func:`table_options`, by parameter name (the
    strings typed, None for an option not given, a flag's True, False or None)."""

    by_name: Mapping[str, Any]

    def __getitem__(self, name: str) -> Any:
        return self.by_name[name]

    def __iter__(self) -> Iterator[str]:
        return iter(self.by_name)

    def __len__(self) -> int:
        return len(self.by_name)


def _table_parameter(
    name: str, optional: bool, default: Any, overrides: Mapping[str, Any]
) -> inspect.Parameter:
    """The typer parameter of the table's entry ``name``: a flag is ``bool | None`` (None: not
    given); a required entry a required ``str`` unless ``optional``; any other a ``str`` with
    the table's default, or ``str | None`` when it has none (or ``default`` is None)."""
    p = PARAMETERS[name]
    opt = option(name, **overrides)
    if p.kind == "flag":
        kind: Any = bool | None
        value: Any = None
    elif p.required and not optional:
        kind, value = str, inspect.Parameter.empty
    else:
        value = p.default if default is ... else default
        kind = str if value is not None else str | None
    return inspect.Parameter(
        name, inspect.Parameter.KEYWORD_ONLY, default=value, annotation=Annotated[kind, opt]
    )


def table_options(
    *order: str,
    optional: tuple[str, ...] = (),
    defaults: Mapping[str, str | None] | None = None,
    overrides: Mapping[str, Mapping[str, Any]] | None = None,
) -> Callable[[Callable[..., None]], Callable[..., None]]:
    """Give a command the options of the table's parameters named in ``order``: the command's
    parameter ``table`` (a :class:`TableValues`) is replaced, in its signature, by those options,
    in that order; a name in ``order`` that is one of the command's own parameters places that
    parameter there instead (``--help`` lists the options in this order). ``optional``: required
    entries the command may go without (``validate --design``); ``defaults``: another default
    than the table's (``design --machine``: None, the spec's); ``overrides``: keyword arguments
    of :func:`option` for one entry (a command that takes some of its choices only)."""
    chosen = defaults or {}
    changed = overrides or {}

    def decorate(command: Callable[..., None]) -> Callable[..., None]:
        own = inspect.signature(command, eval_str=True).parameters
        table_names = [n for n in order if n not in own]
        unknown = [n for n in table_names if n not in PARAMETERS]
        if unknown or TABLE not in own:
            raise TypeError(f"{command.__name__}: no parameter {TABLE!r}, or unknown {unknown}")
        made = {
            n: _table_parameter(n, n in optional, chosen.get(n, ...), changed.get(n, {}))
            for n in table_names
        }
        params: list[inspect.Parameter] = []
        for name, param in own.items():
            if name == TABLE:
                params += [made[n] if n in made else own[n] for n in order]
            elif name not in order:
                params.append(param)
        # typer reads keyword parameters in signature order: required ones may follow defaults
        params = [q.replace(kind=inspect.Parameter.KEYWORD_ONLY) for q in params]

        def run(**kwargs: Any) -> None:
            table = TableValues({n: kwargs.pop(n) for n in table_names})
            command(**kwargs, **{TABLE: table})

        for attr in ("__module__", "__name__", "__qualname__", "__doc__"):
            setattr(run, attr, getattr(command, attr))
        # typer reads this signature (inspect.signature) and these annotations (get_type_hints)
        run.__signature__ = inspect.Signature(params, return_annotation=None)  # type: ignore[attr-defined]
        run.__annotations__ = {q.name: q.annotation for q in params}
        return run

    return decorate
