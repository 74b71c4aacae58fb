"""``corrugate design`` with a load case's ``bearing`` width (docs/load_cases.md 10.5): bad
widths exit 2 with one line naming the spec path; a narrow one lowers the crippling load the
answer reports, and the answer says the width it used."""

from __future__ import annotations

import json
from pathlib import Path
from typing import TYPE_CHECKING

import pytest

if TYPE_CHECKING:
    from conftest import CliRun

SPEC = """
name = "bearing"
joint = "band-edges"
[material]
name = "polypropylene"
thickness = "0.25 mm"
[layout]
shape = "square"
[variables]
W = {{ min = "8 mm", max = "12 mm", step = "1 mm" }}
n = {{ min = 6, max = 12 }}
alpha = {{ min = "60 deg", max = "120 deg", step = "10 deg" }}
[constraints]
side = {{ min = "80 mm", max = "100 mm" }}
deflection = [{{ test = "{test}", load = "0.2 N", max = "5 mm", {bearing} }}]
"""


@pytest.mark.parametrize(
    ("test", "bearing", "words"),
    [
        ("three-point", 'bearing = "0 mm"', "'0 mm' is out of range: allowed > 0 mm"),
        ("three-point", 'bearing = "-2 mm"', "is out of range: allowed > 0 mm"),
        ("three-point", 'bearing = "nan mm"', "cannot be read as a quantity"),
        ("three-point", 'bearing = "150 mm"', "at most the panel's longest length, 100 mm"),
        ("three-point", 'bearing = "10 N"', "bearing"),
        ("platens", 'bearing = "10 mm"', "no bearing for platens"),
    ],
    ids=["zero", "negative", "nan", "longer-than-the-panel", "wrong-dimension", "platens"],
)
def test_bad_bearings_exit_2_in_one_line(
    tmp_path: Path, cli: CliRun, test: str, bearing: str, words: str
) -> None:
    spec = tmp_path / "bad.toml"
    spec.write_text(SPEC.format(test=test, bearing=bearing), "utf-8")
    out_dir = tmp_path / "out"
    code, out, err = cli(["design", str(spec), "--json", "--out", str(out_dir)])
    assert (code, out) == (2, "")
    lines = err.strip().splitlines()
    assert len(lines) == 1, err
    assert lines[0].startswith("corrugate: error: constraints.deflection[0].bearing = "), err
    assert words in lines[0], err
    assert not out_dir.exists()


def _held(tmp_path: Path, cli: CliRun, bearing: str) -> dict[str, object]:
    spec = tmp_path / f"b{len(bearing)}.toml"
    spec.write_text(SPEC.format(test="three-point", bearing=bearing), "utf-8")
    code, out, err = cli(["design", str(spec), "--json"])
    assert code == 0, err
    cons = json.loads(out)["constraints"]
    held = next(c for c in cons if c["name"].endswith("(held at the safety factor)"))
    assert isinstance(held, dict)
    return held


def test_the_answer_states_its_bearing_and_a_narrow_one_cripples_sooner(
    tmp_path: Path, cli: CliRun
) -> None:
    """Default 10 mm, said in the answer; at 0.05 mm the bearing's yield load f_y t s_s =
    33 x 0.25 x 0.05 = 0.41 N per facet is below every facet's elastic patch load, so the
    crippling load falls (docs/load_cases.md 10.5: F_R = min(F_cr, F_y, 0.5 sqrt(F_y F_cr)))."""
    wide = _held(tmp_path, cli, 'span = "80 mm"')
    narrow = _held(tmp_path, cli, 'bearing = "0.05 mm"')
    assert wide["bearing_mm"] == 10.0 and narrow["bearing_mm"] == 0.05
    assert "/b=0.05mm" in str(narrow["quantity"])
    w, n = wide["failure_loads_N"], narrow["failure_loads_N"]
    assert isinstance(w, dict) and isinstance(n, dict)
    assert n["crippling"] < w["crippling"]
