"""The command line's progress of a solve on stderr (``corrugate design`` and ``tolerance``).

:func:`solve_progress` listens to the branch and bound and to the stages of the answer
(:mod:`corrugate.solver.progress`: searching, then explaining: binding checks, runner-ups or the
diagnosis) and shows, once a solve has run :data:`START_AFTER_S` seconds, what it is doing, for
how long, the iterations, the proven gap and the best objective value found:

* on a terminal, one rich status line that refreshes in place and disappears when the solve
  ends (the answer then prints as before);
* otherwise (a pipe, a log, ``make demo``), a plain line ``corrugate: ...`` at each new stage and
  every :data:`PLAIN_INTERVAL_S` seconds.

Nothing is shown with ``--quiet``, nor with ``--json`` unless stderr is a terminal; stdout never
carries progress.
"""

from __future__ import annotations

import math
import sys
import time
from collections.abc import Iterator
from contextlib import contextmanager
from typing import TYPE_CHECKING

if TYPE_CHECKING:
    from rich.console import Console
    from rich.live import Live
    from rich.spinner import Spinner

__all__ = ["PLAIN_INTERVAL_S", "START_AFTER_S", "SolveProgress", "show_progress", "solve_progress"]

#: Seconds (wall) before a solve shows any progress: a faster one prints nothing extra.
START_AFTER_S = 1.0
#: Seconds (wall) between two plain progress lines of one stage off a terminal.
PLAIN_INTERVAL_S = 5.0
#: Seconds (wall) between two text updates of the terminal's status line.
_LIVE_UPDATE_S = 0.2


def show_progress(quiet: bool, as_json: bool) -> bool:
    """Whether a command shows its progress: not with ``--quiet``; with ``--json`` only when
    stderr is a terminal (a script reading the JSON may read stderr too)."""
    if quiet:
        return False
    if not as_json:
        return True
    try:
        return sys.stderr.isatty()
    except (AttributeError, ValueError):  # a replaced or closed stderr
        return False


class SolveProgress:
    """A reporter and stage listener of :mod:`corrugate.solver.progress` that shows the news on
    ``console`` (stderr): a status line refreshed in place when ``live`` (a terminal), else a
    plain line per stage and every :data:`PLAIN_INTERVAL_S` seconds. ``unit``: the objective's
    unit (``g`` for mass)."""

    def __init__(self, console: Console, live: bool, unit: str) -> None:
        self.console = console
        self.live = live
        self.unit = unit
        self.t0 = time.monotonic()
        self.stage = "searching"
        self.iterations = 0
        self.runs = 0
        self.gap = math.inf
        self.best: float | None = None
        self.last_line = -math.inf  # when the last plain line was printed
        self.stage_shown = True  # whether the current stage's first line is out
        self.next_update = 0.0
        self.stopped = False
        self._live: Live | None = None  # started after START_AFTER_S
        self._spinner: Spinner | None = None

    def text(self) -> str:
        """What the solve is doing now, e.g. ``searching: 12 s, 3400 iterations in 1 run, gap
        0.41 %, best 2.162 g``."""
        elapsed = time.monotonic() - self.t0
        what = self.stage
        if self.stage == "searching" and self.best is None:
            what = "searching (no design found yet: proving infeasible or still looking)"
        parts = [f"{what}: {elapsed:.0f} s"]
        if self.iterations:
            runs = f"{self.runs} run" + ("" if self.runs == 1 else "s")
            its = f"{self.iterations} iteration" + ("" if self.iterations == 1 else "s")
            parts.append(f"{its} in {runs}")
        if self.stage == "searching" and self.best is not None:
            if math.isfinite(self.gap):
                parts.append(f"gap {100 * self.gap:.3g} %")
            parts.append(f"best {self.best:.6g} {self.unit}".rstrip())
        return ", ".join(parts)

    def __call__(self, iterations: int, gap: float, best: float | None) -> None:
        self.iterations += 1
        if iterations == 1:
            self.runs += 1
        if self.stage == "searching":  # the explanation's re-solves have objectives of their own
            self.gap, self.best = gap, best
        self._tick()

    def on_stage(self, name: str) -> None:
        """The solve entered the stage ``name``."""
        if name != self.stage:
            self.stage = name
            self.stage_shown = False
        self._tick()

    def _tick(self) -> None:
        now = time.monotonic()
        if self.stopped or now - self.t0 < START_AFTER_S:
            return
        if self.live:
            self._live_update(now)
        elif not self.stage_shown or now - self.last_line >= PLAIN_INTERVAL_S:
            self.stage_shown = True
            self.last_line = now
            self.console.print(f"corrugate: {self.text()}", markup=False, highlight=False)

    def _live_update(self, now: float) -> None:
        from rich.live import Live
        from rich.spinner import Spinner

        if self._spinner is None or self._live is None:
            self._spinner = Spinner("dots", text=self.text())
            self._live = Live(
                self._spinner, console=self.console, transient=True, refresh_per_second=4
            )
            self._live.start()
        if now >= self.next_update or not self.stage_shown:
            self.next_update = now + _LIVE_UPDATE_S
            self.stage_shown = True
            self._spinner.update(text=self.text())

    def stop(self) -> None:
        """Stop showing progress: remove the status line (a terminal) and ignore what follows
        (the FE step of ``design --verify fe`` prints lines of its own)."""
        self.stopped = True
        if self._live is not None:
            self._live.stop()
            self._live = None


@contextmanager
def solve_progress(enabled: bool, unit: str = "g") -> Iterator[SolveProgress | None]:
    """Show the progress of every solve inside the block on stderr (module docstring) when
    ``enabled``; ``unit``: the objective's unit."""
    if not enabled:
        yield None
        return
    from corrugate.cli.console import make_console
    from corrugate.solver.progress import reporting

    console = make_console(stderr=True)
    shown = SolveProgress(console, console.is_terminal, unit)
    try:
        with reporting(shown, shown.on_stage):
            yield shown
    finally:
        shown.stop()
