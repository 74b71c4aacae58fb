"""Free sides, ``support = "free"`` (the default): a bench test, a part held at two edges.

Its model is the free-panel lower bound of :func:`corrugate.mechanics.offaxis.free_panel`
(docs/offaxis.md), which reads a layout other than a square as a coupon of its proportions; the
same plain arithmetic on interval springs is the solver's bound. Its FE fixture is the free
coupon between platens (``platens``, :mod:`corrugate.fea.fixtures.platens`: free sides).
"""

from __future__ import annotations

from corrugate.mechanics.behaviours import STIFFNESS_UNITS, Behaviour
from corrugate.mechanics.offaxis import free_panel

__all__ = ["FREE"]


def off_axis_warning(angles: str, layout: str) -> str:
    """The model warning at the directions ``angles`` (deg, as text) off the creases of a
    ``layout`` (its name): how the free-panel model compares with FE coupons
    (docs/validation/off_axis.md) and how the layout is read off the crease directions."""
    text = (
        f"K and D at eta = {angles} deg are the free-panel model (support 'free', "
        "`corrugate docs offaxis`): against FE coupons K is 0.83-1.22 times the FE, above it "
        "near 15 and 75 deg by 22, 15 and 9 % for square coupons 4, 8 and 16 cells wide and "
        "19 % for a 9 x 18-cell rectangle (the model is the large-panel limit), and D is far "
        "below it where no facet runs from support to support (near 45 deg) "
        "(`corrugate docs validation/off_axis`): check a part loaded there with corrugate validate --eta"
    )
    if layout == "rectangle":
        text += (
            "; a rectangle is read as the coupon of its proportions cut along eta (Lx x Ly "
            "up to 45 deg, Ly x Lx above)"
        )
    elif layout != "square":
        text += (
            f"; a {layout} has no straight edges to load: its value is the smaller of its "
            "box's coupon and the square's formula on its own springs, a convention no FE "
            "has checked"
        )
    return text


FREE = Behaviour(
    name="free",
    model=free_panel,
    bounds=free_panel,  # plain arithmetic: on interval springs it bounds itself
    fixture="platens",
    label="",
    suffix="",
    units=STIFFNESS_UNITS,
    text="free sides, as a bench test or a part held at two edges",
    curve="free sides (lower bound)",
    off_axis=off_axis_warning,
    crease_rule=True,  # along the creases: the paper's rule (docs/theory.md 3.3)
    uses_coupon=True,
)
