"""A calibrated material's entry: its intervals read, written to design.json and back, and bad
values refused in one line (corrugate.materials.calibrated)."""

from __future__ import annotations

import math
from pathlib import Path

import pytest

from corrugate.core.errors import InputError
from corrugate.materials.library import material_from_dict
from corrugate.materials.user import read_materials

ENTRY = """
[my-dura-lar]
extends = "dura-lar"
E = "2818 MPa"

[my-dura-lar.calibration]
date = "2026-12-06"
coupons = ["C1", "F1", "F2"]
measurements = 40
E_along = "3127 MPa"
E_along_90 = ["3034 MPa", "3228 MPa"]
E_across = "2818 MPa"
E_across_90 = ["2738 MPa", "2900 MPa"]
crease_stiffness = "0.09868 N*mm/(rad*mm)"
crease_stiffness_90 = ["0.0949 N*mm/(rad*mm)", "0.103 N*mm/(rad*mm)"]
folded_angle = "83.8 deg"
folded_angle_90 = ["83.1 deg", "84.5 deg"]
springback = "-6.2 deg"
"""


def test_the_entry_of_calibrate_fit_is_read_with_its_intervals(tmp_path: Path) -> None:
    path = tmp_path / "m.toml"
    path.write_text(ENTRY)
    m = read_materials(path)["my-dura-lar"]
    cal = m.calibration
    assert cal is not None
    assert (cal.E_lo, cal.E_hi) == (2738.0, 2900.0)  # the direction whose E was written
    assert m.crease_stiffness == 0.09868
    assert (cal.k_lo, cal.k_hi) == (0.0949, 0.103)
    # springback -6.2 deg measured at 83.8, its interval moved as the angle's 83.1-84.5
    assert cal.springback == -6.2
    assert cal.springback_lo == pytest.approx(-6.9)
    assert cal.springback_hi == pytest.approx(-5.5)
    assert m.as_dict()["crease_stiffness_N_mm_per_rad_mm"] == 0.09868
    back = material_from_dict(m.as_dict())
    assert back.calibration == cal and back.crease_stiffness == m.crease_stiffness
    assert cal.words("my-dura-lar").endswith("from my-dura-lar, 2026-12-06, 40 measurements")


def test_a_library_material_has_rigid_creases_and_no_new_keys() -> None:
    from corrugate.materials.library import get_material

    m = get_material("dura-lar")
    assert math.isinf(m.crease_stiffness) and m.calibration is None
    d = m.as_dict()
    assert "crease_stiffness_N_mm_per_rad_mm" not in d and "calibration" not in d


@pytest.mark.parametrize(
    ("line", "field"),
    [
        ('crease_stiffness = "-0.1 N*mm/(rad*mm)"\nspringback = "-6.2 deg"', "crease_stiffness"),
        ('springback = "-40 deg"', "calibration"),
    ],
)
def test_bad_calibrated_values_are_refused_in_one_line(
    tmp_path: Path, line: str, field: str
) -> None:
    text = ENTRY.replace('crease_stiffness = "0.09868 N*mm/(rad*mm)"\n', "").replace(
        'springback = "-6.2 deg"', line
    )
    path = tmp_path / "m.toml"
    path.write_text(text)
    with pytest.raises(InputError) as err:
        read_materials(path)
    msg = str(err.value)
    assert field in msg and "\n" not in msg
