"""corrugate.design(spec) takes a path, TOML text or a dict and gives what the command line
gives; the solver subpackage still imports as before."""

from __future__ import annotations

import json
import tomllib
from pathlib import Path

import pytest

import corrugate
from corrugate.core.errors import InputError
from corrugate.spec.schema import SpecError

ROOT = Path(__file__).resolve().parents[1]
BLIMP = ROOT / "examples" / "blimp_gripper.toml"


@pytest.mark.slow
def test_path_text_and_dict_give_the_same_certified_answer(tmp_path: Path) -> None:
    text = BLIMP.read_text()
    answers = [
        corrugate.design(BLIMP),
        corrugate.design(str(BLIMP)),
        corrugate.design(text),
        corrugate.design(tomllib.loads(text)),
    ]
    designs = {json.dumps(a.payload["design"], sort_keys=True) for a in answers}
    assert len(designs) == 1
    assert answers[0].solution.certified and answers[0].solution.status == "optimal"
    written = corrugate.write_files(answers[2], tmp_path / "out", cutter="laser:600x400")
    names = {p.name for p in written}
    assert {"cut-1.svg", "cut-1.dxf", "design.json", "report.html"} <= names
    record = json.loads((tmp_path / "out" / "design.json").read_text())
    assert record["design"] == answers[2].payload["design"]


def test_the_solver_subpackage_imports_as_before() -> None:
    import corrugate.workflow as run_module
    from corrugate.solver import Problem, solve

    assert callable(run_module.solve_spec) and callable(solve) and Problem.__name__ == "Problem"
    assert corrugate.solver.solve is solve  # the callable module is still the subpackage


def test_bad_specs_name_what_is_wrong() -> None:
    with pytest.raises(SpecError, match="not valid TOML"):
        corrugate.design("name = [[[\nx = 1")
    with pytest.raises(SpecError, match="cannot be read"):
        corrugate.design("no/such/file.toml")
    with pytest.raises(InputError, match="a path, TOML text or a dict"):
        corrugate.design(42)


@pytest.mark.slow
def test_write_files_writes_for_the_machine_the_spec_was_solved_for(tmp_path: Path) -> None:
    """Without ``cutter``, the files are for the spec's ``[fabrication] machine`` (a Cricut: SVG
    cut files, no DXF), with its fold operations, as ``design --out`` writes them."""
    spec = tomllib.loads(BLIMP.read_text())
    spec["fabrication"] = {"machine": "maker-12x12", "valley": "pen"}
    result = corrugate.design(spec)
    names = {p.name for p in corrugate.write_files(result, tmp_path / "out")}
    assert "cut-1.svg" in names and not any(n.endswith(".dxf") for n in names)
    record = json.loads((tmp_path / "out" / "design.json").read_text())
    assert record["sheets"]["cutter"] == "maker-12x12"
    assert record["fold_operations"]["valley"] == "pen"
