"""The words of every quantity a behaviour gives (issue 36 item 5): the label the answer, the
diagnosis and the web page print, composed of the kind's name, its direction, the support, the
test, the span, the duration and closing words, reads as English.

Independent check: the glue a composition makes when a part lacks its space ("safety
factor(0 deg)", "(0 deg)as a cantilever", two spaces, ")(") is looked for with patterns, over
every kind, support and load case of the registries, not over a list of expected strings.
"""

from __future__ import annotations

import re

from corrugate.mechanics.behaviours import load_cases, supports
from corrugate.solver.quantity import STIFFNESS, Quantity

#: A lowercase word glued to "(" (a direction belongs on a symbol: EI(0 deg), P/delta(0 deg)).
WORD_PAREN = re.compile(r"(?<!P/)\b[a-z]{2,}\(")
#: ")" glued to the next word, or to the next "(".
PAREN_WORD = re.compile(r"\)[A-Za-z(]")


def every_quantity() -> list[Quantity]:
    qs: list[Quantity] = []
    for s in supports():
        for eta in (0.0, 45.0):
            qs += [Quantity(k, eta, s.name) for k in STIFFNESS]
            for t in load_cases():
                for kind in t.units:
                    for span in (None, 150.0):
                        qs.append(Quantity(kind, eta, s.name, t.name, span))
                        qs.append(Quantity(kind, eta, s.name, t.name, span, duration=168.0))
    qs += [Quantity("Pb", 90.0), Quantity("length", 0.0)]
    qs += [Quantity(k) for k in ("Lx", "Ly", "thickness", "flat", "mass", "t_over_W")]
    return qs


def test_every_behaviours_label_has_no_glue() -> None:
    seen = every_quantity()
    assert len(seen) > 100
    for q in seen:
        text = q.description
        assert not WORD_PAREN.search(text), text
        assert not PAREN_WORD.search(text), text
        assert "  " not in text and text == text.strip(), repr(text)


def test_a_load_capacity_reads_in_order() -> None:
    """The case of the issue: 'load capacity at the safety factor(0 deg) as a cantilever'."""
    q = Quantity("Pmax", 0.0, "free", "cantilever", 150.0)
    assert q.description == (
        "load capacity Pmax(0 deg) as a cantilever over 150 mm at the safety factor"
    )
    assert "safety factor" in Quantity("Pmax", 90.0, "frame", "three-point").description
