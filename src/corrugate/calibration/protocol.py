"""The kit's protocol: Markdown text, the set-up figures, the PDF and the measurements template.

Everything a user needs beside the cut coupons (docs/calibration.md section 2): how to fold and
hold each coupon, what to read with a ruler, how many repeats, a sheet to write the readings on,
and ``measurements.toml`` with every dimension filled in and the readings left empty. Lengths in
mm, masses in g.
"""

from __future__ import annotations

import math
from typing import TYPE_CHECKING

from corrugate.calibration.coupons import CLAMP, HOLE, Kit
from corrugate.calibration.measurements import MIN_REPEATS

if TYPE_CHECKING:
    from matplotlib.axes import Axes
    from matplotlib.figure import Figure
    from matplotlib.patches import Rectangle

__all__ = ["REPEATS", "figures", "markdown", "pdf_bytes", "template"]

#: Repeats asked for each reading (at least MIN_REPEATS are required by the fit).
REPEATS = 5


def template(kit: Kit, machine: str) -> str:
    """``measurements.toml``: the sheet and every coupon's dimensions, the readings empty."""
    m, c = kit.material, kit.crease
    lines = [
        "# corrugate calibration: fill in the readings (mm), then run",
        "#   corrugate calibrate fit measurements.toml --save",
        f"# Kit for {m.id} at {kit.t:g} mm, cut on {machine}; protocol: protocol.md / protocol.pdf.",
        f"# Each list takes {REPEATS} readings (at least {MIN_REPEATS}), in mm.",
        "",
        "[sheet]",
        f'material = "{m.id}"',
        f'thickness = "{kit.t:g} mm"    # measure it with a micrometer if you can: E goes as 1/t^3',
        'ruler = "1 mm"           # the error of one reading, +- (1 mm for a ruler read by eye)',
        f'name = "my-{m.id}"       # the id the fitted material is saved under',
        'date = ""                # e.g. "2026-12-06"',
    ]
    for f in kit.flat:
        for overhang, coins in ((f.overhang, 0), (f.coin_overhang, f.coins)):
            expected = f.sag_alone if coins == 0 else f.sag_coins
            lines += [
                "",
                "[[flat]]",
                f'coupon = "{f.name}"',
                f'direction = "{f.direction}"',
                f'width = "{f.width:g} mm"',
                f'overhang = "{overhang:g} mm"   # free length beyond the table edge (the mark)',
                f'tip_mass = "{coins * f.coin_g:g} g"   # {coins} coin(s) of {f.coin_g:g} g taped at the tip',
                f"sag = []   # mm, the tip's drop below the table top; about {expected:.0f} mm expected",
            ]
    lines += [
        "",
        "[crease]",
        f'coupon = "{c.name}"',
        f'width = "{c.width:g} mm"',
        f'facet = "{c.facet:g} mm"',
        f"creases = {c.creases}",
        f'folded_to = "{c.angle:g} deg"   # the angle you fold each crease to',
        f"length = []   # mm, from the first tab crease to the last, unloaded, lying on the table; "
        f"about {c.creases * c.facet * math.sin(math.radians(c.angle) / 2):.0f} mm at {c.angle:g} deg",
        "mass = [" + ", ".join(f'"{n * c.coin_g:g} g"' for n in c.coins) + "]   # coins in the bag",
        "extension = [" + ", ".join("[]" for _ in c.coins) + "]   # mm, one list per mass: length "
        "with the bag less length without",
    ]
    return "\n".join(lines) + "\n"


def markdown(kit: Kit, machine: str) -> str:
    """The protocol as Markdown (the figures as ``setup-*.png`` beside it)."""
    m, c = kit.material, kit.crease
    f = kit.flat[0]
    chord = c.creases * c.facet * math.sin(math.radians(c.angle) / 2)
    sheet_rows = "\n".join(
        f"| {name} | {what} | " + " | ".join(" " for _ in range(REPEATS)) + " |"
        for name, what in (
            *(
                (x.name, f"sag at {L:g} mm, {n} coin(s)")
                for x in kit.flat
                for L, n in ((x.overhang, 0), (x.coin_overhang, x.coins))
            ),
            (c.name, "length unloaded"),
            *((c.name, f"extension, {n} coin(s)") for n in c.coins),
        )
    )
    header = "| coupon | reading (mm) | " + " | ".join(str(i + 1) for i in range(REPEATS)) + " |"
    rule = "|---|---|" + "---|" * REPEATS
    return f"""# Calibrating your {m.name}, {kit.t:g} mm

This kit measures the sheet you will fold: its Young's modulus E along and across the sheet, the
stiffness of its creases and how far a fold springs back (`corrugate docs calibration`). You need
the cut coupons, a ruler marked in mm, a heavy book, a table with a straight edge, tape, a clip
or clothes peg, a small bag (a sandwich bag) and {max(c.coins[-1], f.coins)} coins of the same kind,
each about {kit.coin_g:g} g (weigh one on a kitchen scale if you can, and write the mass in
`measurements.toml`). Lay the sheet on the cutting mat with its roll direction along the mat's x
(left to right) before you cut: coupon F1 then lies along the roll and F2 across it.

Files: `cut-*.svg` / `cut-*.dxf` (for {machine}), `pattern.pdf` (the coupons at full size),
`measurements.toml` (fill in the readings), this protocol (`protocol.md`, `protocol.pdf`).

## 1. Flat strips F1 (along) and F2 (across): sag under their own weight

![the flat strip at the table edge](setup-flat.png)

1. Lay the strip flat on the table, the marked end out, with the mark **{f.overhang:g} mm** from
   the tip exactly on the table edge. Put the book on the part on the table (at least
   {CLAMP:g} mm of it), its edge on the table edge.
2. Wait 10 s. Hold the ruler upright against the table edge's face and read how far the tip hangs
   below the table top (the sag), in mm. Expected: about **{f.sag_alone:.0f} mm** at the datasheet
   E of {m.E:g} MPa.
3. Lift the book, slide the strip a little, put it back at the same mark, read again:
   **{REPEATS} readings** (at least {MIN_REPEATS}). Flip the strip over for half of them (a strip
   that curls from the roll then averages out).
4. The same for F2.

## 2. Flat strips with coins at the tip

![the flat strip with coins at its tip](setup-coin.png)

Slide the strip back to the second mark, **{f.coin_overhang:g} mm** free, tape {f.coins} coin(s)
flat on the tip (their centre about 5 mm from the end), read the sag {REPEATS} times as above.
Expected: about **{f.sag_coins:.0f} mm**.

## 3. The zig-zag strip C1: crease stiffness and springback

![the zig-zag strip pulled by coins](setup-crease.png)

1. Fold every crease of C1 to about {c.angle:g} deg (mountain and valley as drawn), pinching each
   crease firmly once, and the two end creases half as far so that the tabs line up with the
   strip's middle line. Let it rest for an hour: the creases relax.
2. Springback: lay it on the table (on its crease lines) and read its length from the first tab
   crease to the last, {REPEATS} times (about {chord:.0f} mm if the folds kept {c.angle:g} deg).
3. Hang it from the clip by one tab's {HOLE:g} mm hole, hang the empty bag from the other, read the
   length between two points you mark on the tabs. Put {c.coins[0]} coin(s) in the bag, read
   again: the difference is the extension. Then {", ".join(str(n) for n in c.coins[1:])} coins.
   Take the coins out between readings; {REPEATS} readings at each load. Stop adding coins
   before the extension reaches 50 mm or the creases open flat. With creases as stiff as a facet
   {c.facet:g} mm wide the extensions would be about
   {", ".join(f"{x:.0f}" for x in c.soft)} mm; with rigid creases
   {", ".join(f"{x:.1f}" for x in c.rigid)} mm.

## 4. Fit and design

Write the readings into `measurements.toml` and run

    corrugate calibrate fit measurements.toml --save

It prints E for each direction and the crease stiffness with their 90 % intervals, draws
`fit.png` (readings against the model) and, with `--save`, adds the material `my-{m.id}` to your
materials file; a spec then names it as `[material] name = "my-{m.id}"`.

## Measurement sheet

{header}
{rule}
{sheet_rows}
"""


def _table_edge(a: Axes, L: float, sag: float) -> None:
    """A table, a book and a strip of free length L sagging ``sag`` (mm, drawn to scale)."""
    import numpy as np

    a.add_patch(_rect((-80, -30), 80, 30, "#c8a878"))
    a.add_patch(_rect((-70, 0.3), 60, 18, "#7a8fb8"))
    a.text(-40, 9, "book", ha="center", va="center", color="white", fontsize=8)
    s = np.linspace(0, 1, 60)
    x = L * s * (1 - 0.15 * (sag / max(L, 1)) * s)
    y = -sag * (s**2) * (3 - s) / 2
    a.plot(np.r_[-70, 0, x], np.r_[0.3, 0.3, y], color="k", lw=2)
    a.plot([x[-1] + 6] * 2, [2, -sag - 6], color="#b03030", lw=3)
    a.annotate("", (x[-1] + 10, y[-1]), (x[-1] + 10, 0.3), arrowprops={"arrowstyle": "<->"})
    a.text(x[-1] + 12, -sag / 2, "sag\n(ruler)", fontsize=8, va="center")
    a.annotate("", (0, 8), (L, 8), arrowprops={"arrowstyle": "<->"})
    a.text(L / 2, 10, f"free length {L:g} mm (mark on the edge)", ha="center", fontsize=8)


def _rect(xy: tuple[float, float], w: float, h: float, color: str) -> Rectangle:
    from matplotlib.patches import Rectangle

    return Rectangle(xy, w, h, color=color)


def figures(kit: Kit) -> dict[str, Figure]:
    """The set-up figures by file name (``setup-flat.png``, ``setup-coin.png``,
    ``setup-crease.png``), drawn to scale in mm."""
    from matplotlib.patches import Circle

    from corrugate.core.plotting import new_figure

    f, c = kit.flat[0], kit.crease
    out: dict[str, Figure] = {}
    for name, L, sag, coins in (
        ("setup-flat.png", f.overhang, f.sag_alone, 0),
        ("setup-coin.png", f.coin_overhang, f.sag_coins, f.coins),
    ):
        fig = new_figure((6.0, 3.2), dpi=120)
        ax = fig.add_subplot()
        _table_edge(ax, L, sag)
        if coins:
            ax.add_patch(Circle((L - 5, -sag + 2), 4, color="#d4af37"))
            ax.text(L - 5, -sag - 8, f"{coins} coin(s)", ha="center", fontsize=8)
        ax.set_aspect("equal")
        ax.set_xlim(-85, max(L, 60) + 45)
        ax.set_ylim(-max(sag, 20) - 20, 30)
        ax.set_axis_off()
        ax.set_title(
            f"{f.name}/{kit.flat[1].name}: {'coins at the tip' if coins else 'own weight'}",
            fontsize=10,
        )
        out[name] = fig
    fig = new_figure((4.0, 6.0), dpi=120)
    ax = fig.add_subplot()
    p = c.facet * math.sin(math.radians(c.angle) / 2)
    h = c.facet * math.cos(math.radians(c.angle) / 2)
    ys = [0.0, -c.tab]
    xs = [0.0, 0.0]
    for i in range(c.creases + 1):
        step = 0.5 if i in (0, c.creases) else 1.0
        ys.append(ys[-1] - step * p)
        xs.append((h / 2 if i % 2 == 0 else -h / 2) if i < c.creases else 0.0)
    ys.append(ys[-1] - c.tab)
    xs.append(0.0)
    ax.plot(xs, ys, color="k", lw=2)
    ax.plot([-6, 6], [-3.0] * 2, color="#555", lw=6)
    ax.text(8, -3.0, "clip", fontsize=8, va="center")
    ax.add_patch(_rect((-10, ys[-1] - 25), 20, 22, "#dde6f0"))
    ax.text(0, ys[-1] - 14, "bag of\ncoins", ha="center", va="center", fontsize=8)
    ax.plot([-25, -25], [-c.tab, ys[-2]], color="#b03030", lw=3)
    ax.text(-28, ys[-2] / 2, "length\n(ruler)", ha="right", va="center", fontsize=8)
    ax.set_aspect("equal")
    ax.set_xlim(-60, 40)
    ax.set_axis_off()
    ax.set_title(f"{c.name}: pulled along the chords", fontsize=10)
    out["setup-crease.png"] = fig
    return out


def pdf_bytes(kit: Kit, machine: str, figs: dict[str, Figure]) -> bytes:
    """The protocol as a PDF: its text on A4 pages (set in a fixed-width font, as the Markdown
    reads), each set-up figure on the page after its section."""
    import io

    from corrugate.core.plotting import new_figure, pdf_pages

    text = markdown(kit, machine)
    pages: list[list[str]] = [[]]
    for line in text.splitlines():
        if line.startswith("![") and line.endswith(".png)"):
            pages.append([line])
            pages.append([])
            continue
        if len(pages[-1]) >= 64:
            pages.append([])
        pages[-1].append(line)
    buf = io.BytesIO()
    with pdf_pages()(buf) as pdf:
        for page in pages:
            if not page:
                continue
            if len(page) == 1 and page[0].startswith("!["):
                name = page[0].split("(")[-1].rstrip(")")
                pdf.savefig(figs[name])
                continue
            fig = new_figure((8.27, 11.69))
            fig.text(
                0.07,
                0.96,
                "\n".join(_wrap(page)),
                va="top",
                ha="left",
                family="monospace",
                fontsize=7.5,
            )
            pdf.savefig(fig)
    return buf.getvalue()


def _wrap(lines: list[str], width: int = 100) -> list[str]:
    import textwrap

    out: list[str] = []
    for ln in lines:
        out += textwrap.wrap(ln, width, subsequent_indent="   ") or [""]
    return out
