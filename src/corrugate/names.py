"""The names of the moduli variants of :mod:`corrugate.mechanics.moduli`, importable without numpy.

The command line declares its ``--model`` options from these names, so that ``corrugate --help``
does not load numpy; :mod:`corrugate.mechanics.moduli` builds its table of variants under the same names (a
test checks that the two agree).
"""

from __future__ import annotations

__all__ = ["DEFAULT_MODEL", "MODEL_NAMES"]

#: Every moduli variant, in the order tables list them.
MODEL_NAMES: tuple[str, ...] = ("paper", "xia", "refined")

#: The variant used unless one is asked for: it agrees with the unit-cell FE (docs/fea.md 1.3).
DEFAULT_MODEL = "refined"
