"""The ``corrugate`` command line (typer + rich): a registry of commands.

Each command lives in a module of this package and is listed in its ``COMMANDS`` table (command
name -> function); :data:`COMMANDS` names the module of each command, so that a run imports the
one module of the command it runs (:func:`_app_for`); :data:`app`, the group with every command
(the group's help, an unknown name's error), and :data:`COMMAND_MODULES` are built on first use.
A command module imports only typer, rich and the option declarations at module level; the
modules that do the work (the solver, the writers, the FE and web subpackages) are imported
inside the command function, so one command never loads another's dependencies.

Every failure the user can cause prints one line ``corrugate: error: ...`` naming the parameter, its
value and the allowed range, and exits with code 2; nothing is written on failure.

Entry points: the console script ``corrugate`` and ``python -m corrugate`` both call :func:`main`.
"""

from __future__ import annotations

import atexit
import gc
import importlib
import sys
from collections.abc import Callable
from functools import cache
from types import ModuleType
from typing import TYPE_CHECKING, Annotated, Any, Literal

import typer

from corrugate import __version__
from corrugate.core.errors import CorrugateError, describe

__all__ = ["COMMANDS", "COMMAND_MODULES", "EXIT_CODES", "GC_THRESHOLDS", "app", "main"]

#: Each command's module in this package (command name -> module name), in the order
#: ``corrugate --help`` lists them: a run imports only its command's module (importing all eight
#: cost about 8 ms of CPU per run, issue 39); tests/cli/test_app.py checks this table against
#: the modules' own ``COMMANDS``.
COMMANDS: dict[str, str] = {
    "analyze": "analyze",
    "materials": "analyze",
    "design": "design",
    "pareto": "design",
    "tolerance": "design",
    "pattern": "pattern",
    "validate": "validate",
    "verify": "verify",
    "calibrate": "calibrate",
    "serve": "serve",
    "spec": "spec",
    "init": "spec",
    "docs": "spec",
}


if TYPE_CHECKING:  # built on first use by the module's __getattr__
    app: typer.Typer
    COMMAND_MODULES: tuple[ModuleType, ...]


def _module(name: str) -> ModuleType:
    """The command module ``corrugate.cli.<name>``, imported on first use."""
    return importlib.import_module(f"{__name__}.{name}")


@cache
def _command_modules() -> tuple[ModuleType, ...]:
    return tuple(_module(name) for name in dict.fromkeys(COMMANDS.values()))


def _help_markup() -> Literal["rich"] | None:
    """Rich help boxes on a terminal; click's plain, unwrapped-by-rich text when piped or captured.

    Plain help also skips importing rich's markdown renderer (about 0.2 s of CPU per call,
    ``benchmarks/pipeline.py``).
    """
    try:
        return "rich" if sys.stdout.isatty() else None
    except (AttributeError, ValueError):  # a replaced or closed stdout
        return None


#: Plain help (piped) is laid out for 120 columns, as the commands' tables are, so that the
#: command list keeps each summary's first sentence whole instead of cutting it at 80 columns.
_PLAIN_HELP_WIDTH = {"terminal_width": 120, "max_content_width": 120}


#: The exit codes, shown under ``corrugate --help``.
EXIT_CODES = (
    "Exit codes: 0 an answer; 1 no design meets the spec (infeasible, with the diagnosis) or an "
    "FE run failed, or (verify, design --verify fe) a constraint does not hold in FE; 2 bad input (one line naming "
    "the field, the value and what is allowed); 3 a bug (one line; please report it); 4 not "
    "certified within the work budget (design, pareto and tolerance --budget, default 60 s of "
    "CPU time: one line with the best design found so far and "
    "the proven gap); 5 (verify, design --verify fe) no constraint fails in FE but one is not "
    "converged (its mesh series not shown asymptotic up to --max-mesh); 6 (verify, design "
    "--verify fe) every constraint with an FE twin holds, one has none (not checked); 130 "
    "interrupted (Ctrl-C: one line; an --out folder "
    "keeps its earlier set or has the new one whole)."
)

#: The line printed when Ctrl-C stops a command (exit code 130, the shell's code for SIGINT).
INTERRUPTED = (
    "corrugate: interrupted (Ctrl-C), nothing more computed; an --out folder keeps its earlier "
    "set or has the new one whole, never a mix"
)

_MARKUP = _help_markup()


def _new_app() -> typer.Typer:
    """The ``corrugate`` group, its root option (``--version``) registered, no command yet."""
    group = typer.Typer(
        name="corrugate",
        rich_markup_mode=_MARKUP,
        help="Design orthogonally assembled double-layered corrugated (OADLC) stiffening panels.",
        no_args_is_help=True,
        add_completion=True,
        pretty_exceptions_enable=False,
        epilog=EXIT_CODES,
        context_settings=_PLAIN_HELP_WIDTH if _MARKUP is None else {},
    )
    group.callback()(_root)
    return group


def _version(value: bool) -> None:
    if value:
        typer.echo(f"corrugate {__version__}")
        raise typer.Exit()


def _root(
    version: Annotated[
        bool,
        typer.Option("--version", callback=_version, is_eager=True, help="Print the version."),
    ] = False,
) -> None:
    """corrugate: the lightest OADLC panel that provably meets a spec."""


def _register(target: typer.Typer, modules: tuple[ModuleType, ...]) -> None:
    for module in modules:
        commands: dict[str, Callable[..., Any] | typer.Typer] = module.COMMANDS
        for name, function in commands.items():
            _add(target, name, function)


def _add(target: typer.Typer, name: str, function: Callable[..., Any] | typer.Typer) -> None:
    """Register one entry of a ``COMMANDS`` table: a command, or a group of them (a Typer)."""
    if isinstance(function, typer.Typer):
        target.add_typer(function, name=name)
    else:
        target.command(name)(function)


@cache
def _whole_app() -> typer.Typer:
    """The group with every command registered (built once, on first use)."""
    group = _new_app()
    _register(group, _command_modules())
    return group


def __getattr__(name: str) -> object:
    """:data:`app` (the group with every command) and :data:`COMMAND_MODULES` (the command
    modules, in the order of :data:`COMMANDS`), built on first use (PEP 562)."""
    if name == "app":
        return _whole_app()
    if name == "COMMAND_MODULES":
        return _command_modules()
    raise AttributeError(f"module {__name__!r} has no attribute {name!r}")


def _app_for(args: list[str]) -> typer.Typer:
    """The app that runs ``args``: when the first names a command, the group holding that
    command alone, from its own module only (typer builds the click parameters of every command
    it holds, from the function signatures, on each run: 0.04 s of CPU for the twelve, 0.006 s
    for one; issue 24), else :data:`app` (the group's help, ``--version``, an unknown name's
    error)."""
    where = COMMANDS.get(args[0]) if args else None
    if where is None:
        return _whole_app()
    one = _new_app()
    _add(one, args[0], _module(where).COMMANDS[args[0]])
    return one


#: The cyclic garbage collector's thresholds in a command's process (:func:`gc.set_threshold`):
#: the youngest generation is collected once 500 000 objects it tracks were made (net of those
#: freed), not 700. Python's default makes a ``design --out`` run collect 350 times, 3 of them
#: full passes over the objects the libraries keep alive for the whole run, 0.25 s of CPU
#: freeing almost nothing; at 100 000 (issue 24) 2 young collections were left, 0.06 s freeing
#: about 10 000 objects (``gc.callbacks`` timing; 0.060-0.069 s on the case study,
#: wheel_circle, chassis_plate, rectangle_independent and blimp_gripper_robust); at 500 000 none
#: (those runs end with about 250 000 objects tracked; on the case study 1.205 s of CPU against
#: 1.269 s and a peak RSS of 136.3 MB against 134.3 MB, medians of 9 interleaved runs; issue
#: 39). Cycles are still collected; the memory they hold until then is some MB.
GC_THRESHOLDS = (500_000, 20, 100)


def _freeze_at_exit() -> None:
    """At the process's exit (an :mod:`atexit` hook, after the command has written and flushed
    everything): move every object the collector tracks to its permanent generation
    (:func:`gc.freeze`), so that the interpreter's finalization does not run the cyclic collector
    over the million objects the libraries keep alive. The objects are freed with the process, as
    before; no file of ours is open by then (each output set is committed and closed). On the
    case study's ``design --out`` the finalization took about 0.3 s of CPU (issue 24,
    ``benchmarks/pipeline.py``)."""
    gc.freeze()


def main(argv: list[str] | None = None) -> None:
    """Console entry point: runs the app, turning every user error into one line and exit code 2.

    Usage errors found by the option parser (unknown option, missing value) also exit with 2;
    Ctrl-C (SIGINT) prints :data:`INTERRUPTED` and exits with 130; a reader that closes the
    pipe early leaves the command to finish quietly (:mod:`corrugate.cli.closed_pipe`). The
    process collects its garbage cycles less often (:data:`GC_THRESHOLDS`) and not at all at its exit
    (:func:`_freeze_at_exit`), imports matplotlib, when a command draws, without the help
    text of its artists' ``set`` methods (:func:`corrugate.core.plotting.lean_import`),
    numpy with one BLAS thread (:func:`corrugate.core.blas.one_blas_thread`) and pydantic
    without its plugins (:func:`corrugate.core.plugins.without_pydantic_plugins`).
    """
    from corrugate.cli.closed_pipe import pipe_safe_stdout
    from corrugate.core.blas import one_blas_thread
    from corrugate.core.plotting import lean_import
    from corrugate.core.plugins import without_pydantic_plugins

    pipe_safe_stdout()
    one_blas_thread()
    without_pydantic_plugins()
    lean_import()
    gc.set_threshold(*GC_THRESHOLDS)
    atexit.unregister(_freeze_at_exit)  # once, however often main runs in one process
    atexit.register(_freeze_at_exit)
    args = sys.argv[1:] if argv is None else argv
    try:
        _app_for(args)(args=args)
    except SystemExit as exc:
        if exc.code == 130:  # typer's exit for KeyboardInterrupt (SIGINT), silent by itself
            print(INTERRUPTED, file=sys.stderr)
        raise
    except KeyboardInterrupt:  # raised outside typer's own handling
        print(INTERRUPTED, file=sys.stderr)
        sys.exit(130)
    except (CorrugateError, OSError, RecursionError, MemoryError) as exc:
        print(f"corrugate: error: {describe(exc)}", file=sys.stderr)
        sys.exit(2)
    except Exception as exc:  # a bug: still one line, never a traceback
        print(f"corrugate: {describe(exc)}", file=sys.stderr)
        sys.exit(3)
