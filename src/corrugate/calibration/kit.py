"""``corrugate calibrate kit``: a kit's files, written as one set into a folder.

The coupons of :mod:`corrugate.calibration.coupons`, laid out on the machine's sheet as they are
to be cut (F1 along x, F2 across, never turned) and written by the design's own writers
(:func:`corrugate.export.files.write_files`: the cut files with creases and labels, the fold map
and the PDF), with the protocol (:mod:`corrugate.calibration.protocol`) and the measurements
template beside them (docs/calibration.md section 2).
"""

from __future__ import annotations

import os
from pathlib import Path

from corrugate.calibration.coupons import Kit, design_kit
from corrugate.calibration.protocol import figures, markdown, pdf_bytes, template
from corrugate.core.errors import InputError
from corrugate.core.parameters import PARAMETERS
from corrugate.fabrication.model import Part
from corrugate.fabrication.sheets import Placement, Sheet, SheetPlan
from corrugate.materials.library import Material

__all__ = ["layout", "write_kit"]


def layout(kit: Kit, cutter: object, spacing: float = 5.0, margin: float = 5.0) -> SheetPlan:
    """The coupons on one sheet of ``cutter`` (a :class:`~corrugate.core.cutters.Cutter`), none
    turned: the strips along x stacked from the top-left corner, the strip across x at the right.
    :class:`InputError` naming ``--machine`` when they do not fit."""
    from corrugate.core.cutters import Cutter

    assert isinstance(cutter, Cutter)
    parts = kit.parts()
    across = [p for p in parts if p.size[1] > p.size[0]]
    along = [p for p in parts if p not in across]
    placements: list[Placement] = []
    y = cutter.height - margin
    right = cutter.width - margin
    x_col = right
    for p in across:
        w, h = p.size
        x_col -= w
        placements.append(Placement(p, 0, x_col, cutter.height - margin - h))
        x_col -= spacing
    width_used = 0.0
    for p in along:
        w, h = p.size
        y -= h
        placements.append(Placement(p, 0, margin, y))
        y -= spacing
        width_used = max(width_used, margin + w)
    tallest = max((p.size[1] for p in across), default=0.0)
    if y < margin - spacing or width_used > x_col + spacing or tallest > cutter.height - 2 * margin:
        raise InputError(
            PARAMETERS["cutter"].flag,
            cutter.name,
            f"a sheet the coupons fit on: {_needs(along, across, spacing, margin)}",
            reason="is too small for the kit",
        )
    return SheetPlan(
        cutter, (Sheet(cutter.width, cutter.height, tuple(placements)),), spacing, margin
    )


def _needs(along: list[Part], across: list[Part], spacing: float, margin: float) -> str:
    w = max(p.size[0] for p in along) + sum(p.size[0] + spacing for p in across) + 2 * margin
    h = max(sum(p.size[1] + spacing for p in along), max((p.size[1] for p in across), default=0.0))
    return f"about {w:.0f} x {h + 2 * margin:.0f} mm"


def write_kit(
    material: Material, t: float, machine: str, out: str | os.PathLike[str], coin_g: float = 5.0
) -> tuple[Kit, list[Path]]:
    """Design the kit (:func:`~corrugate.calibration.coupons.design_kit`) and write its files
    into ``out`` as one set; returns the kit and the paths written."""
    from corrugate.core.fileio import check_output_folder, staged
    from corrugate.core.plotting import png_bytes
    from corrugate.export.files import write_files
    from corrugate.export.machines import get_machine

    folder = check_output_folder(out)
    m = get_machine(machine)
    # the strips' length: the shorter side less the margins and the column of the across strip
    usable = min(m.cutter.width, m.cutter.height) - 2 * 5.0 - 2 * 25.0
    kit = design_kit(material, t, usable, coin_g)
    plan = layout(kit, m.cutter)
    figs = figures(kit)
    texts: dict[str, str | bytes] = {name: png_bytes(fig) for name, fig in figs.items()}
    texts["protocol.md"] = markdown(kit, m.name)
    texts["protocol.pdf"] = pdf_bytes(kit, m.name, figs)
    texts["measurements.toml"] = template(kit, m.name)
    with staged(folder, "--out", kind="calibration-kit") as st:
        paths = list(write_files(plan, folder, machine=m, labels=True, staging=st))
        for name, data in texts.items():
            target = st.path(folder / name)
            if isinstance(data, bytes):
                target.write_bytes(data)
            else:
                target.write_text(data, encoding="utf-8")
            paths.append(folder / name)
    return kit, paths
