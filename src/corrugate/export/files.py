"""Every 2D file of a sheet plan in one step: ``sheet-N.svg``, ``sheet-N.dxf`` and ``pattern.pdf``
(one mat-size page per sheet), and with ``paper="a4"`` or ``"letter"`` also ``pattern-a4.pdf`` or
``pattern-letter.pdf``: the same sheets at 1:1 on tiled office pages (:func:`.pdf.tile_figure`).

Sheets are numbered from 1 in file names (``sheet-1.svg`` is ``plan.sheets[0]``). Options are
checked and every document is built before anything is written; the files are then written to
temporary names in ``out_dir`` and moved into place together (:mod:`.staging`), so a bad option or
a failure while writing leaves no file behind, new or partial. Files of an earlier run with more
sheets are not removed.
"""

from __future__ import annotations

import contextlib
import os
from collections.abc import Iterable
from pathlib import Path

from ..errors import UnknownNameError
from ..fileio import Staging, staged
from ..pattern.linestyle import SOLID, LineStyle, check_style
from ..pattern.sheets import SheetPlan
from .dxf import dxf_document
from .pdf import check_paper, render_pdf, render_tiled_pdf
from .svg import svg_document

__all__ = ["FORMATS", "write_files"]

#: The 2D formats :func:`write_files` knows.
FORMATS = ("svg", "dxf", "pdf")


def write_files(
    plan: SheetPlan,
    out_dir: str | os.PathLike[str],
    style: LineStyle = SOLID,
    *,
    formats: Iterable[str] = FORMATS,
    labels: bool = True,
    marks: bool = True,
    pdf_name: str = "pattern.pdf",
    paper: str = "mat",
    staging: Staging | None = None,
) -> tuple[Path, ...]:
    """Write ``plan`` to ``out_dir`` (created if missing) in ``formats``; returns the paths written.

    ``style`` is the fold-line style; ``labels`` writes part labels; ``marks=False`` leaves assembly
    marks out of the SVG (Origami Simulator reads them as undriven creases). ``paper`` is ``mat``
    (``pdf_name`` only) or ``a4``/``letter``: then ``pattern-a4.pdf``/``pattern-letter.pdf`` (the
    tiles) is written besides ``pdf_name``, with the PDF format. With ``staging``, the
    files join that output step (committed with it) instead of being committed here. Raises
    :class:`~corrugate.errors.InputError` subclasses for bad options before writing anything.
    """
    wanted = [f.strip().lower() for f in formats]
    for f in wanted:
        if f not in FORMATS:
            raise UnknownNameError("format", f, list(FORMATS))
    tiles = check_paper(paper)
    check_style((p.part for p in plan.placements), style)
    svgs = (
        [svg_document(s, style, labels=labels, marks=marks) for s in plan.sheets]
        if "svg" in wanted
        else []
    )
    dxfs = [dxf_document(s, style, labels=labels) for s in plan.sheets] if "dxf" in wanted else []
    out = Path(out_dir)
    out.mkdir(parents=True, exist_ok=True)
    with contextlib.nullcontext(staging) if staging is not None else staged() as st:
        start = len(st.targets)
        for n, text in enumerate(svgs, start=1):
            st.path(out / f"sheet-{n}.svg").write_text(text, encoding="utf-8")
        for n, doc in enumerate(dxfs, start=1):
            doc.saveas(st.path(out / f"sheet-{n}.dxf"))
        if "pdf" in wanted:
            render_pdf(
                plan, st.path(out / pdf_name), style, labels=labels, title="corrugate pattern"
            )
            if tiles != "mat":
                render_tiled_pdf(
                    plan,
                    st.path(out / f"pattern-{tiles}.pdf"),
                    tiles,
                    style,
                    labels=labels,
                    title=f"corrugate pattern, 1:1 on {tiles} pages",
                )
        written = st.targets[start:]
    return written
