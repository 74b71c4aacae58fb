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


#: The discs of docs/validation/wheel_fe.csv whose series at 0 and 45 deg judge settles, written
#: out (docs/load_cases.md 9): what :func:`settled_wheel_rows` must find.
SETTLED_WHEELS = {
    "d-dl175-n7-w8-a120",
    "d-example",
    "d-pp-n7-w9-a145",
    "d-pp-w11.5-a150",
    "d-pp-w12-a120",
    "d-pp-w9.5-a140",
}


def settled_wheel_rows(rows: list[dict[str, str]]) -> list[dict[str, str]]:
    """The rows (of wheel_fe.csv, its failed runs left out) of the discs whose series at every
    direction of the wheel factor (eta 0 and 45 deg) the project's rule settles:
    corrugate.fea.extrapolate.judge against c(eta) x the model's K, as `corrugate verify` judges
    one (four meshes each twice the one before, monotone, shrinking steps, two Richardson
    estimates within a quarter of the margin)."""
    from corrugate.fea.extrapolate import judge
    from corrugate.mechanics.wheel import WHEEL_FACTOR

    ran = [r for r in rows if r["K_FE"] != "failed"]
    series: dict[tuple[str, float], dict[int, float]] = {}
    model: dict[tuple[str, float], float] = {}
    for r in ran:
        key = (r["design"], float(r["eta_deg"]))
        series.setdefault(key, {})[int(r["along"])] = float(r["K_FE"])
        model[key] = float(r["K_model"])
    settled = {
        d
        for d, _ in series
        if all(
            (d, eta) in series and judge(series[d, eta], c * model[d, eta], "min").verdict != "open"
            for eta, c in WHEEL_FACTOR.items()
        )
    }
    return [r for r in ran if r["design"] in settled]
