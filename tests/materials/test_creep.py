"""Creep moduli (``corrugate.materials.creep``): the library's tables against their datasheets,
reading in log time against the formula by hand, refusals beyond the table."""

from __future__ import annotations

import math

import pytest

from corrugate.core.errors import InputError
from corrugate.materials.creep import CreepTable, duration_text
from corrugate.materials.library import creep_materials, get_material


def test_polycarbonate_table_is_the_makrolon_datasheets() -> None:
    """Covestro Makrolon 2858 / 2458: tensile modulus 2400 MPa, tensile creep modulus (ISO
    899-1) 2200 MPa after 1 h and 1900 MPa after 1000 h."""
    pc = get_material("polycarbonate")
    assert pytest.approx(2400.0) == pc.E
    assert pc.creep is not None and not pc.creep.estimate
    assert pc.creep.hours == (1.0, 1000.0)
    assert pc.creep.moduli == pytest.approx((2200.0, 1900.0))
    assert "Makrolon" in pc.creep.source and "ISO 899-1" in pc.creep.source


def test_polypropylene_is_a_labelled_estimate_of_4_mpa_over_1_percent() -> None:
    """The sheet datasheet's creep stress for 1 % elongation, 4 MPa: E_c = 4 / 0.01 MPa."""
    pp = get_material("polypropylene")
    assert pp.creep is not None and pp.creep.estimate
    assert "ESTIMATE" in pp.creep.source
    assert pp.creep_modulus(1000.0) == pytest.approx(4.0 / 0.01)
    assert pp.creep_modulus(24.0) == pytest.approx(400.0)  # below the first: the first


def test_only_sourced_materials_have_creep_data() -> None:
    assert sorted(creep_materials()) == ["polycarbonate", "polypropylene"]
    for name in creep_materials():
        m = get_material(name)
        assert m.creep is not None and all(e <= m.E for e in m.creep.moduli)


@pytest.mark.parametrize("hours", [2.0, 24.0, 168.0, 500.0])
def test_log_time_interpolation_by_hand(hours: float) -> None:
    """E_c(t) = 2200 + (1900 - 2200) log10(t / 1 h) / log10(1000): 168 h gives 1977.5 MPa."""
    expected = 2200.0 - 300.0 * math.log10(hours) / 3.0
    assert get_material("polycarbonate").creep_modulus(hours) == pytest.approx(expected)
    if hours == 168.0:
        assert expected == pytest.approx(1977.47, abs=0.01)


def test_the_modulus_falls_with_time_and_ends_at_the_table() -> None:
    pc = get_material("polycarbonate")
    values = [pc.creep_modulus(h) for h in (0.1, 1.0, 10.0, 100.0, 1000.0)]
    assert values == sorted(values, reverse=True)
    assert values[0] == 2200.0 and values[-1] == pytest.approx(1900.0)


def test_beyond_the_table_and_nonpositive_durations_are_refused() -> None:
    pc = get_material("polycarbonate")
    with pytest.raises(InputError) as info:
        pc.creep_modulus(8760.0, "x.duration")
    assert str(info.value) == (
        "x.duration = 365 days is beyond the creep table: allowed at most 1000 h "
        "(creep moduli tabulated for 1 h to 1000 h)"
    )
    for bad in (0.0, -1.0, math.nan):
        with pytest.raises(InputError):
            pc.creep_modulus(bad)


def test_a_material_without_creep_data_refuses_in_one_line() -> None:
    with pytest.raises(InputError) as info:
        get_material("dura-lar").creep_modulus(168.0, "d")
    text = str(info.value)
    assert "\n" not in text and text.startswith("d = 168 h needs creep data, which dura-lar")


def test_a_table_must_be_ascending_and_positive() -> None:
    with pytest.raises(ValueError, match="ascending"):
        CreepTable((10.0, 1.0), (1.0, 2.0), "x")
    with pytest.raises(ValueError, match="positive"):
        CreepTable((1.0,), (0.0,), "x")


def test_duration_text() -> None:
    assert [duration_text(h) for h in (1.0, 24.0, 168.0, 336.0, 1000.0)] == [
        "1 h",
        "1 day",
        "1 week",
        "2 weeks",
        "1000 h",
    ]
