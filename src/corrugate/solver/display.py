"""Short text and HTML views of a design's :class:`~corrugate.solver.solve.Solution`, for the REPL
and notebooks: ``repr`` fits in five lines, ``_repr_html_`` (Jupyter calls it) gives a small table
of the constraints. Both only format numbers the solution already holds (mass g); the full record
is ``to_dict()``.
"""

from __future__ import annotations

from html import escape
from typing import TYPE_CHECKING

from corrugate.analysis.display import html_row, layers_text

if TYPE_CHECKING:
    from corrugate.solver.solve import Solution

__all__ = ["solution_html", "solution_repr"]


def solution_repr(s: Solution) -> str:
    """At most five lines: status and certificate, mass, layers, binding constraints."""
    head = f"Solution({s.status}, certified={s.certified}, gap={s.gap:.3g})"
    if s.analysis is None:
        why = s.diagnosis[0].message if s.diagnosis else "no design meets the spec"
        return f"{head}\n  {why}"
    binding = [c.name for c in s.constraints if c.binding or c.active]
    lines = [
        f"{head}: mass {s.analysis.mass.total:.4g} g",
        "  " + layers_text(s.analysis),
        "  binding: " + (", ".join(binding) if binding else "none"),
    ]
    return "\n".join(lines)


def solution_html(s: Solution) -> str:
    """An HTML summary: status, the design and each constraint with its margin."""
    head = (
        f"<b>Design</b> {escape(s.status)}, certified {s.certified}, gap {s.gap:.3g}"
        if s.analysis is None
        else f"<b>Design</b> {escape(s.status)}, certified {s.certified}, "
        f"mass {s.analysis.mass.total:.4g} g<br>{escape(layers_text(s.analysis))}"
    )
    rows = [html_row(["constraint", "value", "bound", "margin", "unit", "binding"], "th")]
    rows += [
        html_row(
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
