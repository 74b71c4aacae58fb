"""``corrugate design`` with a sustained load case: bad durations exit 2 with one line naming
the spec path; a good one prints the creep modulus and its source."""

from __future__ import annotations

from pathlib import Path
from typing import TYPE_CHECKING

import pytest

if TYPE_CHECKING:
    from conftest import CliRun

SPEC = """
name = "held"
tolerances = "none"  # nominal: the test checks the model, not the tolerances (docs/tolerances.md)
joint = "band-edges"  # the band bonded along the edges: free outermost facets buckle first
[material]
name = "{material}"
thickness = "0.25 mm"
[layout]
shape = "square"
[variables]
W = {{ min = "4 mm", max = "20 mm", step = "1 mm" }}
n = {{ min = 2, max = 40 }}
alpha = {{ min = "30 deg", max = "150 deg", step = "5 deg" }}
[constraints]
side = {{ min = "100 mm", max = "120 mm" }}
# 4 N: the band's walls, composite with layer 1, hold at most 4.92 N at the safety factor 2 here
deflection = [{{ test = "three-point", load = "4 N", max = "1 mm", span = "100 mm", duration = {duration} }}]
"""


@pytest.mark.parametrize(
    ("material", "duration", "words"),
    [
        ("polycarbonate", '"-1 week"', "is out of range: allowed > 0 h"),
        ("dura-lar", '"1 week"', "needs creep data, which dura-lar has not"),
        ("polycarbonate", '"2000 h"', "is beyond the creep table: allowed at most 1000 h"),
    ],
    ids=["negative", "no-creep-data", "beyond-the-table"],
)
def test_bad_durations_exit_2_in_one_line(
    tmp_path: Path, cli: CliRun, material: str, duration: str, words: str
) -> None:
    spec = tmp_path / "bad.toml"
    spec.write_text(SPEC.format(material=material, duration=duration), "utf-8")
    out_dir = tmp_path / "out"
    code, out, err = cli(["design", str(spec), "--json", "--out", str(out_dir)])
    assert (code, out) == (2, "")
    lines = err.strip().splitlines()
    assert len(lines) == 1, err
    assert lines[0].startswith("corrugate: error: constraints.deflection[0].duration = ")
    assert words in lines[0]
    assert not out_dir.exists()


def test_a_week_prints_the_creep_modulus_and_its_source(tmp_path: Path, cli: CliRun) -> None:
    spec = tmp_path / "held.toml"
    spec.write_text(SPEC.format(material="polycarbonate", duration='"1 week"'), "utf-8")
    code, out, _ = cli(["design", str(spec)])
    assert code == 0
    text = " ".join(out.split())
    # E_c(168 h) = 2200 - 300 log10(168) / 3 = 1977 MPa (docs/load_cases.md section 11)
    assert "the load held 1 week: polycarbonate at its creep modulus E_c = 1977 MPa" in text
    assert "Makrolon" in text


def test_materials_lists_the_creep_tables(cli: CliRun) -> None:
    import json

    code, out, _ = cli(["materials", "--json"])
    assert code == 0
    creep = {m["id"]: m["creep"] for m in json.loads(out)}
    assert creep["dura-lar"] is None
    assert creep["polycarbonate"]["hours"] == [1.0, 1000.0]
    assert creep["polycarbonate"]["E_MPa"] == [2200.0, 1900.0]  # Makrolon 2858 datasheet
    assert creep["polypropylene"]["estimate"] is True
