"""How fold lines are made on the cutter: solid, scored, or perforated (cut and gap lengths in mm).

``solid``
    Each crease is one line (drawn, or cut at fold pressure, as the user sets up the cutter).
``scored``
    Each crease is one line meant for a scoring tool or a light "kiss" cut; writers that have
    layers put it on a SCORE layer.
``perforated``
    Each crease is cut as dashes of length ``cut`` separated by gaps, so the sheet folds along it.

Dash rule (:func:`dashes`): dashes of exactly ``cut`` separated by gaps of exactly ``gap``, as many
as fit with at least half a gap, gap / 2, left free at each end of the line, and the run centred
on the line: a crease of length L gets N = floor((L - gap / 2 - gap / 2 + gap) / (cut + gap)) =
floor(L / (cut + gap)) dashes, and each end keeps (L - N cut - (N - 1) gap) / 2 >= gap / 2 > 0,
so no dash touches a line end (where the crease meets an edge or a cut, a dash would tear the
sheet). A crease shorter than ``cut + gap`` cannot hold one dash with its end gaps and is an error.

Bounds (:data:`corrugate.core.limits.LIMITS` ``["perforation"]``, checked when the style is made,
before any work): the cut and the gap each lie within 0.1 mm .. 1 m. The 0.1 mm floor is a chosen
bound, of the order of a drag blade's offset and a laser's kerf: a shorter dash or gap is not cut
as one by a Cameo, a Cricut or a laser. A design perforated with more than
:data:`corrugate.core.limits.MAX_DASHES` dashes in all is refused by :func:`check_style` (its cut
files would be tens of MB and take minutes to write).
"""

from __future__ import annotations

import math
from collections.abc import Iterable
from dataclasses import dataclass
from enum import StrEnum

from corrugate.core.errors import InputError, UnknownNameError
from corrugate.core.limits import LIMITS, MAX_DASHES
from corrugate.fabrication.model import Line, Part, Point, Role

__all__ = [
    "SOLID",
    "LineStyle",
    "PerforationError",
    "StyleKind",
    "check_style",
    "crease_name",
    "dash_layout",
    "dashes",
    "is_crease",
    "line_style",
]


class PerforationError(InputError):
    """A perforation that does not fit a crease, whose cut or gap is outside
    ``LIMITS["perforation"]``, or that has more than ``MAX_DASHES`` dashes."""


class StyleKind(StrEnum):
    """The three ways of making a fold line."""

    SOLID = "solid"
    SCORED = "scored"
    PERFORATED = "perforated"


@dataclass(frozen=True, slots=True)
class LineStyle:
    """A fold-line style; ``cut`` and ``gap`` (mm) only matter for ``perforated``."""

    kind: StyleKind = StyleKind.SOLID
    cut: float = 0.0
    gap: float = 0.0

    def __post_init__(self) -> None:
        if self.kind is StyleKind.PERFORATED:
            lim = LIMITS["perforation"]
            for name, value in (("cut", self.cut), ("gap", self.gap)):
                if not lim.contains(value):
                    raise PerforationError(
                        f"perforation {name}",
                        f"{value:g} mm",
                        f"{lim.lo:g} mm <= {name} <= {lim.hi:g} mm (a dash and a gap the cutter "
                        "resolves)",
                    )


#: The default style: every crease one solid line.
SOLID = LineStyle()


def line_style(
    name: str | StyleKind, cut: float | None = None, gap: float | None = None
) -> LineStyle:
    """The style called ``name`` (``solid``, ``scored`` or ``perforated``); ``perforated`` needs
    ``cut`` and ``gap`` in mm. Unknown names raise :class:`~corrugate.core.errors.UnknownNameError`."""
    key = str(name).strip().lower()
    try:
        kind = StyleKind(key)
    except ValueError:
        raise UnknownNameError("fold-line style", str(name), [k.value for k in StyleKind]) from None
    if kind is StyleKind.PERFORATED:
        if cut is None or gap is None:
            raise PerforationError(
                "perforation",
                f"cut = {cut} mm, gap = {gap} mm",
                "both cut and gap lengths (mm)",
                reason="is incomplete",
            )
        return LineStyle(kind, float(cut), float(gap))
    return LineStyle(kind)


def dash_layout(length: float, cut: float, gap: float, *, where: str = "crease") -> list[float]:
    """Start positions (mm from the line's start) of the dashes of a perforated line of ``length``
    mm, by the dash rule of the module docstring. ``where`` names the line in errors."""
    if not (math.isfinite(cut) and cut > 0 and math.isfinite(gap) and gap > 0):
        raise PerforationError(
            f"perforation on {where}", f"cut {cut:g} mm, gap {gap:g} mm", "cut > 0 and gap > 0 mm"
        )
    n = math.floor(length / (cut + gap) + 1e-9)
    if n < 1:
        raise PerforationError(
            f"perforation on {where}",
            f"cut {cut:g} mm + gap {gap:g} mm = {cut + gap:g} mm",
            f"cut + gap <= the crease length {length:.3f} mm (one dash with half a gap at each end)",
            reason="is longer than the crease",
        )
    period = cut + gap
    head = (length - n * cut - (n - 1) * gap) / 2
    return [head + k * period for k in range(n)]


def dashes(
    line: Line, cut: float, gap: float, *, where: str = "crease"
) -> list[tuple[Point, Point]]:
    """The dashes (segments, mm) that perforate ``line``; see :func:`dash_layout`."""
    length = line.length
    starts = dash_layout(length, cut, gap, where=where)
    (ax, ay), (bx, by) = line.a, line.b
    ux, uy = (bx - ax) / length, (by - ay) / length
    out: list[tuple[Point, Point]] = []
    for s in starts:
        e = s + cut
        out.append(((ax + ux * s, ay + uy * s), (ax + ux * e, ay + uy * e)))
    return out


def is_crease(line: Line) -> bool:
    """Whether ``line`` is a mountain or valley fold."""
    return line.role in (Role.MOUNTAIN, Role.VALLEY)


def crease_name(part: Part, index: int) -> str:
    """How errors and files name line ``index`` of ``part.lines``: its 1-based number among the
    part's creases, e.g. ``crease 3 of part 'layer-1'``."""
    number = sum(1 for ln in part.lines[: index + 1] if is_crease(ln))
    return f"crease {number} of part {part.name!r}"


def check_style(parts: Iterable[Part], style: LineStyle) -> None:
    """Raise :class:`PerforationError` if ``style`` cannot perforate some crease of ``parts``
    (nothing to check for solid or scored lines). Call it before writing any file."""
    if style.kind is not StyleKind.PERFORATED:
        return
    total = 0
    for part in parts:
        for i, ln in enumerate(part.lines):
            if is_crease(ln):
                count = math.floor(ln.length / (style.cut + style.gap) + 1e-9)
                if count < 1:  # too short for one dash: dash_layout's error names the crease
                    dash_layout(ln.length, style.cut, style.gap, where=crease_name(part, i))
                total += count
                if total > MAX_DASHES:
                    raise PerforationError(
                        "cut",
                        f"{style.cut:g} mm (gap {style.gap:g} mm)",
                        f"a cut and gap giving at most {MAX_DASHES} dashes in the design",
                        reason="gives too many dashes",
                    )
