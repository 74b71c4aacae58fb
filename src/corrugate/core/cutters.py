"""The cutters a design can be cut on: each one's usable cut area (mm) and where that area
comes from (the machine profiles of :mod:`corrugate.export.machines` and the sheet planner of
:mod:`corrugate.fabrication.sheets` use them; the solver bounds the cut parts by them). The
names and areas are documented in :mod:`corrugate.fabrication.sheets`.
"""

from __future__ import annotations

import re
from dataclasses import dataclass

from corrugate.core.errors import InputError, UnknownNameError
from corrugate.core.limits import LIMITS, is_normal
from corrugate.names import LASER

__all__ = ["CUTTERS", "INCH", "Cutter", "get_cutter"]

INCH = 25.4


@dataclass(frozen=True, slots=True)
class Cutter:
    """A cutter with one sheet (mat or bed) size: ``width`` x ``height`` is the usable cut area
    (mm), ``source`` says where that area comes from."""

    name: str
    width: float
    height: float
    description: str
    source: str


_CAMEO_SOURCE = (
    "assumed: 12 in adhesive area less a 1/4 in cut border each side (Silhouette quotes only the "
    "12 in maximum cutting width)"
)
_MAKER_SOURCE = "Cricut help centre: maximum cut size on the mat"

#: The named cutters; ``laser:WxH`` (mm) is accepted besides these.
CUTTERS: dict[str, Cutter] = {
    c.name: c
    for c in (
        Cutter(
            "cameo4-12x12",
            11.5 * INCH,
            11.5 * INCH,
            "Silhouette Cameo 4, 12 x 12 in mat",
            _CAMEO_SOURCE,
        ),
        Cutter(
            "cameo4-12x24",
            11.5 * INCH,
            23.5 * INCH,
            "Silhouette Cameo 4, 12 x 24 in mat",
            _CAMEO_SOURCE,
        ),
        Cutter(
            "maker-12x12", 11.5 * INCH, 11.5 * INCH, "Cricut Maker, 12 x 12 in mat", _MAKER_SOURCE
        ),
        Cutter(
            "maker-12x24", 11.5 * INCH, 23.5 * INCH, "Cricut Maker, 12 x 24 in mat", _MAKER_SOURCE
        ),
    )
}

_LASER = re.compile(r"^laser:\s*([0-9]*\.?[0-9]+)\s*[x×]\s*([0-9]*\.?[0-9]+)\s*(mm)?$")


def get_cutter(name: str | Cutter) -> Cutter:
    """The cutter called ``name`` (see the module docstring), or a ``laser:WxH`` bed in mm.

    Raises :class:`~corrugate.core.errors.UnknownNameError` for an unknown name and
    :class:`~corrugate.core.errors.InputError` for a laser bed that is not positive or longer than
    any length a spec takes (``LIMITS["length"]``, 1 km: a 4000-digit width is refused as it was
    written, not read as infinity).
    """
    if isinstance(name, Cutter):
        return name
    key = name.strip().lower()
    if key in CUTTERS:
        return CUTTERS[key]
    if key.startswith("laser"):
        m = _LASER.match(key)
        if m is None:
            raise InputError(
                "cutter",
                repr(name),
                "laser:WxH with W and H in mm, e.g. laser:600x400",
                reason="is not a laser bed size",
            )
        w, h = float(m.group(1)), float(m.group(2))
        top = LIMITS["length"].hi
        if not all(is_normal(x) and 0 < x <= top for x in (w, h)):
            raise InputError(
                "cutter", repr(name), f"a bed of positive width and height up to {top:g} mm"
            )
        return Cutter(
            f"laser:{w:g}x{h:g}", w, h, f"laser bed {w:g} x {h:g} mm", "given by the user"
        )
    raise UnknownNameError("cutter", name, [*CUTTERS, LASER])
