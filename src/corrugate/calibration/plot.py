"""The fit's figure: readings against the model (``fit.png``, docs/calibration.md section 5)."""

from __future__ import annotations

from typing import TYPE_CHECKING

import numpy as np

from corrugate.calibration.coupons import expected_sag
from corrugate.calibration.fit import Fit

if TYPE_CHECKING:
    from matplotlib.figure import Figure

__all__ = ["fit_figure"]


def fit_figure(fit: Fit) -> Figure:
    """One panel per direction (sag against free length for each tip load: the readings as dots,
    the elastica at the fitted E as a line, at the interval's ends dotted) and one for the crease
    strip (extension against load)."""
    from corrugate.core.plotting import new_figure

    m = fit.measurements
    panels = len(fit.moduli) + (fit.crease is not None)
    fig = new_figure((4.2 * max(panels, 1), 3.6), dpi=110, layout="constrained")
    axes = [fig.add_subplot(1, max(panels, 1), i + 1) for i in range(max(panels, 1))]
    for ax, mod in zip(axes, fit.moduli, strict=False):
        for j, test in enumerate(mod.tests):
            color = f"C{j}"
            ax.plot(
                [test.overhang] * len(test.sags),
                test.sags,
                "o",
                color=color,
                ms=4,
                label=f"{test.coupon}, {test.overhang:g} mm, {test.tip_g:g} g",
            )
            lengths = np.linspace(0.5 * test.overhang, 1.25 * test.overhang, 12)
            for E, style in ((mod.E, "-"), (mod.lo, ":"), (mod.hi, ":")):
                w = [expected_sag(E, m.material, m.t, test.width, L, test.tip_g) for L in lengths]
                ax.plot(lengths, w, style, color=color, lw=1)
        ax.set_xlabel("free length (mm)")
        ax.set_ylabel("sag (mm)")
        ax.set_title(
            f"{mod.direction}: E = {mod.E:.4g} MPa ({mod.lo:.4g}-{mod.hi:.4g})", fontsize=9
        )
        ax.legend(fontsize=7)
    if fit.crease is not None:
        c = fit.crease
        ax = axes[-1]
        ct = m.crease
        assert ct is not None
        for load, ext in zip(c.loads, ct.extensions, strict=True):
            ax.plot([load * 1000] * len(ext), ext, "o", color="C0", ms=4)
        forces = np.linspace(0, max(c.loads) * 1.1, 20)
        ax.plot(forces * 1000, c.C * forces, "-", color="C0", label="fitted compliance")
        ax.set_xlabel("load (mN)")
        ax.set_ylabel("extension (mm)")
        k = "rigid" if c.k == float("inf") else f"{c.k:.3g} N mm/(rad mm)"
        ax.set_title(f"crease: k = {k}, angle {c.angle:.1f} deg", fontsize=9)
        ax.legend(fontsize=7)
    return fig
