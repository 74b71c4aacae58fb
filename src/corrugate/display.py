"""Short text and HTML views of results, for the REPL and notebooks.

``repr`` of an :class:`~corrugate.analysis.Analysis` or a design
:class:`~corrugate.design.solve.Solution` fits in five lines; ``_repr_html_`` (Jupyter calls it)
gives a small table. Both only format numbers the result already holds (lengths mm, K N/mm,
D N mm, EI N mm^2, mass g); the full record is ``to_dict()``.
"""

from __future__ import annotations

from html import escape
from typing import TYPE_CHECKING

if TYPE_CHECKING:
    from .analysis import Analysis
    from .design.solve import Solution
    from .geometry import Layer

__all__ = ["analysis_html", "analysis_repr", "layer_text", "solution_html", "solution_repr"]

#: Directions shown in a repr before "... and k more".
_ETAS_SHOWN = 2


def layer_text(layer: Layer) -> str:
    """``W 8 mm, n 8, alpha 84 deg, dura-lar 0.125 mm``."""
    return (
        f"W {layer.W:g} mm, n {layer.n}, alpha {layer.alpha_deg:.4g} deg, "
        f"{layer.material.id} {layer.t:g} mm"
    )


def _layers(a: Analysis) -> str:
    l1, l2 = a.assembly.layers
    second = "identical" if l1 == l2 else layer_text(l2)
    return f"layer 1: {layer_text(l1)}; layer 2: {second}"


def analysis_repr(a: Analysis) -> str:
    """At most five lines: model and support, layers, size and mass, K/D/EI at two directions."""
    asm = a.assembly
    lines = [
        f"Analysis(model={a.model!r}, support={a.support!r}, {len(a.warnings)} warning(s))",
        "  " + _layers(a),
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


def _row(cells: list[str], tag: str = "td") -> str:
    return "<tr>" + "".join(f"<{tag}>{c}</{tag}>" for c in cells) + "</tr>"


def analysis_html(a: Analysis) -> str:
    """An HTML summary: the layers, size and mass, a K/D/EI table and the warnings."""
    asm = a.assembly
    rows = [_row(["eta (deg)", "K (N/mm)", "D (N mm)", "EI (N mm^2)"], "th")]
    rows += [
        _row([f"{s.eta_deg:g}", f"{s.K:.4g}", f"{s.D:.4g}", f"{s.EI:.4g}"]) for s in a.stiffness
    ]
    warn = "".join(f"<li>{escape(w.message)}</li>" for w in a.warnings)
    return (
        f"<div><b>Analysis</b> (model {escape(a.model)}, support {escape(a.support)})<br>"
        f"{escape(_layers(a))}<br>"
        f"{escape(asm.layout.name)} {asm.Lx:.4g} x {asm.Ly:.4g} mm, "
        f"t<sub>d</sub> {asm.thickness:.4g} mm, mass {a.mass.total:.4g} g"
        f"<table>{''.join(rows)}</table>" + (f"<ul>{warn}</ul>" if warn else "") + "</div>"
    )


def solution_repr(s: Solution) -> str:
    """At most five lines: status and certificate, mass, layers, binding constraints."""
    head = f"Solution({s.status}, certified={s.certified}, gap={s.gap:.3g})"
    if s.analysis is None:
        why = s.diagnosis[0].message if s.diagnosis else "no design meets the spec"
        return f"{head}\n  {why}"
    binding = [c.name for c in s.constraints if c.binding or c.active]
    lines = [
        f"{head}: mass {s.analysis.mass.total:.4g} g",
        "  " + _layers(s.analysis),
        "  binding: " + (", ".join(binding) if binding else "none"),
    ]
    return "\n".join(lines)


def solution_html(s: Solution) -> str:
    """An HTML summary: status, the design and each constraint with its margin."""
    head = (
        f"<b>Design</b> {escape(s.status)}, certified {s.certified}, gap {s.gap:.3g}"
        if s.analysis is None
        else f"<b>Design</b> {escape(s.status)}, certified {s.certified}, "
        f"mass {s.analysis.mass.total:.4g} g<br>{escape(_layers(s.analysis))}"
    )
    rows = [_row(["constraint", "value", "bound", "margin", "unit", "binding"], "th")]
    rows += [
        _row(
            [
                escape(c.name),
                f"{c.value:.4g}",
                f"{c.bound:.4g}",
                f"{c.margin:.3g}",
                escape(c.unit),
                "yes" if c.binding or c.active else "",
            ]
        )
        for c in s.constraints
    ]
    diag = "".join(f"<li>{escape(d.message)}</li>" for d in s.diagnosis)
    return (
        f"<div>{head}<table>{''.join(rows)}</table>"
        + (f"<ul>{diag}</ul>" if diag else "")
        + "</div>"
    )
