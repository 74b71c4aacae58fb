"""Every file of a design, all in millimetres (docs/theory.md section 7): the registry of output
files (:mod:`.writers`), the cut plan (:mod:`.plan`), the 2D writers (SVG, DXF, PDF, the machines'
cut files), FOLD and meshes (:mod:`.files3d`) and ``design.json`` (:mod:`.record`).

The heavy libraries (ezdxf, matplotlib) are imported inside the functions that need them, so
the core of corrugate never imports them; install them with the ``fab`` extra. The names below
are imported on first use (PEP 562, as :mod:`corrugate` does), so importing one module of the
package (``corrugate.export.machines``: ``corrugate design`` without ``--out`` looks its machine
up there) does not import the writers.
"""

from typing import TYPE_CHECKING as _TYPE_CHECKING

from corrugate.core.lazy import lazy_names as _lazy_names

if _TYPE_CHECKING:
    from corrugate.core.fileio import staged
    from corrugate.export.cutfile import (
        cut_dxf_document,
        cut_paths,
        cut_svg_document,
        write_cut_files,
    )
    from corrugate.export.dxf import dxf_document, write_dxf
    from corrugate.export.files import FORMATS, write_files
    from corrugate.export.machines import DEFAULT_MACHINE, OPERATIONS, Machine, get_machine
    from corrugate.export.pdf import PAPER_CHOICES, write_pdf, write_tiled_pdf
    from corrugate.export.svg import svg_document, write_svg

#: Where each public name lives (a module of this package, or ``core.fileio``).
_WHERE: dict[str, str] = {
    "staged": "corrugate.core.fileio",
    **dict.fromkeys(
        ("cut_dxf_document", "cut_paths", "cut_svg_document", "write_cut_files"),
        "corrugate.export.cutfile",
    ),
    **dict.fromkeys(("dxf_document", "write_dxf"), "corrugate.export.dxf"),
    **dict.fromkeys(("FORMATS", "write_files"), "corrugate.export.files"),
    **dict.fromkeys(
        ("DEFAULT_MACHINE", "OPERATIONS", "Machine", "get_machine"), "corrugate.export.machines"
    ),
    **dict.fromkeys(("PAPER_CHOICES", "write_pdf", "write_tiled_pdf"), "corrugate.export.pdf"),
    **dict.fromkeys(("svg_document", "write_svg"), "corrugate.export.svg"),
}

__all__ = [
    "DEFAULT_MACHINE",
    "FORMATS",
    "OPERATIONS",
    "PAPER_CHOICES",
    "Machine",
    "cut_dxf_document",
    "cut_paths",
    "cut_svg_document",
    "dxf_document",
    "get_machine",
    "staged",
    "svg_document",
    "write_cut_files",
    "write_dxf",
    "write_files",
    "write_pdf",
    "write_svg",
    "write_tiled_pdf",
]


__getattr__ = _lazy_names(__name__, _WHERE, globals())


def __dir__() -> list[str]:
    return sorted(__all__)
