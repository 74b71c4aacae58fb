"""``report.html``: one self-contained file (figures embedded as data URIs: the plots as SVG, the
sheets as the fold maps' SVG; no scripts)."""

from __future__ import annotations

import base64
import html
import re
from typing import TYPE_CHECKING, Any

from corrugate.analysis.evaluate import analyze
from corrugate.core.plotting import svg_text
from corrugate.fabrication.instructions import assembly_steps, instructions_png
from corrugate.fabrication.linestyle import StyleKind
from corrugate.geometry.holes import holes_text
from corrugate.mechanics.moduli import MODELS
from corrugate.report.figures import (
    KeyEntry,
    design_space,
    load_case_figure,
    mass_by_n_figure,
    polar_figure,
)
from corrugate.report.orientation import ORIENTATION_ALT, orientation_svg
from corrugate.solver.solve import Solution

if TYPE_CHECKING:
    from corrugate.export.plan import CutPlan

__all__ = ["report_html"]

_STYLE = """
body{font-family:system-ui,sans-serif;max-width:60rem;margin:2rem auto;padding:0 1rem;color:#222}
h1{font-size:1.6rem}h2{font-size:1.2rem;margin-top:2rem;border-bottom:1px solid #ddd}
.table{overflow-x:auto}table{border-collapse:collapse;margin:.5rem 0}td,th{border:1px solid #ccc;
padding:.2rem .5rem;text-align:right}th{background:#f3f3f3}td:first-child,th:first-child{text-align:left}
td+td{white-space:nowrap}
img{max-width:100%;height:auto}pre{background:#f7f7f7;padding:.75rem;overflow:auto}
.warn{color:#8a5300}.bind{font-weight:bold}
.key{list-style:none;padding:0;margin:0 0 1rem;font-size:.85rem}.key .mark{display:inline-block;width:2em}
"""


def _img(fig: Any, alt: str) -> str:
    """A plot embedded as SVG (:func:`~corrugate.core.plotting.svg_text`: vector, its labels as
    text; cheaper to draw than a PNG, issue 39)."""
    return _img_svg(svg_text(fig), alt)


def _img_png(png: bytes, alt: str) -> str:
    """An image of PNG bytes drawn already (a file beside the report)."""
    src = "data:image/png;base64," + base64.b64encode(png).decode("ascii")
    return f'<img src="{src}" alt="{html.escape(alt)}">'


def _img_svg(svg: str, alt: str) -> str:
    """An image of an SVG text (a fold map ``sheet-N.svg`` beside the report, byte for byte)."""
    src = "data:image/svg+xml;base64," + base64.b64encode(svg.encode("utf-8")).decode("ascii")
    return f'<img src="{src}" alt="{html.escape(alt)}">'


#: How :func:`_key` draws each kind of mark (a character in the mark's colour).
_MARKS = {
    "line": "&#9473;&#9473;",  # ━━
    "dashed": "&#9549;&#9549;",  # ╍╍
    "dashdot": "&#9473;&#183;",  # ━·
    "star": "&#9733;",
    "area": "&#9632;",
}


def _key(entries: list[KeyEntry], figure: str) -> str:
    """A figure's key as text under it: each entry's mark in its colour, then what it stands for
    (:func:`~corrugate.report.figures.design_space`)."""
    items = "".join(
        f'<li><span class="mark" style="color:{e.colour}">{_MARKS[e.mark]}</span> '
        f"{html.escape(e.label)}</li>"
        for e in entries
    )
    return f'<ul class="key" aria-label="key of the {html.escape(figure)}">{items}</ul>'


def _directions(aspect: float = 1.6, creases: tuple[int, int] = (7, 4)) -> str:
    """The panel's directions (x, y, eta, each layer's creases; :mod:`.orientation`) drawn
    ``aspect`` = Lx / Ly wide with ``creases`` crease lines per layer (at most 24 drawn)."""
    svg = orientation_svg(aspect, creases)
    return (
        "<h2>Directions</h2><p>eta is measured from layer 1's creases, which run along y: "
        "eta = 0 deg runs along y (Ly, side_y), eta = 90 deg along x (Lx, side_x).</p>"
        + _img_svg(svg, ORIENTATION_ALT)
    )


def _table(head: list[str], rows: list[list[str]], classes: list[str] | None = None) -> str:
    """A table in a box of its own that scrolls sideways when the table is wider than the page (a
    phone), every cell but the first of a row on one line (a bound reads "<= 250", not "<=" over
    "250")."""
    out = ["<div class='table'><table><tr>", *(f"<th>{html.escape(h)}</th>" for h in head), "</tr>"]
    for i, row in enumerate(rows):
        cls = f' class="{classes[i]}"' if classes and classes[i] else ""
        out.append(f"<tr{cls}>" + "".join(f"<td>{html.escape(c)}</td>" for c in row) + "</tr>")
    out.append("</table></div>")
    return "".join(out)


def _inline_code(text: str) -> str:
    """``text`` as HTML, each span between backticks (a command or a spec key, quoted the command
    line's way, e.g. corrugate docs fea) a ``<code>`` element rather than printed backticks."""
    return re.sub(r"`([^`]+)`", r"<code>\1</code>", html.escape(text, quote=False))


def _g(x: float | None, digits: int = 5) -> str:
    return "-" if x is None else f"{x:.{digits}g}"


def _style_text(cut: CutPlan) -> str:
    st = cut.style
    text = str(st.kind)
    if st.kind is StyleKind.PERFORATED:
        text = f"{st.kind} ({st.cut:g} mm cut, {st.gap:g} mm gap)"
    ops = cut.operations
    made = f"mountains {ops.mountain}, valleys {ops.valley}, band marks {ops.marks}"
    if ops.perforates:
        made += f" (dashes {ops.cut:g} mm, gaps {ops.gap:g} mm)"
    return f"{text} on the fold map; in the cut files {made}"


def _sheet_table(cut: CutPlan) -> str:
    """Where each part lies on its sheet (mm, sheet origin at the lower left), as in the cut
    files."""
    rows = [
        [
            str(pl.sheet + 1),
            pl.part.name,
            f"{pl.x:.2f}",
            f"{pl.y:.2f}",
            f"{pl.size[0]:.2f} x {pl.size[1]:.2f}",
            "yes" if pl.rotated else "no",
        ]
        for pl in cut.plan.placements
    ]
    return _table(["sheet", "part", "x (mm)", "y (mm)", "size (mm)", "turned 90 deg"], rows)


def report_html(sol: Solution, spec_text: str, cut: CutPlan | None = None) -> str:
    """The report of a solved design (see :mod:`corrugate.report`); needs matplotlib.

    ``cut`` is the parts and sheet plan the design's cut files are written from
    (:func:`corrugate.export.plan.cut_plan`), drawn as they are; ``None`` makes one with the default
    output options (a report on its own, without cut files).
    """
    from corrugate.export.files import fold_map_texts

    p = sol.problem
    parts: list[str] = [
        "<!doctype html><html lang='en'><head><meta charset='utf-8'>"
        "<meta name='viewport' content='width=device-width, initial-scale=1'>",
        f"<title>corrugate report: {html.escape(p.name)}</title><style>{_STYLE}</style></head><body>",
        f"<h1>corrugate report: {html.escape(p.name)}</h1>",
    ]
    a = sol.analysis
    if a is None:
        parts.append(f"<p><b>No design meets the spec</b> (status {html.escape(sol.status)}).</p>")
        for d in sol.diagnosis:
            parts.append(f"<p>{html.escape(d.message)}</p>")
        parts.append(_directions())
        parts.append(f"<h2>Spec</h2><pre>{html.escape(spec_text)}</pre></body></html>")
        return "".join(parts)
    asm = a.assembly
    cert = "certified optimal" if sol.certified else "NOT certified"
    if not p.tolerances.nominal:  # docs/tolerances.md
        cert += f" {p.tolerance_sentence}"
    if p.calibrated:  # over the measured intervals (docs/calibration.md 9)
        cert += f" ({html.escape(p.calibration_words)})"
    if sol.extrapolated:
        cert = (
            "EXTRAPOLATED, not certified (outside the validated range: "
            + "; ".join(sol.extrapolated)
            + ")"
        )
    parts.append(
        f"<p><b>{cert}</b> (gap {sol.gap:.1e}); model <code>{html.escape(p.model)}</code>, layout "
        f"{html.escape(asm.layout.name)}, mass <b>{a.mass.total:.4f} g</b> (layers "
        f"{a.mass.layer1:.4f} + {a.mass.layer2:.4f} g, connectors {a.mass.connectors:.4f} g).</p>"
    )
    parts.append("<h2>Design</h2>")
    parts.append(
        _table(
            [
                "layer",
                "material",
                "t (mm)",
                "W (mm)",
                "n",
                "alpha (deg)",
                "pitch (mm)",
                "height (mm)",
            ],
            [
                [
                    str(i + 1),
                    ly.material.id,
                    _g(ly.t),
                    _g(ly.W),
                    str(ly.n),
                    _g(ly.alpha_deg),
                    _g(ly.pitch),
                    _g(ly.height),
                ]
                for i, ly in enumerate(asm.layers)
            ],
        )
    )
    side = f"L = {asm.Lx:.2f} mm" if asm.layout.equal_sides else f"{asm.Lx:.2f} x {asm.Ly:.2f} mm"
    parts.append(f"<p>Folded size {side}, thickness t_d = {asm.thickness:.2f} mm.</p>")
    parts.append(_directions(asm.Lx / asm.Ly, (asm.layer1.n, asm.layers[-1].n)))
    if asm.layout.holes:
        parts.append(
            f"<p>{html.escape(holes_text(asm.layout.holes))}. Model: facets a hole touches carry "
            "nothing in the spanwise (parallel) sums and lose the blocked length in the chordwise "
            "(series) sums; the mass is rho t times the cut area (<code>corrugate docs models</code>, Holes).</p>"
        )
    parts.append("<h2>Constraints and margins</h2>")
    parts.append(
        _table(
            ["constraint", "quantity", "value", "bound", "margin", "unit", "binding"],
            [
                [
                    c.name,
                    c.quantity.key,
                    _g(c.value),
                    ("&ge; " if c.sense == "min" else "&le; ")
                    .replace("&ge; ", ">= ")
                    .replace("&le; ", "<= ")
                    + _g(c.bound),
                    _g(c.margin, 3),
                    c.unit,
                    "yes" if c.binding else ("active" if c.active else "no"),
                ]
                for c in sol.constraints
            ],
            ["bind" if c.binding else "" for c in sol.constraints],
        )
    )
    for c in sol.constraints:  # the load each load case holds (docs/load_cases.md 10)
        if c.load is not None and c.capacity is not None:
            parts.append(
                f"<p>{html.escape(c.name.rsplit('.', 1)[0])} ({c.quantity.test or 'platens'}, "
                f"{c.load:g} N): {html.escape(c.capacity.sentence)}.</p>"
            )
    cases = load_case_figure(sol.constraints, (asm.Lx, asm.Ly))
    if cases is not None:
        parts.append("<h2>Load cases</h2>")
        parts.append(_img(cases, "each load case: supports, load and deflected shape"))
        parts.append(
            "<p>Each test's deflection is the certified model's (pure bending plus the shear "
            "of the facets, <code>corrugate docs load_cases</code>); the shapes are "
            "exaggerated.</p>"
        )
    parts.append("<h2>Design space</h2>")
    space, space_key = design_space(p, a)
    parts.append(_img(space, "design space map: W against alpha"))
    parts.append(_key(space_key, "design space map"))
    parts.append(_img(mass_by_n_figure(p, a), "lightest mass against n"))
    parts.append("<h2>Stiffness in every direction</h2>")
    parts.append(_img(polar_figure(a), "polar plots of K and D"))
    parts.append(
        f"<p>Support condition of this design's stiffness: <b>{a.support}</b>. Along the "
        "creases (0 and 90 deg) both conditions give the paper's springs. Off them, a panel "
        "with free sides (solid or dashed 'free' curve: a lower bound, <code>corrugate docs offaxis</code>) is up "
        "to hundreds of times softer than the paper's cos^2 rule, which holds only for a panel "
        "held in a rigid frame on all four edges (<code>corrugate docs validation/off_axis</code>).</p>"
    )
    if a.buckling:
        parts.append("<h2>Buckling in compression</h2><ul>")
        for b in a.buckling:
            lo, hi = b.travel()
            parts.append(
                f"<li>along {b.eta_deg:g} deg: the end facets (one free edge) buckle at "
                f"{b.low:.3g}-{b.high:.3g} N, a platen travel of {lo:.2g}-{hi:.2g} mm (plate "
                "theory); K holds below that.</li>"
            )
        parts.append(
            "</ul><p>Check the actual load with <code>corrugate validate --buckling</code> "
            "(<code>corrugate docs fea</code>, section 2.6).</p>"
        )
    parts.append("<h2>The three model variants</h2>")
    rows = []
    results = {m: analyze(asm, m, [0.0, 90.0]) for m in MODELS}
    for key in ("Ecx", "Ecy", "Ebx", "Eby"):
        rows.append(
            [f"layer 1 {key} (MPa)", *(_g(r.moduli[0].as_dict()[key]) for r in results.values())]
        )
    for i, eta in enumerate((0, 90)):
        rows.append([f"K({eta}) (N/mm)", *(_g(r.stiffness[i].K) for r in results.values())])
        rows.append([f"D({eta}) (N mm)", *(_g(r.stiffness[i].D) for r in results.values())])
        rows.append([f"EI({eta}) (N mm^2)", *(_g(r.stiffness[i].EI) for r in results.values())])
    parts.append(_table(["quantity", *results], rows))
    parts.append(
        f"<p>The design was solved with <code>{html.escape(p.model)}</code>; "
        "<code>refined</code> is the variant that agrees with finite elements.</p>"
    )
    if cut is None:
        from corrugate.export.plan import cut_plan

        cut = cut_plan(asm)
    pattern, plan = cut.pattern, cut.plan
    parts.append("<h2>Flat pattern and folded part</h2>")
    parts.append(
        f"<p>{len(plan.sheets)} sheet(s) of {html.escape(plan.cutter.description)} "
        f"({plan.cutter.width:.1f} x {plan.cutter.height:.1f} mm usable), fold lines "
        f"{html.escape(_style_text(cut))}. Each sheet is shown as its fold map "
        "<code>sheet-N.svg</code>, the same sheet as the cut files beside this report.</p>"
    )
    drawn = cut.drawings  # what the files step drew of this plan: shown, not drawn again
    maps = drawn.fold_maps
    if len(maps) != len(plan.sheets):  # a report on its own: the fold maps the files would have
        maps = fold_map_texts(plan, cut.style, operations=cut.operations)
    for k, svg in enumerate(maps, start=1):
        parts.append(_img_svg(svg, f"sheet {k} of the cut pattern"))
    parts.append(_sheet_table(cut))
    alt = "the folded assembly, step by step"
    if drawn.assembly_png is not None:
        parts.append(_img_png(drawn.assembly_png, alt))
    else:
        parts.append(_img_png(instructions_png(asm, pattern), alt))
    parts.append("<h2>Assembly</h2><ol>")
    parts.extend(f"<li>{html.escape(s)}</li>" for s in assembly_steps(asm, pattern))
    parts.append("</ol><h2>Warnings</h2>")
    if sol.warnings:
        parts.append("<ul>")
        parts.extend(f"<li class='warn'>{_inline_code(w['message'])}</li>" for w in sol.warnings)
        parts.append("</ul>")
    else:
        parts.append("<p>None.</p>")
    if sol.runner_ups:
        parts.append("<h2>Runner-ups (best design for each n)</h2>")
        parts.append(
            _table(
                ["n", "objective", "layers", "certified"],
                [
                    [
                        str(r.n),
                        _g(r.objective),
                        "; ".join(
                            f"W {_g(float(str(ly['W_mm'])))} alpha {_g(float(str(ly['alpha_deg'])))}"
                            for ly in r.layers
                        ),
                        "yes" if r.certified else "no",
                    ]
                    for r in sol.runner_ups
                ],
            )
        )
    parts.append(f"<h2>Spec</h2><pre>{html.escape(spec_text)}</pre>")
    parts.append("<p><small>made by corrugate</small></p></body></html>")
    return "".join(parts)
