"""The figure of a nonlinear ramp (:mod:`corrugate.fea.nonlinear`): ``nonlinear.png`` of
``corrugate verify DIR --nonlinear`` (docs/fea.md section 6).

Left: the load P (N) against the load point's travel (mm), the initial stiffness's line, the knee
and the peak marked. Right: P against the mode's amplitude at its largest node beyond the linear
response (mm, the imperfection's growth). On both, horizontal lines at the linear buckling load
(FE, dead load) and at the model's first-failure load (its capacity times the safety factor),
and, when the design has a safety factor, at the capacity itself. Needs matplotlib (the ``fea``
extra).
"""

from __future__ import annotations

from corrugate.core.errors import InputError
from corrugate.core.plotting import new_figure, png_bytes
from corrugate.fea.fixtures import get_fixture
from corrugate.fea.nonlinear import NonlinearResult

__all__ = ["nonlinear_png"]


def nonlinear_png(r: NonlinearResult) -> bytes:
    """The PNG file (bytes) of the ramp ``r`` (module docstring)."""
    try:
        import matplotlib  # noqa: F401  # the extra is installed
    except ImportError:
        raise InputError(
            "--nonlinear",
            "nonlinear.png",
            "matplotlib installed (pip install 'corrugate[fea]')",
            reason="cannot be drawn",
        ) from None
    fig = new_figure((9.0, 4.0))
    left, right = fig.subplots(1, 2, sharey=True)
    P = [0.0, *r.loads]
    d = [0.0, *r.travels]
    w = [0.0, *r.mode_amplitudes]
    left.plot(d, P, "o-", ms=3, color="tab:blue", label="FE, NLGEOM")
    if d[-1] > 0:
        left.plot([0.0, d[-1]], [0.0, r.k0 * d[-1]], ":", color="grey", label="linear (k0)")
    right.plot(w, P, "o-", ms=3, color="tab:blue", label="mode's amplitude")
    lines = [(r.buckling_load, "tab:red", "--", "linear buckling (FE, dead)")]
    c = r.case
    if c.model is not None:
        lines.append((c.model, "tab:green", "-.", "model's first failure"))
        if c.safety_factor:
            lines.append(
                (c.model / c.safety_factor, "tab:green", ":", f"capacity at SF {c.safety_factor:g}")
            )
    for ax in (left, right):
        for y, colour, style, label in lines:
            ax.axhline(y, color=colour, ls=style, lw=1, label=label)
        ax.grid(alpha=0.3)
    k, p = r.knee_load, r.peak_load
    if k is not None:
        i = P.index(k)
        left.plot([d[i]], [k], "s", color="tab:orange", ms=8, mfc="none", label=f"knee {k:.3g} N")
        right.plot([w[i]], [k], "s", color="tab:orange", ms=8, mfc="none")
    if p is not None:
        j = P.index(p)
        left.plot([d[j]], [p], "v", color="black", ms=7, label=f"peak {p:.3g} N")
    left.set_xlabel("load point travel (mm)")
    left.set_ylabel("load P (N)")
    right.set_xlabel("mode at its largest node, beyond the linear response (mm)")
    left.legend(fontsize=7, loc="lower right")
    end = {"target": "to its target", "timed out": "until its time-out"}.get(
        r.ended, "until ccx stopped converging"
    )
    fig.suptitle(
        f"{get_fixture(c.test).loading} along eta = {c.eta:g} deg, {r.mesh.label()}: NLGEOM ramp "
        f"{end}, "
        f"imperfection {r.amplitude:.3g} mm ({r.mode_at})",
        fontsize=9,
    )
    fig.tight_layout()
    return png_bytes(fig, dpi=110)
