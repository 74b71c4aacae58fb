"""Xia's general theory: the published benchmark and the zig-zag special case."""

from __future__ import annotations

import json
import math
from collections.abc import Iterator
from pathlib import Path
from typing import Any

import pytest
from hypothesis import given
from hypothesis import strategies as st

from corrugate import moduli
from corrugate.core.errors import InputError
from corrugate.geometry.profile import get_profile, register_profile, unregister_profile
from corrugate.mechanics.profiles import (
    MEMBRANES,
    Trapezoid,
    ZigZag,
    equivalent_plate,
    plate_moduli,
    profile_moduli,
)


def test_xia2012_table5(reference: Path) -> None:
    data = json.loads((reference / "xia2012_table5.json").read_text())
    i, e = data["input"], data["expected"]
    plate = equivalent_plate(
        Trapezoid(i["half_period_c_mm"], i["height_f_mm"], i["incline_deg"]),
        E=i["E_GPa"] * 1e3,
        nu=i["nu"],
        t=i["t_mm"],
    )
    # A in N/mm = 1e-3 MN/m; D in N mm = 1e-3 N m
    for key in ("A11", "A12", "A22"):
        assert getattr(plate, key) * 1e-3 == pytest.approx(e[f"{key}_MN_per_m"], rel=1e-3), key
    for key in ("D11", "D12", "D22", "D66"):
        assert getattr(plate, key) * 1e-3 == pytest.approx(e[f"{key}_N_m"], rel=1e-3), key


@pytest.fixture
def trapezoid() -> Iterator[type[Any]]:
    """The trapezoid registered as a second profile (:mod:`corrugate.geometry.profile`) for one
    test."""
    register_profile("trapezoid", Trapezoid)
    yield get_profile("trapezoid")
    unregister_profile("trapezoid")


def test_xia2012_table5_through_the_seam(reference: Path, trapezoid: type[Any]) -> None:
    # the registered profile, built by its name, gives Table 5's plate through Xia's theory,
    # and its moduli (profile_moduli, variant xia) are those of the table's A and D
    data = json.loads((reference / "xia2012_table5.json").read_text())
    i, e = data["input"], data["expected"]
    profile = get_profile("trapezoid")(i["half_period_c_mm"], i["height_f_mm"], i["incline_deg"])
    E, nu, t = i["E_GPa"] * 1e3, i["nu"], i["t_mm"]
    plate = equivalent_plate(profile, E=E, nu=nu, t=t)
    for key in ("A11", "A12", "A22"):
        assert getattr(plate, key) * 1e-3 == pytest.approx(e[f"{key}_MN_per_m"], rel=5e-3), key
    for key in ("D11", "D12", "D22", "D66"):
        assert getattr(plate, key) * 1e-3 == pytest.approx(e[f"{key}_N_m"], rel=5e-3), key
    # Ecx = det A / (t A22), Ecy = det A / (t A11), Ebx = 12 det D / (t^3 D22), Eby likewise
    # with D11, from the published constants (MN/m -> N/mm: x 1e3; N m -> N mm: x 1e3)
    A11, A12, A22 = (e[f"{k}_MN_per_m"] * 1e3 for k in ("A11", "A12", "A22"))
    D11, D12, D22 = (e[f"{k}_N_m"] * 1e3 for k in ("D11", "D12", "D22"))
    detA, detD = A11 * A22 - A12**2, D11 * D22 - D12**2
    table = {
        "Ecx": detA / (t * A22),
        "Ecy": detA / (t * A11),
        "Ebx": 12 * detD / (t**3 * D22),
        "Eby": 12 * detD / (t**3 * D11),
    }
    seam = profile_moduli(profile, E, nu, t, "xia").as_dict()
    for key, value in table.items():
        assert seam[key] == pytest.approx(value, rel=5e-3), key
    with pytest.raises(InputError, match="zig-zag only"):
        profile_moduli(profile, E, nu, t, "paper")


@given(
    W=st.floats(0.5, 50),
    alpha=st.floats(5, 175),
    t_over_W=st.floats(1e-4, 0.2),
    nu=st.floats(-0.9, 0.49),
)
def test_zigzag_through_the_seam_gives_the_moduli(
    W: float, alpha: float, t_over_W: float, nu: float
) -> None:
    # the default profile, built by its name, gives the moduli analyze prints (the closed forms)
    # and Xia's general theory on the same profile agrees with the xia variant's four
    t = W * t_over_W
    zigzag = get_profile()
    assert zigzag is ZigZag
    profile = zigzag.of(W, alpha)
    for name in ("paper", "xia", "refined"):
        if name == "paper" and nu <= 1 - math.sqrt(2):
            continue  # outside the printed formulas' range (ModuliModel.nu_min)
        seam = profile_moduli(profile, 1.0, nu, t, name).as_dict()
        direct = moduli(1.0, nu, t, W, alpha, name).as_dict()
        # the same closed forms; the profile's own h and W may round the last bit differently
        assert seam == pytest.approx(direct, rel=1e-12), name
    general = plate_moduli(equivalent_plate(profile, 1.0, nu, t), t).as_dict()
    for key, value in profile_moduli(profile, 1.0, nu, t, "xia").as_dict().items():
        assert general[key] == pytest.approx(value, rel=1e-7), key


@pytest.mark.parametrize("model", ["paper", "xia", "refined"])
def test_flat_sheet_limit(model: str) -> None:
    # alpha = 180 deg: pitch W, height 0: the layer is a flat isotropic sheet, so in-plane
    # (A11 A22 - A12^2)/(t A22) = E t/(1 - nu^2) (1 - nu^2)/t = E, and likewise in bending
    # (xia, refined). The paper's printed formulas (docs/theory.md 3.1) reach E in Eby only; its
    # Ebx misses the factor 2 s on its t^2 term, so the flat sheet (s = 1) gets E / 2.
    profile = get_profile().of(8.0, 180.0)
    assert profile.pitch == 8.0
    assert profile.height == pytest.approx(0.0, abs=1e-14)
    got = profile_moduli(profile, 2000.0, 0.3, 0.1, model).as_dict()
    expected = (
        {"Ebx": 1000.0, "Eby": 2000.0}
        if model == "paper"
        else dict.fromkeys(("Ecx", "Ecy", "Ebx", "Eby"), 2000.0)
    )
    for key, value in expected.items():
        assert got[key] == pytest.approx(value, rel=1e-9), (model, key)
    flat = plate_moduli(equivalent_plate(profile, 2000.0, 0.3, 0.1), 0.1).as_dict()
    for key in ("Ecx", "Ecy", "Ebx", "Eby"):
        assert flat[key] == pytest.approx(2000.0, rel=1e-9), key


@given(
    W=st.floats(0.5, 50),
    alpha=st.floats(5, 175),
    t_over_W=st.floats(1e-4, 0.2),
    nu=st.floats(-0.9, 0.49),
)
def test_trapezoid_without_flat_is_the_zigzag_closed_form(
    W: float, alpha: float, t_over_W: float, nu: float
) -> None:
    t = W * t_over_W
    half = math.radians(alpha) / 2
    c, f = W * math.sin(half), W * math.cos(half) / 2
    theta = 90 - alpha / 2  # incline of a facet
    trap = Trapezoid(c, f, theta)
    assert abs(trap.flat) < 1e-9 * c
    for name, membrane in MEMBRANES.items():  # xia: plane-strain, refined: uniaxial
        general = plate_moduli(equivalent_plate(trap, 1.0, nu, t, membrane), t).as_dict()
        zz = plate_moduli(
            equivalent_plate(ZigZag.of_float(W, alpha), 1.0, nu, t, membrane), t
        ).as_dict()
        closed = moduli(1.0, nu, t, W, alpha, name).as_dict()
        for key, value in closed.items():
            if (name, key) == ("refined", "Ebx"):
                continue
            assert general[key] == pytest.approx(value, rel=1e-7), (name, key)
            assert zz[key] == pytest.approx(value, rel=1e-7), (name, key)
    # The refined closed form keeps Xia's Ebx (docs/theory.md 3.1). The general theory with the uniaxial
    # membrane gives Ebx = 12 D11 (1 - nu^2 D11/D22)/t^3 with a smaller D22 >= s D = D11, so it sits
    # below Xia's by a fraction in [0, nu^2/(1 - nu^2)] (hand derivation).
    refined_general = plate_moduli(equivalent_plate(trap, 1.0, nu, t, "uniaxial"), t).Ebx
    xia_closed = moduli(1.0, nu, t, W, alpha, "xia").Ebx
    drop = float((xia_closed - refined_general) / xia_closed)
    assert -1e-9 <= drop <= nu**2 / (1 - nu**2) + 1e-9


def test_trapezoid_rejects_negative_flat() -> None:
    with pytest.raises(InputError, match="f ="):
        Trapezoid(10.0, 20.0, 45.0)
