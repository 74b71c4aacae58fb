"""Flat patterns: the parts of a design to cut, their creases, and the folded geometry.

The names below live in :mod:`corrugate.fabrication.model`, imported when one is first used
(PEP 562): importing a submodule (the machines' palette, on every ``corrugate design``) does not
build the pattern's classes, which only a command that writes files uses (issue 39).
"""

from importlib import import_module as _import_module
from typing import TYPE_CHECKING as _TYPE_CHECKING
from typing import Any as _Any

if _TYPE_CHECKING:
    from corrugate.fabrication.model import Line, Part, Pattern, Role, polygon_area

__all__ = ["Line", "Part", "Pattern", "Role", "polygon_area"]


def __getattr__(name: str) -> _Any:
    if name not in __all__:
        raise AttributeError(f"module {__name__!r} has no attribute {name!r}")
    value = getattr(_import_module(".model", __name__), name)
    globals()[name] = value
    return value


def __dir__() -> list[str]:
    """The module's names, the public API (:data:`__all__`) included before its first use."""
    return sorted({*globals(), *__all__})
