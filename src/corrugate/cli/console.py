"""Console output shared by the commands: a rich console and number formatting."""

from __future__ import annotations

from typing import TYPE_CHECKING

if TYPE_CHECKING:
    from rich.console import Console

__all__ = ["fmt", "make_console"]


#: Width of a console that does not write to a terminal: wide enough that no table squeezes its
#: columns (tables take only the width they need) and no line is broken.
PIPE_WIDTH = 1000


def make_console(stderr: bool = False) -> Console:
    """A rich console. Writing to a terminal: its width, colours. Otherwise (a pipe, a file, a log,
    ``make demo``): plain text, no colour codes, and lines never wrapped (``soft_wrap``), so a
    sentence stays on one line and ``grep`` finds it. Either way without rich's emoji codes: a
    name the user wrote (``:fire:``) prints as written, and rich's emoji table is not loaded
    (about 2 ms of CPU a command)."""
    from rich.console import Console  # imported here: `corrugate --help` never needs rich

    probe = Console(stderr=stderr, emoji=False)
    if probe.is_terminal:
        return probe
    return Console(
        stderr=stderr,
        width=PIPE_WIDTH,
        soft_wrap=True,
        no_color=True,
        highlight=False,
        emoji=False,
    )


def fmt(x: float | None, digits: int = 4) -> str:
    """``x`` with ``digits`` significant digits, ``-`` for None."""
    return "-" if x is None else f"{x:.{digits}g}"
