"""New matplotlib figures without pyplot.

pyplot keeps global state (the current figure, a registry of open figures) that threads share, and
importing it selects a GUI backend. The package draws with the object API instead: a
:class:`matplotlib.figure.Figure` on its own Agg canvas, saved with ``fig.savefig`` and freed when
it is no longer referenced, so figures can be drawn in parallel threads (the web app).
"""

from __future__ import annotations

import io
from typing import TYPE_CHECKING, Any

if TYPE_CHECKING:
    from matplotlib.figure import Figure

__all__ = ["new_figure", "png_bytes"]


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
