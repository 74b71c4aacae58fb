"""Cutter guidance per material: where to start the blade, the pressure or the laser, the
perforation and which fold operation suits the sheet (lengths in mm).

One :class:`Guidance` row per material of the library (``corrugate materials``), each with its
``source``. Only one rule here comes from a machine maker: Silhouette America's support article
"Performing a test cut: how to find optimal settings"
(https://silhouetteamerica.freshdesk.com/support/solutions/articles/35000206256) says the blade
setting exposes the blade in 0.1 mm steps and that a 0.3 mm card needs a setting of at least 3,
i.e. a blade number of at least t / 0.1 mm (:func:`silhouette_blade`). No maker's page giving
settings for these sheets was found (Cricut Design Space's and Silhouette Studio's material lists
are inside the programs), so every pressure, power and perforation value below is an **estimate**
and says so: a starting point for the test cut on a scrap that docs/fabrication.md asks for.

``perforation`` is the cut and gap (mm) a perforated crease of that sheet starts from: a longer
gap leaves more material, a stiffer and stronger hinge; a shorter one folds more easily. The
``valley`` operation is what a valley crease is made with when the machine can do it (see
:mod:`corrugate.export.operations`); ``laser`` is the laser class and any hazard.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from types import MappingProxyType

__all__ = [
    "ESTIMATE",
    "GENERIC",
    "GUIDANCE",
    "SILHOUETTE_BLADE_SOURCE",
    "Guidance",
    "get_guidance",
    "silhouette_blade",
]

#: The source of the blade-number rule (mm of blade per setting step).
SILHOUETTE_BLADE_SOURCE = (
    "Silhouette America support, 'Performing a test cut: how to find optimal settings' "
    "(silhouetteamerica.freshdesk.com, article 35000206256): blades adjust in 0.1 mm steps; "
    "0.3 mm cardstock needs a blade setting of at least 3"
)
#: What a row says for a value no source was found for.
ESTIMATE = "estimate"
_STEP_MM = 0.1


def silhouette_blade(t: float) -> int:
    """The smallest Silhouette blade setting that exposes at least the sheet thickness ``t`` (mm):
    ceil(t / 0.1 mm), at least 1 (:data:`SILHOUETTE_BLADE_SOURCE`)."""
    return max(1, math.ceil(t / _STEP_MM - 1e-9))


@dataclass(frozen=True, slots=True)
class Guidance:
    """Where to start cutting one sheet: ``material`` (library id), the Silhouette ``force``
    class and Cricut ``cricut`` material setting to start from, the ``laser`` class, the
    ``perforation`` (cut, gap) in mm, the ``valley`` operation that suits it, ``notes`` and the
    ``source`` of the row."""

    material: str
    force: str
    cricut: str
    laser: str
    perforation: tuple[float, float]
    valley: str
    notes: str
    source: str

    def blade(self, t: float) -> int:
        """The Silhouette blade setting for a through cut of a ``t`` mm sheet
        (:func:`silhouette_blade`)."""
        return silhouette_blade(t)


_FILM = "estimate (no maker's setting page found for this film)"
_SOURCE = f"{_FILM}; blade number: {SILHOUETTE_BLADE_SOURCE}"


def _row(
    material: str,
    force: str,
    cricut: str,
    laser: str,
    perforation: tuple[float, float],
    valley: str,
    notes: str,
) -> Guidance:
    return Guidance(material, force, cricut, laser, perforation, valley, notes, _SOURCE)


#: The rows, by material id (every material of ``src/corrugate/data/materials.toml``).
GUIDANCE: MappingProxyType[str, Guidance] = MappingProxyType(
    {
        g.material: g
        for g in (
            _row(
                "dura-lar",
                "estimate: high force (dense film), 1-2 passes",
                "estimate: 'Acetate' or a custom setting",
                "estimate: CO2 cuts PET film with melted edges; ventilate",
                (1.0, 0.5),
                "cut-score",
                "a cut-score is the blade at about half the through-cut force: it must not go "
                "through; test it",
            ),
            _row(
                "mylar",
                "estimate: high force, 1-2 passes",
                "estimate: 'Acetate' or a custom setting",
                "estimate: CO2 cuts PET film with melted edges; ventilate",
                (1.0, 0.5),
                "cut-score",
                "as Dura-Lar",
            ),
            _row(
                "polypropylene",
                "estimate: high force, 2 passes (tough, drags)",
                "estimate: a custom setting, 'More' pressure",
                "estimate: CO2 cuts PP but melts and may flame; never unattended",
                (1.5, 0.5),
                "cut-score",
                "PP makes a living hinge: a shallow cut-score folds without cracking",
            ),
            _row(
                "polycarbonate",
                "estimate: high force, 2-3 passes",
                "estimate: a custom setting, 'More' pressure",
                "estimate: CO2 cuts PC poorly (chars, yellow smoke); avoid",
                (1.5, 1.0),
                "cut-score",
                "PC whitens at a sharp fold; a perforation with longer gaps holds better",
            ),
            _row(
                "kapton",
                "estimate: medium force, 1 pass (thin, tough)",
                "estimate: a custom setting",
                "estimate: a CO2 laser chars polyimide; UV lasers cut it",
                (1.0, 0.5),
                "cut-score",
                "very thin gauges fold well enough without any crease operation",
            ),
            _row(
                "petg",
                "estimate: high force, 2-3 passes (0.5 mm: deep-cut blade)",
                "estimate: 'Knife Blade' for 0.5 mm and thicker",
                "estimate: CO2 cuts PETG with melted edges; ventilate",
                (2.0, 1.0),
                "cut-score",
                "thicker sheet: a cut-score of about half the thickness",
            ),
            _row(
                "fr4",
                "not with a drag blade (glass fibre)",
                "not with a drag blade (glass fibre)",
                "do not laser: glass fibre and brominated epoxy fumes",
                (2.0, 1.0),
                "perforate",
                "route, shear or etch FR4; a perforated crease cracks the glass, not the resin",
            ),
            _row(
                "cardstock",
                "estimate: medium force, 1 pass",
                "estimate: 'Heavy Cardstock' (250-300 g/m^2)",
                "estimate: CO2 cuts card at low power, high speed; watch for flame",
                (2.0, 1.0),
                "score",
                "card folds best on a score (a pressed line); a cut-score also works on the "
                "outside of the fold",
            ),
            _row(
                "aluminium-shim",
                "estimate: thin foil only (0.05 mm), highest force, several passes",
                "estimate: 'Knife Blade' or 'Metal' settings with the Maker's engraving tool",
                "estimate: a fibre laser (a CO2 laser reflects off aluminium)",
                (2.0, 1.0),
                "score",
                "metal cracks at a cut crease: score (press) it, never cut-score",
            ),
            _row(
                "stainless-shim",
                "not with a drag blade",
                "not with a drag blade",
                "estimate: a fibre laser",
                (2.0, 1.0),
                "score",
                "shear or etch stainless; fold over a hard edge",
            ),
            _row(
                "pvc",
                "estimate: high force, 1-2 passes",
                "estimate: a custom setting",
                "do not laser: PVC gives off hydrogen chloride",
                (1.5, 0.5),
                "cut-score",
                "rigid PVC whitens at a sharp fold",
            ),
            _row(
                "acetate",
                "estimate: medium-high force, 1-2 passes",
                "estimate: 'Acetate'",
                "estimate: CO2 cuts cellulose acetate; ventilate",
                (1.0, 0.5),
                "cut-score",
                "acetate cracks if cut too deep: keep the cut-score shallow",
            ),
        )
    }
)

#: The row for a material that is not in the library (an inline material).
GENERIC = Guidance(
    "inline",
    "estimate: start from the test cut",
    "estimate: a custom setting",
    "estimate: check the sheet's datasheet before lasering it",
    (1.0, 0.5),
    "cut-score",
    "an inline material: no guidance beyond the test cut",
    ESTIMATE,
)


def get_guidance(material_id: str) -> Guidance:
    """The guidance row of ``material_id`` (a library id), or :data:`GENERIC` for another."""
    return GUIDANCE.get(material_id.strip().lower(), GENERIC)
