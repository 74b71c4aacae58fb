"""Sheet materials: the bundled library (``data/materials.toml``) and inline definitions.

A :class:`Material` holds E (MPa), nu (-), density (g/mm^3), the thicknesses it is sold in (mm),
the allowable stress of a strength check (``yield_strength``, MPa: the tensile yield stress, or the
tensile strength of a material without a yield point; :mod:`corrugate.mechanics.strength`) and where
the values come from. The library is data, not code: edit the TOML file to add a sheet.
"""

from __future__ import annotations

import math
import tomllib
from collections.abc import Mapping
from dataclasses import dataclass, field
from functools import cache, lru_cache
from pathlib import Path
from typing import TYPE_CHECKING, Any

from corrugate.core.errors import InputError, UnknownNameError
from corrugate.core.units import parse_quantity
from corrugate.materials.creep import CreepTable

if TYPE_CHECKING:
    from corrugate.materials.calibrated import Calibration

__all__ = [
    "AmbiguousNameError",
    "Material",
    "creep_materials",
    "get_material",
    "inline_material",
    "library",
    "library_entries",
    "material_from_dict",
    "material_from_entry",
    "validate_elastic",
    "validate_strength",
]

#: g/cm^3 expressed in the internal unit g/mm^3.
G_PER_CM3 = 1.0e-3


@dataclass(frozen=True, slots=True)
class Material:
    """An isotropic sheet material.

    Attributes are in internal units: ``E`` in MPa, ``density`` in g/mm^3, thicknesses in mm,
    ``yield_strength`` in MPa (None when not known: an inline material defined by E, nu and
    density only), ``creep`` its creep moduli under a sustained load (None: no creep data, so
    no sustained load case; docs/load_cases.md section 11), ``crease_stiffness`` the rotational
    stiffness of its creases per unit crease length (N mm/(rad mm); inf, the default: rigid
    creases, :mod:`corrugate.mechanics.creases`) and ``calibration`` the intervals measured on
    the user's sheet (:class:`~corrugate.materials.calibrated.Calibration`; None: a datasheet's
    values).
    """

    id: str
    name: str
    E: float
    nu: float
    density: float
    thicknesses: tuple[float, ...] = ()
    default_thickness: float | None = None
    category: str = "custom"
    source: str = "defined by the user"
    yield_strength: float | None = None
    creep: CreepTable | None = None
    crease_stiffness: float = math.inf
    calibration: Calibration | None = None
    #: Other names that find it (``pet`` for the PET films): how it is looked up, not what it is
    #: (not compared, not written to design.json).
    aliases: tuple[str, ...] = field(default=(), compare=False)

    def __repr__(self) -> str:
        """One short line (the source text is in :meth:`as_dict`)."""
        return (
            f"Material({self.id!r}, E={self.E:g} MPa, nu={self.nu:g}, "
            f"density={self.density_g_cm3:.4g} g/cm^3)"
        )

    @property
    def density_g_cm3(self) -> float:
        """Density in g/cm^3."""
        return self.density / G_PER_CM3

    def as_dict(self) -> dict[str, Any]:
        """A JSON-ready description with units in the keys (``crease_stiffness`` and
        ``calibration`` only when the creases are not rigid, or the material calibrated)."""
        out = self._as_dict()
        if not math.isinf(self.crease_stiffness):
            out["crease_stiffness_N_mm_per_rad_mm"] = self.crease_stiffness
        if self.calibration is not None:
            out["calibration"] = self.calibration.as_dict()
        return out

    def _as_dict(self) -> dict[str, Any]:
        return {
            "id": self.id,
            "name": self.name,
            "E_MPa": self.E,
            "nu": self.nu,
            "density_g_cm3": self.density_g_cm3,
            "thicknesses_mm": list(self.thicknesses),
            "default_thickness_mm": self.default_thickness,
            "yield_strength_MPa": self.yield_strength,
            "category": self.category,
            "source": self.source,
            "creep": None
            if self.creep is None
            else {
                "hours": list(self.creep.hours),
                "E_MPa": list(self.creep.moduli),
                "source": self.creep.source,
                "estimate": self.creep.estimate,
            },
        }

    def creep_modulus(self, hours: float, field: str = "duration") -> float:
        """The creep modulus E_c (MPa) after ``hours`` of sustained load
        (:meth:`corrugate.materials.creep.CreepTable.modulus`); :class:`InputError` naming
        ``field`` when the material has no creep data or the duration is beyond its table."""
        if self.creep is None:
            raise InputError(
                field,
                f"{hours:g} h",
                "no duration (a short-term load) for a material without creep data; "
                "library materials with creep data: " + ", ".join(creep_materials()),
                reason=f"needs creep data, which {self.id} has not",
            )
        return self.creep.modulus(hours, field)


def material_from_dict(d: Any, field: str = "material") -> Material:
    """The material :meth:`Material.as_dict` wrote (design.json's ``material_properties``),
    every property checked as a spec's would be; :class:`InputError` naming ``field``'s key
    that is missing or out of range."""
    if not isinstance(d, dict):
        raise InputError(field, repr(d)[:40], "an object of material properties")

    def number(key: str, optional: bool = False) -> float | None:
        v = d.get(key)
        if v is None and optional:
            return None
        if isinstance(v, bool) or not isinstance(v, int | float):
            raise InputError(f"{field}.{key}", repr(v), "a number", reason="is not one")
        return float(v)

    E, nu, rho = number("E_MPa"), number("nu"), number("density_g_cm3")
    assert E is not None and nu is not None and rho is not None
    validate_elastic(E, nu, rho * G_PER_CM3, prefix=f"{field}.")
    strength = number("yield_strength_MPa", optional=True)
    if strength is not None:
        validate_strength(strength, E, f"{field}.yield_strength_MPa")
    raw_ts = d.get("thicknesses_mm") or []
    if not isinstance(raw_ts, list) or not all(
        isinstance(t, int | float) and not isinstance(t, bool) and t > 0 for t in raw_ts
    ):
        raise InputError(f"{field}.thicknesses_mm", repr(raw_ts)[:40], "a list of thicknesses > 0")
    default = number("default_thickness_mm", optional=True)
    k = number("crease_stiffness_N_mm_per_rad_mm", optional=True)
    if k is not None and not k > 0:
        raise InputError(f"{field}.crease_stiffness_N_mm_per_rad_mm", f"{k:g}", "k > 0")
    cal = d.get("calibration")
    calibration = None
    if cal is not None:  # a measured sheet (corrugate.materials.calibrated, imported for one)
        from corrugate.materials.calibrated import Calibration

        calibration = Calibration.from_dict(cal, f"{field}.calibration")
    creep = d.get("creep")
    table: CreepTable | None = None
    if creep is not None:
        try:
            table = CreepTable(
                tuple(float(h) for h in creep["hours"]),
                tuple(float(m) for m in creep["E_MPa"]),
                str(creep.get("source", "")),
                bool(creep.get("estimate", False)),
            )
        except (TypeError, ValueError, KeyError, AttributeError):
            raise InputError(
                f"{field}.creep",
                repr(creep)[:40],
                "hours and E_MPa: positive ascending durations, one modulus > 0 each",
            ) from None
        if any(m > E for m in table.moduli):
            raise InputError(f"{field}.creep.E_MPa", repr(list(table.moduli)), f"<= E = {E:g} MPa")
    return Material(
        id=str(d.get("id", "custom")),
        name=str(d.get("name", d.get("id", "custom"))),
        E=E,
        nu=nu,
        density=rho * G_PER_CM3,
        thicknesses=tuple(float(t) for t in raw_ts),
        default_thickness=default,
        category=str(d.get("category", "custom")),
        source=str(d.get("source", "defined by the user")),
        yield_strength=strength,
        creep=table,
        crease_stiffness=math.inf if k is None else k,
        calibration=calibration,
    )


def validate_elastic(E: float, nu: float, density: float, *, prefix: str = "") -> None:
    """Raise :class:`InputError` unless E, nu and density lie within :data:`corrugate.core.limits.LIMITS`
    (E in MPa, density in the internal unit, shown in g/cm^3)."""
    from corrugate.core.limits import check

    check("E", E, f"{prefix}E")
    check("nu", nu, f"{prefix}nu")
    check("density", density / G_PER_CM3, f"{prefix}density")


def validate_strength(strength: float, E: float, field: str = "yield_strength") -> None:
    """Raise :class:`InputError` unless the allowable stress ``strength`` (MPa) is a normal
    number with 0 < strength < E (MPa): a sheet that yields at a stress above its modulus would
    yield at a strain above 100 %."""
    from corrugate.core.limits import abnormal_reason

    allowed = f"0 < yield_strength < E = {E:g} MPa"
    reason = abnormal_reason(strength)
    if reason is not None:
        raise InputError(field, f"{strength!r} MPa", allowed, reason=reason)
    if not 0.0 < strength < E:
        raise InputError(field, f"{strength:g} MPa", allowed)


def _creep(where: str, E: float, entry: dict[str, Any] | None) -> CreepTable | None:
    """The ``creep`` table of a library entry: ``moduli`` (duration -> modulus, quantities
    with units), ``source`` and ``estimate``; each modulus at most E (MPa)."""
    from corrugate.core.limits import MAX_TEXT_CHARS

    if entry is None:
        return None
    moduli = entry.get("moduli") if isinstance(entry, dict) else None
    if not isinstance(moduli, dict) or not moduli:
        raise InputError(
            where + "creep",
            repr(entry)[:60],
            "a table with moduli = { DURATION = MODULUS, ... } and a source",
            reason="has no moduli table",
        )
    pairs = sorted(
        (parse_quantity(h, "h", where + "creep.moduli"), parse_quantity(m, "MPa", where + "creep"))
        for h, m in moduli.items()
    )
    for hours, modulus in pairs:
        if not 0 < modulus <= E:
            raise InputError(
                where + "creep.moduli",
                f"{modulus:g} MPa at {hours:g} h",
                f"0 < E_c <= E = {E:g} MPa",
            )
    return CreepTable(
        tuple(h for h, _ in pairs),
        tuple(m for _, m in pairs),
        _text(entry.get("source", ""), where + "creep.source", MAX_TEXT_CHARS),
        bool(entry.get("estimate", False)),
    )


def material_from_entry(key: str, entry: dict[str, Any], file: str = "materials.toml") -> Material:
    """The material of one table ``[key]`` of a materials file (the library's format, the
    module's text); :class:`InputError` naming ``file [key].FIELD``."""
    from corrugate.core.limits import MAX_NAME_CHARS, MAX_TEXT_CHARS, check

    where = f"{file} [{key}]."
    for name in ("E", "nu", "density"):
        if name not in entry:
            raise InputError(where + name, None, "a value", reason="is missing")
    E = parse_quantity(entry["E"], "MPa", where + "E")
    nu = parse_quantity(entry["nu"], "dimensionless", where + "nu")
    density = parse_quantity(entry["density"], "g/cm^3", where + "density") * G_PER_CM3
    validate_elastic(E, nu, density, prefix=where)
    thicknesses = tuple(
        check("thickness", parse_quantity(t, "mm", where + "thicknesses"), where + "thicknesses")
        for t in _array(entry.get("thicknesses", []), where + "thicknesses", "thicknesses")
    )
    default = entry.get("default_thickness")
    strength: float | None = None
    if "yield_strength" in entry:
        strength = parse_quantity(entry["yield_strength"], "MPa", where + "yield_strength")
        validate_strength(strength, E, where + "yield_strength")
    k = math.inf
    if "crease_stiffness" in entry:
        from corrugate.materials.calibrated import parse_crease_stiffness

        k = parse_crease_stiffness(entry["crease_stiffness"], where + "crease_stiffness")
    calibration = None
    cal = entry.get("calibration")
    if cal is not None:
        if not isinstance(cal, Mapping):
            raise InputError(where + "calibration", repr(cal)[:40], "a table")
        from corrugate.materials.calibrated import calibration_of

        calibration, measured = calibration_of(cal, E, where + "calibration.")
        if "crease_stiffness" not in entry:
            k = measured
    return Material(
        id=key,
        name=_text(entry.get("name", key), where + "name", MAX_NAME_CHARS),
        E=E,
        nu=nu,
        density=density,
        thicknesses=thicknesses,
        default_thickness=(
            check(
                "thickness",
                parse_quantity(default, "mm", where + "default_thickness"),
                where + "default_thickness",
            )
            if default is not None
            else (thicknesses[0] if thicknesses else None)
        ),
        category=_text(entry.get("category", ""), where + "category", MAX_NAME_CHARS),
        source=_text(entry.get("source", ""), where + "source", MAX_TEXT_CHARS),
        yield_strength=strength,
        creep=_creep(where, E, entry.get("creep")),
        crease_stiffness=k,
        calibration=calibration,
        aliases=tuple(
            _text(a, where + "aliases", MAX_NAME_CHARS).strip().lower()
            for a in _array(entry.get("aliases", []), where + "aliases", "names")
        ),
    )


def _array(value: Any, field: str, what: str) -> list[Any]:
    """``value`` when it is an array of a materials file, else one :class:`InputError` line
    naming ``field``."""
    if not isinstance(value, list):
        raise InputError(field, repr(value)[:60], f"an array of {what}", reason="is not an array")
    return value


def _text(value: Any, field: str, limit: int) -> str:
    """``value`` when it is a string of at most ``limit`` characters, else one
    :class:`InputError` line naming ``field``."""
    from corrugate.core.limits import check_text

    if not isinstance(value, str):
        raise InputError(field, repr(value)[:60], "a string", reason="is not a string")
    return check_text(field, value, limit)


@lru_cache(maxsize=1)
def library_entries() -> dict[str, dict[str, Any]]:
    """The bundled library's tables as written in ``data/materials.toml`` (read once): what a
    user's materials file extends (:mod:`corrugate.materials.user`)."""
    path = Path(__file__).parents[1] / "data" / "materials.toml"
    if path.is_file():  # an installed or source tree (importlib.resources costs ~20 ms to import)
        text = path.read_text("utf-8")
    else:  # e.g. a zipped install
        from importlib import resources

        text = resources.files("corrugate").joinpath("data/materials.toml").read_text("utf-8")
    return tomllib.loads(text)


@cache
def _bundled(key: str) -> Material:
    """The bundled library's material ``key`` (an id of ``data/materials.toml``), built once."""
    return material_from_entry(key, library_entries()[key])


@lru_cache(maxsize=1)
def library() -> dict[str, Material]:
    """The bundled material library, keyed by id (read once from ``data/materials.toml``)."""
    return {key: _bundled(key) for key in library_entries()}


def creep_materials() -> list[str]:
    """The ids of the library materials with creep data."""
    return [key for key, m in library().items() if m.creep is not None]


class AmbiguousNameError(InputError):
    """A material name that is an alias of several materials (``pet``): the message lists them."""


def get_material(material_id: str, user: Mapping[str, Material] | None = None) -> Material:
    """The material ``material_id`` (case-insensitive): from ``user`` (a spec's own materials,
    :func:`corrugate.materials.user.spec_materials`; None: the user's config folder's,
    :func:`corrugate.materials.user.user_materials`), else the library; else the one material
    whose ``aliases`` hold the name. :class:`AmbiguousNameError` listing them when the name is an
    alias of several (``pet``: the PET films), :class:`UnknownNameError` when nothing has it."""
    from corrugate.materials.user import user_materials

    own = user_materials() if user is None else user
    key = material_id.strip().lower()
    if key in own:
        return own[key]
    if key in library_entries():  # the one material built, not the whole library (issue 39)
        return _bundled(key)
    lib = library()
    every = {**lib, **own}
    matches = sorted(k for k, m in every.items() if key in m.aliases)
    if len(matches) == 1:
        return every[matches[0]]
    if matches:
        names = ", ".join(f"{k} ({every[k].name})" for k in matches)
        raise AmbiguousNameError(
            "material",
            repr(material_id),
            f"one of {', '.join(matches)}: {names}",
            reason=f"names {len(matches)} materials",
        )
    raise UnknownNameError("material", material_id, list(every))


def inline_material(
    E: object, nu: object, density: object, *, name: str = "custom", thickness: object = None
) -> Material:
    """A user-defined material; plain numbers are read as MPa, -, g/cm^3 and mm."""
    E_mpa = parse_quantity(E, "MPa", "E")
    nu_f = parse_quantity(nu, "dimensionless", "nu")
    rho = parse_quantity(density, "g/cm^3", "density") * G_PER_CM3
    validate_elastic(E_mpa, nu_f, rho)
    t = None if thickness is None else parse_quantity(thickness, "mm", "thickness")
    return Material(
        id=name,
        name=name,
        E=E_mpa,
        nu=nu_f,
        density=rho,
        thicknesses=() if t is None else (t,),
        default_thickness=t,
    )
