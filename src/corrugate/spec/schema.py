"""Design specs: TOML files validated with pydantic, quantities with units read by pint.

A spec states what a part must do (docs/theory.md section 5); :func:`load_spec` reads one from a TOML
file and :func:`parse_spec` from a dict. Every quantity may carry units (``"48 mm"``,
``"80 mN*m^2"``, ``"84 deg"``). A plain number is read in the field's internal unit only where
that unit cannot be mistaken: lengths (mm), angles (deg), counts and ratios (:data:`PLAIN_UNITS`).
Every other quantity (a rigidity, stiffness, load, modulus, density, mass) must carry its unit:
``min = 80`` for a rigidity is refused (:class:`MissingUnitError`), because 80 N mm^2 and the
80 mN m^2 a user most likely meant differ 1000-fold. The validated :class:`Spec` holds plain
floats in the internal units (mm, deg, N mm^2, N mm, N/mm, N, MPa, g).

Anything wrong (an unknown key, a wrong unit, min > max, a negative size, an unknown material)
raises :class:`SpecError`, an :class:`~corrugate.core.errors.InputError` whose ``field`` is the TOML path
of the offending value (``constraints.side.min``, ``constraints.flexural_rigidity[0].eta``), with
the value and what is allowed. The CLI prints it as one line and exits with code 2.

Example (the paper's case study, ``examples/blimp_gripper.toml``)::

    name = "blimp-gripper"
    model = "refined"
    tolerances = "none"  # the paper's reproduction: the nominal certificate
    [material]
    name = "dura-lar"
    thickness = "0.125 mm"
    [layout]
    shape = "square"
    [variables]
    W = { min = "1 mm", max = "30 mm", step = "1 mm" }
    n = { min = 1, max = 200 }
    alpha = { min = "1 deg", max = "120 deg", step = "1 deg" }
    [constraints]
    sheet_max = "250 mm"
    side = { min = "48 mm", max = "60 mm" }
    thickness = { min = "10 mm", max = "12.5 mm" }
    flexural_rigidity = [{ min = "80 mN*m^2", eta = "0 deg" }]
    [objective]
    minimize = "mass"
"""

# No ``from __future__ import annotations`` here: pydantic reads each model's annotations as the
# objects they are instead of evaluating their text (importing this module after its libraries
# and its corrugate imports: 0.0158 s of CPU against 0.0214 s with the future import, medians of
# 11 interleaved runs, 16:19 UTC; issue 39).
import math
import tomllib
import typing
from collections.abc import Callable, Mapping
from pathlib import Path
from typing import TYPE_CHECKING, Annotated, Any, Literal

from pydantic import (
    AfterValidator,
    BaseModel,
    BeforeValidator,
    ConfigDict,
    GetJsonSchemaHandler,
    PrivateAttr,
    ValidationError,
    model_validator,
)
from pydantic.json_schema import JsonSchemaValue
from pydantic_core import CoreSchema, PydanticCustomError

from corrugate.core.errors import InputError
from corrugate.core.limits import (
    LIMITS,
    MAX_COUNTS,
    MAX_DEPTH,
    MAX_NAME_CHARS,
    MAX_SPEC_BYTES,
    MAX_TEXT_CHARS,
    abnormal_reason,
    bracket_depth,
    check_depth,
    check_grid,
    check_integer,
    check_items,
    check_text,
)
from corrugate.core.text import printable
from corrugate.core.units import parse_quantity
from corrugate.materials.library import G_PER_CM3, Material
from corrugate.mechanics.behaviours import deflection_tests, either, load_cases, support_names
from corrugate.mechanics.load_cases import DEFAULT_SAFETY_FACTOR
from corrugate.names import (
    DEFAULT_HOLE_SHAPE,
    DEFAULT_LAYOUT,
    DEFAULT_MODEL,
    DEFAULT_SUPPORT,
    HoleShape,
    LayoutShape,
    ModelName,
    StiffnessName,
)

if TYPE_CHECKING:
    from corrugate.geometry.holes import Hole

__all__ = [
    "NO_TOLERANCES",
    "PLAIN_UNITS",
    "STIFFNESS_KINDS",
    "ConstraintsSpec",
    "HoleSpec",
    "LayoutSpec",
    "MaterialSpec",
    "MissingUnitError",
    "ObjectiveSpec",
    "Range",
    "RobustSpec",
    "Spec",
    "SpecError",
    "StiffnessSpec",
    "TolerancesSpec",
    "Variable",
    "VariablesSpec",
    "load_spec",
    "load_spec_text",
    "parse_spec",
    "parse_spec_text",
    "unit_example",
]

#: Stiffness quantities a spec may bound or maximise, with their internal unit.
STIFFNESS_KINDS: dict[StiffnessName, str] = {
    "flexural_rigidity": "N*mm^2",  # EI(eta)
    "bending_stiffness": "N*mm",  # D(eta)
    "inplane_stiffness": "N/mm",  # K(eta)
}

#: Largest number of creases a spec may allow.
N_MAX = int(LIMITS["n"].hi)
#: Longest list (thicknesses, vertices, holes) in a spec.
MAX_LIST_ITEMS = 10_000


class SpecError(InputError):
    """A spec value is invalid; ``field`` is its TOML path (e.g. ``constraints.side.min``)."""

    def __init__(self, path: str, value: Any, allowed: str, *, reason: str = "is invalid"):
        super().__init__(path, value, allowed, reason=reason)


class MissingUnitError(SpecError):
    """A quantity whose unit is not mm or deg was given as a plain number: one line saying how
    to write it, e.g. ``constraints.flexural_rigidity[0].min = 80 has no unit: write it with one,
    e.g. "80 mN*m^2" (or "80 N*mm^2")``."""

    def __init__(self, path: str, value: str, example: str):
        super().__init__(
            path, value, f"a quantity with a unit, e.g. {example}", reason="has no unit"
        )
        self.args = (f"{path} = {value} has no unit: write it with one, e.g. {example}",)


# -- quantities --------------------------------------------------------------------------------

#: Internal units in which a spec value may be a plain number: lengths, angles and pure numbers
#: (counts, ratios). A plain number for any other quantity is refused (:class:`MissingUnitError`).
PLAIN_UNITS = frozenset({"mm", "deg", "dimensionless"})

#: How to write a quantity of each internal unit that needs one: the unit a user most likely
#: means first (the web form and the docs show it), then another one.
_UNIT_EXAMPLES: dict[str, tuple[str, ...]] = {
    "N*mm^2": ("mN*m^2", "N*mm^2"),
    "N*mm": ("N*mm", "mN*m"),
    "N/mm": ("N/mm", "kN/m"),
    "N": ("N",),
    "g": ("g",),
    "MPa": ("MPa", "GPa"),
    "g/cm^3": ("g/cm^3", "kg/m^3"),
    "h": ("h", "day", "week"),
}


def _plain_number(value: Any) -> str | None:
    """``value`` as its text when it is a plain number (a TOML/JSON number or a string holding
    only one), else None."""
    if isinstance(value, bool):
        return None
    if isinstance(value, int | float):
        return str(value)
    if isinstance(value, str):
        try:
            float(value)
        except ValueError:
            return None
        return value.strip()
    return None


def unit_example(number: str, unit: str) -> str:
    """How to write ``number`` with a unit compatible with ``unit``, e.g. ``"80 mN*m^2" (or "80
    N*mm^2")``."""
    first, *others = _UNIT_EXAMPLES.get(unit, (unit,))
    text = f'"{number} {first}"'
    return text + "".join(f' (or "{number} {u}")' for u in others)


def _quantity(
    unit: str,
    *,
    lo: float | None = None,
    lo_open: bool = True,
    hi: float | None = None,
    hi_open: bool = True,
    scale: float = 1.0,
    shown: str | None = None,
) -> Callable[[Any], float]:
    """A pydantic before-validator reading a quantity in ``unit`` and checking its range; a plain
    number is refused unless ``unit`` is in :data:`PLAIN_UNITS`."""
    label = unit if shown is None else shown
    tail = f" {label}" if label else ""
    plain_ok = unit in PLAIN_UNITS
    parts = []
    if lo is not None:
        parts.append(f"{'>' if lo_open else '>='} {lo:g}{tail}")
    if hi is not None:
        parts.append(f"{'<' if hi_open else '<='} {hi:g}{tail}")
    allowed = " and ".join(parts) if parts else f"a quantity in {label}"

    def validate(value: Any) -> float:
        number = None if plain_ok else _plain_number(value)
        if number is not None:
            raise PydanticCustomError(
                "unit",
                "{number} has no unit",
                {"number": number, "example": unit_example(number, label)},
            )
        try:
            x = parse_quantity(value, unit, "value")
        except InputError as exc:
            raise PydanticCustomError(
                "quantity", "{reason}", {"reason": exc.reason, "allowed": exc.allowed}
            ) from None
        reason = abnormal_reason(x)
        if reason is not None:
            raise PydanticCustomError(
                "quantity", "{reason}", {"reason": reason, "allowed": allowed}
            )
        bad = False
        if lo is not None:
            bad |= x <= lo if lo_open else x < lo
        if hi is not None:
            bad |= x >= hi if hi_open else x > hi
        if bad:
            raise PydanticCustomError(
                "quantity", "{reason}", {"reason": "is out of range", "allowed": allowed}
            )
        return x * scale

    return validate


def _limited(key: str, unit: str, **kw: Any) -> Callable[[Any], float]:
    """:func:`_quantity` with the bounds of :data:`corrugate.core.limits.LIMITS` ``[key]``."""
    lim = LIMITS[key]
    return _quantity(unit, lo=lim.lo, lo_open=lim.open_lo, hi=lim.hi, hi_open=lim.open_hi, **kw)


Length = Annotated[
    float, BeforeValidator(_quantity("mm", lo=0.0, hi=LIMITS["length"].hi, hi_open=False))
]
FacetWidth = Annotated[float, BeforeValidator(_limited("W", "mm"))]
SheetThickness = Annotated[float, BeforeValidator(_limited("thickness", "mm"))]
FoldAngle = Annotated[float, BeforeValidator(_quantity("deg", lo=0.0, hi=180.0))]
#: A name the answer prints (the spec's, a material's): its control characters removed, so an
#: escape sequence in a spec never reaches the terminal (corrugate.core.text.printable).
Name = Annotated[str, AfterValidator(printable)]
#: A direction eta: -360 to 360 deg (LIMITS["eta"]; docs/spec.md, "Directions").
Direction = Annotated[float, BeforeValidator(_limited("eta", "deg"))]
MassQ = Annotated[
    float, BeforeValidator(_quantity("g", lo=0.0, hi=LIMITS["mass"].hi, hi_open=False))
]
Modulus = Annotated[float, BeforeValidator(_limited("E", "MPa"))]
Poisson = Annotated[float, BeforeValidator(_limited("nu", "dimensionless", shown=""))]
#: How long a load is held (hours; > 0, with its unit: "1 week", "168 h"): a sustained load
#: case, read at the material's creep modulus (docs/load_cases.md section 11).
Duration = Annotated[float, BeforeValidator(_quantity("h", lo=0.0))]
Density = Annotated[
    float, BeforeValidator(_limited("density", "g/cm^3", scale=G_PER_CM3, shown="g/cm^3"))
]


def _counter(key: str, name: str) -> Callable[[Any], int]:
    """A pydantic before-validator reading an integer within ``LIMITS[key]`` (``name`` in the
    allowed range it reports). Compared as an int: a huge integer neither overflows a float nor
    reaches numpy."""
    lim = LIMITS[key]
    allowed = f"an integer {lim.lo:g} <= {name} <= {lim.hi:g}"

    def validate(value: Any) -> int:
        if isinstance(value, bool) or not isinstance(value, int | float | str):
            raise PydanticCustomError(
                "count", "{reason}", {"reason": "is not an integer", "allowed": allowed}
            )
        if isinstance(value, int):
            i = value
        else:
            try:
                f = float(value)
            except ValueError:
                f = math.nan
            if not (math.isfinite(f) and f.is_integer()):
                raise PydanticCustomError(
                    "count", "{reason}", {"reason": "is not an integer", "allowed": allowed}
                )
            i = int(f)
        if not lim.lo <= i <= lim.hi:
            raise PydanticCustomError(
                "count", "{reason}", {"reason": "is out of range", "allowed": allowed}
            )
        return i

    return validate


_count = _counter("n", "n")

Count = Annotated[int, BeforeValidator(_count)]

_length = _limited("thickness", "mm")


def _thicknesses(value: Any) -> Any:
    """One thickness, a list of them (each checked, the index in the path) or ``"all"``."""
    if value is None or value == "all":
        return value
    if isinstance(value, list):
        if not value:
            raise PydanticCustomError(
                "quantity", "{reason}", {"reason": "is empty", "allowed": "at least one thickness"}
            )
        out = []
        for i, item in enumerate(value):
            try:
                out.append(_length(item))
            except PydanticCustomError as exc:
                ctx = exc.context or {}
                raise PydanticCustomError(
                    "quantity",
                    "{reason}",
                    {
                        "reason": f"has item [{i}] = {item!r} that {ctx.get('reason')}",
                        "allowed": ctx.get("allowed"),
                    },
                ) from None
        return out
    return _length(value)


Thicknesses = Annotated[float | list[float] | Literal["all"] | None, BeforeValidator(_thicknesses)]


class _Strict(BaseModel):
    """The spec's sections: unknown keys refused, values frozen. Each model's validator is built
    on its first use (``defer_build``), not as its class is defined: a spec is validated by
    :class:`Spec`'s, built with the sections inside it, so the sections' own validators (about
    twenty) are never built on the way to an answer (``load_spec`` of the case study after its
    libraries' import: 0.223 s of CPU against 0.231 s, medians of 15 interleaved runs; issue
    39). The same schema validates, so the same values and errors come out. The sections'
    default instances (a field's default, :data:`NO_TOLERANCES`) are made with
    ``model_construct`` from values already valid, so that defining them builds no validator
    either: made by validation, they built nine at import (``import corrugate.spec.schema``
    0.032 s of CPU against 0.020 s, its first ``load_spec`` 0.026 s against 0.031 s, after its
    libraries' import, 4 runs each, 15:44 UTC). Equal to the validated ones: the same values,
    the same fields set (tests/spec/test_schema.py)."""

    model_config = ConfigDict(extra="forbid", frozen=True, defer_build=True)


# -- sections ----------------------------------------------------------------------------------


class Range(_Strict):
    """Lower and/or upper bound of a length (mm)."""

    min: Length | None = None
    max: Length | None = None


class Variable(_Strict):
    """Bounds of a continuous design variable (mm or deg) and an optional grid ``step``.

    Without ``step`` the variable is continuous on [min, max]; with it, it takes the values
    min, min + step, ... up to max.
    """

    min: float
    max: float
    step: float | None = None


class LengthVariable(Variable):
    min: FacetWidth
    max: FacetWidth
    step: Length | None = None


class AngleVariable(Variable):
    min: FoldAngle
    max: FoldAngle
    step: FoldAngle | None = None


class CountVariable(_Strict):
    """Bounds of the (integer) number of creases n."""

    min: Count = 1
    max: Count = 200


class VariablesSpec(_Strict):
    """Bounds of the design variables, shared by both layers."""

    W: LengthVariable = LengthVariable.model_construct(min=1.0, max=50.0)
    n: CountVariable = CountVariable.model_construct()
    alpha: AngleVariable = AngleVariable.model_construct(min=10.0, max=170.0)


YieldStrength = Annotated[float, BeforeValidator(_limited("E", "MPa"))]

#: The largest finite crease stiffness a spec takes (N mm/(rad mm)): far stiffer than any sheet's
#: facets (D = E t^3 / 12 (1 - nu^2) is 0.5 N mm for 0.125 mm Dura-Lar), "inf" above it.
CREASE_STIFFNESS_MAX = 1e6
_CREASE_ALLOWED = f'> 0 and <= {CREASE_STIFFNESS_MAX:g} N*mm/(rad*mm), or "inf" (rigid)'


def _crease_stiffness(value: Any) -> float:
    """A crease's rotational stiffness per unit length (N mm/(rad mm); docs/calibration.md 4):
    ``"0.1 N*mm/(rad*mm)"`` or ``"inf"`` (rigid); a plain number is refused for its unit."""
    if isinstance(value, str) and value.strip().lower() in ("inf", "rigid"):
        return math.inf
    number = _plain_number(value)
    if number is not None:
        raise PydanticCustomError(
            "unit",
            "{number} has no unit",
            {"number": number, "example": f'"{number} N*mm/(rad*mm)"'},
        )
    try:
        k = parse_quantity(value, "N", "value")
    except InputError as exc:
        raise PydanticCustomError(
            "quantity", "{reason}", {"reason": exc.reason, "allowed": _CREASE_ALLOWED}
        ) from None
    if not (0.0 < k <= CREASE_STIFFNESS_MAX):
        raise PydanticCustomError(
            "quantity", "{reason}", {"reason": "is out of range", "allowed": _CREASE_ALLOWED}
        )
    return k


CreaseStiffness = Annotated[float, BeforeValidator(_crease_stiffness)]
#: The angle a fold opens by after it is released (deg; docs/calibration.md 4): within +-30 deg.
Springback = Annotated[
    float, BeforeValidator(_quantity("deg", lo=-30.0, hi=30.0, lo_open=False, hi_open=False))
]


class MaterialSpec(_Strict):
    """A library material (``name``) or an inline one (``E``, ``nu``, ``density``, ``thickness``),
    with an optional ``yield_strength`` (MPa; for a library material it replaces the library's).

    ``thickness``: one quantity, a list of candidate thicknesses, ``"all"`` (every thickness the
    library sells) or nothing (the material's default thickness).

    An inline material may state its creases' rotational stiffness ``crease_stiffness``
    (N mm/(rad mm), ``"inf"`` rigid, the default) and its folds' ``springback`` (deg, the angle
    a fold opens by after it is released; 0 the default): the models take the creases as
    springs, the certificate and ``verify`` the folds at alpha + springback (docs/calibration.md
    9). A library or calibrated material's come from its materials file (docs/calibration.md 6).
    """

    name: Name = "custom"
    thickness: Thicknesses = None
    E: Modulus | None = None
    nu: Poisson | None = None
    density: Density | None = None
    yield_strength: YieldStrength | None = None
    crease_stiffness: CreaseStiffness | None = None
    springback: Springback | None = None


Coordinate = Annotated[
    float,
    BeforeValidator(
        _quantity(
            "mm",
            lo=LIMITS["coordinate"].lo,
            hi=LIMITS["coordinate"].hi,
            lo_open=False,
            hi_open=False,
        )
    ),
]


class HoleSpec(_Strict):
    """An inner cut-out (:mod:`corrugate.geometry.holes`): a ``circle`` of ``diameter`` or a ``polygon`` of
    ``vertices`` (relative to ``center``), placed at ``center``; lengths in mm from the centre of
    the layout's bounding box, x across layer 1's creases, y along them."""

    shape: HoleShape = DEFAULT_HOLE_SHAPE
    diameter: Length | None = None
    center: tuple[Coordinate, Coordinate] = (0.0, 0.0)
    vertices: list[tuple[Coordinate, Coordinate]] | None = None


class LayoutSpec(_Strict):
    """The plan outline: ``square`` | ``rectangle`` | ``circle`` | ``polygon`` (with vertices),
    and its ``holes``, e.g. ``holes = [{ shape = "circle", diameter = "6 mm", center = ["0 mm",
    "0 mm"] }]``. A layout with holes needs a minimum size (``constraints.side.min``,
    ``diameter.min`` or ``side_x.min`` and ``side_y.min``): every hole must fit the smallest
    panel allowed, hence every larger one (not supported for polygon outlines)."""

    shape: LayoutShape = DEFAULT_LAYOUT
    vertices: list[tuple[float, float]] | None = None
    holes: list[HoleSpec] = []

    def hole_list(self) -> "tuple[Hole, ...]":
        """The holes as :class:`~corrugate.geometry.holes.Hole` values (mm); errors name
        ``layout.holes[i].<key>``."""
        if not self.holes:
            return ()
        from corrugate.geometry.holes import Hole  # a layout with holes only

        out = []
        for i, h in enumerate(self.holes):
            where = f"layout.holes[{i}]"
            if h.shape == "circle" and h.vertices is not None:
                raise SpecError(
                    f"{where}.vertices",
                    "[...]",
                    "only for shape = 'polygon'",
                    reason="does not apply",
                )
            if h.shape == "polygon" and h.diameter is not None:
                raise SpecError(
                    f"{where}.diameter",
                    f"{h.diameter:g} mm",
                    "only for shape = 'circle'",
                    reason="does not apply",
                )
            key = "diameter" if h.shape == "circle" else "vertices"
            if getattr(h, key) is None:
                raise SpecError(f"{where}.{key}", None, "a value", reason="is missing")
            try:
                out.append(
                    Hole(
                        h.shape,
                        h.center,
                        diameter=h.diameter or 0.0,
                        vertices=tuple(h.vertices or ()),
                    )
                )
            except InputError as exc:
                raise SpecError(
                    f"{where}.{exc.field}", exc.value, exc.allowed, reason=exc.reason
                ) from None
        return tuple(out)


def _check_holes(spec: "Spec") -> None:
    """Every hole of the layout fits the smallest panel the size constraints allow."""
    lay = spec.layout
    holes = lay.hole_list()
    if not holes:
        return
    if lay.shape == "polygon":
        raise SpecError(
            "layout.holes",
            f"{len(holes)} hole(s)",
            "holes with a square, rectangle or circle layout in a design spec "
            "(a polygon's fit is not monotone in its size; use analyze or pattern)",
            reason="is not supported for a polygon layout",
        )
    c = spec.constraints
    keys = {"square": ("side", "side"), "circle": ("diameter", "diameter")}.get(
        lay.shape, ("side_x", "side_y")
    )
    sizes = []
    for key in keys:
        r: Range | None = getattr(c, key)
        if r is None or r.min is None:
            raise SpecError(
                f"constraints.{key}.min",
                None,
                "a minimum size, to check that layout.holes fit every panel allowed",
                reason="is missing",
            )
        sizes.append(r.min)
    from corrugate.geometry.holes import check_holes
    from corrugate.geometry.layouts import make_layout

    Lx, Ly = sizes
    outline = make_layout(lay.shape).plan_outline(Lx, Ly)
    try:
        check_holes(holes, outline, Lx, Ly, "layout.holes")
    except InputError as exc:
        raise SpecError(exc.field, exc.value, exc.allowed, reason=exc.reason) from None


def _stiffness_validator(kind: StiffnessName) -> Callable[[Any], float]:
    return _quantity(STIFFNESS_KINDS[kind], lo=0.0, hi=LIMITS["stiffness"].hi, hi_open=False)


class _Choice:
    """A name one of ``names()`` (the registry's when the value is read or the schema made): a
    pydantic before-validator giving the error a ``Literal`` gives, and the JSON Schema of an
    ``enum``."""

    def __init__(self, names: Callable[[], tuple[str, ...]]) -> None:
        self.names = names

    def __call__(self, value: Any) -> Any:
        names = self.names()
        if not (isinstance(value, str) and value in names):
            raise PydanticCustomError(
                "literal_error", "Input should be {expected}", {"expected": either(names)}
            )
        return value

    def __get_pydantic_json_schema__(
        self, core_schema: CoreSchema, handler: GetJsonSchemaHandler
    ) -> JsonSchemaValue:
        return {"enum": list(self.names()), "type": "string"}


#: A support condition, by name (``free``, ``frame`` or any other registered one:
#: :func:`corrugate.mechanics.behaviours.support_names`).
_SUPPORTS = _Choice(support_names)
Support = Annotated[str, BeforeValidator(_SUPPORTS), _SUPPORTS]


#: What a stiffness bound's ``test = "pure"`` names: pure bending, the panel's own rigidity (EI
#: and D: the default; not a registered load case).
PURE = "pure"


def _stiffness_tests() -> tuple[str, ...]:
    """The tests a stiffness bound may name (docs/load_cases.md): ``pure`` and every registered
    load case (:func:`corrugate.mechanics.behaviours.load_cases`). ``pure`` (EI and D) and the
    in-plane test of the support's own K (``platens``) keep the meaning a bound without
    ``test`` has; ``wheel`` (K of a circle) is a disc's radial stiffness (section 9)."""
    return (PURE, *(b.name for b in load_cases()))


def _deflection_tests() -> tuple[str, ...]:
    """The load cases a deflection or strength bound may name
    (:func:`corrugate.mechanics.behaviours.deflection_tests`)."""
    return tuple(b.name for b in deflection_tests())


_STIFFNESS_TESTS = _Choice(_stiffness_tests)
_DEFLECTION_TESTS = _Choice(_deflection_tests)
#: A test a stiffness bound may name, by name.
StiffnessTest = Annotated[str, BeforeValidator(_STIFFNESS_TESTS), _STIFFNESS_TESTS]
#: A load case a deflection or strength bound may name, by name.
DeflectionTest = Annotated[str, BeforeValidator(_DEFLECTION_TESTS), _DEFLECTION_TESTS]


class StiffnessSpec(_Strict):
    """A lower bound ``min`` on a stiffness at direction ``eta`` (deg from layer 1's creases),
    under ``support`` (``free`` sides, a rigid ``frame`` or another registered support
    condition; default: the spec's ``support``), as measured in ``test`` (default: ``pure``
    bending for EI and D, ``platens`` for K; docs/load_cases.md), under a load held for
    ``duration`` (hours; None: short-term; docs/load_cases.md section 11)."""

    min: float
    eta: Direction = 0.0
    support: Support | None = None
    test: StiffnessTest | None = None
    duration: Duration | None = None


class RigiditySpec(StiffnessSpec):
    min: Annotated[float, BeforeValidator(_stiffness_validator("flexural_rigidity"))]


class BendingSpec(StiffnessSpec):
    min: Annotated[float, BeforeValidator(_stiffness_validator("bending_stiffness"))]


class InPlaneSpec(StiffnessSpec):
    min: Annotated[float, BeforeValidator(_stiffness_validator("inplane_stiffness"))]


class BucklingSpec(_Strict):
    """A lower bound ``min`` (N) on the in-plane compressive load at which the panel buckles
    along ``eta`` (0 or 90 deg, required): the plate lower bound of :mod:`corrugate.mechanics.buckling`,
    under a load held for ``duration`` (hours; None: short-term)."""

    min: Annotated[float, BeforeValidator(_quantity("N", lo=0.0))]
    eta: Direction
    duration: Duration | None = None


class DeflectionSpec(_Strict):
    """At most ``max`` (mm) of deflection under ``load`` (N) in the load case ``test``
    (docs/load_cases.md): supported over ``span`` (mm; cantilever: its free length; default and
    platens: the panel's length along ``eta``), along ``eta`` (deg), under ``support`` (default:
    the spec's), the load held for ``duration`` (hours; None: short-term; docs/load_cases.md
    section 11), the load and support lines ``bearing`` mm wide (None: 10 mm,
    :data:`corrugate.mechanics.capacity.DEFAULT_BEARING`; docs/load_cases.md 10.5)."""

    test: DeflectionTest
    load: Annotated[float, BeforeValidator(_quantity("N", lo=0.0, hi=LIMITS["load"].hi))]
    max: Annotated[float, BeforeValidator(_quantity("mm", lo=0.0, hi=LIMITS["length"].hi))]
    span: Length | None = None
    eta: Direction = 0.0
    support: Support | None = None
    duration: Duration | None = None
    bearing: Length | None = None


class StrengthSpec(_Strict):
    """The panel holds ``load`` (N) in the load case ``test`` (over ``span`` mm, along ``eta`` 0
    or 90 deg, under ``support``) with every facet's peak stress times the spec's
    ``safety_factor`` at or below its material's yield strength (docs/load_cases.md, section 6),
    its load and support lines ``bearing`` mm wide (None: 10 mm; section 10.5)."""

    test: DeflectionTest
    load: Annotated[float, BeforeValidator(_quantity("N", lo=0.0, hi=LIMITS["load"].hi))]
    span: Length | None = None
    eta: Direction = 0.0
    support: Support | None = None
    bearing: Length | None = None


class MassBound(_Strict):
    """An upper bound on the mass (g)."""

    max: MassQ


class ConstraintsSpec(_Strict):
    """Fabrication, size and behaviour constraints (docs/theory.md section 5).

    ``side`` bounds the folded side L of a square; ``diameter`` that of a circle; ``side_x`` and
    ``side_y`` the folded extents Lx and Ly of a rectangle or of a polygon's bounding box.
    ``thickness`` bounds the folded thickness t_d. ``sheet_max`` bounds the flat blank (n + 1) W
    and every facet length L_j.
    """

    sheet_max: Length | None = None
    side: Range | None = None
    diameter: Range | None = None
    side_x: Range | None = None
    side_y: Range | None = None
    thickness: Range | None = None
    flexural_rigidity: list[RigiditySpec] = []
    bending_stiffness: list[BendingSpec] = []
    inplane_stiffness: list[InPlaneSpec] = []
    buckling_load: list[BucklingSpec] = []
    deflection: list[DeflectionSpec] = []
    strength: list[StrengthSpec] = []
    mass: MassBound | None = None


class ObjectiveSpec(_Strict):
    """``minimize = "mass"`` (the default when neither is given) or ``maximize = <stiffness
    kind>`` at ``eta`` (then a ``constraints.mass`` budget is usually wanted)."""

    minimize: Literal["mass"] | None = None
    maximize: StiffnessName | None = None
    eta: Direction = 0.0
    support: Support | None = None


def _fraction(value: Any) -> float:
    """A relative tolerance: ``"5%"`` or ``0.05``; 0 <= x < 1."""
    try:
        x = (
            float(value[:-1]) / 100
            if isinstance(value, str) and value.strip().endswith("%")
            else (float(value))
        )
    except (TypeError, ValueError):
        raise PydanticCustomError(
            "quantity",
            "{reason}",
            {"reason": "cannot be read", "allowed": "a fraction such as 0.05 or '5%'"},
        ) from None
    if not 0 <= x < 1:
        raise PydanticCustomError(
            "quantity",
            "{reason}",
            {"reason": "is out of range", "allowed": "0 <= tolerance < 100 %"},
        )
    return x


Fraction = Annotated[float, BeforeValidator(_fraction)]
Probability = Annotated[
    float, BeforeValidator(_quantity("dimensionless", lo=0.0, hi=1.0, shown=""))
]


class RobustSpec(_Strict):
    """Ask for a design that still meets every bound with ``probability`` under manufacturing
    and material tolerances (one-sigma: W in mm, alpha in deg, t and E relative)."""

    probability: Probability = 0.9
    W: Annotated[float, BeforeValidator(_limited("W_tol", "mm"))] = 0.1
    alpha: Annotated[float, BeforeValidator(_limited("alpha_tol", "deg"))] = 2.0
    t: Fraction = 0.05
    E: Fraction = 0.10
    samples: Annotated[int, BeforeValidator(_counter("samples", "samples"))] = 4000
    seed: Annotated[int, BeforeValidator(_counter("seed", "seed"))] = 0


class TolerancesSpec(_Strict):
    """Worst-case half-widths the certificate covers (docs/tolerances.md): every part whose fold
    angles are within +-``alpha`` (deg) and facet widths within +-``W`` (mm) of the design's,
    on a sheet whose thickness and Young's modulus are within +-``t`` and +-``E`` (relative) of
    the nominal ones, meets every behavioural bound. The defaults describe hand folding on a
    hobby cutter with a datasheet's sheet (each a stated assumption, docs/tolerances.md);
    ``tolerances = "none"`` (all zero) is the nominal certificate of the paper's reproduction."""

    alpha: Annotated[float, BeforeValidator(_limited("alpha_worst", "deg"))] = 3.0
    W: Annotated[float, BeforeValidator(_limited("W_worst", "mm"))] = 0.1
    t: Fraction = 0.05
    E: Fraction = 0.10

    @property
    def nominal(self) -> bool:
        """Whether every half-width is 0 (the nominal certificate)."""
        return not (self.alpha or self.W or self.t or self.E)


#: ``tolerances = "none"``: the nominal certificate (every half-width 0).
NO_TOLERANCES = TolerancesSpec.model_construct(alpha=0.0, W=0.0, t=0.0, E=0.0)


def _tolerances(value: Any) -> Any:
    """``"none"`` (any case) as :data:`NO_TOLERANCES`; a table as itself (validated by
    :class:`TolerancesSpec`); anything else refused in one line."""
    if isinstance(value, str) and value.strip().lower() == "none":
        return NO_TOLERANCES
    if not isinstance(value, Mapping | TolerancesSpec):
        raise PydanticCustomError(
            "quantity",
            "{reason}",
            {
                "reason": "is not a table or 'none'",
                "allowed": "a table { alpha, W, t, E } or 'none'",
            },
        )
    return value


Tolerances = Annotated[TolerancesSpec, BeforeValidator(_tolerances)]


#: 1 to 100, both included (the reference says 1-100; 100 was refused as "< 100" before).
SafetyFactor = Annotated[
    float,
    BeforeValidator(
        _quantity("dimensionless", lo=1.0, lo_open=False, hi=100.0, hi_open=False, shown="")
    ),
]

#: The narrowest facet anyone folds by default (mm; docs/fabrication.md, "What the solve asks of
#: the making").
DEFAULT_MIN_FACET_MM = 3.0
#: The thickest sheet for its facet by default, t / W (docs/fabrication.md): the models are
#: checked against unit-cell FE up to t / W = 0.02 and Eby to 0.06, and the thick-sheet warning
#: starts at (t/W)(90/alpha)^2 = 0.05.
DEFAULT_MAX_T_OVER_W = 0.05
ThicknessRatio = Annotated[
    float, BeforeValidator(_quantity("dimensionless", lo=0.0, hi=1.0, hi_open=False, shown=""))
]


def _machine(value: Any) -> str:
    """A machine profile's name (``corrugate.core.cutters.get_cutter``) or ``"none"``."""
    from corrugate.core.cutters import get_cutter

    if not isinstance(value, str):
        raise PydanticCustomError(
            "quantity",
            "{reason}",
            {"reason": "is not a name", "allowed": "a machine such as 'cameo4-12x12' or 'none'"},
        )
    if value.strip().lower() == "none":
        return "none"
    try:
        return get_cutter(value).name
    except InputError as exc:
        raise PydanticCustomError(
            "quantity", "{reason}", {"reason": exc.reason, "allowed": exc.allowed}
        ) from None


MachineName = Annotated[str, BeforeValidator(_machine)]


#: How a crease kind or the band's marks reach the machine (corrugate.export.operations.FoldOp).
FoldOperation = Literal["cut-score", "perforate", "score", "pen", "none"]


class FabricationSpec(_Strict):
    """What making the part asks (docs/fabrication.md, "What the solve asks of the making"):
    ``machine``, the cutter whose usable area every cut part must fit (turned or not; default
    the command line's ``--machine`` or ``cameo4-12x12``; ``"none"``: no machine);
    ``min_facet``, the narrowest facet W (default 3 mm); ``max_t_over_W``, the thickest sheet
    for its facet (default 0.05); ``max_creases``, the most creases n of a layer (default: no
    limit); ``mountain``, ``valley`` and ``marks``, how those reach the cutter (default: the
    machine's, docs/fabrication.md; ``design --mountain/--valley/--marks`` override them)."""

    machine: MachineName | None = None
    min_facet: Length = DEFAULT_MIN_FACET_MM
    max_t_over_W: ThicknessRatio = DEFAULT_MAX_T_OVER_W
    max_creases: Count | None = None
    mountain: FoldOperation | None = None
    valley: FoldOperation | None = None
    marks: FoldOperation | None = None


class Spec(_Strict):
    """A validated design spec; every quantity in internal units (mm, deg, g, N)."""

    name: Name = "design"
    model: ModelName = DEFAULT_MODEL
    support: Support = DEFAULT_SUPPORT
    layers: Literal["identical", "independent"] = "identical"
    material: MaterialSpec | None = None
    materials: list[MaterialSpec] | None = None
    layout: LayoutSpec = LayoutSpec.model_construct()
    variables: VariablesSpec = VariablesSpec.model_construct()
    constraints: ConstraintsSpec = ConstraintsSpec.model_construct()
    objective: ObjectiveSpec = ObjectiveSpec.model_construct()
    robust: RobustSpec | None = None
    # the stated defaults (docs/tolerances.md section 1) unless the spec says otherwise:
    # tolerances = "none" is nominal; [robust] without [tolerances] is nominal (_robust_nominal)
    tolerances: Tolerances = TolerancesSpec.model_construct()
    safety_factor: SafetyFactor = DEFAULT_SAFETY_FACTOR
    joint: Literal["none", "band-edges", "band-flanges"] = "none"
    fabrication: FabricationSpec = FabricationSpec.model_construct()
    # where the answer may lie: inside every validated range of the models it uses (default) or
    # anywhere, marked extrapolated (docs/spec.md; corrugate.solver.validity)
    trust: Literal["certified", "extrapolate"] = "certified"
    # the unit text each quantity was written in, by spec path (spec.written: the diagnosis
    # answers in it); set by parse_spec, not a key of the spec
    _written: dict[str, str] = PrivateAttr(default_factory=dict)
    # the user's own materials the spec may name (corrugate.materials.user.spec_materials: the
    # config folder's and those beside the spec file); set by parse_spec, not a key of the spec
    _materials: dict[str, Material] = PrivateAttr(default_factory=dict)

    @model_validator(mode="before")
    @classmethod
    def _robust_nominal(cls, data: Any) -> Any:
        """A spec with ``[robust]`` (the probabilistic alternative) and no ``[tolerances]`` of
        its own is certified nominally under it: the worst case is not added on top
        (docs/tolerances.md)."""
        if (
            isinstance(data, Mapping)
            and data.get("robust") is not None
            and "tolerances" not in data
        ):
            return {**data, "tolerances": "none"}
        return data

    @property
    def own_materials(self) -> dict[str, Material]:
        """The user's materials this spec may name, by id (docs/calibration.md section 6)."""
        return self._materials

    def unit_written(self, path: str) -> str | None:
        """The unit the spec wrote the quantity at ``path`` in (``constraints.side.max`` ->
        ``mm``), None for a plain number or a key not given (:mod:`corrugate.spec.written`)."""
        return self._written.get(path)


def with_machine(spec: Spec, machine: str | None) -> Spec:
    """``spec`` with its ``[fabrication] machine`` set to ``machine`` (a checked machine name,
    e.g. the command line's ``--machine``); None: ``spec`` itself."""
    if machine is None:
        return spec
    fab = spec.fabrication.model_copy(update={"machine": _machine(machine)})
    return spec.model_copy(update={"fabrication": fab})


# -- errors with TOML paths -------------------------------------------------------------------


def _toml_path(loc: tuple[int | str, ...]) -> str:
    out = ""
    for part in loc:
        if isinstance(part, int):
            out += f"[{part}]"
        else:
            out += ("." if out else "") + part
    return out or "spec"


def _model_at(loc: tuple[int | str, ...]) -> type[BaseModel] | None:
    """The pydantic model class found by following ``loc`` from :class:`Spec`."""
    cls: Any = Spec
    for part in loc:
        if isinstance(part, int):
            continue
        if not (isinstance(cls, type) and issubclass(cls, BaseModel)):
            return None
        field = cls.model_fields.get(part)
        if field is None:
            return None
        cls = _unwrap(field.annotation)
    return cls if isinstance(cls, type) and issubclass(cls, BaseModel) else None


def _unwrap(annotation: Any) -> Any:
    """The model class inside ``X | None`` or ``list[X]``, else ``annotation``."""
    for arg in (*typing.get_args(annotation), annotation):
        if isinstance(arg, type) and issubclass(arg, BaseModel):
            return arg
        inner = typing.get_args(arg)
        for a in inner:
            if isinstance(a, type) and issubclass(a, BaseModel):
                return a
    return annotation


def _from_validation_error(exc: ValidationError) -> SpecError:
    err = exc.errors()[0]
    loc = tuple(p for p in err["loc"] if not (isinstance(p, str) and "[" in p))
    # pydantic tags union members (e.g. 'list[...]'); drop those tags from the path
    path = _toml_path(loc)
    value = err.get("input")
    ctx = err.get("ctx") or {}
    kind = err["type"]
    if kind == "extra_forbidden":
        parent = _model_at(loc[:-1])
        known = sorted(parent.model_fields) if parent is not None else []
        return SpecError(
            path,
            repr(value),
            "one of " + ", ".join(known) if known else "no key",
            reason="is not a known key",
        )
    if kind == "missing":
        return SpecError(path, None, "a value", reason="is missing")
    if kind == "unit":
        return MissingUnitError(path, str(ctx["number"]), str(ctx["example"]))
    if kind in {"quantity", "count"}:
        return SpecError(path, repr(value), str(ctx.get("allowed")), reason=str(ctx["reason"]))
    if kind == "literal_error":
        return SpecError(path, repr(value), str(ctx.get("expected")), reason="is not allowed")
    return SpecError(
        path,
        repr(value),
        "see the spec reference in corrugate.spec.schema",
        reason=str(err["msg"]).lower(),
    )


# -- cross-field checks -----------------------------------------------------------------------

_EQUAL_SIDES_SIZES = {"square": ("side",), "circle": ("diameter",)}
_SIZE_KEYS = ("side", "diameter", "side_x", "side_y")


def _check_range(path: str, lo: float | None, hi: float | None, unit: str) -> None:
    if lo is not None and hi is not None and lo > hi:
        raise SpecError(
            f"{path}.min",
            f"{lo:g} {unit}",
            f"at most {path}.max = {hi:g} {unit}",
            reason="is greater than max",
        )


def _check(spec: Spec, raw: Mapping[str, Any]) -> None:
    v = spec.variables
    for key, unit in (("W", "mm"), ("alpha", "deg")):
        var: Variable = getattr(v, key)
        _check_range(f"variables.{key}", var.min, var.max, unit)
    _check_range("variables.n", v.n.min, v.n.max, "")
    for key, unit in (("W", "mm"), ("alpha", "deg")):
        var = getattr(v, key)
        check_grid(f"variables.{key}", var.min, var.max, var.step, unit)
    c = spec.constraints
    for key in (*_SIZE_KEYS, "thickness"):
        r: Range | None = getattr(c, key)
        if r is not None:
            _check_range(f"constraints.{key}", r.min, r.max, "mm")
            if r.min is None and r.max is None:
                raise SpecError(
                    f"constraints.{key}", "{}", "a table with min and/or max", reason="is empty"
                )
    shape = spec.layout.shape
    allowed_sizes = _EQUAL_SIDES_SIZES.get(shape, ("side_x", "side_y"))
    for key in _SIZE_KEYS:
        if getattr(c, key) is not None and key not in allowed_sizes:
            raise SpecError(
                f"constraints.{key}",
                raw["constraints"][key] if "constraints" in raw else key,
                f"for layout {shape!r}: " + ", ".join(allowed_sizes),
                reason=f"does not apply to a {shape} layout",
            )
    if shape == "polygon" and spec.layout.vertices is None:
        raise SpecError("layout.vertices", None, "at least 3 [x, y] pairs", reason="is missing")
    if shape != "polygon" and spec.layout.vertices is not None:
        raise SpecError(
            "layout.vertices",
            spec.layout.vertices,
            "only for shape = 'polygon'",
            reason="does not apply",
        )
    if spec.layout.vertices is not None:
        from corrugate.geometry.layouts import make_layout

        try:
            make_layout("polygon", spec.layout.vertices)
        except InputError as exc:
            raise SpecError("layout.vertices", exc.value, exc.allowed, reason=exc.reason) from None
    _check_holes(spec)
    if spec.layers == "independent" and shape in _EQUAL_SIDES_SIZES:
        raise SpecError(
            "layers",
            "'independent'",
            "'identical' for a square or circle layout, "
            "or layout 'rectangle' / 'polygon' for independent layers",
            reason=f"is not supported by the solver for a {shape} layout (Lx = Ly)",
        )
    if (spec.material is None) == (spec.materials is None):
        raise SpecError(
            "material",
            None,
            "exactly one of [material] or [[materials]]",
            reason="is missing" if spec.material is None else "is given twice",
        )
    mats = [spec.material] if spec.material is not None else list(spec.materials or [])
    if not mats:
        raise SpecError("materials", "[]", "at least one material", reason="is empty")
    for i, m in enumerate(mats):
        where = "material" if spec.material is not None else f"materials[{i}]"
        _check_material(where, m, spec.own_materials)
    o = spec.objective
    if o.minimize is not None and o.maximize is not None:  # neither: minimise mass
        raise SpecError(
            "objective.maximize",
            repr(o.maximize),
            "either minimize = 'mass' or maximize = '<stiffness>', not both",
            reason="conflicts with objective.minimize",
        )


def _check_material(where: str, m: MaterialSpec, own: dict[str, Material]) -> None:
    inline = [x is not None for x in (m.E, m.nu, m.density)]
    if not any(inline) and "name" not in m.model_fields_set:  # neither a name nor E, nu, density
        raise SpecError(
            f"{where}.E",
            None,
            "E, nu and density for an inline material, or a library material's name",
            reason="is missing",
        )
    if any(inline):
        for key, given in zip(("E", "nu", "density"), inline, strict=True):
            if not given:
                raise SpecError(
                    f"{where}.{key}",
                    None,
                    "E, nu and density together for an inline material",
                    reason="is missing",
                )
        if m.thickness is None or m.thickness == "all":
            raise SpecError(
                f"{where}.thickness",
                m.thickness,
                "a thickness (or a list) for an inline material",
                reason="is missing",
            )
        return
    for key in ("crease_stiffness", "springback"):
        if getattr(m, key) is not None:
            raise SpecError(
                f"{where}.{key}",
                f"{getattr(m, key):g}",
                "only with an inline material (E, nu, density); a library or calibrated "
                "material's comes from a materials file (`corrugate docs calibration`, section 6)",
                reason=f"does not apply to name = {m.name!r}",
            )
    from corrugate.materials.library import get_material

    try:
        get_material(m.name, own)
    except InputError as exc:
        raise SpecError(f"{where}.name", exc.value, exc.allowed, reason=exc.reason) from None


def _check_raw(data: Mapping[str, Any]) -> None:
    """Limits on the raw data before pydantic sees it: nesting depth, text lengths and integers
    of at most :data:`~corrugate.core.limits.MAX_INT_DIGITS` digits (a JSON or TOML integer of
    400 digits is named by its key, never converted to a float)."""
    check_depth(data, "spec")
    stack: list[tuple[Any, str]] = [(data, "")]
    while stack:
        obj, path = stack.pop()
        if isinstance(obj, int) and not isinstance(obj, bool):
            check_integer(path or "spec", obj)
        elif isinstance(obj, str):
            limit = MAX_NAME_CHARS if path.rsplit(".", 1)[-1] == "name" else MAX_TEXT_CHARS
            check_text(path or "spec", obj, limit)
        elif isinstance(obj, Mapping):
            for k, val in obj.items():
                check_text(f"{path}.<key>" if path else "<key>", str(k), MAX_NAME_CHARS)
                stack.append((val, f"{path}.{k}" if path else str(k)))
        elif isinstance(obj, list | tuple):
            if len(obj) > MAX_LIST_ITEMS:
                raise SpecError(
                    path,
                    f"[{len(obj)} items]",
                    f"at most {MAX_LIST_ITEMS} items",
                    reason="is too long",
                )
            stack.extend((val, f"{path}[{i}]") for i, val in enumerate(obj))


#: The lists of behavioural bounds, capped together at ``MAX_COUNTS["bounds"]``.
_BOUND_KEYS = (
    "flexural_rigidity",
    "bending_stiffness",
    "inplane_stiffness",
    "buckling_load",
    "deflection",
    "strength",
)


def _check_counts(data: Mapping[str, Any]) -> None:
    """The lists that set how much work a solve is, capped before any of their items is read
    (:data:`~corrugate.core.limits.MAX_COUNTS`): holes, the vertices of the outline and of each
    hole, the behavioural bounds together, the candidate thicknesses over every material."""
    lay = data.get("layout")
    if isinstance(lay, Mapping):
        holes = lay.get("holes")
        if isinstance(holes, list):
            check_items("holes", "layout.holes", len(holes), "holes")
            for i, h in enumerate(holes):
                if isinstance(h, Mapping) and isinstance(h.get("vertices"), list):
                    where = f"layout.holes[{i}].vertices"
                    check_items("vertices", where, len(h["vertices"]), "vertices")
        if isinstance(lay.get("vertices"), list):
            check_items("vertices", "layout.vertices", len(lay["vertices"]), "vertices")
    cons = data.get("constraints")
    if isinstance(cons, Mapping):
        counts = {k: len(cons[k]) for k in _BOUND_KEYS if isinstance(cons.get(k), list)}
        for k, count in counts.items():
            check_items("bounds", f"constraints.{k}", count, "bounds")
        if sum(counts.values()) > MAX_COUNTS["bounds"]:
            shown = ", ".join(f"{k} {c}" for k, c in counts.items() if c)
            check_items("bounds", "constraints", sum(counts.values()), f"bounds ({shown})")
    mats: list[tuple[str, Any]] = []
    if isinstance(data.get("material"), Mapping):
        mats.append(("material", data["material"]))
    if isinstance(data.get("materials"), list):
        mats += [(f"materials[{i}]", m) for i, m in enumerate(data["materials"])]
    total = 0
    for where, m in mats:
        t = m.get("thickness") if isinstance(m, Mapping) else None
        count = len(t) if isinstance(t, list) else 1
        check_items("thicknesses", f"{where}.thickness", count, "thicknesses")
        total += count
    check_items("thicknesses", "materials", total, "candidate sheets (material and thickness)")


def parse_spec(data: Mapping[str, Any], spec_dir: str | Path | None = None) -> Spec:
    """Validate a spec given as a dict (as read from TOML); raise :class:`SpecError`. A material
    name is looked up in the user's own materials first: the config folder's and, with
    ``spec_dir`` (the spec file's folder), its ``corrugate-materials.toml``
    (:func:`corrugate.materials.user.spec_materials`)."""
    from corrugate.materials.user import spec_materials

    try:
        own = spec_materials(spec_dir)
    except InputError as exc:
        raise SpecError(exc.field, exc.value, exc.allowed, reason=exc.reason) from None
    try:
        _check_raw(data)
        _check_counts(data)
    except InputError as exc:
        raise SpecError(exc.field, exc.value, exc.allowed, reason=exc.reason) from None
    try:
        spec = Spec.model_validate(dict(data))
    except ValidationError as exc:
        raise _from_validation_error(exc) from None
    except RecursionError:
        raise SpecError(
            "spec", "(nested data)", f"at most {MAX_DEPTH} levels", reason="is nested too deeply"
        ) from None
    spec._materials.update(own)
    _check(spec, data)
    from corrugate.spec.written import written_units

    spec._written.update(written_units(data))
    return spec


def load_spec(path: str | Path) -> Spec:
    """Read and validate the TOML spec file ``path`` (``-``: standard input); raise
    :class:`SpecError`.

    The file must be at most :data:`~corrugate.core.limits.MAX_SPEC_BYTES` long, UTF-8 and nested at
    most :data:`~corrugate.core.limits.MAX_DEPTH` deep; each failure is one line naming the file."""
    return load_spec_text(path)[0]


def load_spec_text(path: str | Path) -> tuple[Spec, str]:
    """:func:`load_spec` and the spec's text as read (for the report), from a file or, for
    ``-``, from standard input (read once)."""
    import sys

    p = Path(path)
    stdin = str(path) == "-"
    shown = "<stdin>" if stdin else str(p) if len(str(p)) <= 200 else str(p)[:200] + "..."
    from corrugate.core.fileio import decode_input, read_input

    try:
        if stdin:
            raw = sys.stdin.buffer.read(MAX_SPEC_BYTES + 1)
        else:  # a regular file only, never a FIFO or a device (read as untrusted input)
            raw = read_input(p, "spec", MAX_SPEC_BYTES)
    except InputError as exc:
        raise SpecError(exc.field, shown, exc.allowed, reason=exc.reason) from None
    except (OSError, ValueError) as exc:
        reason = getattr(exc, "strerror", None) or type(exc).__name__
        raise SpecError(
            "spec", shown, "a readable TOML file", reason=f"cannot be read ({reason})"
        ) from None
    if len(raw) > MAX_SPEC_BYTES:
        raise SpecError(
            "spec", shown, f"a file of at most {MAX_SPEC_BYTES} bytes", reason="is too large"
        )
    try:
        text = decode_input(raw, "spec", shown)
    except InputError as exc:
        raise SpecError(exc.field, shown, exc.allowed, reason=exc.reason) from None
    return parse_spec_text(text, shown, None if stdin else p.resolve().parent), text


def parse_spec_text(text: str, shown: str = "<text>", spec_dir: str | Path | None = None) -> Spec:
    """Validate a spec given as TOML ``text`` (``shown`` names it in errors; ``spec_dir`` its
    folder, where its own materials file is, :func:`parse_spec`); nesting deeper than
    :data:`~corrugate.core.limits.MAX_DEPTH` is refused before the TOML parser recurses into it."""
    text = text.removeprefix("\ufeff")  # a byte-order mark (a file's goes when it is decoded)
    if bracket_depth(text) > MAX_DEPTH:
        raise SpecError(
            "spec",
            shown,
            f"at most {MAX_DEPTH} levels of arrays and tables",
            reason="is nested too deeply",
        )
    try:
        data = tomllib.loads(text)
    except ValueError as exc:
        if not isinstance(exc, tomllib.TOMLDecodeError):  # an integer too long to convert
            raise _long_integer(text, shown) from None
        msg = str(exc).splitlines()[0] if str(exc) else "syntax error"
        raise SpecError("spec", shown, "valid TOML", reason=f"is not valid TOML ({msg})") from None
    except RecursionError:
        raise SpecError(
            "spec",
            shown,
            f"at most {MAX_DEPTH} levels of arrays and tables",
            reason="is nested too deeply",
        ) from None
    return parse_spec(data, spec_dir)


def _long_integer(text: str, shown: str) -> SpecError:
    """The error for a TOML integer longer than Python converts (``sys.get_int_max_str_digits``,
    4300 digits): its key and line when they can be found in ``text``."""
    import re
    import sys

    digits = sys.get_int_max_str_digits() or 4300
    allowed = f"an integer of at most {digits} digits"
    m = re.search("[0-9_]{" + str(digits + 1) + ",}", text)  # one pass, no backtracking
    if m is None:
        return SpecError("spec", shown, allowed, reason="has a longer integer")
    start = text.rfind("\n", 0, m.start()) + 1
    key = re.findall(r"([A-Za-z0-9_.\"'-]+)\s*=", text[start : m.start()])
    line = text.count("\n", 0, m.start()) + 1
    where = f"{key[-1] if key else 'value'} (line {line} of {shown})"
    return SpecError(
        where,
        f"an integer of {len(m.group(0).replace('_', ''))} digits",
        allowed,
        reason="is too long",
    )
