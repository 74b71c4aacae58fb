"""The panel's directions drawn: x, y, eta and each layer's creases (issue 36 item 2).

A direction eta is measured from layer 1's creases, which run along y; layer 2's run along x
(docs/models.md, "Layouts and facet lengths"; docs/spec.md: ``eta``, "from layer 1's creases"). So eta =
0 deg runs along y, where the panel's length is its extent Ly (``side_y``), and eta = 90 deg
along x (Lx, ``side_x``): a load case's span along eta needs the panel that long
(:mod:`corrugate.solver.orientation` names the trap). :func:`orientation_svg` draws this as a
small SVG with no scripts and no external resources: the report embeds it
(:mod:`corrugate.report.html`), and the web page shows the same drawing beside its size and
requirement fields (``web/static/orientation.svg``, written by :func:`orientation_svg` with its
defaults: ``tests/report/test_orientation.py`` checks that they agree).
"""

from __future__ import annotations

from html import escape

__all__ = ["ORIENTATION_ALT", "orientation_svg"]

#: The drawing's text alternative (the report's ``alt``, the page's ``aria-label``).
ORIENTATION_ALT = (
    "The panel seen from above: x to the right, y up. Layer 1's creases run along y, layer 2's "
    "along x. eta is measured from layer 1's creases: eta = 0 deg runs along y (the panel's "
    "length there is Ly, side_y), eta = 90 deg along x (Lx, side_x)."
)

_L1 = "#1f5fa8"  # layer 1's creases (blue)
_L2 = "#c0561b"  # layer 2's creases (orange)
_ETA = "#222"


def orientation_svg(aspect: float = 1.6, creases: tuple[int, int] = (7, 4)) -> str:
    """An SVG (text) of a panel ``aspect`` = Lx / Ly wide (clipped to 0.5-2.5 for the drawing)
    with ``creases`` = (layer 1's, layer 2's) crease lines, the axes x and y, the directions
    eta = 0 and 90 deg with the side each spans, and a legend."""
    aspect = min(max(aspect, 0.5), 2.5)
    n1, n2 = (max(1, min(k, 24)) for k in creases)
    # the panel's box in the drawing (px of a 360 x 270 view box)
    h = 150.0 if aspect <= 1.6 else 240.0 / aspect
    w = h * aspect
    x0, y0 = 60.0, 40.0 + (150.0 - h) / 2  # top left
    x1, y1 = x0 + w, y0 + h
    cx, cy = (x0 + x1) / 2, (y0 + y1) / 2
    out = [
        '<svg xmlns="http://www.w3.org/2000/svg" viewBox="0 0 360 270" width="360" height="270" '
        f'role="img" aria-label="{escape(ORIENTATION_ALT)}" font-family="system-ui, sans-serif" '
        'font-size="11">',
        f"<title>{escape(ORIENTATION_ALT)}</title>",
        '<defs><marker id="arrow" viewBox="0 0 10 10" refX="9" refY="5" markerWidth="7" '
        'markerHeight="7" orient="auto-start-reverse"><path d="M0,0 L10,5 L0,10 z" '
        f'fill="{_ETA}"/></marker></defs>',
        f'<rect x="{x0:g}" y="{y0:g}" width="{w:g}" height="{h:g}" fill="#f6f6f2" '
        'stroke="#555" stroke-width="1.5"/>',
    ]
    for i in range(1, n1 + 1):  # layer 1: lines along y, spaced along x
        x = x0 + w * i / (n1 + 1)
        out.append(
            f'<line x1="{x:.1f}" y1="{y0:g}" x2="{x:.1f}" y2="{y1:g}" stroke="{_L1}" '
            'stroke-width="1.2"/>'
        )
    for j in range(1, n2 + 1):  # layer 2: lines along x, spaced along y
        y = y0 + h * j / (n2 + 1)
        out.append(
            f'<line x1="{x0:g}" y1="{y:.1f}" x2="{x1:g}" y2="{y:.1f}" stroke="{_L2}" '
            'stroke-width="1.2" stroke-dasharray="5 3"/>'
        )
    # eta = 0 along y (up), eta = 90 deg along x (right), from the centre
    ry, rx = h / 2 - 6, w / 2 - 6
    arc = 0.3 * min(rx, ry)
    # an arrowhead is the marker's 7 units of the arrow's 2.2 px stroke across: its labels stand
    # clear of it, the eta = 0 label right of its head, the eta = 90 deg label below its head
    head = 7 * 2.2 / 2
    halo = 'stroke="#fff" stroke-width="3" paint-order="stroke"'
    out += [
        f'<line x1="{cx:.1f}" y1="{cy:.1f}" x2="{cx:.1f}" y2="{cy - ry:.1f}" stroke="{_ETA}" '
        'stroke-width="2.2" marker-end="url(#arrow)"/>',
        f'<line x1="{cx:.1f}" y1="{cy:.1f}" x2="{cx + rx:.1f}" y2="{cy:.1f}" stroke="{_ETA}" '
        'stroke-width="2.2" marker-end="url(#arrow)"/>',
        f'<path d="M{cx:.1f},{cy - arc:.1f} A{arc:.1f},{arc:.1f} 0 0 1 '
        f'{cx + arc:.1f},{cy:.1f}" fill="none" stroke="{_ETA}" stroke-width="1" '
        'marker-end="url(#arrow)"/>',
        f'<text x="{cx + head + 3:.1f}" y="{cy - ry + 12:.1f}" font-weight="bold" {halo}>'
        "eta = 0 deg</text>",
        f'<text x="{cx + rx - 4:.1f}" y="{cy + head + 12:.1f}" font-weight="bold" '
        f'text-anchor="end" {halo}>eta = 90 deg</text>',
        f'<text x="{cx + arc * 0.75 + 3:.1f}" y="{cy - arc * 0.75 - 3:.1f}" {halo}>eta</text>',
    ]
    # the axes at the lower left and the sides
    out += [
        f'<line x1="{x0 - 30:g}" y1="{y1 + 30:g}" x2="{x0 + 5:g}" y2="{y1 + 30:g}" stroke="#000" '
        'stroke-width="1.2" marker-end="url(#arrow)"/>',
        f'<line x1="{x0 - 30:g}" y1="{y1 + 30:g}" x2="{x0 - 30:g}" y2="{y1 - 5:g}" stroke="#000" '
        'stroke-width="1.2" marker-end="url(#arrow)"/>',
        f'<text x="{x0 + 8:g}" y="{y1 + 34:g}">x</text>',
        f'<text x="{x0 - 34:g}" y="{y1 - 9:g}">y</text>',
        f'<text x="{cx:.1f}" y="{y1 + 16:g}" text-anchor="middle">Lx: side_x (eta = 90 deg)</text>',
        f'<text x="{x0 - 8:g}" y="{cy:.1f}" text-anchor="middle" '
        f'transform="rotate(-90 {x0 - 8:g} {cy:.1f})">Ly: side_y (eta = 0 deg)</text>',
        # the legend
        f'<line x1="20" y1="16" x2="44" y2="16" stroke="{_L1}" stroke-width="1.5"/>',
        '<text x="50" y="20">layer 1: creases along y</text>',
        f'<line x1="190" y1="16" x2="214" y2="16" stroke="{_L2}" stroke-width="1.5" '
        'stroke-dasharray="5 3"/>',
        '<text x="220" y="20">layer 2: along x</text>',
        '<text x="20" y="258">a span along eta 0 needs side_y; along eta 90 deg, side_x</text>',
        "</svg>",
    ]
    return "\n".join(out) + "\n"
