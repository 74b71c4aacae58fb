"""Richardson extrapolation of a mesh series: the FE value a refined mesh tends to.

A series maps the elements per facet of each run (2, 4, 8, ...: each mesh twice as fine as the
one before) to the value it gave. With three meshes h, h/2, h/4 and the steps d1 = v(h) - v(h/2),
d2 = v(h/2) - v(h/4), the observed order of convergence is p = log2(d1 / d2) and the limit
v(h/4) - d2 / (2^p - 1). The estimate is trusted only when the series looks asymptotic: monotone
(the steps have one sign), the steps shrinking, and 0.5 <= p <= 4 (the S8R shells of
:mod:`corrugate.fea.assembly` converge at p of about 1-2, docs/fea.md 2.2). Otherwise the series
is "not asymptotic" and the finest value is all there is.

:func:`richardson` is the step the benchmarks' tables use (``benchmarks/offaxis_table.py``);
:func:`extrapolate` is what ``corrugate verify`` reports: the estimate, the observed order and
how it was found.
"""

from __future__ import annotations

import math
from collections.abc import Mapping
from dataclasses import dataclass

__all__ = [
    "MAX_ORDER",
    "MIN_ORDER",
    "Extrapolation",
    "extend_reason",
    "extrapolate",
    "observed_order",
    "richardson",
]

#: The observed orders accepted as asymptotic.
MIN_ORDER = 0.5
MAX_ORDER = 4.0

#: A mesh series: elements per facet -> value.
Series = Mapping[int, float]


def _finest_three(series: Series) -> tuple[tuple[int, int, int], tuple[float, float, float]] | None:
    alongs = sorted(series)
    if len(alongs) < 3:
        return None
    a = alongs[-3:]
    if a[1] != 2 * a[0] or a[2] != 2 * a[1]:
        return None  # the formula needs a refinement ratio of 2
    return (a[0], a[1], a[2]), (series[a[0]], series[a[1]], series[a[2]])


def observed_order(series: Series) -> float | None:
    """p = log2(d1 / d2) of the three finest meshes (each twice as fine as the one before), or
    None when there are fewer than three, the ratio is not 2, or the steps change sign or vanish
    (no order can be read)."""
    three = _finest_three(series)
    if three is None:
        return None
    v1, v2, v3 = three[1]
    d1, d2 = v1 - v2, v2 - v3
    if d1 * d2 <= 0 or not math.isfinite(d1 / d2):
        return None
    return math.log2(d1 / d2)


def richardson(series: Series) -> tuple[float, str] | None:
    """Richardson extrapolation of the three finest meshes at their observed order p =
    log2(d1 / d2), when the series is monotone with shrinking steps and 0.5 <= p <= 4: (value,
    ``"extrapolated (p = ...)"``); None otherwise."""
    p = observed_order(series)
    if p is None or not MIN_ORDER <= p <= MAX_ORDER:
        return None
    three = _finest_three(series)
    assert three is not None
    v2, v3 = three[1][1], three[1][2]
    return v3 - (v2 - v3) / (2**p - 1), f"extrapolated (p = {p:.2f})"


@dataclass(frozen=True, slots=True)
class Extrapolation:
    """What a mesh series says: ``value`` (the extrapolated limit when ``asymptotic``, else the
    finest mesh's value; None for an empty series), the observed ``order`` p (None when none
    could be read), whether the series is ``asymptotic`` (Richardson applies) and ``how``, one
    phrase for a table."""

    value: float | None
    order: float | None
    asymptotic: bool
    how: str


def extrapolate(series: Series) -> Extrapolation:
    """The estimate of a mesh series (module docstring): Richardson's limit when the three finest
    meshes are asymptotic; otherwise the finest value, saying why (one or two meshes: no order;
    three or more: "not asymptotic", with the order read when there is one)."""
    finite = {k: v for k, v in series.items() if math.isfinite(v)}
    if not finite:
        return Extrapolation(None, None, False, "no FE value")
    alongs = sorted(finite)
    finest = finite[alongs[-1]]
    if len(alongs) < 3:
        what = "one mesh" if len(alongs) == 1 else "two meshes"
        return Extrapolation(finest, None, False, f"{what}: no observed order, the finest value")
    p = observed_order(finite)
    r = richardson(finite)
    if r is not None:
        return Extrapolation(r[0], p, True, r[1])
    if p is None:
        why = "not asymptotic (the steps change sign or vanish, or the meshes do not double)"
    else:
        why = f"not asymptotic (p = {p:.2f})"
    return Extrapolation(finest, p, False, f"{why}, the finest value")


def extend_reason(series: Series, bound: float) -> str | None:
    """Why the verdict "estimate against ``bound``" of a mesh series could still flip on a finer
    mesh (a phrase for the table), or None when it cannot within the series' own error scale.

    The error of a Richardson estimate is of the order of its own correction |v_finest -
    estimate| (the part of the answer the extrapolation supplies: were the observed order off,
    that part is what moves; docs/fea.md 2.9 and 6: the K(15) series 126.24 / 93.20 / 85.22 /
    81.60 N/mm extrapolates to 82.68 from 2 / 4 / 8 and 78.59 from 4 / 8 / 16: it moved by 4.09,
    1.6 times the 2 / 4 / 8 correction of 2.54). So, with ``est`` the estimate of
    :func:`extrapolate`:

    - asymptotic: extend when |est - bound| <= |v_finest - est|;
    - not asymptotic, or fewer than three meshes (the estimate is the finest value): extend when
      |v_finest - bound| <= |v_finest - v_previous|, the last step (the next step of a
      converging series is smaller than the last one, so a bound farther than that cannot be
      crossed).

    A single mesh or no finite value: None (nothing to scale the error by)."""
    finite = {k: v for k, v in series.items() if math.isfinite(v)}
    if len(finite) < 2:
        return None
    alongs = sorted(finite)
    finest, previous = finite[alongs[-1]], finite[alongs[-2]]
    e = extrapolate(finite)
    assert e.value is not None
    if e.asymptotic:
        gap, correction = abs(e.value - bound), abs(finest - e.value)
        if gap <= correction:
            return (
                f"|estimate - bound| = {gap:.3g} <= the Richardson correction "
                f"|finest - estimate| = {correction:.3g}"
            )
        return None
    gap, step = abs(finest - bound), abs(finest - previous)
    if gap <= step:
        why = "not asymptotic" if len(alongs) >= 3 else "no observed order"
        return f"{why} and |finest - bound| = {gap:.3g} <= the last step {step:.3g}"
    return None
