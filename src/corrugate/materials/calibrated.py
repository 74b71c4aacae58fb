"""What a calibrated material carries beyond its nominal values: the measured intervals.

``corrugate calibrate fit --save`` writes a ``[ID.calibration]`` table beside the material's E
(docs/calibration.md section 6): the date, the coupons, the number of readings and each fitted
value with its 90 % interval. :func:`calibration_of` reads it into a :class:`Calibration`, the
value the certificate bounds over (docs/calibration.md section 9): E over its interval (in place
of the default +-10 % E tolerance), the crease stiffness k (N mm/(rad mm)) over its interval,
and the fold angle shifted by the springback (deg) over its interval. Units: E in MPa, k in
N mm/(rad mm) (inf: rigid), angles in deg.
"""

from __future__ import annotations

import math
from collections.abc import Mapping
from dataclasses import dataclass
from typing import Any

from corrugate.core.errors import InputError
from corrugate.core.units import parse_quantity

__all__ = ["Calibration", "calibration_of", "parse_crease_stiffness"]


@dataclass(frozen=True, slots=True)
class Calibration:
    """A material's measured intervals (module docstring): ``E_lo``, ``E_hi`` (MPa) the 90 %
    interval of the E the material takes; ``k_lo``, ``k_hi`` (N mm/(rad mm), inf: rigid) the
    crease stiffness's; ``springback`` (deg) the folded angle less the angle folded to, and its
    interval ``springback_lo``, ``springback_hi`` (0 when not measured); ``date``, ``measurements``
    (readings) and ``coupons``: where it comes from."""

    date: str
    measurements: int
    coupons: tuple[str, ...]
    E_lo: float
    E_hi: float
    k_lo: float = math.inf
    k_hi: float = math.inf
    springback: float = 0.0
    springback_lo: float = 0.0
    springback_hi: float = 0.0
    E_measured: bool = True

    @classmethod
    def stated(cls, E: float, k: float, springback: float) -> Calibration:
        """The crease stiffness ``k`` (N mm/(rad mm), inf: rigid) and ``springback`` (deg) a
        spec's inline material states, without intervals and without a measured E (E keeps
        the ``[tolerances]`` E: ``E_measured`` False; docs/calibration.md 9)."""
        cal = cls(
            "stated in the spec", 0, (), E, E, k, k, springback, springback, springback, False
        )
        cal.check("material")
        return cal

    def words(self, material_id: str) -> str:
        """What a certificate covers of it: ``calibrated E 2738-2900 MPa, crease stiffness
        0.0949-0.103 N*mm/(rad*mm), springback -6.9 to -5.5 deg, from my-dura-lar, 2026-12-06,
        40 measurements`` (the crease and springback when measured)."""
        parts = [f"calibrated E {self.E_lo:.4g}-{self.E_hi:.4g} MPa"] if self.E_measured else []
        if not math.isinf(self.k_lo):
            hi = "inf" if math.isinf(self.k_hi) else f"{self.k_hi:.3g}"
            k = f"{self.k_lo:.3g}" if not self.E_measured else f"{self.k_lo:.3g}-{hi}"
            parts.append(f"crease stiffness {k} N*mm/(rad*mm)")
        if not self.E_measured and self.springback:  # stated: one value, no interval
            parts.append(f"springback {self.springback:+.1f} deg")
        elif self.springback_lo or self.springback_hi:
            parts.append(f"springback {self.springback_lo:+.1f} to {self.springback_hi:+.1f} deg")
        return ", ".join(parts) + f", from {self.source(material_id)}"

    def source(self, material_id: str) -> str:
        """``my-dura-lar, 2026-12-06, 40 measurements``: where the intervals come from
        (``custom, stated in the spec`` for a :meth:`stated` one)."""
        if not self.E_measured and not self.measurements:
            return f"{material_id}, {self.date}"
        return f"{material_id}, {self.date}, {self.measurements} measurements"

    def as_dict(self) -> dict[str, Any]:
        """JSON-ready (units in the keys; inf as None)."""

        def fin(x: float) -> float | None:
            return None if math.isinf(x) else x

        return {
            "date": self.date,
            "measurements": self.measurements,
            "coupons": list(self.coupons),
            "E_MPa_90": [self.E_lo, self.E_hi],
            "crease_stiffness_90": [fin(self.k_lo), fin(self.k_hi)],
            "springback_deg": self.springback,
            "springback_deg_90": [self.springback_lo, self.springback_hi],
            **({} if self.E_measured else {"E_measured": False}),
        }

    @classmethod
    def from_dict(cls, d: Any, field: str = "material.calibration") -> Calibration:
        """The value :meth:`as_dict` wrote (design.json); :class:`InputError` naming ``field``."""
        try:
            k_lo, k_hi = (math.inf if v is None else float(v) for v in d["crease_stiffness_90"])
            cal = cls(
                str(d["date"]),
                int(d["measurements"]),
                tuple(str(c) for c in d["coupons"]),
                float(d["E_MPa_90"][0]),
                float(d["E_MPa_90"][1]),
                k_lo,
                k_hi,
                float(d["springback_deg"]),
                float(d["springback_deg_90"][0]),
                float(d["springback_deg_90"][1]),
                {True: True, False: False}[d.get("E_measured", True)],
            )
        except (TypeError, ValueError, KeyError, IndexError):
            raise InputError(field, repr(d)[:40], "the calibration design.json wrote") from None
        cal.check(field)
        return cal

    def check(self, field: str) -> None:
        """:class:`InputError` naming ``field`` unless 0 < E_lo <= E_hi, 0 < k_lo <= k_hi and
        springback_lo <= springback <= springback_hi, every one within +-30 deg."""
        ok = (
            0.0 < self.E_lo <= self.E_hi < math.inf
            and 0.0 < self.k_lo <= self.k_hi
            and self.springback_lo <= self.springback <= self.springback_hi
            and self.springback_lo >= -30.0
            and self.springback_hi <= 30.0
        )
        if not ok:
            raise InputError(
                field,
                f"E {self.E_lo:g}-{self.E_hi:g} MPa, k {self.k_lo:g}-{self.k_hi:g}, springback "
                f"{self.springback_lo:g}-{self.springback_hi:g} deg",
                "0 < E_lo <= E_hi, 0 < k_lo <= k_hi, -30 <= springback_lo <= springback <= "
                "springback_hi <= 30 deg",
            )


def parse_crease_stiffness(value: object, field: str) -> float:
    """A crease stiffness k (N mm/(rad mm), per unit crease length) from a materials file:
    ``"0.1 N*mm/(rad*mm)"``, a plain number, or ``"inf"`` (rigid); :class:`InputError` naming
    ``field`` unless 0 < k."""
    if isinstance(value, str) and value.strip().lower() in ("inf", "rigid"):
        return math.inf
    k = parse_quantity(value, "N", field)
    if not (k > 0.0):
        raise InputError(field, f"{k:g}", "k > 0 N*mm/(rad*mm), or inf for a rigid crease")
    return k


def _pair(value: object, unit: str, field: str) -> tuple[float, float]:
    if not isinstance(value, list | tuple) or len(value) != 2:
        raise InputError(field, repr(value)[:40], "[low, high]")
    if unit == "N":
        lo, hi = (parse_crease_stiffness(v, field) for v in value)
    else:
        lo, hi = (parse_quantity(v, unit, field) for v in value)
    return lo, hi


def calibration_of(table: Mapping[str, Any], E: float, where: str) -> tuple[Calibration, float]:
    """The :class:`Calibration` of a material's ``[ID.calibration]`` table (``where``: its name
    in messages, ``file [ID].calibration.``) and the crease stiffness k it measured (inf when it
    has none). E's interval is that of the direction whose fitted E is the material's ``E``
    (MPa, the smaller one: docs/calibration.md section 6), else the widest scaled to E."""
    moduli: list[tuple[float, float, float]] = []
    for key, value in table.items():
        if key.startswith("E_") and not key.endswith(("_90", "_n")):
            fitted = parse_quantity(value, "MPa", where + key)
            lo, hi = _pair(table.get(f"{key}_90"), "MPa", where + key + "_90")
            moduli.append((fitted, lo, hi))
    if moduli:
        fitted, lo, hi = min(moduli, key=lambda m: abs(m[0] - E))
        if abs(fitted - E) > 1e-3 * E:  # E written by hand: the interval's relative width
            lo, hi = E * lo / fitted, E * hi / fitted
    else:
        lo = hi = E
    k = math.inf
    k_lo = k_hi = math.inf
    if "crease_stiffness" in table:
        k = parse_crease_stiffness(table["crease_stiffness"], where + "crease_stiffness")
        k_lo, k_hi = k, k
        if "crease_stiffness_90" in table:
            k_lo, k_hi = _pair(table["crease_stiffness_90"], "N", where + "crease_stiffness_90")
    sb = sb_lo = sb_hi = 0.0
    if "springback" in table:
        sb = parse_quantity(table["springback"], "deg", where + "springback")
        sb_lo = sb_hi = sb
        if "folded_angle" in table and "folded_angle_90" in table:
            angle = parse_quantity(table["folded_angle"], "deg", where + "folded_angle")
            a_lo, a_hi = _pair(table["folded_angle_90"], "deg", where + "folded_angle_90")
            sb_lo, sb_hi = sb + (a_lo - angle), sb + (a_hi - angle)
    count = table.get("measurements", 0)
    cal = Calibration(
        str(table.get("date", "undated")),
        int(count) if isinstance(count, int) and not isinstance(count, bool) else 0,
        tuple(str(c) for c in table.get("coupons", [])),
        lo,
        hi,
        k_lo,
        k_hi,
        sb,
        min(sb_lo, sb),
        max(sb_hi, sb),
    )
    cal.check(where.rstrip("."))
    return cal, k
