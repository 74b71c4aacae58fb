"""A measurements file (TOML) read into typed values, every field checked.

The file ``corrugate calibrate kit`` writes (``measurements.toml``) holds the sheet and the
coupons' dimensions; the user fills in the readings (docs/calibration.md section 2)::

    [sheet]
    material = "dura-lar"     # density and nu from it; E is what is measured
    thickness = "0.125 mm"
    ruler = "1 mm"            # the reading error of one measurement (+-)
    name = "my-dura-lar"      # the id the fitted material is saved under

    [[flat]]                  # one per strip, free length and tip load
    coupon = "F1"
    direction = "along"       # along the sheet's x (the roll) or across
    width = "20 mm"
    overhang = "75 mm"        # free length beyond the table edge
    tip_mass = "0 g"          # coins taped at the tip
    sag = [15, 14, 15]        # mm, the tip's drop below the table top, one per repeat

    [crease]                  # the zig-zag strip (optional)
    coupon = "C1"
    width = "20 mm"
    facet = "12 mm"
    creases = 9
    folded_to = "90 deg"      # the angle the creases were folded to
    length = [77, 78, 77]     # mm, end to end of the zig-zag (not the tabs), unloaded
    mass = ["5 g", "10 g", "15 g"]          # coins in the bag, one per load
    extension = [[3, 3, 4], [7, 7, 6], [10, 11, 10]]   # mm, one list of repeats per load

Lengths are mm and masses g when plain numbers. Every error is one
:class:`~corrugate.core.errors.InputError` naming the field (``flat[1].sag[2]``), the value and
what is allowed.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from pathlib import Path
from typing import Any

from corrugate.core.errors import InputError
from corrugate.core.units import parse_quantity
from corrugate.materials.library import Material, get_material

__all__ = [
    "MIN_REPEATS",
    "CreaseTest",
    "FlatTest",
    "Measurements",
    "load_measurements",
    "parse_measurements",
]

#: The fewest repeats of one reading: two cannot tell a slip of the ruler from the scatter.
MIN_REPEATS = 3
#: The largest measurements file read (bytes).
MAX_BYTES = 1 << 20
DIRECTIONS = ("along", "across")


@dataclass(frozen=True, slots=True)
class FlatTest:
    """One set-up of a flat strip: ``coupon``, ``direction``, ``width`` and free length
    ``overhang`` (mm), ``tip_g`` grams at the tip, the ``sags`` read (mm), and ``field`` (its
    place in the file, for messages)."""

    coupon: str
    direction: str
    width: float
    overhang: float
    tip_g: float
    sags: tuple[float, ...]
    field: str


@dataclass(frozen=True, slots=True)
class CreaseTest:
    """The zig-zag strip: ``width``, ``facet`` (mm), ``creases``, the angle it was ``folded_to``
    (deg), its unloaded ``lengths`` (mm) and, per load of ``masses`` (g), the ``extensions`` read
    (mm)."""

    coupon: str
    width: float
    facet: float
    creases: int
    folded_to: float
    lengths: tuple[float, ...]
    masses: tuple[float, ...]
    extensions: tuple[tuple[float, ...], ...]


@dataclass(frozen=True, slots=True)
class Measurements:
    """A measurements file: the sheet's library ``material``, thickness ``t`` (mm), ``ruler``
    reading error (mm), the ``name`` to save the fit under, the ``date`` measured (ISO text or
    empty), the flat set-ups and the crease test (None: not measured)."""

    material: Material
    t: float
    ruler: float
    name: str
    date: str
    flat: tuple[FlatTest, ...]
    crease: CreaseTest | None

    @property
    def count(self) -> int:
        """The number of readings (sags, lengths and extensions)."""
        n = sum(len(f.sags) for f in self.flat)
        if self.crease is not None:
            n += len(self.crease.lengths) + sum(len(e) for e in self.crease.extensions)
        return n


def _table(data: Any, field: str) -> dict[str, Any]:
    if not isinstance(data, dict):
        raise InputError(field, repr(data)[:40], "a table", reason="is not one")
    return data


def _get(d: dict[str, Any], key: str, field: str) -> Any:
    if key not in d:
        raise InputError(f"{field}.{key}", None, "a value", reason="is missing")
    return d[key]


def _positive(value: Any, unit: str, field: str, hi: float = math.inf) -> float:
    x = parse_quantity(value, unit, field)
    if not (math.isfinite(x) and 0.0 < x < hi):
        shown = "" if math.isinf(hi) else f" < {hi:g} {unit}"
        raise InputError(field, f"{x:g} {unit}", f"0 < {field.rsplit('.', 1)[-1]}{shown}")
    return x


def _readings(
    value: Any, field: str, hi: float, what: str, zero: bool = False
) -> tuple[float, ...]:
    """A list of at least :data:`MIN_REPEATS` readings (mm), each >= 0 (> 0 unless ``zero``) and
    below ``hi`` (``what`` names that bound)."""
    if not isinstance(value, list):
        raise InputError(
            field, repr(value)[:40], f"a list of at least {MIN_REPEATS} readings in mm"
        )
    if len(value) < MIN_REPEATS:
        raise InputError(
            field,
            f"{len(value)} reading{'s' if len(value) != 1 else ''}",
            f"at least {MIN_REPEATS} repeats",
            reason="has too few repeats",
        )
    out = []
    for i, v in enumerate(value):
        x = parse_quantity(v, "mm", f"{field}[{i}]")
        if not math.isfinite(x) or x < 0 or (x == 0 and not zero) or x >= hi:
            low = "0 <=" if zero else "0 <"
            raise InputError(f"{field}[{i}]", f"{x:g} mm", f"{low} reading < {what} = {hi:g} mm")
        out.append(x)
    return tuple(out)


def _flat(d: dict[str, Any], field: str) -> FlatTest:
    direction = str(_get(d, "direction", field))
    if direction not in DIRECTIONS:
        raise InputError(f"{field}.direction", repr(direction), "one of along, across")
    overhang = _positive(_get(d, "overhang", field), "mm", f"{field}.overhang", 1000.0)
    sags = _readings(_get(d, "sag", field), f"{field}.sag", overhang, "the overhang")
    return FlatTest(
        coupon=str(d.get("coupon", field)),
        direction=direction,
        width=_positive(_get(d, "width", field), "mm", f"{field}.width", 1000.0),
        overhang=overhang,
        tip_g=_mass(d.get("tip_mass", 0), f"{field}.tip_mass"),
        sags=sags,
        field=field,
    )


def _mass(value: Any, field: str) -> float:
    x = parse_quantity(value, "g", field)
    if not (math.isfinite(x) and 0.0 <= x <= 1000.0):
        raise InputError(field, f"{x:g} g", "0 <= mass <= 1000 g")
    return x


def _crease(d: dict[str, Any]) -> CreaseTest:
    f = "crease"
    facet = _positive(_get(d, "facet", f), "mm", f"{f}.facet", 1000.0)
    creases = _get(d, "creases", f)
    if isinstance(creases, bool) or not isinstance(creases, int) or not 1 <= creases <= 100:
        raise InputError(f"{f}.creases", repr(creases), "an integer 1-100")
    folded_to = parse_quantity(_get(d, "folded_to", f), "deg", f"{f}.folded_to")
    if not 0.0 < folded_to < 180.0:
        raise InputError(f"{f}.folded_to", f"{folded_to:g} deg", "0 < folded_to < 180 deg")
    flat_length = creases * facet
    lengths = _readings(_get(d, "length", f), f"{f}.length", flat_length, "the unfolded length")
    masses_raw = _get(d, "mass", f)
    ext_raw = _get(d, "extension", f)
    if not isinstance(masses_raw, list) or not masses_raw:
        raise InputError(f"{f}.mass", repr(masses_raw)[:40], "a list of the loads' masses in g")
    if not isinstance(ext_raw, list) or len(ext_raw) != len(masses_raw):
        raise InputError(
            f"{f}.extension",
            repr(ext_raw)[:40],
            f"one list of readings per mass ({len(masses_raw)})",
        )
    masses = tuple(_mass(m, f"{f}.mass[{i}]") for i, m in enumerate(masses_raw))
    if any(m <= 0 for m in masses):
        raise InputError(f"{f}.mass", repr(list(masses)), "masses > 0 g")
    room = flat_length - min(lengths)
    extensions = tuple(
        _readings(e, f"{f}.extension[{i}]", room, "the unfolded length less the length", zero=True)
        for i, e in enumerate(ext_raw)
    )
    return CreaseTest(
        coupon=str(d.get("coupon", "C1")),
        width=_positive(_get(d, "width", f), "mm", f"{f}.width", 1000.0),
        facet=facet,
        creases=creases,
        folded_to=folded_to,
        lengths=lengths,
        masses=masses,
        extensions=extensions,
    )


def parse_measurements(data: dict[str, Any]) -> Measurements:
    """The :class:`Measurements` of a file's content ``data`` (as read from TOML)."""
    known = {"sheet", "flat", "crease"}
    for key in data:
        if key not in known:
            raise InputError(
                str(key), "...", "one of " + ", ".join(sorted(known)), reason="is unknown"
            )
    sheet = _table(_get(data, "sheet", "measurements"), "sheet")
    name = str(_get(sheet, "material", "sheet"))
    try:
        material = get_material(name)
    except InputError as exc:
        raise exc.renamed("sheet.material") from None
    t = _positive(_get(sheet, "thickness", "sheet"), "mm", "sheet.thickness", 20.0)
    ruler = _positive(sheet.get("ruler", 1.0), "mm", "sheet.ruler", 20.0)
    saved = str(sheet.get("name", f"{material.id}-calibrated")).strip().lower()
    if not saved or len(saved) > 60 or not all(c.isalnum() or c in "-_." for c in saved):
        raise InputError("sheet.name", repr(saved), "1-60 letters, digits, '-', '_' or '.'")
    raw_flat = data.get("flat", [])
    if not isinstance(raw_flat, list):
        raise InputError("flat", repr(raw_flat)[:40], "an array of tables [[flat]]")
    flat = tuple(_flat(_table(d, f"flat[{i}]"), f"flat[{i}]") for i, d in enumerate(raw_flat))
    crease = None if "crease" not in data else _crease(_table(data["crease"], "crease"))
    if not flat and crease is None:
        raise InputError(
            "flat", "[]", "at least one [[flat]] set-up or a [crease] test", reason="is empty"
        )
    return Measurements(material, t, ruler, saved, str(sheet.get("date", "")), flat, crease)


def load_measurements(path: str | Path) -> Measurements:
    """Read and check the measurements file ``path`` (TOML)."""
    from corrugate.core.fileio import parse_toml_input, read_input_text

    # a regular file only, size-capped, strict UTF-8 (read as untrusted input)
    text = read_input_text(path, "MEASUREMENTS", MAX_BYTES)
    data = parse_toml_input(text, "MEASUREMENTS", str(path))
    return parse_measurements(data)
