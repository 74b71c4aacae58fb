"""Plots of a validation sweep like the paper's Fig. 7: model line, +-20 % band, FE points.

One column per swept parameter (W, n, alpha), one row per quantity (K and D at eta = 0). The
default model (``refined``) is the solid line with its +-20 % band (the paper's acceptance band);
``paper`` and ``xia`` are dashed lines; the FE results are points (for D: 3-point bending as the
paper tested, and the pure bending stiffness of the 4-point diagnostic). Needs matplotlib (the
``fea`` extra).
"""

from __future__ import annotations

from collections.abc import Sequence
from pathlib import Path

import numpy as np

from corrugate.analysis.evaluate import analyze
from corrugate.core.errors import InputError
from corrugate.core.plotting import new_figure
from corrugate.fea.validation import CaseResult
from corrugate.geometry.layer import Assembly, Layer
from corrugate.mechanics.moduli import DEFAULT_MODEL, MODELS

__all__ = ["plot_sweep"]

_QUANTITIES = (("K_N_per_mm", "K (N/mm)"), ("D_Nmm", "D (N mm)"))
_PURE = "D4_Nmm"


def _model_line(
    results: Sequence[CaseResult], group: str, eta: float
) -> tuple[np.ndarray, dict[str, dict[str, np.ndarray]]]:
    base = results[0].case.assembly.layer1
    lo = min(r.case.value for r in results)
    hi = max(r.case.value for r in results)
    xs = np.arange(lo, hi + 1) if group == "n" else np.linspace(lo, hi, 61)
    out: dict[str, dict[str, list[float]]] = {m: {"K": [], "D": []} for m in MODELS}
    for x in xs:
        W, n, alpha = base.W, base.n, base.alpha_deg
        if group == "W":
            W = float(x)
        elif group == "n":
            n = int(x)
        else:
            alpha = float(x)
        a = Assembly.identical(Layer(W, n, alpha, base.material, base.t))
        for m in MODELS:
            d = analyze(a, m, [eta]).stiffness[0]
            out[m]["K"].append(d.K)
            out[m]["D"].append(d.D)
    return xs, {m: {k: np.asarray(v) for k, v in q.items()} for m, q in out.items()}


def plot_sweep(results: Sequence[CaseResult], path: Path, eta: float = 0.0) -> Path:
    """Write the figure of a sweep to ``path`` (format from its suffix) and return the path."""
    try:
        import matplotlib  # noqa: F401  # the extra is installed
    except ImportError:
        raise InputError(
            "plot",
            str(path),
            "matplotlib installed (pip install 'corrugate[fea]')",
            reason="cannot be written",
        ) from None
    groups = [g for g in ("W", "n", "alpha") if any(r.case.group == g for r in results)]
    fig = new_figure((4.2 * len(groups), 6.4))
    axes = fig.subplots(2, len(groups), squeeze=False)
    e = f"{eta:g}"
    for col, g in enumerate(groups):
        rs = [r for r in results if r.case.group == g]
        xs, lines = _model_line(rs, g, eta)
        for row, (key, label) in enumerate(_QUANTITIES):
            ax = axes[row][col]
            q = key[0]
            y = lines[DEFAULT_MODEL][q]
            ax.fill_between(
                xs, 0.8 * y, 1.2 * y, color="tab:blue", alpha=0.15, label=f"{DEFAULT_MODEL} +-20 %"
            )
            ax.plot(xs, y, color="tab:blue", label=DEFAULT_MODEL)
            for m, style in (("xia", "--"), ("paper", ":")):
                ax.plot(xs, lines[m][q], style, color="grey", label=m)
            ok = [r for r in rs if not r.error]
            ax.plot(
                [r.case.value for r in ok],
                [r.fe[f"{key}@{e}"] for r in ok],
                "o",
                color="tab:red",
                label="FE 3-point bending" if key == "D_Nmm" else "FE (CalculiX)",
            )
            pure = [r for r in ok if f"{_PURE}@{e}" in r.fe]
            if key == "D_Nmm" and pure:
                ax.plot(
                    [r.case.value for r in pure],
                    [r.fe[f"{_PURE}@{e}"] for r in pure],
                    "^",
                    mfc="none",
                    color="tab:green",
                    label="FE pure bending (4-point)",
                )
            ax.set_xlabel(rs[0].case.parameter)
            ax.set_ylabel(f"{label}, eta = {e} deg")
            ax.grid(alpha=0.3)
            if col == 0:
                ax.legend(fontsize=7)
    fig.tight_layout()
    path.parent.mkdir(parents=True, exist_ok=True)
    fig.savefig(path, dpi=130)
    return path
