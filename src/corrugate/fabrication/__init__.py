"""Flat patterns: the parts of a design to cut, their creases, and the folded geometry.

The names below live in :mod:`corrugate.fabrication.model`, imported when one is first used
(PEP 562): importing a submodule (the machines' palette, on every ``corrugate design``) does not
build the pattern's classes, which only a command that writes files uses (issue 39).
"""

from typing import TYPE_CHECKING as _TYPE_CHECKING

from corrugate.core.lazy import lazy_names as _lazy_names

if _TYPE_CHECKING:
    from corrugate.fabrication.model import Line, Part, Pattern, Role, polygon_area

__all__ = ["Line", "Part", "Pattern", "Role", "polygon_area"]


__getattr__ = _lazy_names(__name__, dict.fromkeys(__all__, ".model"), globals())


def __dir__() -> list[str]:
    """The module's names, the public API (:data:`__all__`) included before its first use."""
    return sorted({*globals(), *__all__})
