"""New matplotlib figures without pyplot.

pyplot keeps global state (the current figure, a registry of open figures) that threads share, and
importing it selects a GUI backend. The package draws with the object API instead: a
:class:`matplotlib.figure.Figure` on its own Agg canvas, saved with ``fig.savefig`` and freed when
it is no longer referenced, so figures can be drawn in parallel threads (the web app).
"""

from __future__ import annotations

import importlib.util
import io
import sys
import threading
from typing import TYPE_CHECKING, Any

if TYPE_CHECKING:
    from matplotlib.backends.backend_pdf import PdfPages
    from matplotlib.figure import Figure

__all__ = ["LAZY_FOR_PDF", "new_figure", "pdf_pages", "png_bytes"]

#: Modules matplotlib's PDF backend imports at its top but uses only for what the package's PDF
#: files do not hold: fontTools' subsetter (``matplotlib.backends._backend_pdf_ps``, for Type 42
#: fonts; the files embed matplotlib's default Type 3 fonts). :func:`pdf_pages` has it loaded on
#: first use instead: about 0.13 s of CPU less per process that writes a PDF (``import
#: matplotlib.backends.backend_pdf`` after matplotlib.figure: 0.134-0.176 s against 0.007-0.010
#: s, 4 runs each; issue 24). (fontTools' glyph list, which ``matplotlib.dviread`` imports for
#: TeX, cannot wait so: a second ``import`` of a lazy module executes it; it costs 0.02 s.)
LAZY_FOR_PDF = ("fontTools.subset",)

_LAZY_LOCK = threading.Lock()


def new_figure(figsize: tuple[float, float], dpi: float | None = None, **kwargs: Any) -> Figure:
    """A figure of ``figsize`` (inches) at ``dpi`` (dots per inch; None: matplotlib's default)
    on an Agg canvas; ``kwargs`` go to :class:`~matplotlib.figure.Figure`."""
    from matplotlib.backends.backend_agg import FigureCanvasAgg
    from matplotlib.figure import Figure

    fig = Figure(figsize=figsize, dpi=dpi, **kwargs)
    FigureCanvasAgg(fig)
    return fig


def png_bytes(fig: Figure, compress_level: int = 6, **kwargs: Any) -> bytes:
    """The PNG file of ``fig`` (bytes), compressed at zlib level ``compress_level`` (Pillow's
    option; 6 is its default, the pixels are the same at every level); ``kwargs`` go to
    :meth:`~matplotlib.figure.Figure.savefig` (``dpi``, ...)."""
    buf = io.BytesIO()
    fig.savefig(buf, format="png", pil_kwargs={"compress_level": compress_level}, **kwargs)
    return buf.getvalue()


def _import_lazily(name: str) -> None:
    """Put the submodule ``name`` into :data:`sys.modules` (and on its package) as a module that
    is executed at its first attribute access (:class:`importlib.util.LazyLoader`, the standard
    library's lazy import); nothing when it is imported already or cannot be found."""
    if name in sys.modules:
        return
    spec = importlib.util.find_spec(name)
    if spec is None or spec.loader is None:
        return
    loader = importlib.util.LazyLoader(spec.loader)
    spec.loader = loader
    module = importlib.util.module_from_spec(spec)
    sys.modules[name] = module
    loader.exec_module(module)
    package, _, child = name.rpartition(".")
    setattr(sys.modules[package], child, module)


def pdf_pages() -> type[PdfPages]:
    """matplotlib's :class:`~matplotlib.backends.backend_pdf.PdfPages`, its backend imported with
    the modules of :data:`LAZY_FOR_PDF` loaded on first use (the same files: a Type 42 font or a
    TeX text would load them as it needs them)."""
    with _LAZY_LOCK:
        if "matplotlib.backends.backend_pdf" not in sys.modules:
            for name in LAZY_FOR_PDF:
                _import_lazily(name)
        from matplotlib.backends.backend_pdf import PdfPages
    return PdfPages
