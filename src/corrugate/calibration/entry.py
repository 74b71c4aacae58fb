"""A fit written as a material of the user's own (docs/calibration.md section 6).

The entry extends the library material the sheet is (its nu, density, strength, creep data) with
the fitted E, the thickness measured at, and a ``[ID.calibration]`` table: the date, the coupons,
the number of readings and every fitted value with its 90 % interval. One E is written, the
smaller of the directions fitted: the models take the sheet as isotropic, and the smaller E is
the safe side for every stiffness and buckling bound.
"""

from __future__ import annotations

import datetime
import math
from typing import Any

from corrugate.calibration.fit import Fit

__all__ = ["material_entry", "summary"]


def _fmt(x: float, unit: str) -> str:
    return "inf" if math.isinf(x) else f"{x:.4g} {unit}"


def material_entry(fit: Fit, today: datetime.date | None = None) -> dict[str, Any]:
    """The materials-file table of ``fit`` (see the module docstring); needs a modulus fit."""
    m = fit.measurements
    date = m.date or (today or datetime.date.today()).isoformat()
    cal: dict[str, Any] = {
        "date": date,
        "coupons": sorted({f.coupon for f in m.flat} | ({m.crease.coupon} if m.crease else set())),
        "measurements": m.count,
        "thickness": f"{m.t:g} mm",
        "interval": "90 % (least squares, parametric bootstrap)",
    }
    for mod in fit.moduli:
        cal[f"E_{mod.direction}"] = _fmt(mod.E, "MPa")
        cal[f"E_{mod.direction}_90"] = [_fmt(mod.lo, "MPa"), _fmt(mod.hi, "MPa")]
        cal[f"E_{mod.direction}_n"] = mod.n
    if fit.crease is not None:
        c = fit.crease
        cal["crease_stiffness"] = _fmt(c.k, "N*mm/(rad*mm)")
        cal["crease_stiffness_90"] = [_fmt(c.k_lo, "N*mm/(rad*mm)"), _fmt(c.k_hi, "N*mm/(rad*mm)")]
        cal["folded_angle"] = f"{c.angle:.1f} deg"
        cal["folded_angle_90"] = [f"{c.angle_lo:.1f} deg", f"{c.angle_hi:.1f} deg"]
        cal["springback"] = f"{c.springback:+.1f} deg"
    E = min(mod.E for mod in fit.moduli) if fit.moduli else m.material.E
    which = ", ".join(f"{mod.direction} {mod.E:.4g} MPa" for mod in fit.moduli) or "not measured"
    return {
        "extends": m.material.id,
        "name": f"{m.material.name}, calibrated {date}",
        "E": f"{E:.4g} MPa",
        "thicknesses": [f"{m.t:g} mm"],
        "default_thickness": f"{m.t:g} mm",
        "source": (
            f"E calibrated on the user's sheet {date} by corrugate calibrate fit "
            f"({m.count} readings, coupons {', '.join(cal['coupons'])}; E {which}, the smaller "
            f"taken); nu, density and strength from the library's {m.material.id}"
        ),
        "calibration": cal,
    }


def summary(fit: Fit) -> list[str]:
    """The fit as lines of text (what ``corrugate calibrate fit`` prints)."""
    m = fit.measurements
    lines = [f"sheet {m.material.id} at {m.t:g} mm, ruler +-{m.ruler:g} mm, {m.count} readings"]
    for mod in fit.moduli:
        lines.append(
            f"E {mod.direction:<6} = {mod.E:7.4g} MPa   90 % interval {mod.lo:.4g} - {mod.hi:.4g} MPa"
            f"   ({mod.n} sags; library {m.material.E:g} MPa)"
        )
        for test in mod.tests:
            i0 = sum(len(t.sags) for t in mod.tests[: mod.tests.index(test)])
            pred = mod.predicted[i0]
            res = mod.residuals[i0 : i0 + len(test.sags)]
            lines.append(
                f"    {test.field}: {test.coupon} free {test.overhang:g} mm, tip {test.tip_g:g} g: model "
                f"{pred:.1f} mm, residuals " + " ".join(f"{r:+.1f}" for r in res) + " mm"
            )
    c = fit.crease
    if c is not None:
        k = (
            "rigid (stiffer than the readings tell)"
            if math.isinf(c.k)
            else f"{c.k:.3g} N*mm/(rad*mm)"
        )
        lo = "inf" if math.isinf(c.k_lo) else f"{c.k_lo:.3g}"
        hi = "inf" if math.isinf(c.k_hi) else f"{c.k_hi:.3g}"
        lines.append(f"crease stiffness k = {k}   90 % interval {lo} - {hi} (at E = {c.E:.4g} MPa)")
        lines.append(
            f"folded angle {c.angle:.1f} deg (90 %: {c.angle_lo:.1f} - {c.angle_hi:.1f}), springback "
            f"{c.springback:+.1f} deg from the angle folded to"
        )
        for F, e in zip(c.loads, c.extensions, strict=True):
            lines.append(
                f"    load {F * 1000:.0f} mN: extension {e:.1f} mm read, {c.C * F:.1f} mm fitted"
            )
    return lines
