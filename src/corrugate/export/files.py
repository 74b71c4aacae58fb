"""Every 2D file of a sheet plan in one step: the fold map, the machine's cut files and the PDF.

For sheet N (numbered from 1: ``sheet-1.svg`` is ``plan.sheets[0]``):

``sheet-N.svg``
    The fold map, for people and for Origami Simulator (:mod:`.svg`): outlines, mountain and valley
    creases in their colours, assembly marks, labels with the folding order. Not for a cutter.
``cut-N.dxf`` / ``cut-N.svg``
    The cut-ready files of the machine (:mod:`.machines`, :mod:`.cutfile`): only what it should
    cut, score or draw, each operation on its own layer or colour. A Silhouette gets DXF, a Cricut
    SVG, a laser both.

and ``pattern.pdf`` (every sheet at 1:1, :mod:`.pdf`). Options are checked and every document is
built before anything is written; the files are then written to temporary names in ``out_dir`` and
moved into place together (:mod:`corrugate.core.fileio`), so a bad option or a failure while writing
leaves no file behind, new or partial. Files of an earlier run with more sheets are not removed.
"""

from __future__ import annotations

import contextlib
import os
from collections.abc import Iterable, Sequence
from pathlib import Path
from typing import TYPE_CHECKING

from corrugate.core.errors import UnknownNameError
from corrugate.core.fileio import Staging, staged
from corrugate.export.cutfile import cut_dxf_document, cut_svg_document
from corrugate.export.machines import Machine, get_machine
from corrugate.export.pdf import check_paper, render_pdf, render_tiled_pdf
from corrugate.export.svg import svg_document
from corrugate.fabrication.linestyle import SOLID, LineStyle, check_style
from corrugate.fabrication.model import Part
from corrugate.fabrication.sheets import SheetPlan

if TYPE_CHECKING:
    from matplotlib.figure import Figure

__all__ = ["FORMATS", "fold_order", "write_files"]

#: What :func:`write_files` can write: the fold map (``svg``), the cut files (``cut``), the PDF.
FORMATS = ("svg", "cut", "pdf")


def fold_order(parts: Iterable[Part]) -> dict[str, int]:
    """Each part's step (from 1) in the folding order of the assembly steps: the layers first
    (L1, L2, ...), then the connector band segments (B1, B2, ...), then any other part."""

    def key(p: Part) -> tuple[int, int, str]:
        rank = {"layer": 0, "connector": 1}.get(p.kind, 2)
        digits = "".join(c for c in p.name if c.isdigit())
        return rank, int(digits) if digits else 0, p.name

    return {p.name: k for k, p in enumerate(sorted(parts, key=key), start=1)}


def write_files(
    plan: SheetPlan,
    out_dir: str | os.PathLike[str],
    style: LineStyle = SOLID,
    *,
    machine: str | Machine | None = None,
    formats: Iterable[str] = FORMATS,
    labels: bool | None = None,
    marks: bool = True,
    pdf_name: str = "pattern.pdf",
    paper: str = "mat",
    staging: Staging | None = None,
    sheet_figures: Sequence[Figure] | None = None,
) -> tuple[Path, ...]:
    """Write ``plan`` to ``out_dir`` (created if missing) in ``formats``; returns the paths written.

    ``style`` is the fold-line style; ``machine`` the machine profile (default: the plan's
    cutter). ``labels``: ``None`` writes labels on the fold map and the PDF but not in the cut
    files, ``True`` everywhere (in the cut files as the LABEL operation), ``False`` nowhere.
    ``marks=False`` leaves assembly marks out of the fold map (Origami Simulator reads them as
    undriven creases). With ``staging``, the files join that output step (committed with it)
    instead of being committed here. ``paper`` is ``mat`` (``pdf_name`` only) or ``a4``/``letter``:
    then ``pattern-a4.pdf``/``pattern-letter.pdf`` (the tiles) is written besides ``pdf_name``.
    ``sheet_figures``: the sheets' :func:`~corrugate.export.pdf.sheet_figure` with these
    ``style`` and labels, built already, for ``pdf_name`` (``None``: built here). Raises :class:`~corrugate.core.errors.InputError` subclasses for
    bad options before writing anything.
    """
    wanted = [f.strip().lower() for f in formats]
    for f in wanted:
        if f not in FORMATS:
            raise UnknownNameError("format", f, list(FORMATS))
    tiles = check_paper(paper)
    m = get_machine(plan.cutter if machine is None else machine)
    check_style((p.part for p in plan.placements), style)
    people = labels is not False
    order = fold_order(p.part for p in plan.placements)
    svgs = (
        [svg_document(s, style, labels=people, marks=marks, fold_order=order) for s in plan.sheets]
        if "svg" in wanted
        else []
    )
    cut_svgs: list[str] = []
    cut_dxfs = []
    if "cut" in wanted:
        on = labels is True
        if "svg" in m.formats:
            cut_svgs = [cut_svg_document(s, m, style, labels=on) for s in plan.sheets]
        if "dxf" in m.formats:
            cut_dxfs = [cut_dxf_document(s, m, style, labels=on) for s in plan.sheets]
    out = Path(out_dir)
    out.mkdir(parents=True, exist_ok=True)
    with contextlib.nullcontext(staging) if staging is not None else staged() as st:
        start = len(st.targets)
        for n, text in enumerate(svgs, start=1):
            st.path(out / f"sheet-{n}.svg").write_text(text, encoding="utf-8")
        for n, text in enumerate(cut_svgs, start=1):
            st.path(out / f"cut-{n}.svg").write_text(text, encoding="utf-8")
        for n, doc in enumerate(cut_dxfs, start=1):
            doc.saveas(st.path(out / f"cut-{n}.dxf"))
        if "pdf" in wanted:
            render_pdf(
                plan,
                st.path(out / pdf_name),
                style,
                labels=people,
                title="corrugate pattern",
                figures=sheet_figures,
            )
            if tiles != "mat":
                render_tiled_pdf(
                    plan,
                    st.path(out / f"pattern-{tiles}.pdf"),
                    tiles,
                    style,
                    labels=people,
                    title=f"corrugate pattern, 1:1 on {tiles} pages",
                )
        written = st.targets[start:]
    return written
