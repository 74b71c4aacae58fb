"""The one exception hierarchy of corrugate.

Every error the package raises on purpose derives from :class:`CorrugateError`; each specific error
is also the matching built-in (``InputError`` is a ``ValueError``), so callers may catch either.
"""

from __future__ import annotations

from typing import Any

from corrugate.core.text import clipped, printable

__all__ = [
    "SHOWN_NAMES",
    "CorrugateError",
    "InputError",
    "MissingExtraError",
    "OutputError",
    "ResultError",
    "StaleSetError",
    "UnknownNameError",
    "describe",
]


class CorrugateError(Exception):
    """Base class of every error raised by corrugate.

    Every subclass survives pickling as it is (message, class and attributes such as
    :attr:`InputError.field`), whatever its constructor takes: a worker process (the web app's
    design pool, the FE sweep) can raise it and the parent sees the same error.
    """

    def __reduce__(self) -> tuple[Any, ...]:
        return (_restore, (type(self), self.args, dict(self.__dict__)))


def _restore(cls: type[CorrugateError], args: tuple[Any, ...], state: dict[str, Any]) -> Any:
    """The error ``cls`` with ``args`` and attributes ``state``, its constructor not called."""
    exc = cls.__new__(cls)
    exc.args = args
    exc.__dict__.update(state)
    return exc


class InputError(CorrugateError, ValueError):
    """A user-supplied value is invalid.

    The message names the parameter, the value given and what is allowed, in one line, e.g.
    ``alpha = 190 deg is out of range: allowed 0 < alpha < 180 deg``. The field, the value and
    what is allowed (which may list names read from a file: material ids) are shown without
    control characters, and a value longer than 100 characters by its first 60 and its length
    (:mod:`corrugate.core.text`): a name or a 4000-digit number from a file never takes over the
    terminal or the line.
    """

    def __init__(self, field: str, value: Any, allowed: str, *, reason: str = "is out of range"):
        self.field = field
        self.value = value
        self.allowed = allowed
        self.reason = reason
        shown = clipped(printable(str(value)))
        super().__init__(  # the allowed text may list names read from a file (material ids)
            f"{clipped(printable(field), tail=True)} = {shown} {reason}: "
            f"allowed {printable(allowed)}"
        )

    def renamed(self, field: str, value: Any = None, reason: str | None = None) -> InputError:
        """The same error naming ``field`` instead (the caller's name for what the library
        checked under its own), optionally with another ``value`` shown or ``reason``."""
        return InputError(
            field,
            self.value if value is None else value,
            self.allowed,
            reason=self.reason if reason is None else reason,
        )


#: Most names an unknown name's error lists (a materials file may hold thousands of tables).
SHOWN_NAMES = 50


class UnknownNameError(InputError, KeyError):
    """A name (material, model, layout, ...) that is not in its registry; the message lists the
    known names, the first :data:`SHOWN_NAMES` of them and how many more."""

    def __init__(self, field: str, value: str, known: list[str] | tuple[str, ...]):
        names = sorted(known)
        shown = ", ".join(names[:SHOWN_NAMES])
        if len(names) > SHOWN_NAMES:
            shown += f" and {len(names) - SHOWN_NAMES} more"
        super().__init__(field, repr(value), "one of " + shown, reason="is unknown")

    def __str__(self) -> str:  # KeyError would otherwise quote the message
        return str(self.args[0])


class OutputError(CorrugateError, OSError):
    """A file or folder could not be written (the OS said why); nothing was left half-written."""

    def __init__(self, field: str, path: object, reason: str):
        self.field = field
        self.path = path
        self.reason = reason  # the OS's words: what the web app says without the path
        super().__init__(
            f"{printable(field)} = {printable(str(path))} cannot be written ({reason}): "
            "allowed a writable folder"
        )

    def __str__(self) -> str:
        return str(self.args[0])


class StaleSetError(OutputError):
    """A set made of other files of its folder (a verification of ``design.json``) was not
    written because those files changed while it was computed (another design was written
    there): its result is of a design the folder no longer holds."""

    def __init__(self, field: str, path: object, changed: str):
        self.changed = changed
        OutputError.__init__(self, field, path, "")
        self.args = (
            f"{field} = {path!s}: its {changed} changed while this run read it (another design "
            f"was written there); the result of the old {changed} is not written: run again",
        )


class MissingExtraError(CorrugateError, ImportError):
    """Something was asked for that needs an optional extra which is not installed.

    The message names what was asked for, the extra, the modules missing and the command that
    installs them, e.g. ``writing a design's files needs the 'fab' extra (matplotlib is missing): pip
    install 'corrugate[fab]'``.
    """

    def __init__(self, what: str, extra: str, missing: tuple[str, ...] | list[str]):
        self.what = what
        self.extra = extra
        self.missing = tuple(missing)
        verb = "is" if len(self.missing) == 1 else "are"
        super().__init__(
            f"{what} needs the '{extra}' extra ({', '.join(self.missing)} {verb} missing): "
            f"pip install 'corrugate[{extra}]'"
        )

    def __str__(self) -> str:
        return str(self.args[0])


class ResultError(CorrugateError, ArithmeticError):
    """A computed result is not a finite number (never printed). The inputs of the request as a
    whole caused it: ``field`` is ``"body"`` (what the web API names in its 422 answer)."""

    field = "body"


def describe(exc: BaseException) -> str:
    """One line for an error the user's input caused, whatever its type (no traceback).

    Errors of corrugate give their own message; an OS error names the path and the OS's words;
    anything else (a bug) names its type, so that it can be reported.
    """
    if isinstance(exc, CorrugateError):
        return str(exc)
    if isinstance(exc, OSError):
        where = exc.filename if exc.filename is not None else "a file"
        return f"{clipped(printable(str(where)))} cannot be used ({exc.strerror or type(exc).__name__})"
    if isinstance(exc, RecursionError):
        return "the input is nested too deeply"
    if isinstance(exc, MemoryError):
        return "the input needs more memory than is available"
    text = printable(str(exc).splitlines()[0][:200]) if str(exc) else ""
    return f"internal error ({type(exc).__name__}{': ' + text if text else ''})"
