"""Richardson extrapolation of a mesh series: the FE value a refined mesh tends to.

A series maps the elements per facet of each run (2, 4, 8, ...: each mesh twice as fine as the
one before) to the value it gave. With three meshes h, h/2, h/4 and the steps d1 = v(h) - v(h/2),
d2 = v(h/2) - v(h/4), the observed order of convergence is p = log2(d1 / d2) and the limit
v(h/4) - d2 / (2^p - 1). The estimate is trusted only when the series looks asymptotic: monotone
(the steps have one sign), the steps shrinking, and 0.5 <= p <= 4 (the S8R shells of
:mod:`corrugate.fea.assembly` converge at p of about 1-2, docs/fea.md 2.2). Otherwise the series
is "not asymptotic", and its finest value is not presented as its limit: below p = 0.5 or where
the steps turn, a series that softens as the mesh refines may end anywhere beyond it (issue 35:
100 / 90 / 82.42, p = 0.40, continues geometrically to 58.7).

:func:`richardson` is the step the benchmarks' tables use (``benchmarks/offaxis_table.py``);
:func:`extrapolate` is what ``corrugate validate --fixture`` and verify's first-failure rows
report: the estimate, the observed order and how it was found, and, given the side a bound
lies on, only a value that is safe on that side. :func:`judge` is what ``corrugate verify``
decides a constraint and a first-failure row by: a series counts only when it is shown asymptotic (four meshes, two
successive extrapolations that agree within a share of the bound's margin); otherwise it is
refined further, and left "not converged" at the finest mesh allowed (docs/fea.md 6).
"""

from __future__ import annotations

import itertools
import math
from collections.abc import Mapping
from dataclasses import dataclass
from typing import Literal

__all__ = [
    "MARGIN_SHARE",
    "MAX_ORDER",
    "MIN_ORDER",
    "ROUND_OFF",
    "Extrapolation",
    "Judgement",
    "Outcome",
    "extrapolate",
    "judge",
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
    log2(d1 / d2) (:func:`_limit`, the one formula :func:`judge` uses too), when the series is
    monotone with shrinking steps and 0.5 <= p <= 4: (value, ``"extrapolated (p = ...)"``); None
    otherwise."""
    three = _finest_three(series)
    found = None if three is None else _limit(three[1])
    if found is None or not MIN_ORDER <= found[1] <= MAX_ORDER:
        return None
    return found[0], f"extrapolated (p = {found[1]:.2f})"


@dataclass(frozen=True, slots=True)
class Extrapolation:
    """What a mesh series says (:func:`extrapolate`): ``value`` (the extrapolated limit when
    ``asymptotic``; else a bound on the limit on the safe side of ``sense``, the finest value of
    one mesh, or of two without a sense; None when the series gives nothing that may be presented: an empty series,
    or one shown not asymptotic with nothing safe to say), the observed ``order`` p (None when
    none could be read), whether the series is ``asymptotic`` (Richardson applies), ``how``, one
    phrase for a table, and ``finest``, the finest mesh's value (None for an empty series)."""

    value: float | None
    order: float | None
    asymptotic: bool
    how: str
    finest: float | None = None


def extrapolate(series: Series, sense: str | None = None) -> Extrapolation:
    """The estimate of a mesh series (module docstring): Richardson's limit when the three finest
    meshes are asymptotic (or the finest value when the last two steps vanish: a
    mesh-independent value). Otherwise no value is presented as a limit (docs/fea.md 6, "The
    series and when it counts"):

    - with ``sense`` (``min``: the value must be at least a bound, so what is safe is a value at
      or below the limit; ``max``: at or above it), the finest value when the series is
      monotone and moves towards the safe side as the mesh refines (a stiffness that rises
      under a minimum: the limit lies beyond the finest value), said to be a bound; None when it
      moves the other way or turns (a series that softens under a minimum may go anywhere
      below its finest value: 100 / 90 / 82.42 at p = 0.40 continues to 58.7), "not converged";
    - without a sense, two meshes give the finest value (no order, said so); three or more
      that are not asymptotic give None, "not converged", naming the finest value.

    One mesh gives its value, said to be one mesh (no order, no direction). A Richardson limit
    of the other sign than the finest value (a first-yield load that falls towards zero as a
    stress concentration sharpens: 102.6 / 55.9 / 30.2 N at p = 0.87 gives -0.92 N) is no limit
    of a positive quantity: not asymptotic."""
    finite = {k: v for k, v in series.items() if math.isfinite(v)}
    if not finite:
        return Extrapolation(None, None, False, "no FE value")
    if sense not in (None, "min", "max"):
        raise ValueError(f"sense must be min, max or None, not {sense!r}")  # a caller's bug
    vs = [finite[a] for a in sorted(finite)]
    finest = vs[-1]
    if len(vs) == 1:
        return Extrapolation(
            finest, None, False, "one mesh: no observed order, the finest value", finest
        )
    steps = [b - a for a, b in itertools.pairwise(vs)]  # finer minus coarser
    tiny = ROUND_OFF * max(abs(v) for v in vs)
    p = observed_order(finite)
    if len(vs) >= 3:
        r = richardson(finite)
        if r is not None and r[0] * finest > 0:
            return Extrapolation(r[0], p, True, r[1] + _before(finite), finest)
        if all(abs(d) <= tiny for d in steps[-2:]):
            return Extrapolation(finest, None, True, "converged: the last two steps vanish", finest)
        if p is None:
            why = "not asymptotic (the steps change sign or vanish, or the meshes do not double)"
        elif r is not None:  # a load or stiffness whose limit would cross zero: no limit to trust
            why = f"not asymptotic (p = {p:.2f}, but the limit {_fmt(r[0])} has the other sign)"
        else:
            why = f"not asymptotic (p = {p:.2f})"
    else:
        why = "two meshes: no observed order"
    if sense is None:
        if len(vs) == 2:
            return Extrapolation(finest, None, False, f"{why}, the finest value", finest)
        return Extrapolation(
            None, p, False, f"not converged: {why}; the finest value {_fmt(finest)}", finest
        )
    sign = 1.0 if sense == "min" else -1.0
    side = "lower" if sense == "min" else "upper"
    moving = [d for d in steps if abs(d) > tiny]
    if moving and all(sign * d > 0 for d in moving):
        toward = "rises" if sense == "min" else "falls"
        return Extrapolation(
            finest,
            p,
            False,
            f"{why}: the finest value, {'a' if sense == 'min' else 'an'} {side} bound (the series "
            f"{toward} as the mesh refines)",
            finest,
        )
    return Extrapolation(
        None,
        p,
        False,
        f"not converged: {why}; the finest value {_fmt(finest)} is no {side} bound",
        finest,
    )


#: A series counts (:func:`judge`) when its two successive Richardson extrapolations differ by at
#: most this share of the bound's margin |estimate - bound|: the bound then lies at least four
#: disagreements away from the estimate (docs/fea.md 6, "The series and the extrapolation").
MARGIN_SHARE = 0.25
#: Steps smaller than this fraction of the series' largest |value| are round-off: zero.
ROUND_OFF = 1e-9

#: What a mesh series says of its bound: ``holds``, ``fails``, or ``open`` (not settled yet:
#: refine further; a row left open at the finest mesh allowed is "not converged").
Outcome = Literal["holds", "fails", "open"]


@dataclass(frozen=True, slots=True)
class Judgement:
    """What :func:`judge` reads from a mesh series against a bound: the ``verdict``, the
    ``value`` it rests on (the second extrapolation of a converged series; otherwise the
    Richardson estimate of the three finest meshes when they are monotone with shrinking steps,
    else the finest value; None without a value), the observed ``order`` p of the three finest
    meshes, ``how`` (one phrase for the table) and, when ``open``, ``why`` (what the series has
    not shown yet)."""

    verdict: Outcome
    value: float | None
    order: float | None
    how: str
    why: str = ""


def _chain(series: Series) -> list[int]:
    """The meshes of ``series`` that end at its finest, each twice the one before (the longest
    such run), coarsest first."""
    alongs = sorted(series)
    chain = [alongs[-1]]
    while chain[0] % 2 == 0 and chain[0] // 2 in series:
        chain.insert(0, chain[0] // 2)
    return chain


def _limit(v: tuple[float, float, float]) -> tuple[float, float] | None:
    """Richardson's limit v3 - d2 / (2^p - 1) and the observed order p = log2(d1 / d2) of three
    values on meshes h, h/2, h/4 (d1 = v1 - v2, d2 = v2 - v3) when their steps have one sign and
    shrink (any order p > 0), else None: the one formula of :func:`richardson` (which also asks
    0.5 <= p <= 4) and :func:`judge`."""
    d1, d2 = v[0] - v[1], v[1] - v[2]
    if d1 * d2 <= 0 or abs(d2) >= abs(d1):
        return None
    p = math.log2(d1 / d2)
    return v[2] - d2 / (2**p - 1), p


def _fmt(x: float) -> str:
    return f"{x:.5g}"


def _before(series: Series) -> str:
    """The extrapolation from the meshes before the three finest (k, 2k, 4k of k, 2k, 4k, 8k),
    as "; 82.679 from 2 / 4 / 8", when there is one: what the finest three's estimate moved
    from (:func:`judge` asks the two to agree)."""
    chain = _chain(series)
    if len(chain) < 4:
        return ""
    first = _limit((series[chain[-4]], series[chain[-3]], series[chain[-2]]))
    if first is None:
        return ""
    return f"; {_fmt(first[0])} from {' / '.join(map(str, chain[-4:-1]))} (p = {first[1]:.2f})"


def judge(series: Series, bound: float, sense: str) -> Judgement:
    """Whether a mesh series (elements per facet -> value) shows that its limit meets ``bound``
    (``sense`` ``min``: at or above it; ``max``: at or below), docs/fea.md 6.

    A series counts only when it is shown asymptotic: on its four finest meshes, each twice as
    fine as the one before (k, 2k, 4k, 8k), it is monotone with shrinking steps and its two
    successive Richardson extrapolations, R1 from k, 2k, 4k and R2 from 2k, 4k, 8k (each at its
    own observed order p = log2(d1 / d2)), differ by at most :data:`MARGIN_SHARE` of the margin
    |R2 - bound|. Then R2 decides: ``holds`` or ``fails``. Two more cases are settled:

    - the last two steps vanish (to :data:`ROUND_OFF`, a mesh-independent quantity): the
      finest value decides;
    - ``fails`` early: the finest value is already past the bound and the last two steps move
      away from it (a series that softens under a minimum, stiffens under a maximum): refining
      only takes it further.

    Anything else is ``open``: refine further. Neither the finest value of a series that is
    still moving nor a remaining error of at most the last step is ever assumed: the K(15)
    series 126.24 / 93.20 / 85.22 extrapolates to 82.68 at p = 2.05 and 4 / 8 / 16 (81.60)
    gives 78.59 (docs/fea.md 2.9)."""
    finite = {k: float(v) for k, v in series.items() if math.isfinite(v)}
    if not finite:
        return Judgement("open", None, None, "no FE value", "no FE value")
    if sense not in ("min", "max"):
        raise ValueError(f"sense must be min or max, not {sense!r}")  # a caller's bug
    sign = 1.0 if sense == "min" else -1.0
    chain = _chain(finite)
    vs = [finite[a] for a in chain]
    finest = vs[-1]
    tiny = ROUND_OFF * max(abs(v) for v in vs)
    steps = [a - b for a, b in itertools.pairwise(vs)]
    three = _limit((vs[-3], vs[-2], vs[-1])) if len(vs) >= 3 else None
    order = None if three is None else three[1]
    estimate = finest if three is None else three[0]

    def margin(x: float) -> float:
        return sign * (x - bound)

    def decided(x: float) -> Outcome:
        return "holds" if margin(x) >= 0 else "fails"

    if len(steps) >= 2 and all(abs(d) <= tiny for d in steps[-2:]):
        return Judgement(
            decided(finest),
            finest,
            None,
            f"converged: the last two steps vanish (at {' / '.join(map(str, chain[-3:]))})",
        )
    why = (
        f"two successive extrapolations need four meshes each twice as fine as the one before "
        f"(k, 2k, 4k, 8k); the series has {len(vs)}"
    )
    if len(vs) >= 4:
        first = _limit((vs[-4], vs[-3], vs[-2]))
        at1 = " / ".join(map(str, chain[-4:-1]))
        at2 = " / ".join(map(str, chain[-3:]))
        if first is None or three is None:
            why = f"not monotone with shrinking steps over {' / '.join(map(str, chain[-4:]))}"
        else:
            r1, r2 = first[0], three[0]
            u, m = abs(r2 - r1), abs(r2 - bound)
            pair = (
                f"extrapolations {_fmt(r1)} ({at1}, p = {first[1]:.2f}) and {_fmt(r2)} "
                f"({at2}, p = {three[1]:.2f})"
            )
            if u <= MARGIN_SHARE * m:
                return Judgement(
                    decided(r2),
                    r2,
                    three[1],
                    f"converged: {pair} differ by {u:.3g} <= {MARGIN_SHARE:g} x the margin "
                    f"|estimate - bound| = {m:.3g}",
                )
            why = f"{pair} differ by {u:.3g} > {MARGIN_SHARE:g} x the margin {m:.3g}"
    if len(steps) >= 2 and margin(finest) < 0 and all(sign * d > tiny for d in steps[-2:]):
        return Judgement(
            "fails",
            estimate,
            order,
            f"fails: the finest value {_fmt(finest)} is past the bound and the series moves "
            "away from it as the mesh refines",
        )
    how = "not converged: " + (
        f"Richardson {_fmt(estimate)} (p = {order:.2f})"
        if three is not None and order is not None
        else f"the finest value {_fmt(finest)}"
    )
    return Judgement("open", estimate, order, how, why)
