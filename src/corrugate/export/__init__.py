"""Writers for the 2D cut files (SVG, DXF, PDF), all in millimetres (DESIGN.md section 7).

The heavy libraries (ezdxf, matplotlib) are imported inside the functions that need them, so
importing this package costs nothing and the core of corrugate never imports them; install them
with the ``fab`` extra.
"""

from ..fileio import staged
from .dxf import dxf_document, write_dxf
from .files import FORMATS, write_files
from .pdf import PAPER_CHOICES, write_pdf, write_tiled_pdf
from .svg import svg_document, write_svg

__all__ = [
    "FORMATS",
    "PAPER_CHOICES",
    "dxf_document",
    "staged",
    "svg_document",
    "write_dxf",
    "write_files",
    "write_pdf",
    "write_svg",
    "write_tiled_pdf",
]
