"""A load held for a ``duration`` in a spec: what is refused, in one line naming the TOML path
(docs/load_cases.md section 11)."""

from __future__ import annotations

import copy
from typing import Any

import pytest

from corrugate.solver import Problem
from corrugate.spec.schema import MissingUnitError, SpecError, parse_spec

BASE: dict[str, Any] = {
    "material": {"name": "polycarbonate", "thickness": "0.25 mm"},
    "layout": {"shape": "square"},
    "constraints": {
        "side": {"min": "100 mm", "max": "120 mm"},
        "deflection": [{"test": "three-point", "load": "10 N", "max": "1 mm"}],
    },
}


def held(duration: Any, material: dict[str, Any] | None = None) -> dict[str, Any]:
    d = copy.deepcopy(BASE)
    d["constraints"]["deflection"][0]["duration"] = duration
    if material is not None:
        d["material"] = material
    return d


def problem(d: dict[str, Any]) -> Problem:
    return Problem.from_spec(parse_spec(d))


@pytest.mark.parametrize(("text", "hours"), [("1 week", 168.0), ("2 day", 48.0), ("90 min", 1.5)])
def test_a_duration_is_read_in_hours(text: str, hours: float) -> None:
    cons = {c.name: c.quantity for c in problem(held(text)).constraints}
    q = cons["constraints.deflection[0].max"]
    assert q.duration == pytest.approx(hours)
    assert q.key == f"k3pt@0/t={hours:.12g}h"
    # the load must be held as long: the capacity bound it adds carries the same duration
    held_q = cons["constraints.deflection[0].load (held at the safety factor)"]
    assert held_q.duration == pytest.approx(hours)
    assert held_q.key == f"Pmax3pt@0/t={hours:.12g}h"


@pytest.mark.parametrize("bad", ["-1 h", "0 h", "-2 weeks"])
def test_a_negative_or_zero_duration_is_refused(bad: str) -> None:
    with pytest.raises(SpecError) as info:
        parse_spec(held(bad))
    assert info.value.field == "constraints.deflection[0].duration"
    assert "is out of range: allowed > 0 h" in str(info.value)


def test_a_plain_number_needs_its_unit() -> None:
    with pytest.raises(MissingUnitError) as info:
        parse_spec(held(168))
    assert str(info.value) == (
        'constraints.deflection[0].duration = 168 has no unit: write it with one, e.g. "168 h" '
        '(or "168 day") (or "168 week")'
    )


def test_a_duration_beyond_the_creep_table_is_refused() -> None:
    with pytest.raises(SpecError) as info:
        problem(held("1 year"))
    # a year is 365.25 days, 8766 h (pint's), past the Makrolon table's last duration
    assert str(info.value) == (
        "constraints.deflection[0].duration = 8766 h is beyond the creep table: allowed at "
        "most 1000 h (creep moduli tabulated for 1 h to 1000 h)"
    )


def test_a_material_without_creep_data_refuses_a_sustained_load() -> None:
    with pytest.raises(SpecError) as info:
        problem(held("1 week", {"name": "dura-lar", "thickness": "0.125 mm"}))
    text = str(info.value)
    assert info.value.field == "constraints.deflection[0].duration" and "\n" not in text
    assert "needs creep data, which dura-lar has not" in text


def test_an_inline_material_refuses_a_sustained_load() -> None:
    inline = {"name": "mine", "E": "2 GPa", "nu": 0.35, "density": "1.2 g/cm^3", "thickness": 0.2}
    with pytest.raises(SpecError) as info:
        problem(held("1 h", inline))
    assert "needs creep data, which mine has not" in str(info.value)
    assert problem(copy.deepcopy({**BASE, "material": inline})).constraints  # short-term: fine


def test_a_strength_bound_takes_no_duration() -> None:
    d = copy.deepcopy(BASE)
    d["constraints"]["strength"] = [{"test": "three-point", "load": "1 N", "duration": "1 h"}]
    with pytest.raises(SpecError) as info:
        parse_spec(d)
    assert info.value.field == "constraints.strength[0].duration"
    assert "is not a known key" in str(info.value)
