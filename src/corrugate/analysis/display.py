"""Short text and HTML views of results, for the REPL and notebooks.

``repr`` of an :class:`~corrugate.analysis.evaluate.Analysis` fits in five lines (a design's
:class:`~corrugate.solver.solve.Solution` has its own, :mod:`corrugate.solver.display`); ``_repr_html_`` (Jupyter calls it)
gives a small table. Both only format numbers the result already holds (lengths mm, K N/mm,
D N mm, EI N mm^2, mass g); the full record is ``to_dict()``.
"""

from __future__ import annotations

from html import escape
from typing import TYPE_CHECKING

if TYPE_CHECKING:
    from corrugate.analysis.evaluate import Analysis
    from corrugate.geometry.layer import Layer

__all__ = ["analysis_html", "analysis_repr", "html_row", "layer_text", "layers_text"]

#: Directions shown in a repr before "... and k more".
_ETAS_SHOWN = 2


def layer_text(layer: Layer) -> str:
    """``W 8 mm, n 8, alpha 84 deg, dura-lar 0.125 mm``."""
    return (
        f"W {layer.W:g} mm, n {layer.n}, alpha {layer.alpha_deg:.4g} deg, "
        f"{layer.material.id} {layer.t:g} mm"
    )


def layers_text(a: Analysis) -> str:
    """``layer 1: ...; layer 2: identical`` (or layer 2's own text)."""
    l1, l2 = a.assembly.layers
    second = "identical" if l1 == l2 else layer_text(l2)
    return f"layer 1: {layer_text(l1)}; layer 2: {second}"


def analysis_repr(a: Analysis) -> str:
    """At most five lines: model and support, layers, size and mass, K/D/EI at two directions."""
    asm = a.assembly
    lines = [
        f"Analysis(model={a.model!r}, support={a.support!r}, {len(a.warnings)} warning(s))",
        "  " + layers_text(a),
        f"  {asm.layout.name} {asm.Lx:.4g} x {asm.Ly:.4g} mm, t_d {asm.thickness:.4g} mm, "
        f"mass {a.mass.total:.4g} g",
    ]
    shown = a.stiffness[:_ETAS_SHOWN]
    if shown:
        parts = [
            f"eta {s.eta_deg:g}: K {s.K:.4g} N/mm, D {s.D:.4g} N mm, EI {s.EI:.4g} N mm^2"
            for s in shown
        ]
        more = len(a.stiffness) - len(shown)
        lines.append("  " + "; ".join(parts) + (f"; ... {more} more" if more > 0 else ""))
    return "\n".join(lines)


def html_row(cells: list[str], tag: str = "td") -> str:
    """One HTML table row of ``cells`` (already escaped)."""
    return "<tr>" + "".join(f"<{tag}>{c}</{tag}>" for c in cells) + "</tr>"


def analysis_html(a: Analysis) -> str:
    """An HTML summary: the layers, size and mass, a K/D/EI table and the warnings."""
    asm = a.assembly
    rows = [html_row(["eta (deg)", "K (N/mm)", "D (N mm)", "EI (N mm^2)"], "th")]
    rows += [
        html_row([f"{s.eta_deg:g}", f"{s.K:.4g}", f"{s.D:.4g}", f"{s.EI:.4g}"]) for s in a.stiffness
    ]
    warn = "".join(f"<li>{escape(w.message)}</li>" for w in a.warnings)
    return (
        f"<div><b>Analysis</b> (model {escape(a.model)}, support {escape(a.support)})<br>"
        f"{escape(layers_text(a))}<br>"
        f"{escape(asm.layout.name)} {asm.Lx:.4g} x {asm.Ly:.4g} mm, "
        f"t<sub>d</sub> {asm.thickness:.4g} mm, mass {a.mass.total:.4g} g"
        f"<table>{''.join(rows)}</table>" + (f"<ul>{warn}</ul>" if warn else "") + "</div>"
    )
