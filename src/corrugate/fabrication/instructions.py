"""Assembly instructions: numbered steps (Markdown) and a figure, made from the design itself."""

from __future__ import annotations

import contextlib
import io
from pathlib import Path
from typing import Any

import numpy as np
from numpy.typing import NDArray

from corrugate.core.fileio import Staging, staged
from corrugate.core.plotting import new_figure
from corrugate.fabrication.adhesives import adhesive_for
from corrugate.fabrication.folded import band_walls, layer_faces
from corrugate.fabrication.model import Pattern, Role
from corrugate.fabrication.palette import LINES, PALETTE
from corrugate.geometry.layer import Assembly

__all__ = [
    "VIEW_AZIM_DEG",
    "VIEW_ELEV_DEG",
    "assembly_steps",
    "instructions_figure",
    "instructions_png",
    "write_instructions",
]

FloatArray = NDArray[np.float64]

#: Line colours of the figure: the palette's (:mod:`corrugate.fabrication.palette`), as in the fold
#: map and the cut files.
_COLOURS = {
    Role.MOUNTAIN: LINES["mountain"].hex,
    Role.VALLEY: LINES["valley"].hex,
    Role.MARK: LINES["mark"].hex,
    Role.CUT: LINES["slit"].hex,
}


def assembly_steps(a: Assembly, pattern: Pattern) -> list[str]:
    """The numbered assembly steps for this design (plain sentences, mm and degrees)."""
    bands = [p.name for p in pattern.parts if p.kind == "connector"]
    l1, l2 = a.layer1, a.layer2
    ring = " -> ".join([*bands, bands[0]])

    def deg(angle: float) -> str:  # to the tenth of a degree a protractor is read at, at most
        return f"{round(angle, 1):g}"

    folds = (
        f"{deg(l1.fold_angle_deg)} deg (facets meet at {deg(l1.alpha_deg)} deg)"
        if l1.alpha_deg == l2.alpha_deg
        else f"{deg(l1.fold_angle_deg)} deg on L1 and {deg(l2.fold_angle_deg)} deg on L2"
    )
    glue = adhesive_for(l1.material.id)
    if l2.material.id != l1.material.id:
        glue += f" (L2: {adhesive_for(l2.material.id)})"
    return [
        f"Cut L1, L2 and {', '.join(bands)} from the cut files (cut-N.dxf or cut-N.svg, on the "
        f"cutter; the fold maps sheet-N.svg are for you, not the cutter): L1 {l1.material.id} "
        f"{l1.t:g} mm, L2 {l2.material.id} {l2.t:g} mm, the band from L1's sheet. Each part "
        "carries its name, drawn by the pen (engraved on a laser); with --no-labels match each "
        "to its name on the fold map.",
        f"Pre-fold L1 and L2 along every crease: mountains (red on the fold map) towards you, "
        f"valleys (blue) away, each by {folds}.",
        "On each band segment fold the glue tabs on both long edges 90 deg towards the face with "
        f"the drawn marks (the inner face); {_overlap_folds(pattern)}.",
        f"Join the band into a ring, {ring}: glue each overlap tab behind the start of the next "
        f"segment, marks facing in. Glue: {glue}.",
        f"Lower L1 into the ring, valleys down on the bottom tabs. Set each crease end on its lower "
        f"mark (the marks from the base to {l1.height:.1f} mm); this sets the fold angle. Glue.",
        f"Lay L2 on top, its creases at 90 deg to L1's, its valleys on L1's ridges, each crease end on "
        f"its upper mark ({l1.height:.1f} to {a.thickness:.1f} mm). Fold the top tabs over its ridges "
        "and glue.",
        f"Check: the panel measures {a.Lx:.1f} x {a.Ly:.1f} mm and {a.thickness:.1f} mm thick.",
    ]


def _overlap_folds(pattern: Pattern) -> str:
    """What to do with the line before each band segment's overlap tab, with its angles: the
    fold by the outline's turning angle at that corner (valley at a convex corner, mountain at a
    reflex one), or along a smooth outline no fold (a drawn mark)."""
    folds: dict[tuple[str, float], list[str]] = {}
    for part in pattern.parts:
        if part.kind != "connector":
            continue
        e = float(part.meta["length"])
        for ln in part.lines:
            vertical = abs(ln.a[0] - e) < 1e-9 and abs(ln.b[0] - e) < 1e-9
            if vertical and ln.role in (Role.VALLEY, Role.MOUNTAIN):
                kind = "valley" if ln.role is Role.VALLEY else "mountain"
                folds.setdefault((kind, round(float(ln.fold_angle_deg), 1)), []).append(part.name)
    if not folds:
        return "the line before each overlap tab is a mark, not a fold (a smooth outline)"
    text = "; ".join(
        f"{', '.join(names)}: {kind} {angle:g} deg"
        for (kind, angle), names in sorted(folds.items(), key=lambda kv: kv[1][0])
    )
    return f"fold the line before each overlap tab by the corner's angle ({text})"


#: The view of the figure's folded panels: azimuth and elevation (deg) of the viewer, matplotlib's
#: default 3-D view (from +x, -y and above).
VIEW_AZIM_DEG, VIEW_ELEV_DEG = -60.0, 30.0


#: The first panel's title above its axes (points): clear of the parts' names, which stand 2 pt
#: above the tallest part in 7 pt type (their ascent, about 7 pt, with a few points between).
_NAMES_PAD_PT = 14.0


def _view_axes(azim_deg: float, elev_deg: float) -> tuple[FloatArray, FloatArray, FloatArray]:
    """The orthographic (parallel) projection of a view: the screen's right and up directions and
    the direction towards the viewer, unit vectors in model coordinates. A point p is drawn at
    (p . right, p . up); p . towards is its nearness to the viewer (the painter's order)."""
    az, el = np.radians(azim_deg), np.radians(elev_deg)
    right = np.array([-np.sin(az), np.cos(az), 0.0])
    up = np.array([-np.sin(el) * np.cos(az), -np.sin(el) * np.sin(az), np.cos(el)])
    towards = np.array([np.cos(el) * np.cos(az), np.cos(el) * np.sin(az), np.sin(el)])
    return right, up, towards


def _painted(
    faces: list[FloatArray], right: FloatArray, up: FloatArray, towards: FloatArray
) -> list[FloatArray]:
    """The faces (each a (k, 3) array, mm) projected onto the screen (each a (k, 2) array, mm),
    far ones first (the painter's algorithm, by the nearness of each face's centroid)."""
    order = sorted(range(len(faces)), key=lambda i: float(faces[i].mean(axis=0) @ towards))
    return [faces[i] @ np.column_stack([right, up]) for i in order]


def instructions_figure(a: Assembly, pattern: Pattern) -> Any:
    """The assembly figure: the cut parts, then the folded layers, band and finished panel.

    The folded panels are drawn in an orthographic projection (:func:`_view_axes`, the view of
    :data:`VIEW_AZIM_DEG` and :data:`VIEW_ELEV_DEG`) on 2-D axes: each layer's facets and the band's
    walls are painted far to near (the band's walls behind the panel before the layers, those in
    front of it after), the footprint (z = 0) is outlined in grey and its two front edges carry
    the panel's extents in mm. 3-D axes would add a box, grids and ticks at about ten times the
    drawing's cost (``benchmarks/pipeline.py``)."""
    from matplotlib.collections import LineCollection, PolyCollection

    fig = new_figure((11, 8.5), dpi=110)
    ax0 = fig.add_subplot(2, 2, 1)
    x0 = 0.0
    shift = np.zeros(2)
    # one collection per colour (outlines, then each role), not one Line2D per line
    rings: list[Any] = []
    lines: dict[str, list[Any]] = {}
    for part in pattern.parts:
        o = np.asarray(part.outline)
        w = o[:, 0].max() - o[:, 0].min()
        shift[0] = x0
        rings.append(np.vstack([o, o[:1]]) + shift)
        for hole in part.holes:
            h = np.asarray(hole)
            rings.append(np.vstack([h, h[:1]]) + shift)
        for ln in part.lines:
            seg = ((ln.a[0] + x0, ln.a[1]), (ln.b[0] + x0, ln.b[1]))
            lines.setdefault(_COLOURS[ln.role], []).append(seg)
        # the name 2 pt above the part, in points: a length in mm would be a different height
        # on the page for every pattern, and the title (above) must clear it
        ax0.annotate(
            part.name,
            (x0 + w / 2, o[:, 1].max()),
            xytext=(0, 2),
            textcoords="offset points",
            ha="center",
            va="bottom",
            fontsize=7,
        )
        x0 += w + 6
    ax0.add_collection(LineCollection(rings, colors=LINES["cut"].hex, linewidths=0.6))
    for colour, segs in lines.items():
        ax0.add_collection(LineCollection(segs, colors=colour, linewidths=0.5))
    ax0.autoscale_view()
    ax0.set_aspect("equal")
    ax0.set_title(
        f"1. cut ({LINES['cut'].name}), mountain {LINES['mountain'].name}, "
        f"valley {LINES['valley'].name}, marks {LINES['mark'].name}",
        fontsize=9,
        y=1.0,
        pad=_NAMES_PAD_PT,
    )
    ax0.axis("off")

    right, up, towards = _view_axes(VIEW_AZIM_DEG, VIEW_ELEV_DEG)
    screen = np.column_stack([right, up])
    walls = band_walls(a)
    centre = np.array([a.Lx / 2, a.Ly / 2, a.thickness / 2]) @ towards
    back = [w for w in walls if float(w.mean(axis=0) @ towards) <= centre]
    front = [w for w in walls if float(w.mean(axis=0) @ towards) > centre]
    f1, f2 = layer_faces(a, pattern.parts, 1), layer_faces(a, pattern.parts, 2)
    c1, c2, cb = PALETTE.parts["L1"], PALETTE.parts["L2"], PALETTE.parts["band"]
    views: list[tuple[str, list[tuple[list[Any], str]], bool]] = [
        (f"2. fold L1 ({c1.name}); L2 ({c2.name}) alike", [(f1, c1.hex)], False),
        (f"3-5. band ring ({cb.name}), L1 inside on the lower marks", [(f1, c1.hex)], True),
        ("6. L2 on top: the finished panel", [(f1, c1.hex), (f2, c2.hex)], True),
    ]
    foot = np.array([[0.0, 0.0, 0.0], [a.Lx, 0.0, 0.0], [a.Lx, a.Ly, 0.0], [0.0, a.Ly, 0.0]])
    box = np.vstack([foot, foot + np.array([0.0, 0.0, a.thickness])]) @ screen
    pad = 0.08 * float(np.ptp(box[:, 0]))
    (x_lo, y_lo), (x_hi, y_hi) = box.min(axis=0) - pad, box.max(axis=0) + pad
    flat = foot @ screen
    for k, (title, layers, band) in enumerate(views):
        ax = fig.add_subplot(2, 2, k + 2)
        ring = np.vstack([flat, flat[:1]])
        ax.plot(ring[:, 0], ring[:, 1], color="0.6", lw=0.6, zorder=0)
        paint = [(back, cb.hex, 0.35)] if band and back else []
        paint += [(faces, colour, 1.0) for faces, colour in layers]
        paint += [(front, cb.hex, 0.35)] if band and front else []
        for z, (faces, colour, alpha) in enumerate(paint, start=1):
            ax.add_collection(
                PolyCollection(
                    _painted(faces, right, up, towards),
                    facecolor=colour,
                    edgecolor="#303030",
                    lw=0.3,
                    alpha=alpha,
                    zorder=z,
                ),
                autolim=False,
            )
        for (p, q), text, side in (
            ((flat[0], flat[1]), f"{a.Lx:.1f} mm", "top"),
            ((flat[1], flat[2]), f"{a.Ly:.1f} mm", "top"),
        ):
            angle = float(np.degrees(np.arctan2(q[1] - p[1], q[0] - p[0])))
            mid = (p + q) / 2
            ax.text(
                mid[0],
                mid[1] - 0.02 * (y_hi - y_lo),
                text,
                fontsize=7,
                ha="center",
                va=side,
                rotation=angle,
                rotation_mode="anchor",
                color="0.3",
            )
        ax.set_xlim(x_lo, x_hi)
        ax.set_ylim(y_lo, y_hi)
        ax.set_aspect("equal")
        ax.axis("off")
        ax.set_title(title, fontsize=9, y=1.0)
    # fixed margins: tight_layout measures every text once more
    fig.subplots_adjust(left=0.03, right=0.97, bottom=0.04, top=0.95, wspace=0.1, hspace=0.15)
    return fig


def instructions_png(a: Assembly, pattern: Pattern) -> bytes:
    """:func:`instructions_figure` as PNG bytes (the file ``assembly.png``; the report embeds the
    same bytes)."""
    buf = io.BytesIO()
    instructions_figure(a, pattern).savefig(buf, format="png")
    return buf.getvalue()


def write_instructions(
    a: Assembly,
    pattern: Pattern,
    out_dir: Path,
    staging: Staging | None = None,
    png: bytes | None = None,
) -> list[Path]:
    """Write ``ASSEMBLY.md`` (numbered steps) and ``assembly.png`` (the figure, or ``png`` when
    it was drawn already: :func:`instructions_png`) into ``out_dir``."""
    image = instructions_png(a, pattern) if png is None else png
    steps = assembly_steps(a, pattern)
    text = (
        "# Assembly\n\n![assembly steps](assembly.png)\n\n"
        + "\n".join(f"{i}. {s}" for i, s in enumerate(steps, 1))
        + "\n"
    )
    out_dir.mkdir(parents=True, exist_ok=True)
    png_path, md = out_dir / "assembly.png", out_dir / "ASSEMBLY.md"
    with contextlib.nullcontext(staging) if staging is not None else staged() as st:
        st.path(png_path).write_bytes(image)
        st.path(md).write_text(text, encoding="utf-8")
    return [md, png_path]
