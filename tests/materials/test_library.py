"""The bundled material library (a data file) and inline materials."""

from __future__ import annotations

import pytest

from corrugate import get_material, inline_material, library
from corrugate.core.errors import InputError

REQUIRED = {
    "dura-lar",
    "mylar",
    "polypropylene",
    "polycarbonate",
    "kapton",
    "petg",
    "fr4",
    "cardstock",
    "aluminium-shim",
    "stainless-shim",
}


def test_library_contents() -> None:
    lib = library()
    assert set(lib) >= REQUIRED
    assert len(lib) >= 9
    for m in lib.values():
        assert m.E > 0 and -1 < m.nu < 0.5 and m.density > 0
        assert m.thicknesses == tuple(sorted(m.thicknesses)) and m.thicknesses
        assert m.default_thickness in m.thicknesses
        assert len(m.source) > 20, m.id  # says where the values come from


def test_duralar_is_the_papers_sheet() -> None:
    """Liu, Yan and Mehta: E = 2.7 GPa, nu = 0.43, t = 0.125 mm; density of PET ~1.38-1.40 g/cm^3."""
    m = get_material("Dura-Lar")
    assert pytest.approx(2700.0) == m.E
    assert m.nu == pytest.approx(0.43)
    assert m.default_thickness == pytest.approx(0.125)
    assert 1.38 <= m.density_g_cm3 <= 1.40


def test_metals_are_metals() -> None:
    """Handbook sanity: aluminium ~69-72 GPa, 2.7 g/cm^3; stainless ~190-200 GPa, ~8 g/cm^3."""
    al, ss = get_material("aluminium-shim"), get_material("stainless-shim")
    assert 68e3 <= al.E <= 73e3 and al.density_g_cm3 == pytest.approx(2.7, abs=0.05)
    assert 185e3 <= ss.E <= 200e3 and ss.density_g_cm3 == pytest.approx(7.95, abs=0.1)


def test_inline_units() -> None:
    m = inline_material("2.7 GPa", "0.43", "1390 kg/m^3", thickness="5 mil")
    assert pytest.approx(2700.0) == m.E
    assert m.density_g_cm3 == pytest.approx(1.39)
    assert m.default_thickness == pytest.approx(0.127)


def test_a_length_for_a_modulus_is_rejected() -> None:
    with pytest.raises(InputError, match=r"^E = '2 mm' has the wrong dimension"):
        inline_material("2 mm", 0.3, 1.0)


def test_repr_is_one_short_line_with_units() -> None:
    m = get_material("dura-lar")
    text = repr(m)
    assert "\n" not in text and len(text) < 100
    assert text.startswith("Material('dura-lar'") and "2700 MPa" in text
    assert m.source not in text  # the source text is in as_dict, not the repr


def test_every_library_material_has_an_allowable_stress() -> None:
    """Each sheet carries a yield (or tensile) strength with its source, positive and below
    E/20: no engineering sheet yields at a strain above 5 % in the linear range (the polymers
    here yield at about 2-5 %, metals at 0.2-0.5 %)."""
    for m in library().values():
        assert m.yield_strength is not None, m.id
        assert 0 < m.yield_strength < m.E / 20, m.id
        assert "yield_strength:" in m.source, m.id
        assert m.as_dict()["yield_strength_MPa"] == m.yield_strength


def test_yield_strength_units_are_parsed() -> None:
    """ "100 MPa" and "0.1 GPa" are one stress; "14.5 ksi" is 100 MPa to 0.1 % (1 ksi = 6.895 MPa)."""
    from corrugate.materials.library import material_from_entry

    base = {"name": "x", "E": "2 GPa", "nu": 0.3, "density": "1 g/cm^3"}
    a = material_from_entry("a", {**base, "yield_strength": "100 MPa"})
    b = material_from_entry("b", {**base, "yield_strength": "0.1 GPa"})
    c = material_from_entry("c", {**base, "yield_strength": "14.5 ksi"})
    assert a.yield_strength == pytest.approx(100.0)
    assert b.yield_strength == pytest.approx(100.0)
    assert c.yield_strength == pytest.approx(100.0, rel=1e-3)
    assert material_from_entry("d", base).yield_strength is None


@pytest.mark.parametrize("bad", ["0 MPa", "-5 MPa", "3 GPa", "2 mm"])
def test_a_yield_strength_outside_zero_to_E_is_refused(bad: str) -> None:
    from corrugate.materials.library import material_from_entry

    base = {"name": "x", "E": "2 GPa", "nu": 0.3, "density": "1 g/cm^3"}
    with pytest.raises(InputError, match=r"yield_strength"):
        material_from_entry("x", {**base, "yield_strength": bad})


def test_inline_materials_have_no_yield_strength() -> None:
    assert inline_material("2.7 GPa", 0.43, 1.39).yield_strength is None


def test_kapton_and_mylar_yield_match_their_datasheets() -> None:
    """Kapton HN data sheet: yield point at 3 % 69 MPa; Mylar bulletin: F-5 10 kg/mm^2 = 98.1 MPa."""
    assert get_material("kapton").yield_strength == pytest.approx(69.0)
    assert get_material("mylar").yield_strength == pytest.approx(10 * 9.80665, rel=0.01)
