"""Every 2D file of a sheet plan in one step: the fold map, the machine's cut files and the PDF.

For sheet N (numbered from 1: ``sheet-1.svg`` is ``plan.sheets[0]``):

``sheet-N.svg``
    The fold map, for people and for Origami Simulator (:mod:`.svg`): outlines, mountain and valley
    creases in their colours, assembly marks, labels with the folding order. Not for a cutter.
``cut-N.dxf`` / ``cut-N.svg``
    The cut-ready files of the machine (:mod:`.machines`, :mod:`.cutfile`): only what it should
    cut, score or draw, each kind of line and its operation (:mod:`.operations`: by default
    mountains perforated, valleys cut-scored or scored, the band's marks drawn) on its own layer
    or colour, and a legend on the pen layer. A Silhouette gets DXF, a Cricut SVG, a laser both.

and ``pattern.pdf`` (every sheet at 1:1, :mod:`.pdf`), with ``--paper a4`` or ``letter`` also
``pattern-a4.pdf`` / ``pattern-letter.pdf``. Each is an entry of the writers registry
(:mod:`corrugate.export.writers`) and the functions below are their write steps;
:func:`write_files` writes the entries of the formats asked for through it. Options are checked
and every document is built before anything is written; the files are then written to temporary names in ``out_dir`` and
moved into place together (:mod:`corrugate.core.fileio`), so a bad option or a failure while writing
leaves no file behind, new or partial. Files of an earlier run with more sheets are not removed.
"""

from __future__ import annotations

import os
from collections.abc import Callable, Iterable, Sequence
from pathlib import Path
from typing import TYPE_CHECKING, Any, TypeVar

from corrugate.core.errors import UnknownNameError
from corrugate.core.fileio import Staging
from corrugate.export.cutfile import cut_dxf_document, cut_svg_document
from corrugate.export.machines import Machine, get_machine
from corrugate.export.operations import (
    FoldOperations,
    check_operations,
    default_operations,
    style_operations,
)
from corrugate.export.pdf import check_paper, render_pdf, render_tiled_pdf
from corrugate.export.svg import svg_document
from corrugate.export.writers import WRITERS, Commit, Job, Writer, get_writer, write_job
from corrugate.fabrication.linestyle import SOLID, LineStyle, check_style
from corrugate.fabrication.model import Part
from corrugate.fabrication.sheets import SheetPlan

if TYPE_CHECKING:
    from matplotlib.figure import Figure

#: One sheet's document: an SVG text or an ezdxf drawing.
_Item = TypeVar("_Item")

__all__ = [
    "FORMATS",
    "cut_dxfs",
    "cut_svgs",
    "fold_map_texts",
    "fold_maps",
    "fold_order",
    "pattern_pdf",
    "pattern_tiles",
    "plan_job",
    "write_files",
]

#: What :func:`write_files` can write: the fold map (``svg``), the cut files (``cut``), the PDF
#: (``pdf``): the ``format`` groups of the writers registry (:mod:`corrugate.export.writers`).
FORMATS = tuple(dict.fromkeys(w.format for w in WRITERS if w.format is not None))


def fold_order(parts: Iterable[Part]) -> dict[str, int]:
    """Each part's step (from 1) in the folding order of the assembly steps: the layers first
    (L1, L2, ...), then the connector band segments (B1, B2, ...), then any other part."""

    def key(p: Part) -> tuple[int, int, str]:
        rank = {"layer": 0, "connector": 1}.get(p.kind, 2)
        digits = "".join(c for c in p.name if c.isdigit())
        return rank, int(digits) if digits else 0, p.name

    return {p.name: k for k, p in enumerate(sorted(parts, key=key), start=1)}


def plan_job(
    plan: SheetPlan,
    out_dir: str | os.PathLike[str],
    style: LineStyle | None = None,
    *,
    machine: Machine | None = None,
    operations: FoldOperations | None = None,
    labels: bool | None = None,
    marks: bool = True,
    pdf_name: str | None = None,
    paper: str = "mat",
    sheet_figures: Sequence[Figure] | None = None,
) -> Job:
    """The :class:`~corrugate.export.writers.Job` of ``plan``'s files, its options checked (see
    :func:`write_files`); raises :class:`~corrugate.core.errors.InputError` subclasses for a bad
    paper, machine, fold-line style or fold operation."""
    tiles = check_paper(paper)
    m = get_machine(plan.cutter) if machine is None else machine
    parts = [p.part for p in plan.placements]
    line = SOLID if style is None else style
    check_style(parts, line)
    if operations is None:
        material = parts[0].material_id if parts else ""
        operations = (
            default_operations(m, material)
            if style is None
            else style_operations(style, m, material)
        )
    check_operations(parts, operations)
    return Job(
        out=Path(out_dir),
        plan=plan,
        style=line,
        operations=operations,
        machine=m,
        labels=labels,
        marks=marks,
        paper=tiles,
        pdf_name=pdf_name,
        sheet_figures=sheet_figures,
    )


def write_files(
    plan: SheetPlan,
    out_dir: str | os.PathLike[str],
    style: LineStyle | None = None,
    *,
    machine: Machine | None = None,
    operations: FoldOperations | None = None,
    formats: Iterable[str] = FORMATS,
    labels: bool | None = None,
    marks: bool = True,
    pdf_name: str | None = None,
    paper: str = "mat",
    staging: Staging | None = None,
    sheet_figures: Sequence[Figure] | None = None,
) -> tuple[Path, ...]:
    """Write ``plan`` to ``out_dir`` (created if missing) in ``formats``; returns the paths written.

    ``style`` is the fold-line style of the fold map and the PDF (None: solid) and, without
    ``operations``, the ``--fold-style`` shorthand of the cut files' fold operations
    (:func:`~corrugate.export.operations.style_operations`); ``operations`` are the cut files'
    fold operations (None with no style: the machine's default for the sheet's material,
    :func:`~corrugate.export.operations.default_operations`); ``machine`` the machine profile
    (default: the plan's cutter). ``labels``: ``None`` or ``True`` writes labels everywhere (in the cut files as the LABEL
    operation: the part's name drawn by the pen or engraved, so that the cut parts carry the names
    the assembly steps use), ``False`` nowhere.
    ``marks=False`` leaves assembly marks out of the fold map (Origami Simulator does not import
    them either way: they sit in ``<defs>``, :mod:`corrugate.export.svg`). With ``staging``, the files join that output step (committed with it)
    instead of being committed here. ``paper`` is ``mat`` (``pdf_name`` only) or ``a4``/``letter``:
    then ``pattern-a4.pdf``/``pattern-letter.pdf`` (the tiles) is written besides ``pdf_name``
    (None: ``pattern.pdf``). ``sheet_figures``: the sheets' :func:`~corrugate.export.pdf.sheet_figure`
    with these ``style`` and labels, built already, for ``pdf_name`` (``None``: built here). The
    files are those of the writers registry's entries of ``formats``
    (:mod:`corrugate.export.writers`). Raises :class:`~corrugate.core.errors.InputError`
    subclasses for bad options before writing anything.
    """
    wanted = [f.strip().lower() for f in formats]
    for f in wanted:
        if f not in FORMATS:
            raise UnknownNameError("format", f, list(FORMATS))
    job = plan_job(
        plan,
        out_dir,
        style,
        machine=machine,
        operations=operations,
        labels=labels,
        marks=marks,
        pdf_name=pdf_name,
        paper=paper,
        sheet_figures=sheet_figures,
    )
    return tuple(write_job(job, [w for w in WRITERS if w.format in wanted], staging))


# -- the registry's steps of a sheet plan's files (see corrugate.export.writers) ----------------


def _commit_sheets(
    out: Path, writer: Writer, items: Sequence[_Item], save: Callable[[_Item, Path], None]
) -> Commit:
    """What writes ``items`` (one per sheet, from sheet 1) under ``writer``'s file names, each by
    ``save(item, path)``."""

    def commit(st: Staging, _: Sequence[Path]) -> list[Path]:
        paths = []
        for n, item in enumerate(items, start=1):
            target = out / writer.file(sheet=n)
            save(item, st.path(target))
            paths.append(target)
        return paths

    return commit


def _save_text(text: str, path: Path) -> None:
    path.write_text(text, encoding="utf-8")


def _save_dxf(doc: Any, path: Path) -> None:
    doc.saveas(path)


def fold_map_texts(
    plan: SheetPlan,
    style: LineStyle = SOLID,
    *,
    labels: bool = True,
    marks: bool = True,
    operations: FoldOperations | None = None,
) -> list[str]:
    """The SVG text of each sheet's fold map (:func:`~corrugate.export.svg.svg_document`), labels
    with the folding order (:func:`fold_order`) unless ``labels`` is False: ``sheet-N.svg``."""
    order = fold_order(p.part for p in plan.placements)
    return [
        svg_document(
            s,
            style,
            labels=labels,
            marks=marks,
            fold_order=order,
            operations=operations,
            margin=plan.margin,
            spacing=plan.spacing,
        )
        for s in plan.sheets
    ]


def fold_maps(job: Job) -> Commit:
    """``sheet-N.svg``: the fold map of each sheet (:func:`fold_map_texts`), labels with the
    folding order unless ``labels`` is False; the texts are kept in ``job.drawings`` (when the job
    has one) for the report."""
    texts = fold_map_texts(
        job.plan,
        job.style,
        labels=job.labels is not False,
        marks=job.marks,
        operations=job.operations,
    )
    if job.drawings is not None:  # the report embeds these very files
        job.drawings.fold_maps = texts
    return _commit_sheets(job.out, get_writer("fold-map"), texts, _save_text)


def cut_svgs(job: Job) -> Commit:
    """``cut-N.svg`` for a machine that takes SVG (:func:`~corrugate.export.cutfile.cut_svg_document`),
    labels unless ``labels`` is False; nothing for another machine."""
    texts = (
        [
            cut_svg_document(
                s,
                job.machine,
                job.operations,
                labels=job.labels is not False,
                margin=job.plan.margin,
                spacing=job.plan.spacing,
            )
            for s in job.plan.sheets
        ]
        if "svg" in job.machine.formats
        else []
    )
    return _commit_sheets(job.out, get_writer("cut-svg"), texts, _save_text)


def cut_dxfs(job: Job) -> Commit:
    """``cut-N.dxf`` for a machine that takes DXF (:func:`~corrugate.export.cutfile.cut_dxf_document`),
    labels unless ``labels`` is False; nothing for another machine."""
    docs = (
        [
            cut_dxf_document(
                s,
                job.machine,
                job.operations,
                labels=job.labels is not False,
                margin=job.plan.margin,
                spacing=job.plan.spacing,
            )
            for s in job.plan.sheets
        ]
        if "dxf" in job.machine.formats
        else []
    )
    return _commit_sheets(job.out, get_writer("cut-dxf"), docs, _save_dxf)


def pattern_pdf(job: Job) -> Commit:
    """``pattern.pdf`` (``pdf_name``): every sheet at 1:1, one page each
    (:func:`~corrugate.export.pdf.render_pdf`, drawn when it is written, from ``sheet_figures``
    when given)."""

    def commit(st: Staging, _: Sequence[Path]) -> list[Path]:
        target = job.out / (job.pdf_name or get_writer("pattern-pdf").pattern)
        render_pdf(
            job.plan,
            st.path(target),
            job.style,
            labels=job.labels is not False,
            title="corrugate pattern",
            figures=job.sheet_figures,
            operations=job.operations,
        )
        return [target]

    return commit


def pattern_tiles(job: Job) -> Commit:
    """``pattern-a4.pdf`` / ``pattern-letter.pdf`` with ``paper`` a4 or letter: the sheets at 1:1 on
    office pages (:func:`~corrugate.export.pdf.render_tiled_pdf`); nothing with ``mat``."""

    def commit(st: Staging, _: Sequence[Path]) -> list[Path]:
        if job.paper == "mat":
            return []
        target = job.out / get_writer("pattern-tiles").file(paper=job.paper)
        render_tiled_pdf(
            job.plan,
            st.path(target),
            job.paper,
            job.style,
            labels=job.labels is not False,
            title=f"corrugate pattern, 1:1 on {job.paper} pages",
            operations=job.operations,
        )
        return [target]

    return commit
