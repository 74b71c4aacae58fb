"""Every file of a design, all in millimetres (docs/theory.md section 7): the registry of output
files (:mod:`.writers`), the cut plan (:mod:`.plan`), the 2D writers (SVG, DXF, PDF, the machines'
cut files), FOLD and meshes (:mod:`.files3d`) and ``design.json`` (:mod:`.record`).

The heavy libraries (ezdxf, matplotlib) are imported inside the functions that need them, so
importing this package costs nothing and the core of corrugate never imports them; install them
with the ``fab`` extra.
"""

from corrugate.core.fileio import staged
from corrugate.export.cutfile import cut_dxf_document, cut_paths, cut_svg_document, write_cut_files
from corrugate.export.dxf import dxf_document, write_dxf
from corrugate.export.files import FORMATS, write_files
from corrugate.export.machines import DEFAULT_MACHINE, OPERATIONS, Machine, get_machine
from corrugate.export.pdf import PAPER_CHOICES, write_pdf, write_tiled_pdf
from corrugate.export.svg import svg_document, write_svg

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
