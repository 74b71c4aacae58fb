"""corrugate.core.plotting: PNG bytes at a chosen zlib level, and matplotlib's PDF backend with
fontTools' subsetter and glyph list loaded on first use (issue 24).

The PDF checks run in fresh interpreters: the test process may have imported matplotlib's PDF
backend (and fontTools) already, and then :func:`~corrugate.core.plotting.pdf_pages` leaves the
imports as they are.
"""

from __future__ import annotations

import io
import subprocess
import sys
import textwrap
from pathlib import Path

import numpy as np
import pytest
from PIL import Image

from corrugate.core.plotting import new_figure, png_bytes

#: A one-page PDF with text (so a font is embedded) written to sys.argv[1] by pdf_pages; prints
#: whether fontTools' subsetter was executed (a lazy module that was never touched is still
#: importlib's _LazyModule).
_WRITE = textwrap.dedent(
    """
    import sys
    import matplotlib
    matplotlib.rcParams["pdf.fonttype"] = int(sys.argv[3])
    from corrugate.core.plotting import new_figure, pdf_pages
    if sys.argv[2] == "eager":
        import matplotlib.backends.backend_pdf
    PdfPages = pdf_pages()
    fig = new_figure((3, 2))
    fig.text(0.1, 0.5, "sheet 1: L1 A, 10 mm check square")
    fig.add_subplot().plot([0, 1], [0, 1])
    with PdfPages(sys.argv[1], metadata={"Creator": "test", "CreationDate": None}) as pdf:
        pdf.savefig(fig)
    print(type(sys.modules["fontTools.subset"]).__name__)
    """
)


def _write_pdf(path: Path, how: str, fonttype: int) -> str:
    """Writes the PDF; the type of the subsetter's module after writing it."""
    out = subprocess.run(
        [sys.executable, "-c", _WRITE, str(path), how, str(fonttype)],
        capture_output=True,
        text=True,
        check=True,
    )
    return out.stdout.strip()


@pytest.mark.slow
def test_pdf_pages_writes_the_same_pdf_without_running_the_subsetter(tmp_path: Path) -> None:
    """Type 3 fonts (matplotlib's default, the package's PDFs): the file is byte for byte the one
    written with the backend imported as usual, and the subsetter was never executed."""
    lazy, eager = tmp_path / "lazy.pdf", tmp_path / "eager.pdf"
    assert _write_pdf(lazy, "lazy", 3) == "_LazyModule"
    assert _write_pdf(eager, "eager", 3) == "module"
    data = lazy.read_bytes()
    assert data.startswith(b"%PDF-") and b"/Subtype /Type3" in data
    assert data == eager.read_bytes()


@pytest.mark.slow
def test_pdf_pages_loads_the_subsetter_when_a_font_needs_it(tmp_path: Path) -> None:
    """Type 42 fonts are subset with fontTools: the lazy module loads on that first use and the
    file is the one written with the backend imported as usual."""
    lazy, eager = tmp_path / "lazy.pdf", tmp_path / "eager.pdf"
    assert _write_pdf(lazy, "lazy", 42) == "module"  # executed when the font was subset
    _write_pdf(eager, "eager", 42)
    data = lazy.read_bytes()
    assert b"/FontFile2" in data  # the TrueType font embedded, as subset by fontTools
    assert data == eager.read_bytes()


def _pixels(png: bytes) -> np.ndarray:
    assert png.startswith(b"\x89PNG\r\n\x1a\n")
    return np.asarray(Image.open(io.BytesIO(png)))


def test_png_bytes_levels_keep_the_pixels() -> None:
    """zlib's level changes the bytes, never the image: the same pixels at levels 1, 3 and 6,
    and the default level's file is what savefig writes by itself."""
    fig = new_figure((3, 2), dpi=80)
    ax = fig.add_subplot()
    ax.plot([0, 1, 2], [0, 1, 0.5], label="a line")
    ax.set_title("title")
    ax.legend()
    files = {level: png_bytes(fig, compress_level=level) for level in (1, 3, 6)}
    reference = _pixels(files[6])
    assert reference.shape == (160, 240, 4)
    for level in (1, 3):
        assert files[level] != files[6]
        assert np.array_equal(_pixels(files[level]), reference)
    plain = io.BytesIO()
    fig.savefig(plain, format="png")
    assert plain.getvalue() == files[6]


#: Draws a figure (line, legend, text, polar axes, contour labels: the report's kinds of artist)
#: to PNG and prints its SHA-256, whether matplotlib's ``set`` help of Line2D was written, and
#: whether Artist's method is matplotlib's own again afterwards; ``lean`` as sys.argv[1].
_LEAN = textwrap.dedent(
    """
    import hashlib, inspect, sys
    import numpy as np
    from corrugate.core import plotting
    plotting.lean_import(sys.argv[1] == "lean")
    fig = plotting.new_figure((4, 3), dpi=80)
    ax = fig.add_subplot(1, 2, 1)
    ax.plot([0, 1, 2], [0, 1, 0.5], label="a line")
    x, y = np.meshgrid(np.linspace(0, 1, 20), np.linspace(0, 1, 20))
    ax.clabel(ax.contour(x, y, x + y, levels=3), fontsize=6)
    ax.set_title("title")
    ax.legend(loc="best")
    fig.add_subplot(1, 2, 2, projection="polar").plot([0, 1], [1, 2])
    print(hashlib.sha256(plotting.png_bytes(fig)).hexdigest())
    import matplotlib.artist, matplotlib.lines
    print("property list in help:", "linewidth" in (matplotlib.lines.Line2D.set.__doc__ or ""))
    class Later(matplotlib.artist.Artist):
        def set_colour_name(self, value):
            pass
    print("later class has its signature:", "colour_name" in str(inspect.signature(Later.set)))
    print("kwdoc is matplotlib's:", matplotlib.artist.kwdoc.__module__ == "matplotlib.artist")
    import matplotlib.axes
    print("data note in help:", "data[s]" in (matplotlib.axes.Axes.scatter.__doc__ or ""))
    from matplotlib import _docstring
    _docstring.interpd.register(later_name="filled")
    @_docstring.interpd
    def later():
        \"\"\"%(later_name)s\"\"\"
    @_docstring.Substitution(word="filled")
    def later_too():
        \"\"\"%(word)s\"\"\"
    print("later docstrings:", later.__doc__, later_too.__doc__)
    """
)


@pytest.mark.slow
def test_lean_import_draws_the_same_pixels_without_the_set_help() -> None:
    """:func:`~corrugate.core.plotting.lean_import` (the command line's): the same PNG, byte for
    byte, as matplotlib imported as usual; only the artists' ``set`` help and the docstrings'
    filled-in fields and data notes are left out (``Axes.scatter``'s note on ``data``), and a
    class defined after the import gets its own again, a docstring decorated after it is filled
    in (matplotlib's method, ``kwdoc`` and docstring decorators put back)."""
    runs = {
        how: subprocess.run(
            [sys.executable, "-c", _LEAN, how], capture_output=True, text=True, check=True
        ).stdout.splitlines()
        for how in ("lean", "full")
    }
    assert runs["lean"][0] == runs["full"][0]  # the same file
    back = ["later class has its signature: True", "kwdoc is matplotlib's: True"]
    later = "later docstrings: filled filled"
    assert runs["full"][1:] == [
        "property list in help: True",
        *back,
        "data note in help: True",
        later,
    ]
    assert runs["lean"][1:] == [
        "property list in help: False",
        *back,
        "data note in help: False",
        later,
    ]
