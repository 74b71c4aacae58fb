"""The flat pattern: parts to cut, with their creases, as plain values (all lengths in mm).

A :class:`Part` is a closed outline (cut), optional holes (cut), and line segments of three roles
that are not cut through: mountain and valley folds (with their dihedral fold angle) and marks
(assembly guides, such as where a crease end meets the edge band). Part coordinates are local, in
mm, with the outline's bounding box starting at (0, 0). A :class:`Pattern` is every part of one
design; writers (SVG, DXF, PDF, FOLD) and the sheet layout take it as it is.
"""

from __future__ import annotations

from dataclasses import dataclass, field
from enum import StrEnum

import numpy as np

__all__ = ["Line", "Part", "Pattern", "Role", "polygon_area"]

Point = tuple[float, float]


class Role(StrEnum):
    """What a line is for. CUT lines go through the sheet; the others do not."""

    CUT = "cut"
    MOUNTAIN = "mountain"
    VALLEY = "valley"
    MARK = "mark"


@dataclass(frozen=True, slots=True)
class Line:
    """A straight segment from ``a`` to ``b`` (mm) with its role.

    ``fold_angle_deg`` is the dihedral fold angle of a mountain or valley crease, 180 deg - alpha for
    the layers' creases (0 = flat, 180 = folded flat); 0 for marks.
    """

    a: Point
    b: Point
    role: Role
    fold_angle_deg: float = 0.0

    @property
    def length(self) -> float:
        return float(np.hypot(self.b[0] - self.a[0], self.b[1] - self.a[1]))


def polygon_area(points: tuple[Point, ...] | list[Point]) -> float:
    """Area (mm^2) of a simple polygon by the shoelace formula (either orientation)."""
    if len(points) < 3:
        return 0.0
    p = np.asarray(points, dtype=np.float64)
    x, y = p[:, 0], p[:, 1]
    return float(abs(0.5 * np.sum(x * np.roll(y, -1) - np.roll(x, -1) * y)))


@dataclass(frozen=True, slots=True)
class Part:
    """One part to cut: ``outline`` (closed polygon, counter-clockwise), ``holes`` (closed polygons
    cut out of it), ``lines`` (folds and marks), a short ``name`` and a human ``label``."""

    name: str
    label: str
    outline: tuple[Point, ...]
    lines: tuple[Line, ...] = ()
    holes: tuple[tuple[Point, ...], ...] = ()
    #: What the part is: "layer" or "connector" (mass is reported by kind).
    kind: str = "layer"
    #: Free-form data the 3D and FOLD exporters need (e.g. the layer index).
    meta: dict[str, float] = field(default_factory=dict, compare=False, hash=False)
    #: The sheet this part is cut from, when it differs from the pattern's (t in mm, density in
    #: g/mm^3; 0 means "the pattern's").
    material_id: str = ""
    t: float = 0.0
    density: float = 0.0

    @property
    def area(self) -> float:
        """Cut area (mm^2): outline minus holes."""
        return polygon_area(self.outline) - sum(polygon_area(h) for h in self.holes)

    @property
    def size(self) -> tuple[float, float]:
        """Width and height of the outline's bounding box (mm)."""
        p = np.asarray(self.outline)
        span = p.max(axis=0) - p.min(axis=0)
        return float(span[0]), float(span[1])

    def creases(self) -> tuple[Line, ...]:
        """The mountain and valley lines."""
        return tuple(ln for ln in self.lines if ln.role in (Role.MOUNTAIN, Role.VALLEY))


@dataclass(frozen=True, slots=True)
class Pattern:
    """Every part of one design, with the sheet they are cut from (``t`` in mm, ``density`` in
    g/mm^3)."""

    parts: tuple[Part, ...]
    material_id: str
    t: float
    density: float

    def part_mass(self, part: Part) -> float:
        """rho t times the cut area (g) of one part, with the part's own sheet if it has one."""
        t = part.t if part.t > 0 else self.t
        rho = part.density if part.density > 0 else self.density
        return rho * t * part.area

    def mass(self, kind: str | None = None) -> float:
        """rho t times the cut area (g) of every part, or of the parts of one ``kind``."""
        return sum(self.part_mass(p) for p in self.parts if kind is None or p.kind == kind)
