"""Readers of the PDF files the tests parse back: the sub-paths of a page's content stream, in mm
(used by the tiled PDF's tests and the holes' tests)."""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any

from pypdf.generic import ContentStream

PT = 72.0 / 25.4  # points per mm

Point = tuple[float, float]


@dataclass
class SubPath:
    """One stroked or filled sub-path of a page, in mm from the page's lower-left corner."""

    points: list[Point]
    closed: bool
    stroke: tuple[float, ...]
    painted: bool


def _mul(a: list[float], b: list[float]) -> list[float]:
    """PDF matrix product a x b ([a b c d e f])."""
    return [
        a[0] * b[0] + a[1] * b[2],
        a[0] * b[1] + a[1] * b[3],
        a[2] * b[0] + a[3] * b[2],
        a[2] * b[1] + a[3] * b[3],
        a[4] * b[0] + a[5] * b[2] + b[4],
        a[4] * b[1] + a[5] * b[3] + b[5],
    ]


def page_paths(reader: Any, page: Any) -> list[SubPath]:
    """The sub-paths of a page's content stream (m, l, c, re, h; S, s, f, B, n), in mm, with the
    stroke colour (G or RG) in force; q/Q/cm are followed. Curves keep their end points only."""
    out: list[SubPath] = []
    ctm = [1.0, 0.0, 0.0, 1.0, 0.0, 0.0]
    stack: list[tuple[list[float], tuple[float, ...]]] = []
    stroke: tuple[float, ...] = (0.0,)
    current: list[SubPath] = []

    def tr(x: float, y: float) -> Point:
        return (
            (ctm[0] * x + ctm[2] * y + ctm[4]) / PT,
            (ctm[1] * x + ctm[3] * y + ctm[5]) / PT,
        )

    for operands, op in ContentStream(page.get_contents(), reader).operations:
        args = [float(v) for v in operands] if op not in (b"d", b"Tf", b"TJ", b"cs", b"CS") else []
        if op == b"q":
            stack.append((list(ctm), stroke))
        elif op == b"Q":
            ctm, stroke = stack.pop()
        elif op == b"cm":
            ctm = _mul(args, ctm)
        elif op == b"G":
            stroke = (args[0],) * 3
        elif op == b"RG":
            stroke = tuple(args)
        elif op == b"m":
            current.append(SubPath([tr(*args)], False, stroke, False))
        elif op in (b"l", b"c"):
            current[-1].points.append(tr(*args[-2:]))
        elif op == b"re":
            x, y, w, h = args
            corners = [(x, y), (x + w, y), (x + w, y + h), (x, y + h)]
            current.append(SubPath([tr(*c) for c in corners], True, stroke, False))
        elif op == b"h":
            current[-1].closed = True
        elif op in (b"S", b"s", b"f", b"B", b"b", b"n", b"f*", b"B*"):
            for sp in current:
                sp.painted = op != b"n"
                sp.stroke = stroke
                sp.closed = sp.closed or op in (b"s", b"b")
            out.extend(sp for sp in current if sp.painted)
            current = []
    return out
