"""A calibrated material's certificate: every directional bound over the measured intervals
(E's interval in place of the default E tolerance, the crease stiffness's, the fold angle moved
by the springback's), and the answer says it was calibrated, from what (docs/calibration.md 9).
"""

from __future__ import annotations

import math
from dataclasses import replace
from pathlib import Path

import pytest

from corrugate.analysis.evaluate import analyze
from corrugate.geometry.layer import Assembly, Layer
from corrugate.solver.problem import Problem
from corrugate.solver.solve import solve
from corrugate.spec.examples import example_text
from corrugate.spec.schema import load_spec, parse_spec_text

CALIBRATION = """
[my-sheet]
extends = "dura-lar"
E = "2700 MPa"
thicknesses = ["0.125 mm"]

[my-sheet.calibration]
date = "2026-12-06"
coupons = ["F1"]
measurements = 10
E_along = "2700 MPa"
E_along_90 = ["{lo} MPa", "{hi} MPa"]
{extra}
"""


def _solve(tmp_path: Path, name: str, lo: float = 2500.0, hi: float = 2900.0, extra: str = ""):
    (tmp_path / "corrugate-materials.toml").write_text(
        CALIBRATION.format(lo=lo, hi=hi, extra=extra)
    )
    text = example_text("blimp_gripper").replace('"dura-lar"', f'"{name}"', 1)
    spec = tmp_path / "gripper.toml"
    spec.write_text(text)
    return solve(Problem.from_spec(load_spec(spec)))


def _ei(sol, material, alpha_shift: float = 0.0) -> float:
    lay = sol.assembly.layer1
    moved = Layer(
        W=lay.W, n=lay.n, alpha_deg=lay.alpha_deg + alpha_shift, material=material, t=lay.t
    )
    return analyze(Assembly.identical(moved), eta_deg=[0]).stiffness[0].EI


def _certified_ei(sol) -> float:
    (c,) = [c for c in sol.constraints if "flexural_rigidity" in c.name]
    return c.value


def test_the_datasheet_answer_is_nominal_and_says_nothing_of_a_calibration(tmp_path: Path) -> None:
    sol = _solve(tmp_path, "dura-lar")
    assert "calibrated" not in sol.certificate
    assert _certified_ei(sol) == pytest.approx(_ei(sol, sol.assembly.layer1.material), rel=1e-12)


@pytest.mark.slow
def test_a_calibrated_E_is_certified_at_its_interval_low_end(tmp_path: Path) -> None:
    """Hand computation: with rigid creases and no springback every modulus is E times a
    function of the geometry, so the certified EI(0) over E in [2500, 2900] MPa is the EI at
    2500 MPa, 2500 / 2700 of the nominal: the interval replaces the `tolerances = "none"`
    spec's nominal E."""
    sol = _solve(tmp_path, "my-sheet")
    m = sol.assembly.layer1.material
    assert m.calibration is not None and math.isinf(m.crease_stiffness)
    nominal = _ei(sol, m)
    assert _certified_ei(sol) == pytest.approx(nominal * 2500 / 2700, rel=1e-9)
    assert _certified_ei(sol) >= 80000.0 * (1 - 1e-9)  # the bound holds at E's low end
    assert "calibrated E 2500-2900 MPa, from my-sheet, 2026-12-06, 10 measurements" in (
        sol.certificate
    )


@pytest.mark.slow
def test_a_springback_certifies_the_angle_the_folds_take(tmp_path: Path) -> None:
    """A springback of exactly -4 deg (interval of zero width) and E known exactly: the
    certified EI(0) is the model's at alpha - 4 deg (the cut files keep alpha)."""
    extra = 'springback = "-4 deg"\nfolded_angle = "86 deg"\nfolded_angle_90 = ["86 deg", "86 deg"]'
    sol = _solve(tmp_path, "my-sheet", 2700.0, 2700.0, extra)
    m = sol.assembly.layer1.material
    assert m.calibration is not None and m.calibration.springback == -4.0
    assert _certified_ei(sol) == pytest.approx(_ei(sol, m, -4.0), rel=1e-6)
    assert "springback -4.0 to -4.0 deg" in sol.certificate


@pytest.mark.slow
def test_a_calibrated_crease_is_certified_at_its_softest(tmp_path: Path) -> None:
    """k in [0.05, 0.2] N mm/(rad mm), E exact: the certified EI(0) is the model's at k = 0.05
    (layer 2's chordwise bending D_C falls with k, nothing rises)."""
    extra = (
        'crease_stiffness = "0.1 N*mm/(rad*mm)"\n'
        'crease_stiffness_90 = ["0.05 N*mm/(rad*mm)", "0.2 N*mm/(rad*mm)"]'
    )
    sol = _solve(tmp_path, "my-sheet", 2700.0, 2700.0, extra)
    m = sol.assembly.layer1.material
    assert m.crease_stiffness == 0.1
    soft = _ei(sol, replace(m, crease_stiffness=0.05))
    assert _certified_ei(sol) == pytest.approx(soft, rel=1e-6)
    assert soft < _ei(sol, m) < _ei(sol, replace(m, crease_stiffness=math.inf))


INLINE = """
E = "2700 MPa"
nu = 0.43
density = "1.39 g/cm^3"
thickness = "0.125 mm"
crease_stiffness = "0.1 N*mm/(rad*mm)"
springback = "-4 deg"
"""


def _inline_problem(tolerances: str = 'tolerances = "none"') -> Problem:
    text = example_text("blimp_gripper").replace('tolerances = "none"', tolerances, 1)
    head, _, rest = text.partition("[material]\n")
    _, _, tail = rest.partition("\n\n")
    return Problem.from_spec(parse_spec_text(f"{head}[material]{INLINE}\n{tail}"))


@pytest.mark.slow
def test_an_inline_crease_and_springback_are_certified_as_stated() -> None:
    """An inline [material] stating crease_stiffness 0.1 N mm/(rad mm) and springback -4 deg,
    with tolerances "none": the certified EI(0) is the model's at alpha - 4 deg with k = 0.1
    (nothing else moves: E is the stated 2700 MPa, exact), and the answer says so."""
    sol = solve(_inline_problem())
    m = sol.assembly.layer1.material
    assert m.crease_stiffness == 0.1 and m.calibration is not None
    assert _certified_ei(sol) == pytest.approx(_ei(sol, m, -4.0), rel=1e-6)
    assert "crease stiffness 0.1 N*mm/(rad*mm), springback -4.0 deg, from custom, stated in " in (
        sol.certificate
    )


def test_an_inline_springback_keeps_the_tolerance_on_E() -> None:
    """Stated values are not a measured E: the default tolerances' +-10 % E stays (the sheet of
    the tolerance box spans 2430-2970 MPa), where a calibrated entry's interval replaces it."""
    from corrugate.solver.tolerance_box import sheet

    p = _inline_problem("")
    (c,) = p.candidates
    assert c.material.calibration is not None and not c.material.calibration.E_measured
    E = sheet(c, p.tolerances).material.E
    assert (E.lo, E.hi) == (pytest.approx(2430.0), pytest.approx(2970.0))


def test_the_answer_names_the_E_the_certificate_was_bounded_over(tmp_path: Path) -> None:
    """Under the default tolerances a measured E's interval replaces +-10 % E (the sheet of the
    tolerance box spans the calibrated 2500-2900 MPa, not 2430-2970): the answer does not
    name the +-10 %, it says the calibrated interval; stated inline values keep the +-10 % E
    and the answer says it."""
    from corrugate.solver.tolerance_box import sheet

    (tmp_path / "corrugate-materials.toml").write_text(
        CALIBRATION.format(lo=2500.0, hi=2900.0, extra="")
    )
    text = example_text("blimp_gripper").replace('"dura-lar"', '"my-sheet"', 1)
    spec = tmp_path / "gripper.toml"
    spec.write_text(text.replace('tolerances = "none"', "", 1))
    p = Problem.from_spec(load_spec(spec))
    (c,) = p.candidates
    E = sheet(c, p.tolerances).material.E
    assert (E.lo, E.hi) == (pytest.approx(2500.0), pytest.approx(2900.0))
    assert p.tolerance_sentence == (
        "for every part within +-3 deg, +-0.1 mm, +-5 % thickness, E within its calibrated interval"
    )
    assert "% E" not in p.tolerance_sentence
    stated = _inline_problem("")
    assert stated.tolerance_sentence.endswith("+-5 % thickness, +-10 % E")
