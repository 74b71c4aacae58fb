"""A rigid frame, ``support = "frame"``: the panel held on all four edges (the paper's rule).

Its model is the cos^2 rule of :func:`corrugate.mechanics.offaxis.frame_rule` (docs/theory.md
3.3; the project's frame FE agrees within 0.2 %, docs/fea.md 2.5), its bound the same arithmetic
on interval springs, and its FE fixture ``frame``, the panel in a rigid frame (:mod:`corrugate.fea.fixtures.frame`,
two runs combined by :mod:`corrugate.fea.frame`).
"""

from __future__ import annotations

from corrugate.mechanics.behaviours import STIFFNESS_UNITS, Behaviour
from corrugate.mechanics.offaxis import frame_rule

__all__ = ["FRAME"]


def off_axis_warning(angles: str, layout: str) -> str:
    """The model warning at the directions ``angles`` (deg, as text) off the creases: the rule
    holds only in a rigid frame (the same for every ``layout``)."""
    return (
        f"K and D at eta = {angles} deg follow the paper's cos^2 rule (support 'frame'): "
        "true only for a panel held in a rigid frame on all four edges; a panel with free "
        "sides is up to hundreds of times softer off-axis (`corrugate docs fea`, section 2.5)"
    )


FRAME = Behaviour(
    name="frame",
    model=frame_rule,
    bounds=frame_rule,  # plain arithmetic: on interval springs it bounds itself
    fixture="frame",
    label=" in a frame",
    suffix="frame",
    units=STIFFNESS_UNITS,
    text="a rigid frame: the paper's cos^2 rule",
    curve="rigid frame (cos^2 rule)",
    off_axis=off_axis_warning,
    crease_rule=True,  # along the creases: the paper's rule (docs/theory.md 3.3)
)
