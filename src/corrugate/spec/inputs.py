"""From user options to a design: the one conversion behind ``corrugate analyze`` and the web API.

The command line and the JSON API take the same fields (``W``, ``n``, ``alpha``, ``material`` or an
inline ``E``/``nu``/``density``, ``thickness``, the layer 2 variants ``W2`` ... ``thickness2``,
``layout``, ``vertices``, ``holes``, ``model``, ``eta``). Each value is a plain number, read in the field's
default unit (mm, deg, MPa, g/cm^3), or a string that may carry units (``"0.3 in"``, ``"2.7 GPa"``).
Every bad value raises :class:`~corrugate.core.errors.InputError` naming the field, so the CLI and the
web app report the same errors with the same words.
"""

from __future__ import annotations

import json
from collections.abc import Mapping, Sequence
from dataclasses import dataclass

from corrugate.analysis.evaluate import Analysis, analyze
from corrugate.core.errors import InputError, UnknownNameError
from corrugate.core.limits import MAX_DEPTH, bracket_depth, check, check_items
from corrugate.core.text import foreign_digits
from corrugate.core.units import parse_quantity
from corrugate.geometry.holes import Hole, holes_from_data
from corrugate.geometry.layer import Assembly, Layer
from corrugate.geometry.layouts import make_layout
from corrugate.materials.library import Material, get_material, inline_material
from corrugate.mechanics.behaviours import check_support
from corrugate.mechanics.moduli import get_model
from corrugate.names import DEFAULT_LAYOUT, DEFAULT_MODEL, DEFAULT_SUPPORT

__all__ = [
    "ASSEMBLY_OPTIONS",
    "DEFAULT_ETAS",
    "AnalysisRequest",
    "analysis_request",
    "assembly_from_namespace",
    "assembly_from_options",
    "layer_from_options",
    "material_from_options",
    "parse_etas",
    "parse_holes",
    "parse_int",
    "parse_vertices",
]

#: Directions (deg) analysed when none are given.
DEFAULT_ETAS: tuple[float, ...] = (0.0, 90.0)

_N_ALLOWED = "an integer n >= 1 (number of creases)"


def parse_int(value: object, field: str, allowed: str = _N_ALLOWED) -> int:
    """``value`` (an int, an integral float or a string such as ``"8"``) as an int."""
    if isinstance(value, bool):
        raise InputError(field, value, allowed, reason="is not an integer")
    if isinstance(value, int):
        return value
    if isinstance(value, str) and foreign_digits(value):  # int("８") is 8
        raise InputError(field, repr(value), allowed, reason="has digits other than 0-9")
    try:
        f = float(value)  # type: ignore[arg-type]
    except (TypeError, ValueError):
        raise InputError(field, repr(value), allowed, reason="is not an integer") from None
    text = str(value).strip()
    if len(text) > 100:  # never echoed whole: one line (a 4400-digit integer is out of range)
        digits = text.lstrip("+-").isdigit()
        raise InputError(
            field,
            f"{text[:20]}... ({len(text)} characters)",
            allowed,
            reason="is out of range" if digits else "is not an integer",
        )
    if not f.is_integer():
        raise InputError(field, value, allowed, reason="is not an integer")
    return int(f)


def material_from_options(
    name: str | None,
    E: object,
    nu: object,
    density: object,
    thickness: object,
    suffix: str = "",
) -> Material:
    """A library material by ``name`` (default ``dura-lar``) or an inline one from E, nu, density.

    The inline values must come together and exclude ``name``.
    """
    inline = [x is not None for x in (E, nu, density)]
    if any(inline):
        if not all(inline):
            missing = [k for k, v in (("E", E), ("nu", nu), ("density", density)) if v is None]
            raise InputError(
                f"{missing[0]}{suffix}",
                None,
                "--E, --nu and --density together for an inline material",
                reason="is missing",
            )
        if name is not None:
            raise InputError(
                f"material{suffix}",
                name,
                "either --material or --E/--nu/--density",
                reason="conflicts with the inline material",
            )
        return inline_material(E, nu, density, name="custom", thickness=thickness)
    try:
        return get_material(name or "dura-lar")
    except UnknownNameError as exc:
        if suffix:
            raise exc.renamed(exc.field + suffix) from None
        raise


def layer_from_options(
    W: object, n: object, alpha: object, material: Material, thickness: object, suffix: str = ""
) -> Layer:
    """One layer from user values (W in mm, alpha in deg, thickness in mm unless units are given).

    ``suffix`` ("2" for layer 2) is appended to the field named by any error.
    """
    t = None if thickness is None else parse_quantity(thickness, "mm", f"thickness{suffix}")
    w = parse_quantity(W, "mm", f"W{suffix}")
    a = parse_quantity(alpha, "deg", f"alpha{suffix}")
    nn = parse_int(n, f"n{suffix}")
    try:
        if t is None:
            return Layer(w, nn, a, material)
        return Layer(w, nn, a, material, t)
    except InputError as exc:
        if suffix:
            raise exc.renamed(exc.field + suffix) from None
        raise


def parse_vertices(value: object) -> list[tuple[float, float]] | None:
    """A polygon outline: the text ``"0,0 1,0 0.5,1"`` or a sequence of (x, y) pairs; None stays None."""
    if value is None:
        return None
    pts: list[tuple[float, float]] = []
    if isinstance(value, str) and foreign_digits(value):  # float() reads full-width digits
        raise InputError(
            "vertices",
            repr(value),
            "pairs 'x,y' in ASCII digits 0-9, e.g. '0,0 1,0 0.5,1'",
            reason="has digits other than 0-9",
        )
    if isinstance(value, str):
        count = len(value.replace(";", " ").split())
    else:
        count = len(value) if isinstance(value, Sequence) else 0
    check_items("vertices", "vertices", count, "vertices")  # as a spec's layout.vertices
    try:
        if isinstance(value, str):
            for pair in value.replace(";", " ").split():
                x, y = pair.split(",")
                pts.append((float(x), float(y)))
        elif isinstance(value, Sequence):
            for pair in value:
                if isinstance(pair, str | bytes) or not isinstance(pair, Sequence):
                    raise ValueError(pair)
                coords = list(pair)
                if len(coords) != 2 or any(isinstance(c, bool) for c in coords):
                    raise ValueError(pair)
                pts.append((float(coords[0]), float(coords[1])))
        else:
            raise ValueError(value)
    except (TypeError, ValueError):
        raise InputError(
            "vertices",
            repr(value),
            "pairs 'x,y' separated by spaces, e.g. '0,0 1,0 0.5,1'",
            reason="cannot be read",
        ) from None
    return pts


def parse_holes(value: object) -> tuple[Hole, ...]:
    """Holes (:mod:`corrugate.geometry.holes`): a list of tables ``{shape, diameter | vertices, center}``
    (numbers in mm or strings with units) or the same as JSON text; None gives none. Errors name
    ``holes[i].<key>``."""
    if value is None:
        return ()
    if isinstance(value, str):
        example = (
            'a JSON list, e.g. \'[{"shape": "circle", "diameter": "6 mm", "center": [0, 0]}]\''
        )
        if bracket_depth(value) > MAX_DEPTH:  # before json recurses into it
            raise InputError(
                "holes",
                value,
                f"{example}, nested at most {MAX_DEPTH} deep",
                reason="is nested too deeply",
            )
        try:
            value = json.loads(value)
        except ValueError:  # also a number of more than 4300 digits, beyond int()
            raise InputError("holes", repr(value), example, reason="cannot be read") from None
    if isinstance(value, list):  # as a spec's layout.holes: each hole is work in every point
        check_items("holes", "holes", len(value), "holes")
        for i, hole in enumerate(value):
            corners = hole.get("vertices") if isinstance(hole, dict) else None
            if isinstance(corners, list):
                check_items("vertices", f"holes[{i}].vertices", len(corners), "vertices")
    return holes_from_data(value, "holes")


def parse_etas(eta: Sequence[object] | None) -> tuple[float, ...]:
    """Directions in deg (plain numbers or strings with units); none given: 0 and 90 deg."""
    if not eta:
        return DEFAULT_ETAS
    etas = tuple(parse_quantity(e, "deg", "eta") for e in eta)
    return tuple(check("eta", e) for e in etas)  # -360..360 deg (docs/spec.md, "Directions")


def assembly_from_options(
    *,
    W: object,
    n: object,
    alpha: object,
    material: str | None = None,
    thickness: object = None,
    E: object = None,
    nu: object = None,
    density: object = None,
    W2: object = None,
    n2: object = None,
    alpha2: object = None,
    material2: str | None = None,
    thickness2: object = None,
    layout: str = DEFAULT_LAYOUT,
    vertices: object = None,
    holes: object = None,
) -> Assembly:
    """The assembly that ``corrugate analyze``'s options describe.

    Layer 2 takes layer 1's value for every option it does not set; its thickness is layer 1's
    unless it has a material of its own (then that material's default) or ``thickness2``.
    """
    mat1 = material_from_options(material, E, nu, density, thickness)
    layer1 = layer_from_options(W, n, alpha, mat1, thickness)
    mat2 = (
        mat1 if material2 is None else material_from_options(material2, None, None, None, None, "2")
    )
    t2 = (
        thickness2
        if thickness2 is not None
        else (layer1.t if material2 is None or thickness is not None else None)
    )
    layer2 = layer_from_options(
        W if W2 is None else W2,
        n if n2 is None else n2,
        alpha if alpha2 is None else alpha2,
        mat2,
        t2,
        suffix="2",
    )
    return Assembly(
        layer1, layer2, make_layout(layout, parse_vertices(vertices), parse_holes(holes))
    )


#: The keyword options of :func:`assembly_from_options`, as the commands name their parameters.
ASSEMBLY_OPTIONS = (
    "W",
    "n",
    "alpha",
    "material",
    "thickness",
    "E",
    "nu",
    "density",
    "W2",
    "n2",
    "alpha2",
    "material2",
    "thickness2",
    "layout",
    "vertices",
    "holes",
)


def assembly_from_namespace(values: Mapping[str, object]) -> Assembly:
    """:func:`assembly_from_options` with the options found in ``values`` (a command's
    ``locals()``: every name of :data:`ASSEMBLY_OPTIONS` it has), so that the commands that take
    a design's options do not each pass them on one by one."""
    options = {k: values[k] for k in ASSEMBLY_OPTIONS if k in values}
    return assembly_from_options(**options)  # type: ignore[arg-type]


@dataclass(frozen=True, slots=True)
class AnalysisRequest:
    """A validated ``analyze`` request: the assembly, the model name and the directions (deg)."""

    assembly: Assembly
    model: str
    eta_deg: tuple[float, ...]
    support: str = DEFAULT_SUPPORT
    joint: str = "none"

    def run(self) -> Analysis:
        """Analyse it (:func:`corrugate.analysis.evaluate.analyze`)."""
        return analyze(
            self.assembly, self.model, self.eta_deg, support=self.support, joint=self.joint
        )


def analysis_request(
    *,
    model: str = DEFAULT_MODEL,
    eta: Sequence[object] | None = None,
    support: str = DEFAULT_SUPPORT,
    joint: str = "none",
    **options: object,
) -> AnalysisRequest:
    """Validate the options of ``corrugate analyze`` (as keywords, see
    :func:`assembly_from_options`) into an :class:`AnalysisRequest`; ``joint``: how its layers
    are joined (:data:`corrugate.names.JOINTS`)."""
    assembly = assembly_from_options(**options)  # type: ignore[arg-type]
    etas = parse_etas(eta)
    return AnalysisRequest(assembly, get_model(model).name, etas, check_support(support), joint)
