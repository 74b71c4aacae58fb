"""Creep moduli of a sheet under a sustained load: a table per material, read in log time.

A polymer held under a constant load keeps deforming: its strain at time t is the stress over
the *creep modulus* E_c(t) (tensile creep, ISO 899-1; docs/load_cases.md section 11), which
falls below the short-term modulus E of a tensile test as t grows. A :class:`CreepTable` holds
E_c (MPa) at a few durations (hours, ascending) at room temperature (about 23 C), with where
they come from (``source``, one line printed with an answer) and whether they are an estimate
(``estimate``: no published creep curve was found for the sheet, the value is derived from one
and says how).

:meth:`CreepTable.modulus` reads the table at a duration t (hours): linear in log10(t) between
two tabulated durations, the first tabulated modulus below the first duration (the creep
modulus only falls with time, so this is the lower, safe side: it is at most E and at least the
true E_c(t) of the curve), and :class:`~corrugate.core.errors.InputError` beyond the last: the
table says nothing there, and creep curves are not extrapolated.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

from corrugate.core.errors import InputError

__all__ = ["CreepTable", "duration_text"]


def duration_text(hours: float) -> str:
    """A duration (hours) as a short text: ``1 h``, ``1 day``, ``1 week``, ``1000 h``."""
    for name, size in (("week", 168.0), ("day", 24.0)):
        count = hours / size
        if count >= 1 and math.isclose(count, round(count), rel_tol=1e-9):
            c = round(count)
            return f"{c} {name}{'s' if c != 1 else ''}"
    return f"{hours:.4g} h"


@dataclass(frozen=True, slots=True)
class CreepTable:
    """Creep moduli ``moduli`` (MPa) at ``hours`` (ascending, > 0) under a sustained load at
    room temperature, from ``source`` (an ``estimate`` when no published curve gives them)."""

    hours: tuple[float, ...]
    moduli: tuple[float, ...]
    source: str
    estimate: bool = False

    def __post_init__(self) -> None:
        if not self.hours or len(self.hours) != len(self.moduli):
            raise ValueError("a creep table needs one modulus per duration")
        if any(h <= 0 for h in self.hours) or list(self.hours) != sorted(set(self.hours)):
            raise ValueError("creep table durations must be positive and ascending")
        if any(not (m > 0) for m in self.moduli):
            raise ValueError("creep moduli must be positive")

    @property
    def last(self) -> float:
        """The longest tabulated duration (hours)."""
        return self.hours[-1]

    @property
    def range_text(self) -> str:
        """The tabulated durations, e.g. ``1 h to 1000 h``."""
        first, last = duration_text(self.hours[0]), duration_text(self.last)
        return first if first == last else f"{first} to {last}"

    def modulus(self, hours: float, field: str = "duration") -> float:
        """The creep modulus E_c (MPa) after ``hours`` of sustained load (module docstring);
        :class:`InputError` naming ``field`` for a duration that is not > 0 or is beyond the
        table."""
        if not (hours > 0 and math.isfinite(hours)):
            raise InputError(field, f"{hours:g} h", "a duration > 0 h")
        if hours > self.last * (1 + 1e-12):
            raise InputError(
                field,
                duration_text(hours),
                f"at most {duration_text(self.last)} (creep moduli tabulated for "
                f"{self.range_text})",
                reason="is beyond the creep table",
            )
        if hours <= self.hours[0]:
            return self.moduli[0]
        for (h0, e0), (h1, e1) in zip(
            zip(self.hours, self.moduli, strict=True),
            zip(self.hours[1:], self.moduli[1:], strict=True),
            strict=True,
        ):
            if hours <= h1:
                f = (math.log10(hours) - math.log10(h0)) / (math.log10(h1) - math.log10(h0))
                return e0 + f * (e1 - e0)
        return self.moduli[-1]  # hours == last within the tolerance
