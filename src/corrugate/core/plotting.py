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

__all__ = [
    "LAZY_FOR_PDF",
    "import_figure_module",
    "lean_import",
    "new_figure",
    "pdf_pages",
    "png_bytes",
    "svg_text",
]

#: Modules matplotlib's PDF backend imports at its top but uses only for what the package's PDF
#: files do not hold: fontTools' subsetter (``matplotlib.backends._backend_pdf_ps``, for Type 42
#: fonts; the files embed matplotlib's default Type 3 fonts). :func:`pdf_pages` has it loaded on
#: first use instead: about 0.13 s of CPU less per process that writes a PDF (``import
#: matplotlib.backends.backend_pdf`` after matplotlib.figure: 0.134-0.176 s against 0.007-0.010
#: s, 4 runs each; issue 24). (fontTools' glyph list, which ``matplotlib.dviread`` imports for
#: TeX, cannot wait so: a second ``import`` of a lazy module executes it; it costs 0.02 s.)
LAZY_FOR_PDF = ("fontTools.subset",)

_LAZY_LOCK = threading.Lock()

#: Whether the first import of matplotlib's figure module in this process skips the text it
#: builds for introspection only (:func:`lean_import`); off unless a command asks.
_LEAN = False
#: The class method of matplotlib's ``Artist`` that writes each artist class's ``set`` help.
_SET_HELP = "_update_set_signature_and_docstring"


def lean_import(on: bool = True) -> None:
    """Have :func:`import_figure_module` import matplotlib without the signature and docstring of
    each artist class's ``set`` method: matplotlib writes both for every class it defines (about
    a hundred), listing every property of the class with its help text, and interpolates the
    same lists into other docstrings: 0.09 s of CPU of the 0.30 s its import takes (``import
    matplotlib.figure`` as usual and leanly, five interleaved runs each, 0.29-0.31 s against
    0.195-0.214 s; issue 39). Nothing drawn depends on them; ``help(Line2D.set)`` and
    ``inspect.signature(Line2D.set)`` then show ``set(**kwargs)`` without the property list.
    The command line asks for it (:func:`corrugate.cli.main`: its process only draws files); a
    notebook or a program importing the package keeps matplotlib's full help."""
    global _LEAN
    _LEAN = on


def _no_property_list(artist: object) -> str:
    """What :func:`import_figure_module` has ``matplotlib.artist.kwdoc`` (an artist class's
    property list, interpolated into the docstrings of the functions that take its properties)
    return while matplotlib is imported leanly: nothing."""
    return ""


def _decorate_as_written(decorator: object, obj: Any) -> Any:
    """What :func:`import_figure_module` has matplotlib's docstring decorators do (their
    ``__call__``) while matplotlib is imported leanly: give back the decorated object, its
    docstring as written."""
    return obj


def _no_data_note(docstring: str | None, replace_names: object) -> str | None:
    """What :func:`import_figure_module` has ``matplotlib._add_data_doc`` (the note on a
    ``data`` argument, added to the docstring of each function that takes one) do while
    matplotlib is imported leanly: give back the docstring as written."""
    return docstring


def import_figure_module() -> None:
    """Import ``matplotlib.figure`` (and the Agg backend) once, leanly when :func:`lean_import`
    asked: matplotlib's ``Artist._update_set_signature_and_docstring`` (called for each artist
    class as it is defined) only marks the class's ``set`` as its own, and
    ``matplotlib.artist.kwdoc`` (the property lists matplotlib interpolates into the docstrings
    of ``plot``, ``Line2D`` and the like) gives an empty text, while the figure module and the
    modules it imports are loaded; both are then put back, so classes defined later get their
    full help again (the docstrings made during the import keep no property list; the empty
    ``kwdoc`` saves 0.013 s of the 0.09 s). matplotlib's docstring decorators
    (``_docstring.interpd`` and ``_docstring.Substitution``, which tidy each decorated
    docstring's indentation and fill in its ``%(name)s`` fields) and ``_add_data_doc`` (the
    note on a ``data`` argument) leave the docstrings as written for that time too: about 0.01 s
    of CPU less again (this function, leanly, after ``import numpy``: 0.187 s against 0.203 s,
    medians of 21 interleaved runs, and 0.200 s against 0.207 s in another 11; issue 39); a
    docstring decorated after the import is filled in as before. Nothing changes
    when matplotlib is imported already, when it is not asked for, or when matplotlib does not
    have those (another version: the plain import)."""
    if "matplotlib.figure" in sys.modules or not _LEAN:
        import matplotlib.backends.backend_agg
        import matplotlib.figure

        return
    with _LAZY_LOCK:
        import matplotlib
        import matplotlib._docstring
        import matplotlib.artist

        artist = matplotlib.artist.Artist
        docstring = matplotlib._docstring
        substitutions = [
            getattr(docstring, name, None)
            for name in ("_ArtistPropertiesSubstitution", "Substitution")
        ]
        original = artist.__dict__.get(_SET_HELP)
        add_data_doc = getattr(matplotlib, "_add_data_doc", None)
        if (
            not isinstance(original, classmethod)  # not the matplotlib this was measured on
            or not all(isinstance(c, type) and "__call__" in c.__dict__ for c in substitutions)
            or not callable(add_data_doc)
        ):
            import matplotlib.backends.backend_agg
            import matplotlib.figure

            return

        def mark_only(cls: type) -> None:
            cls.set._autogenerated_signature = True  # type: ignore[attr-defined]

        # (owner, attribute, lean value, matplotlib's value), put back after the import
        patches: list[tuple[Any, str, Any, Any]] = [
            (artist, _SET_HELP, classmethod(mark_only), original),
            (matplotlib.artist, "kwdoc", _no_property_list, matplotlib.artist.kwdoc),
            (matplotlib, "_add_data_doc", _no_data_note, add_data_doc),
        ]
        patches += [
            (c, "__call__", _decorate_as_written, c.__dict__["__call__"]) for c in substitutions
        ]
        for owner, name, lean, _ in patches:
            setattr(owner, name, lean)
        try:
            import matplotlib.backends.backend_agg
            import matplotlib.figure
        finally:
            for owner, name, _, own in patches:
                setattr(owner, name, own)


def new_figure(figsize: tuple[float, float], dpi: float | None = None, **kwargs: Any) -> Figure:
    """A figure of ``figsize`` (inches) at ``dpi`` (dots per inch; None: matplotlib's default)
    on an Agg canvas; ``kwargs`` go to :class:`~matplotlib.figure.Figure`."""
    import_figure_module()
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


#: One SVG drawn at a time: :func:`svg_text`'s options are matplotlib's global settings, set
#: while it draws.
_SVG_LOCK = threading.Lock()


def svg_text(fig: Figure) -> str:
    """The SVG file of ``fig`` (text): vector, its labels as searchable ``<text>`` in the
    viewer's font (DejaVu Sans first, then matplotlib's fallbacks down to ``sans-serif``), not
    each glyph drawn as a path; the ids of clip paths and markers hashed with a fixed salt and
    no date written, so the same figure gives the same text.

    The report's plots (issue 39): the blimp example's three drawn and encoded as SVG in 0.141 s
    of CPU against 0.258 s as PNG, ``report_html`` 0.252 s against 0.371 s
    (``benchmarks/figures.py --base main --repeats 5``, 16:10 UTC), 120 677 bytes against 259 448
    and report.html 380 KB against 565 KB: matplotlib lays each label out to place it either
    way, but an SVG does not rasterise its glyphs, its lines or its filled regions."""
    import matplotlib

    buf = io.BytesIO()
    with _SVG_LOCK, matplotlib.rc_context({"svg.fonttype": "none", "svg.hashsalt": "corrugate"}):
        fig.savefig(buf, format="svg", metadata={"Date": None})
    return buf.getvalue().decode("utf-8")


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
    import_figure_module()
    with _LAZY_LOCK:
        if "matplotlib.backends.backend_pdf" not in sys.modules:
            for name in LAZY_FOR_PDF:
                _import_lazily(name)
        from matplotlib.backends.backend_pdf import PdfPages
    return PdfPages
