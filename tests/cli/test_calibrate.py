"""``corrugate calibrate kit`` and ``fit`` (docs/calibration.md): the kit's files, the fit of
readings made from a known sheet, the fit saved as a material a spec then designs with, and bad
readings refused in one line naming the field (exit 2)."""

from __future__ import annotations

import json
import os
import re
import tomllib
from pathlib import Path
from typing import TYPE_CHECKING

import numpy as np
import pytest

from corrugate.calibration.coupons import design_kit
from corrugate.calibration.virtual import measurements_toml, virtual_measurements
from corrugate.materials.library import get_material

if TYPE_CHECKING:
    from conftest import CliRun


@pytest.fixture(scope="module")
def readings() -> str:
    """A measurements file of the Dura-Lar 0.125 mm kit from a sheet of E 3100 MPa along, 2900
    across, creases k = 0.1 N mm/(rad mm) at 84 deg, readings within +-1 mm."""
    kit = design_kit(get_material("dura-lar"), 0.125, 222.1)
    m = virtual_measurements(kit, 3100.0, 0.1, 84.0, np.random.default_rng(7), E_across=2900.0)
    return measurements_toml(m)


@pytest.mark.slow
def test_kit_writes_cut_files_protocol_and_a_template(tmp_path: Path, cli: CliRun) -> None:
    out = tmp_path / "kit"
    args = ["calibrate", "kit", "--material", "dura-lar", "--thickness", "0.125mm"]
    code, text, err = cli([*args, "--out", str(out)])
    assert code == 0, err
    names = {p.name for p in out.iterdir()}
    assert {"cut-1.dxf", "pattern.pdf", "protocol.md", "protocol.pdf", "measurements.toml"} <= names
    assert {"setup-flat.png", "setup-coin.png", "setup-crease.png"} <= names
    assert (out / "protocol.pdf").read_bytes()[:5] == b"%PDF-"
    protocol = (out / "protocol.md").read_text()
    assert "## Measurement sheet" in protocol and "![the flat strip" in protocol
    import ezdxf

    layers = [e.dxf.layer for e in ezdxf.readfile(out / "cut-1.dxf").modelspace()]
    assert layers.count("CUT") == 5  # three coupons and the crease strip's two holes
    assert any(name.startswith(("MOUNTAIN", "VALLEY")) for name in layers)  # C1's creases
    assert "LABEL" in layers
    # every expected sag the kit prints lies in what a ruler reads well, 5-50 mm
    sags = [float(x) for x in re.findall(r"sag ~(\d+) mm", text)]
    assert sags and all(5 <= s <= 50 for s in sags)
    template = tomllib.loads((out / "measurements.toml").read_text())
    assert template["sheet"]["material"] == "dura-lar" and len(template["flat"]) == 4
    # the template as written is refused until the readings are in, naming the field
    code, _, err = cli(["calibrate", "fit", str(out / "measurements.toml")])
    assert code == 2 and err.count("\n") == 1
    assert "flat[0].sag = 0 readings has too few repeats" in err


@pytest.mark.slow
def test_fit_recovers_the_sheet_and_saves_a_material_a_spec_designs_with(
    tmp_path: Path, cli: CliRun, readings: str
) -> None:
    path = tmp_path / "measurements.toml"
    path.write_text(readings)
    materials = tmp_path / "corrugate-materials.toml"
    code, out, err = cli(
        ["calibrate", "fit", str(path), "--save", "--materials", str(materials), "--json"]
    )
    assert code == 0, err
    answer = json.loads(out)
    along, across = answer["moduli"]
    assert along["E_90_MPa"][0] < 3100.0 < along["E_90_MPa"][1]
    assert across["E_90_MPa"][0] < 2900.0 < across["E_90_MPa"][1]
    assert answer["crease"]["k_N_per_rad"] == pytest.approx(0.1, rel=0.1)  # its interval: 5 %
    assert answer["crease"]["angle_deg"] == pytest.approx(84.0, abs=1.5)
    assert (tmp_path / "fit.png").read_bytes()[:4] == b"\x89PNG"
    # the smaller E is saved; a spec beside the file names it
    from corrugate.solver.problem import Problem
    from corrugate.spec.examples import example_text
    from corrugate.spec.schema import load_spec

    spec = tmp_path / "gripper.toml"
    spec.write_text(example_text("blimp_gripper").replace('"dura-lar"', '"virtual-dura-lar"', 1))
    (cand,) = Problem.from_spec(load_spec(spec)).candidates
    assert pytest.approx(across["E_MPa"], rel=1e-3) == cand.material.E
    entry = tomllib.loads(materials.read_text())["virtual-dura-lar"]
    assert entry["calibration"]["measurements"] == 40
    assert entry["extends"] == "dura-lar"


@pytest.mark.parametrize(
    ("old", "new", "field"),
    [
        ("sag = [", "sag = [-3.0, ", "flat[0].sag[0] = -3 mm is out of range"),  # negative
        (r"sag = \[[^\]]*\]", "sag = [12.0, 13.0]", "flat[0].sag = 2 readings has too few repeats"),
        ("sag = [", "sag = [80.0, ", "flat[0].sag[0] = 80 mm is out of range"),  # > overhang
        # the coin set-up (the second) sags 1 mm where the first needs a soft sheet: no E fits
        (r"sag = \[[^\]]*\]", "sag = [1.0, 1.0, 1.0]", "flat (along) = "),
    ],
)
def test_bad_readings_are_one_line_naming_the_field(
    tmp_path: Path, cli: CliRun, readings: str, old: str, new: str, field: str
) -> None:
    pattern = re.compile(re.escape(old) if "\\" not in old else old)
    spots = list(pattern.finditer(readings))
    at = spots[1] if field.startswith("flat (along)") else spots[0]
    text = readings[: at.start()] + new + readings[at.end() :]
    path = tmp_path / "m.toml"
    path.write_text(text)
    code, out, err = cli(["calibrate", "fit", str(path)])
    assert code == 2 and out == ""
    assert err.count("\n") == 1 and err.startswith("corrugate: error: "), err
    assert field in err, err


@pytest.mark.parametrize(
    ("target", "words"),
    [
        ("folder", "is a folder"),  # the staged file's name was shown: '.folder.corrugate-...tmp'
        ("fifo", "is a FIFO"),  # replaced by a regular file, silently
        ("latin1.toml", "is not UTF-8 text"),  # exit 3: UnicodeDecodeError
        ("a" * 300, "File name too long"),  # after the fit, naming no option
        ("afile/m.toml", "Not a directory"),  # 'afile cannot be used (File exists)'
    ],
)
def test_a_materials_file_it_cannot_read_or_write_is_one_line_before_the_fit(
    tmp_path: Path,
    cli: CliRun,
    readings: str,
    monkeypatch: pytest.MonkeyPatch,
    target: str,
    words: str,
) -> None:
    monkeypatch.chdir(tmp_path)
    (tmp_path / "measurements.toml").write_text(readings)
    (tmp_path / "folder").mkdir()
    os.mkfifo(tmp_path / "fifo")
    (tmp_path / "latin1.toml").write_bytes(b'[x]\nextends = "dura-lar"\nname = "\xe9"\n')
    (tmp_path / "afile").write_text("")
    code, out, err = cli(
        ["calibrate", "fit", "measurements.toml", "--save", "--materials", target, "-q"]
    )
    assert code == 2, err
    assert err.count("\n") == 1 and err.startswith("corrugate: error: --materials = "), err
    assert words in err and out == "", err
    assert not (tmp_path / "fit.png").exists()  # refused before the fit and its figure
    assert (tmp_path / "fifo").is_fifo()


@pytest.mark.parametrize(
    ("target", "words"),
    [("folder", "Is a directory"), ("a" * 300, "File name too long")],
)
def test_a_plot_it_cannot_write_is_one_line_naming_plot(
    tmp_path: Path,
    cli: CliRun,
    readings: str,
    monkeypatch: pytest.MonkeyPatch,
    target: str,
    words: str,
) -> None:
    """The OS error named the staged file beside the target ('.folder.corrugate-...tmp cannot
    be used (Is a directory)'), not the option."""
    monkeypatch.chdir(tmp_path)
    (tmp_path / "measurements.toml").write_text(readings)
    (tmp_path / "folder").mkdir()
    code, _, err = cli(["calibrate", "fit", "measurements.toml", "--plot", target, "-q"])
    assert code == 2, err
    assert err.count("\n") == 1 and err.startswith("corrugate: error: --plot = "), err
    assert f"cannot be written ({words})" in err and ".corrugate-" not in err, err
    assert sorted(p.name for p in tmp_path.iterdir()) == ["folder", "measurements.toml"]
