"""Designs of the FE tables under docs/validation/ by their names (tests/ is on the path, as for
plan_readers): the tests that check a model against those rows rebuild each design from its
name."""

from __future__ import annotations

import re

from corrugate.geometry.layer import Assembly, Layer
from corrugate.materials.library import get_material


def identical_square(design: str) -> Assembly | None:
    """The square of identical layers a design name of docs/validation/load_cases_fe.csv names
    ('W 10, n 10, alpha 40', 'case study W 8, n 8, alpha 84', 'thin Dura-Lar 0.05: W 10, n 7,
    alpha 50', 'polypropylene 0.3: W 8, n 6, alpha 120'; Dura-Lar 0.125 mm unless the sheet is
    named before the colon); None for differing layers or a rectangle."""
    if "layer" in design or "rectangle" in design or "chassis" in design:
        return None
    head, _, tail = design.rpartition(":")
    m = re.search(r"W (\d+(?:\.\d+)?), n (\d+), alpha (\d+(?:\.\d+)?)", tail)
    assert m is not None, design
    sheet = re.search(r"(Dura-Lar|polypropylene) (\d+(?:\.\d+)?)", head)
    material = get_material(
        "polypropylene" if sheet and sheet[1] == "polypropylene" else "dura-lar"
    )
    t = float(sheet[2]) if sheet else 0.125
    layer = Layer(W=float(m[1]), n=int(m[2]), alpha_deg=float(m[3]), material=material, t=t)
    return Assembly.identical(layer)
