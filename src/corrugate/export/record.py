"""``design.json``: the typed record of one design, with its one writer and its one reader.

``corrugate design --out``, ``corrugate pattern --out`` and ``POST /api/design`` write it
(:func:`write_record`, through :func:`corrugate.workflow.write_design` and
:func:`corrugate.workflow.write_design_files`); ``corrugate validate --design`` reads it back
(:func:`read_record`, then :meth:`DesignRecord.assembly`).

The file is one JSON object. Its keys (every length in mm, mass in g, stiffness as the keys say):
the analysis of the design (``corrugate analyze --json``: ``model``, ``layout``, ``layers``,
``stiffness``, ...; each layer with ``material_properties``, every property of its material:
E, nu, density, thicknesses, yield strength, creep table, so that a design of an inline
material can be read back), the cut parts (``cut_parts``), the sheets (``sheets``), the fold-line style
(``fold_style``), the answer of ``corrugate design --json`` when the design came from a spec, and
``files``, the names of the files written beside it. An infeasible spec's record holds only the
design answer (no ``layers``).
"""

from __future__ import annotations

import hashlib
import json
from collections.abc import Mapping
from dataclasses import dataclass, field
from pathlib import Path
from typing import TYPE_CHECKING, Any

from corrugate.core.errors import InputError
from corrugate.core.fileio import Staging, write_set
from corrugate.core.text import printable
from corrugate.geometry.holes import Hole
from corrugate.names import DEFAULT_LAYOUT, RECTANGULAR_LAYOUTS

if TYPE_CHECKING:
    from corrugate.geometry.layer import Assembly, Layer

__all__ = [
    "RECORD_NAME",
    "VERIFY_KIND",
    "VERIFY_NAME",
    "DesignFile",
    "DesignRecord",
    "LayerRecord",
    "check_verify_target",
    "design_label",
    "load_record",
    "parse_record",
    "read_design",
    "read_design_file",
    "read_record",
    "write_record",
]

#: The record's file name in an output folder.
RECORD_NAME = "design.json"
#: The file ``corrugate verify`` and ``design --verify fe --out`` write into a design's folder,
#: and its set kind in the folder's manifest (:mod:`corrugate.core.fileio`).
VERIFY_NAME = "verify.json"
VERIFY_KIND = "verify"

_LAYER_FIELDS = ("W_mm", "n", "alpha_deg", "material", "t_mm")


@dataclass(frozen=True, slots=True)
class LayerRecord:
    """One layer as design.json stores it: facet width ``W_mm`` (mm), crease count ``n``, fold
    angle ``alpha_deg`` (deg), ``material`` id, sheet thickness ``t_mm`` (mm) and
    ``material_properties``, every property of the material the design used
    (:meth:`corrugate.materials.library.Material.as_dict`; None in a design.json written before
    it was stored, which then names a library material)."""

    W_mm: float
    n: int
    alpha_deg: float
    material: str
    t_mm: float
    material_properties: Mapping[str, Any] | None = None

    def material_of(self, i: int) -> Any:
        """The :class:`~corrugate.materials.library.Material` of layer ``i``: from its stored
        properties, else the library's material of its id; an :class:`InputError` naming the
        field otherwise."""
        from corrugate.materials.library import get_material, library, material_from_dict

        if self.material_properties is not None:
            return material_from_dict(
                dict(self.material_properties), f"layers[{i}].material_properties"
            )
        if self.material.strip().lower() not in library():
            raise InputError(
                f"layers[{i}].material",
                repr(self.material),
                "a library material id, or the layer's material_properties (this design.json "
                "was written before they were stored: write the design again with `corrugate "
                "design SPEC --out DIR`, or use --W, --n, --alpha, --E, --nu)",
                reason="is not in the library",
            )
        return get_material(self.material)


@dataclass(frozen=True, slots=True)
class DesignRecord:
    """The content of one design.json.

    ``shape`` is the layout's shape (None when there is no design: an infeasible spec), ``holes``
    its inner cut-outs (mm from the layout's centre), ``layers`` the two layers (empty without a
    design); ``content`` is the whole JSON object, every key as written (see the module docstring).
    """

    shape: str | None
    holes: tuple[Hole, ...]
    layers: tuple[LayerRecord, ...]
    content: Mapping[str, Any] = field(repr=False)

    def to_json(self) -> str:
        """The file's text (indented JSON)."""
        return json.dumps(self.content, indent=2)

    def assembly(self, any_layout: bool = False) -> Assembly:
        """The assembly of this record for the FE model: two layers of library materials on a
        square or rectangle (with ``any_layout``, also a circle or a polygon, for the outline
        fixtures of :mod:`corrugate.fea.outline`); anything else is an :class:`InputError`
        naming the field."""
        from corrugate.geometry.layer import Assembly, Layer
        from corrugate.geometry.layouts import Rectangle, Square, make_layout

        if any_layout and self.shape in ("circle", "polygon"):
            pass
        elif self.shape not in RECTANGULAR_LAYOUTS:
            raise InputError(
                "layout.shape",
                repr(self.shape),
                "square or rectangle for the FE assembly (to check the layers of another outline, "
                "validate them on a square: the same --W --n --alpha)",
                reason="is not supported",
            )
        if len(self.layers) != 2:
            raise InputError(
                "layers", "?", "a list of two layer objects", reason="is missing or malformed"
            )
        built: list[Layer] = []
        for i, entry in enumerate(self.layers):
            material = entry.material_of(i)
            try:
                built.append(
                    Layer(
                        W=entry.W_mm,
                        n=entry.n,
                        alpha_deg=entry.alpha_deg,
                        material=material,
                        t=entry.t_mm,
                    )
                )
            except InputError as exc:
                raise exc.renamed(f"layers[{i}].{exc.field}") from None
        if self.shape in ("circle", "polygon"):
            layout_content = self.content.get("layout")
            vertices = (
                layout_content.get("vertices") if isinstance(layout_content, Mapping) else None
            )
            try:
                layout_ = make_layout(str(self.shape), vertices, self.holes)
            except InputError as exc:
                raise exc.renamed(f"layout.{exc.field}") from None
            return Assembly(built[0], built[1], layout_)
        layout = Square(holes=self.holes) if self.shape == "square" else Rectangle(holes=self.holes)
        return Assembly(built[0], built[1], layout)


def parse_record(content: Mapping[str, Any]) -> DesignRecord:
    """The record of a design.json object; an :class:`InputError` names a malformed field."""
    layout = content.get("layout")
    shape = layout.get("shape") if isinstance(layout, Mapping) else None
    holes = _holes(layout.get("holes")) if isinstance(layout, Mapping) else ()
    raw = content.get("layers")
    if raw is None:
        return DesignRecord(None if shape is None else str(shape), holes, (), content)
    if not isinstance(raw, list) or len(raw) != 2 or not all(isinstance(x, dict) for x in raw):
        raise InputError(
            "layers", "?", "a list of two layer objects", reason="is missing or malformed"
        )
    layers = tuple(_layer(i, entry) for i, entry in enumerate(raw))
    return DesignRecord(None if shape is None else str(shape), holes, layers, content)


def _layer(i: int, entry: Mapping[str, Any]) -> LayerRecord:
    for key in _LAYER_FIELDS:
        if key not in entry:
            raise InputError(f"layers[{i}].{key}", None, "a value", reason="is missing")
    props = entry.get("material_properties")
    if props is not None and not isinstance(props, Mapping):
        raise InputError(
            f"layers[{i}].material_properties",
            repr(props)[:40],
            "an object of material properties",
            reason="is malformed",
        )
    try:
        return LayerRecord(
            W_mm=float(entry["W_mm"]),
            n=int(entry["n"]),
            alpha_deg=float(entry["alpha_deg"]),
            material=str(entry["material"]),
            t_mm=float(entry["t_mm"]),
            material_properties=props,
        )
    except (TypeError, ValueError):
        raise InputError(
            f"layers[{i}]", "?", "numbers for W_mm, n, alpha_deg, t_mm", reason="is malformed"
        ) from None


def _holes(raw: object) -> tuple[Hole, ...]:
    """The holes of ``layout.holes`` (as :meth:`Hole.describe` writes them)."""
    if raw is None:
        return ()
    if not isinstance(raw, list):
        raise InputError("layout.holes", repr(raw), "a list of holes", reason="is malformed")
    out = []
    for i, h in enumerate(raw):
        try:
            out.append(
                Hole(
                    h["shape"],
                    (float(h["center_mm"][0]), float(h["center_mm"][1])),
                    diameter=float(h.get("diameter_mm", 0.0)),
                    vertices=tuple((float(x), float(y)) for x, y in h.get("vertices_mm", [])),
                )
            )
        except InputError as exc:
            raise exc.renamed(f"layout.holes[{i}].{exc.field}") from None
        except (TypeError, ValueError, KeyError, IndexError, AttributeError):
            raise InputError(
                f"layout.holes[{i}]",
                "?",
                "shape, center_mm and diameter_mm or vertices_mm",
                reason="is malformed",
            ) from None
    return tuple(out)


def write_record(
    content: Mapping[str, Any], folder: str | Path, staging: Staging | None = None
) -> Path:
    """Write ``content`` as ``folder/design.json`` (checked by :func:`parse_record` first, so
    what is written can be read back); with ``staging`` the file joins that output step, otherwise
    it is written all or nothing. Returns the path."""
    record = parse_record(content)
    target = Path(folder) / RECORD_NAME
    if staging is None:  # design.json alone, committed as the folder's design set
        write_set(
            folder,
            {RECORD_NAME: record.to_json() + "\n"},
            kind="design",
            supersedes=(VERIFY_KIND,),  # a verdict that names no design.json leaves with it
        )
        return target
    staging.path(target).write_text(record.to_json() + "\n", encoding="utf-8")
    return target


def read_record(path: str | Path) -> DesignRecord:
    """The record in ``path`` (a design.json or its folder), read as untrusted input
    (:func:`load_record`); an :class:`InputError` when it cannot be read or is malformed."""
    path = Path(path)
    file = path / RECORD_NAME if path.is_dir() else path
    return parse_record(load_record(file)[0])


def load_record(file: Path) -> tuple[dict[str, Any], str]:
    """The object of the design.json ``file`` checked by its schema
    (:func:`corrugate.export.record_schema.validate_record`) and the SHA-256 of the bytes it was
    read from. The file is read as untrusted input (:func:`corrugate.core.fileio.read_input`: a
    regular file of at most 8 MiB, never a FIFO or a device, strict UTF-8); an integer of more
    digits than Python converts is named by its key. Every failure is one :class:`InputError`
    line naming the file."""
    from corrugate.core.fileio import decode_input, read_input
    from corrugate.export.record_schema import validate_record

    shown = printable(str(file))
    raw = read_input(file, "design")
    text = decode_input(raw, "design", shown)
    try:
        data = json.loads(text)  # a NaN is named by its key below (validate_record)
    except json.JSONDecodeError as exc:
        raise InputError(
            "design", shown, "a JSON file", reason=f"is not JSON ({exc.msg})"
        ) from None
    except ValueError:  # an integer longer than int() converts (4300 digits)
        raise _long_integer(text, shown) from None
    except RecursionError:
        raise InputError(
            "design", shown, "a JSON object of bounded nesting", reason="is nested too deeply"
        ) from None
    if not isinstance(data, dict):
        raise InputError("design", shown, "a JSON object", reason="is not an object")
    return validate_record(data, f"{shown}"), hashlib.sha256(raw).hexdigest()


def _long_integer(text: str, shown: str) -> InputError:
    """The error of a JSON integer longer than Python converts: its key when it can be found."""
    import re

    m = re.search("[0-9]{4000,}", text)
    key = None
    if m is not None:
        keys = re.findall(r'"([^"\\]{1,80})"\s*:', text[max(0, m.start() - 400) : m.start()])
        key = keys[-1] if keys else None
    from corrugate.core.limits import MAX_INT_DIGITS

    return InputError(
        f"{shown}: {printable(key or 'a value', 80)}",
        "an integer of more than 4000 digits",
        f"a number of at most {MAX_INT_DIGITS} digits",
        reason="is too long",
    )


@dataclass(frozen=True, slots=True)
class DesignFile:
    """A design's folder as ``corrugate verify`` reads it: the ``assembly``, the
    ``constraints`` (design.json's entries, checked by its schema), the ``joint``, and
    ``sha256``, the SHA-256 of the design.json bytes they were read from (the verification names
    its design by it: docs/fea.md section 6)."""

    assembly: Any
    constraints: list[dict[str, Any]]
    joint: str
    sha256: str


def read_design(folder: Path) -> tuple[Any, list[dict[str, Any]], str]:
    """The assembly, the constraints and the joint of ``folder/design.json``
    (:func:`read_design_file`)."""
    d = read_design_file(folder)
    return d.assembly, d.constraints, d.joint


def read_design_file(folder: Path) -> DesignFile:
    """The design of ``folder/design.json`` (:class:`DesignFile`); an InputError naming the file
    when it is missing, not a regular file, not JSON, or not a valid design record
    (:func:`load_record`)."""
    from corrugate.fea.verify import check_layout

    try:
        is_dir = folder.is_dir()
    except OSError as exc:  # a name too long: the OS's words, naming DIR
        raise InputError(
            "DIR",
            str(folder),
            "a folder written by `corrugate design --out`",
            reason=f"cannot be read ({exc.strerror or type(exc).__name__})",
        ) from None
    if not is_dir:
        raise InputError(
            "DIR",
            str(folder),
            "a folder written by `corrugate design --out`",
            reason="is not a folder",
        )
    file = folder / RECORD_NAME
    data, digest = load_record(file)  # one line naming the file when it cannot be trusted
    record = parse_record(data)
    if data.get("design", {}) is None:
        status = data.get("status")
        raise InputError(
            "DIR",
            str(folder),
            "the folder of a design",
            reason=f"holds no design (its design.json: status {_shown_text(status)})",
        )
    constraints = data.get("constraints")
    if not isinstance(constraints, list) or not all(isinstance(c, dict) for c in constraints):
        raise InputError(
            f"{file}: constraints",
            type(constraints).__name__,
            "a list of constraint objects",
            reason="is malformed",
        )
    joint = str(data.get("joint", "none"))
    if record.shape is not None:  # a missing shape: record.assembly() names it
        check_layout(record.shape)
    # every layout: a circle's and a polygon's twins are the outline fixtures (docs/fea.md 2.8)
    return DesignFile(record.assembly(any_layout=True), constraints, joint, digest)


def _shown_text(value: object) -> str:
    return printable(value, 60)


def check_verify_target(folder: Path) -> None:
    """Refuse, before any FE run, a ``folder/verify.json`` that could not be replaced by a file:
    a folder, a FIFO, a device (a symlink to a regular file, or none, is fine)."""
    import os
    import stat

    target = folder / VERIFY_NAME
    try:
        mode = os.lstat(target).st_mode
    except FileNotFoundError:
        return
    except OSError as exc:
        raise InputError(
            "DIR", str(target), "a file verify.json can replace", reason=f"cannot be read ({exc})"
        ) from None
    if stat.S_ISREG(mode) or stat.S_ISLNK(mode):
        return
    what = "a folder" if stat.S_ISDIR(mode) else "not a regular file"
    raise InputError(
        "DIR", str(target), "a file verify.json can replace (remove it)", reason=f"is {what}"
    )


def design_label(a: Assembly) -> str:
    """A short name of the design: each layer's W, n, alpha and t (one set when identical)."""

    def one(x: Layer) -> str:
        return f"W={x.W:g} n={x.n} alpha={x.alpha_deg:g} t={x.t:g}"

    text = one(a.layer1) if a.layer1 == a.layer2 else f"{one(a.layer1)} / {one(a.layer2)}"
    return text if a.layout.name == DEFAULT_LAYOUT else f"{text} {a.layout.name}"
