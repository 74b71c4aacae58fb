"""The user's own materials files (corrugate.materials.user): the config folder's and the one
beside a spec, found by the spec loader; a library entry extended; aliases ("pet")."""

from __future__ import annotations

from pathlib import Path

import pytest

from corrugate.core.errors import InputError
from corrugate.materials.library import AmbiguousNameError, get_material, library
from corrugate.materials.user import SPEC_FILE, read_materials, spec_materials, write_entry
from corrugate.solver.problem import Problem
from corrugate.spec.examples import example_text
from corrugate.spec.schema import SpecError, load_spec, parse_spec_text


def _spec(folder: Path, material: str) -> Path:
    text = example_text("blimp_gripper").replace('name = "dura-lar"', f'name = "{material}"', 1)
    path = folder / "gripper.toml"
    path.write_text(text)
    return path


def test_pet_lists_the_pet_films_and_a_unique_alias_finds_its_material() -> None:
    with pytest.raises(AmbiguousNameError) as info:
        get_material("pet")
    text = str(info.value)
    assert "dura-lar" in text and "mylar" in text and "2 materials" in text
    assert get_material("BOPET").id == "mylar"
    with pytest.raises(SpecError, match=r"^material\.name = 'pet' names 2 materials"):
        parse_spec_text(example_text("blimp_gripper").replace('"dura-lar"', '"pet"', 1))


def test_a_materials_file_beside_the_spec_is_found_and_designs_with_its_e(tmp_path: Path) -> None:
    write_entry(tmp_path / SPEC_FILE, "my-film", {"extends": "dura-lar", "E": "3.3 GPa"})
    spec = load_spec(_spec(tmp_path, "my-film"))
    (cand,) = Problem.from_spec(spec).candidates
    assert pytest.approx(3300.0) == cand.material.E
    lib = library()["dura-lar"]  # the rest is the library's entry
    assert (cand.material.nu, cand.material.density) == (lib.nu, lib.density)
    # the same spec elsewhere does not know it
    other = tmp_path / "elsewhere"
    other.mkdir()
    with pytest.raises(SpecError, match=r"^material\.name = 'my-film' is unknown"):
        load_spec(_spec(other, "my-film"))


def test_the_config_folder_serves_every_spec_and_the_spec_folder_wins(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    config = tmp_path / "config"
    monkeypatch.setenv("CORRUGATE_CONFIG_DIR", str(config))
    write_entry(config / "materials.toml", "my-film", {"extends": "mylar", "E": "4.0 GPa"})
    assert pytest.approx(4000.0) == get_material("my-film").E  # the command line's lookup
    here = tmp_path / "project"
    here.mkdir()
    assert pytest.approx(4000.0) == spec_materials(here)["my-film"].E
    write_entry(here / SPEC_FILE, "my-film", {"extends": "mylar", "E": "4.2 GPa"})
    assert pytest.approx(4200.0) == spec_materials(here)["my-film"].E


def test_write_entry_replaces_a_table_and_keeps_the_others(tmp_path: Path) -> None:
    path = tmp_path / "m.toml"
    write_entry(path, "a", {"extends": "dura-lar", "E": "3 GPa"})
    write_entry(path, "b", {"extends": "mylar", "E": "4 GPa", "calibration": {"n": 3}})
    write_entry(path, "a", {"extends": "dura-lar", "E": "3.1 GPa"})
    found = read_materials(path)
    assert pytest.approx(3100.0) == found["a"].E and pytest.approx(4000.0) == found["b"].E
    assert path.read_text().count("[a]") == 1


def test_a_bad_entry_is_refused_before_anything_is_written(tmp_path: Path) -> None:
    path = tmp_path / "m.toml"
    with pytest.raises(InputError, match=r"m\.toml \[x\]\.E"):
        write_entry(path, "x", {"extends": "dura-lar", "E": "-3 GPa"})
    assert not path.exists()
    with pytest.raises(InputError, match=r"\[x\]\.extends = 'nope'"):
        write_entry(path, "x", {"extends": "nope", "E": "3 GPa"})
