"""What the machine does with each kind of crease: the fold operations of a cut file.

A :class:`FoldOperations` value says how mountain creases, valley creases and the band's angle
marks reach the machine, each by one :class:`FoldOp`:

``cut-score``
    one line cut part-way through (a kiss cut: the blade at a lower force, a laser at a low
    power), opening on the outside of the fold;
``perforate``
    the crease cut through as dashes of ``cut`` mm with gaps of ``gap`` mm
    (:func:`corrugate.fabrication.linestyle.dashes`);
``score``
    one line pressed, not cut (Cricut's scoring wheel or stylus, an embossing tool);
``pen``
    one line drawn with a pen (a laser engraves it at its lowest power);
``none``
    not in the cut file (fold it by hand from the fold map).

Each kind keeps its palette colour in every operation (:mod:`corrugate.fabrication.palette`:
mountain red, valley blue, marks magenta), so the cut part itself tells mountain from valley
(different operations) and carries the band's marks, which set the fold angle.

The default (:func:`default_operations`): mountains perforated, valleys by the operation that suits
the sheet (:mod:`corrugate.export.guidance`: a cut-score for films, a score for card and metal),
the marks drawn with the pen; the perforation's cut and gap are the material's. A machine that
cannot do an operation gets the nearest one it can: Cricut Design Space sets one pressure for the
whole mat, so a Cricut scores where a cut-score is asked for; a laser cannot press, so it
cut-scores where a score is asked for (:func:`fold_operations` refuses such an operation when it is
asked for by name). A perforated mark is refused: it would be a tear line across the band's wall.

``--fold-style`` is a shorthand (:func:`style_operations`): ``machine`` is the default above;
``solid`` leaves the creases out (marks still drawn); ``scored`` scores both kinds (a laser
cut-scores them); ``perforated`` perforates both.

:func:`fold_operations` is the one entry point for the command line, the web app and the spec's
``[fabrication]`` section: it takes names as the user writes them and returns the value, or raises
an :class:`~corrugate.core.errors.InputError` naming the field.
"""

from __future__ import annotations

from collections.abc import Iterable
from dataclasses import dataclass
from enum import StrEnum

from corrugate.core.errors import InputError, UnknownNameError
from corrugate.export.guidance import get_guidance
from corrugate.export.machines import Family, Machine
from corrugate.fabrication.linestyle import (
    LineStyle,
    PerforationError,
    StyleKind,
    check_style,
    line_style,
)
from corrugate.fabrication.model import Part, Role
from corrugate.names import FOLD_OP_NAMES

__all__ = [
    "CREASE_KINDS",
    "FoldChoice",
    "FoldOp",
    "FoldOperations",
    "check_operations",
    "default_operations",
    "fold_operations",
    "style_operations",
]

#: The kinds of line a :class:`FoldOperations` decides, by role.
CREASE_KINDS: dict[Role, str] = {
    Role.MOUNTAIN: "mountain",
    Role.VALLEY: "valley",
    Role.MARK: "marks",
}


class FoldOp(StrEnum):
    """One way of making a crease or a mark on the machine (module docstring)."""

    CUT_SCORE = "cut-score"
    PERFORATE = "perforate"
    SCORE = "score"
    PEN = "pen"
    NONE = "none"


#: What each family of machine cannot do, and what it does instead.
_SUBSTITUTE: dict[Family, dict[FoldOp, FoldOp]] = {
    Family.SILHOUETTE: {},
    Family.CRICUT: {FoldOp.CUT_SCORE: FoldOp.SCORE},
    Family.LASER: {FoldOp.SCORE: FoldOp.CUT_SCORE},
}
_WHY: dict[Family, str] = {
    Family.SILHOUETTE: "",
    Family.CRICUT: "Cricut Design Space sets one pressure for the whole mat, so it cannot cut "
    "part-way through one layer",
    Family.LASER: "a laser cannot press a line into the sheet",
}


@dataclass(frozen=True, slots=True)
class FoldOperations:
    """How ``mountain`` and ``valley`` creases and the band's ``marks`` reach the machine, and the
    perforation's ``cut`` and ``gap`` (mm; used by the kinds that are perforated)."""

    mountain: FoldOp = FoldOp.PERFORATE
    valley: FoldOp = FoldOp.CUT_SCORE
    marks: FoldOp = FoldOp.PEN
    cut: float = 1.0
    gap: float = 0.5

    def __post_init__(self) -> None:
        if self.marks is FoldOp.PERFORATE:
            raise InputError(
                "marks",
                "perforate",
                "cut-score, score, pen or none (a perforated mark tears the band's wall)",
            )
        if self.perforates:
            self.perforation  # noqa: B018 - checks the cut and gap (LIMITS["perforation"])

    def of(self, role: Role) -> FoldOp:
        """The operation of a line of ``role`` (``none`` for a cut line)."""
        if role is Role.MOUNTAIN:
            return self.mountain
        if role is Role.VALLEY:
            return self.valley
        if role is Role.MARK:
            return self.marks
        return FoldOp.NONE

    @property
    def perforates(self) -> bool:
        """Whether some kind is perforated."""
        return FoldOp.PERFORATE in (self.mountain, self.valley)

    @property
    def perforation(self) -> LineStyle:
        """The perforated style of the dashes (raises a ``PerforationError`` for a cut or gap
        outside ``LIMITS["perforation"]``)."""
        return LineStyle(StyleKind.PERFORATED, self.cut, self.gap)

    def as_dict(self) -> dict[str, object]:
        """The record of ``design.json``: each kind's operation and the perforation (mm)."""
        return {
            "mountain": self.mountain.value,
            "valley": self.valley.value,
            "marks": self.marks.value,
            "perforation_cut_mm": self.cut,
            "perforation_gap_mm": self.gap,
        }


def _substitute(op: FoldOp, machine: Machine) -> FoldOp:
    return _SUBSTITUTE[machine.family].get(op, op)


def default_operations(machine: Machine, material_id: str = "") -> FoldOperations:
    """The default of ``machine`` for a sheet of ``material_id``: mountains perforated with the
    material's cut and gap, valleys by the material's operation (or the machine's nearest), marks
    drawn with the pen (module docstring)."""
    m = machine
    g = get_guidance(material_id)
    cut, gap = g.perforation
    valley = _substitute(FoldOp(g.valley), m)
    return FoldOperations(FoldOp.PERFORATE, valley, FoldOp.PEN, cut, gap)


def style_operations(
    style: str | LineStyle, machine: Machine, material_id: str = ""
) -> FoldOperations:
    """The operations ``--fold-style`` stands for (``machine``, ``solid``, ``scored`` or
    ``perforated``; a :class:`LineStyle` keeps its cut and gap)."""
    m = machine
    base = default_operations(m, material_id)
    if isinstance(style, LineStyle):
        kind = style.kind
    else:
        key = str(style).strip().lower()
        if key == "machine":
            return base
        kind = line_style(key, base.cut, base.gap).kind
    if kind is StyleKind.SOLID:
        return FoldOperations(FoldOp.NONE, FoldOp.NONE, FoldOp.PEN, base.cut, base.gap)
    if kind is StyleKind.SCORED:
        op = _substitute(FoldOp.SCORE, m)
        return FoldOperations(op, op, FoldOp.PEN, base.cut, base.gap)
    cut, gap = (style.cut, style.gap) if isinstance(style, LineStyle) else (base.cut, base.gap)
    return FoldOperations(FoldOp.PERFORATE, FoldOp.PERFORATE, FoldOp.PEN, cut, gap)


def _op(name: str, field: str, machine: Machine) -> FoldOp:
    key = name.strip().lower()
    try:
        op = FoldOp(key)
    except ValueError:
        raise UnknownNameError(field, name, list(FOLD_OP_NAMES)) from None
    if _substitute(op, machine) is not op:
        allowed = [o.value for o in FoldOp if _substitute(o, machine) is o]
        raise InputError(
            field,
            key,
            f"one of {', '.join(allowed)} on {machine.name} ({_WHY[machine.family]})",
            reason="is not an operation this machine can do",
        )
    return op


def fold_operations(
    machine: Machine,
    material_id: str = "",
    *,
    style: str | None = None,
    mountain: str | None = None,
    valley: str | None = None,
    marks: str | None = None,
    cut: float | None = None,
    gap: float | None = None,
) -> FoldOperations:
    """The fold operations asked for: ``style`` (the ``--fold-style`` shorthand, None: the
    machine's default for ``material_id``), then each kind named (``mountain``, ``valley``,
    ``marks``: ``cut-score``, ``perforate``, ``score``, ``pen`` or ``none``), and the perforation's
    ``cut`` and ``gap`` in mm (None: the material's, :mod:`corrugate.export.guidance`).

    Raises :class:`~corrugate.core.errors.UnknownNameError` for an unknown operation or style and
    :class:`~corrugate.core.errors.InputError` naming the field (``mountain``, ``valley``,
    ``marks``, ``cut``, ``gap``) for an operation the machine cannot do or a bad perforation.
    """
    m = machine
    base = style_operations(style or "machine", m, material_id)
    ops = {
        "mountain": base.mountain if mountain is None else _op(mountain, "mountain", m),
        "valley": base.valley if valley is None else _op(valley, "valley", m),
        "marks": base.marks if marks is None else _op(marks, "marks", m),
    }
    try:
        return FoldOperations(
            ops["mountain"],
            ops["valley"],
            ops["marks"],
            base.cut if cut is None else float(cut),
            base.gap if gap is None else float(gap),
        )
    except PerforationError as exc:
        raise exc.renamed("cut" if exc.field.endswith("cut") else "gap") from None


@dataclass(frozen=True, slots=True)
class FoldChoice:
    """Fold operations as the user asks for them, before the sheet's material is known: the
    ``style`` shorthand (``machine``: the default), each kind's operation name or None, and the
    perforation's ``cut`` and ``gap`` (mm, None: the material's). :meth:`resolve` makes the value
    for a machine and a material (:func:`fold_operations`)."""

    style: str = "machine"
    mountain: str | None = None
    valley: str | None = None
    marks: str | None = None
    cut: float | None = None
    gap: float | None = None

    def resolve(self, machine: Machine, material_id: str = "") -> FoldOperations:
        """The operations for ``machine`` and a sheet of ``material_id``."""
        return fold_operations(
            machine,
            material_id,
            style=self.style,
            mountain=self.mountain,
            valley=self.valley,
            marks=self.marks,
            cut=self.cut,
            gap=self.gap,
        )


def check_operations(parts: Iterable[Part], ops: FoldOperations) -> None:
    """Raise a :class:`~corrugate.fabrication.linestyle.PerforationError` if ``ops`` perforate a
    crease too short for one dash (or give too many dashes); call it before writing any file."""
    if not ops.perforates:
        return
    kinds = {r for r in (Role.MOUNTAIN, Role.VALLEY) if ops.of(r) is FoldOp.PERFORATE}
    chosen = [
        Part(p.name, p.label, p.outline, tuple(ln for ln in p.lines if ln.role in kinds), p.holes)
        for p in parts
    ]
    check_style(chosen, ops.perforation)
