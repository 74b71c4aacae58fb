"""Console output shared by the commands: a rich console and number formatting."""

from __future__ import annotations

from typing import TYPE_CHECKING

if TYPE_CHECKING:
    from rich.console import Console

__all__ = ["fmt", "make_console"]


def make_console(stderr: bool = False) -> Console:
    """A rich console; 120 columns when not writing to a terminal (logs, pipes, make demo)."""
    from rich.console import Console  # imported here: `corrugate --help` never needs rich

    probe = Console(stderr=stderr)
    return probe if probe.is_terminal else Console(stderr=stderr, width=120)


def fmt(x: float | None, digits: int = 4) -> str:
    """``x`` with ``digits`` significant digits, ``-`` for None."""
    return "-" if x is None else f"{x:.{digits}g}"
