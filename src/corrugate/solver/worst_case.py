"""The worst-case tolerances a certificate covers, as a value (docs/tolerances.md).

A :class:`WorstCase` holds the half-widths of the spec's ``[tolerances]``: the fold angle alpha
(deg) and the facet width W (mm) of every layer, each on its own, and the sheet's thickness t and
Young's modulus E (relative, 0.05 = 5 %). The solver bounds every directional quantity (a
stiffness, a load case's P / delta or capacity, a buckling load, the panel's length) over the
box of parts within them around each design (:mod:`~.tolerance_box`), so a certified design
meets every such bound at every corner. :data:`NOMINAL` (all zero, ``tolerances = "none"``) is
the nominal certificate of the paper's reproduction. ``[robust]`` (:mod:`~.tolerance`) is the
probabilistic alternative (one-sigma errors, Monte Carlo) and is not this.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import TYPE_CHECKING

if TYPE_CHECKING:
    from corrugate.spec.schema import TolerancesSpec

__all__ = ["NOMINAL", "WorstCase"]


@dataclass(frozen=True, slots=True)
class WorstCase:
    """Worst-case half-widths: ``alpha`` (deg), ``W`` (mm), ``t`` and ``E`` relative."""

    alpha: float = 0.0
    W: float = 0.0
    t: float = 0.0
    E: float = 0.0

    @classmethod
    def of(cls, spec: TolerancesSpec) -> WorstCase:
        """The half-widths of a spec's ``[tolerances]``."""
        return cls(float(spec.alpha), float(spec.W), float(spec.t), float(spec.E))

    @property
    def nominal(self) -> bool:
        """Whether every half-width is 0 (the nominal certificate)."""
        return not (self.alpha or self.W or self.t or self.E)

    @property
    def words(self) -> str:
        """E.g. ``+-3 deg, +-0.1 mm, +-5 % thickness, +-10 % E``; ``nominal`` when all zero."""
        return "nominal" if self.nominal else self._words(f"+-{100 * self.E:g} % E")

    def _words(self, E_words: str) -> str:
        """The half-widths of alpha, W and t in words, then ``E_words``."""
        return f"+-{self.alpha:g} deg, +-{self.W:g} mm, +-{100 * self.t:g} % thickness, {E_words}"

    @property
    def sentence(self) -> str:
        """What the certificate covers, in words for the answer."""
        if self.nominal:
            return "for the nominal part"
        return f"for every part within {self.words}"

    def sentence_for(self, E_measured: bool) -> str:
        """:attr:`sentence` for sheets whose E is measured (``E_measured``: every candidate a
        calibrated material with a measured E, whose interval replaces the tolerance's +-dE,
        docs/calibration.md 9): the E half-width is then not named."""
        if self.nominal or not E_measured:
            return self.sentence
        return f"for every part within {self._words('E within its calibrated interval')}"

    def as_dict(self, E_measured: bool = False) -> dict[str, object]:
        """The JSON of the answer and design.json (units in the keys); ``covers`` as
        :meth:`sentence_for` says it."""
        return {
            "nominal": self.nominal,
            "alpha_deg": self.alpha,
            "W_mm": self.W,
            "t_rel": self.t,
            "E_rel": self.E,
            "covers": self.sentence_for(E_measured),
        }


#: No tolerances: the nominal certificate (``tolerances = "none"``).
NOMINAL = WorstCase()
