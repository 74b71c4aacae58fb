"""One request, one run (:mod:`corrugate.workflow.steps`): ``corrugate design`` and the web app's
design job both read their input into a :class:`~corrugate.workflow.request.DesignRequest` and
call :func:`corrugate.workflow.run`; the ``--refine`` loop runs inside it, typed; the files
step's errors are named as the boundary names them.

The spec is the small Dura-Lar square of tests/fea/test_refine.py (one behavioural bound,
EI(0) >= 10 mN m^2); without CalculiX, the FE is a stand-in whose ratio to the model is known, so
the corrected bound is stated by hand (docs/fea.md 6: b' = B x model / FE).
"""

from __future__ import annotations

import json
from pathlib import Path
from typing import TYPE_CHECKING, Any

import pytest

from corrugate import names
from corrugate.core.errors import InputError
from corrugate.export.machines import get_machine
from corrugate.fabrication.sheets import PartTooLargeError
from corrugate.fea.verify import Row, Verification
from corrugate.solver.problem import Problem
from corrugate.solver.solve import ConstraintReport
from corrugate.spec.schema import parse_spec_text
from corrugate.workflow import (
    DesignRequest,
    FeOptions,
    Names,
    Output,
    Run,
    output_options,
    run,
)

if TYPE_CHECKING:
    from conftest import CliRun

SPEC = """
name = "request-small"

[material]
name = "dura-lar"
thickness = "0.125 mm"

[layout]
shape = "square"

[variables]
W = { min = "4 mm", max = "8 mm", step = "1 mm" }
n = { min = 6, max = 9 }  # from 7 facets: the springs' validated range (docs/validation/ranges.md)
alpha = { min = "60 deg", max = "120 deg", step = "1 deg" }

[constraints]
side = { min = "20 mm", max = "30 mm" }
flexural_rigidity = [{ min = "10 mN*m^2", eta = "0 deg" }]

[objective]
minimize = "mass"
"""
NAME = "constraints.flexural_rigidity[0].min"
B = 10_000.0  # N mm^2: 10 mN m^2


def _request(**kwargs: Any) -> DesignRequest:
    spec = parse_spec_text(SPEC)
    return DesignRequest(spec, SPEC, Problem.from_spec(spec), get_machine(), **kwargs)


def _recording(monkeypatch: pytest.MonkeyPatch, target: str) -> list[DesignRequest]:
    """Replace ``run`` at ``target`` (module, name) by a wrapper that records each request."""
    import importlib

    seen: list[DesignRequest] = []
    module_name, attr = target.rsplit(".", 1)
    module = importlib.import_module(module_name)

    def recording(request: DesignRequest, events: Any = None) -> Run:
        seen.append(request)
        return run(request, events)

    monkeypatch.setattr(module, attr, recording)
    return seen


def test_corrugate_design_reads_one_request_and_calls_the_run(
    cli: CliRun, tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    seen = _recording(monkeypatch, "corrugate.workflow.run")
    spec = tmp_path / "s.toml"
    spec.write_text(SPEC)
    code, out, _ = cli(["design", str(spec), "--json", "--machine", "maker-12x12"])
    assert code == 0
    [request] = seen
    # the machine given on the command line, resolved once into its profile (a Cricut: SVG)
    assert request.machine == get_machine("maker-12x12") and request.machine.formats == ("svg",)
    assert request.spec.fabrication.machine == "maker-12x12"
    assert request.output is None and request.fe is None and not request.strict_json
    assert json.loads(out)["constraints"]  # the answer printed is the run's
    # without --machine: the default machine (the spec has no [fabrication] machine)
    code, _, _ = cli(["design", str(spec), "--json"])
    assert code == 0 and seen[1].machine.name == names.DEFAULT_MACHINE


@pytest.mark.slow
def test_the_web_design_job_reads_one_request_and_calls_the_run(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    import tomllib

    from corrugate.web import WebSettings
    from corrugate.web.app import design_job
    from corrugate.web.ondemand import design_files_job
    from corrugate.web.schemas import DesignBody

    seen = _recording(monkeypatch, "corrugate.web.app.run")
    body = DesignBody.model_validate({**tomllib.loads(SPEC), "cutter": "laser:200x200"})
    folder = tmp_path / "result"
    folder.mkdir()
    payload, recipe = design_job(body, WebSettings())  # what a worker process runs
    [request] = seen
    assert request.machine.name == "laser:200x200" and request.strict_json
    assert request.output is None  # answers first: the files are made on demand
    assert recipe is not None and not any(folder.iterdir())
    paths = design_files_job(recipe, folder)  # what a worker runs when the page asks for them
    assert {p.name for p in paths} >= {"design.json", "cut-1.svg", "cut-1.dxf"}  # a laser's
    assert json.loads((folder / "design.json").read_text())["design"] == payload["design"]


def _stand_in_fe(ratio: float) -> tuple[Any, list[list[ConstraintReport]]]:
    """``verify_design`` with the EI row's FE ``ratio`` x the model value, judged against the
    bound its constraint reports give it (the spec's)."""
    seen: list[list[ConstraintReport]] = []

    def verify_design(assembly: Any, constraints: Any, *args: Any, **kwargs: Any) -> Verification:
        rows = list(constraints)
        assert all(isinstance(c, ConstraintReport) for c in rows)  # typed values, not JSON
        seen.append(rows)
        [c] = [c for c in rows if c.name == NAME]
        fe = ratio * c.value
        holds = fe >= c.bound
        row = Row(NAME, "EI@0", "min", c.unit, c.bound, c.value, {4: fe}, fe, holds=holds)
        return Verification((row,), (2, 4))

    return verify_design, seen


@pytest.mark.slow
def test_the_refine_loop_runs_inside_the_run_typed(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    """FE = 0.8 x model: the spec's own design misses B in FE; the loop corrects the bound to
    B x model / FE = B / 0.8 = 12500 N mm^2 (by hand), re-solves, and the answer (a design whose
    stand-in FE meets B) is the chosen attempt's own run, with verify.json beside its files."""
    import corrugate.fea.verify as fe_verify

    stand_in, seen = _stand_in_fe(0.8)
    monkeypatch.setattr(fe_verify, "verify_design", stand_in)
    out = tmp_path / "out"
    request = _request(
        output=Output(out, output_options()), fe=FeOptions((2, 4), (0.0,), refine=True)
    )
    answer = run(request)
    assert answer.fe is not None and answer.fe.refined is not None
    refined = answer.fe.refined
    first = refined.attempts[0]
    assert first.verification is not None and not first.verification.holds
    assert refined.attempts[1].bounds[NAME] == pytest.approx(B / 0.8)
    assert refined.chosen is not None and refined.chosen >= 1
    # the answer is the chosen attempt's run itself (no look-up by identity)
    assert answer.solution is refined.answer.run.solution is refined.answer.solution
    [c] = [c for c in answer.payload["constraints"] if c["name"] == NAME]
    assert c["bound"] == pytest.approx(B) and c["model_bound"] == pytest.approx(B / 0.8)
    assert 0.8 * c["value"] >= B  # the stand-in FE of the answer meets the spec's bound
    # every FE check judged against the spec's bound, never the corrected one
    assert all(next(r for r in rows if r.name == NAME).bound == pytest.approx(B) for rows in seen)
    assert answer.payload["refine"]["verified"] is True and answer.fe.holds
    assert out / "verify.json" in answer.files and out / "design.json" in answer.files
    written = json.loads((out / "verify.json").read_text())
    assert written["holds"] is True and written["meshes"] == [2, 4]
    record = json.loads((out / "design.json").read_text())
    assert record["refine"]["chosen"] == refined.chosen


def test_without_refine_the_fe_check_is_the_spec_designs(monkeypatch: pytest.MonkeyPatch) -> None:
    import corrugate.fea.verify as fe_verify

    stand_in, seen = _stand_in_fe(1.5)
    monkeypatch.setattr(fe_verify, "verify_design", stand_in)
    answer = run(_request(fe=FeOptions((2, 4), (0.0,), refine=False)))
    assert answer.fe is not None and answer.fe.refined is None and answer.fe.holds
    assert len(seen) == 1 and answer.files == ()
    assert answer.payload["verification"]["holds"] is True
    assert "refine" not in answer.payload


def test_the_files_steps_errors_take_the_boundarys_names(tmp_path: Path) -> None:
    """The square's side is at least 20 mm (the spec): its layers cannot fit the 15 x 15 mm a
    25 x 25 mm bed leaves inside its 5 mm margin.
    The command line's names keep the part's own error; the web's blame its ``cutter``."""
    small = get_machine("laser:25x25")
    options = output_options(small)
    with pytest.raises(PartTooLargeError):
        run(_request(output=Output(tmp_path / "cli", options)))
    with pytest.raises(InputError, match=r"^cutter = 'laser:25x25' is too small for") as caught:
        run(
            DesignRequest(
                **{
                    **_request().__dict__,
                    "machine": small,
                    "output": Output(tmp_path / "web", options),
                    "names": Names(machine="cutter", cut="cut", gap="gap"),
                }
            )
        )
    assert caught.value.field == "cutter"
    assert not (tmp_path / "cli").exists() or not any((tmp_path / "cli").iterdir())


@pytest.mark.slow
def test_the_answer_is_told_before_the_files_are_written(tmp_path: Path) -> None:
    """``Events.answered`` hears the final answer once, while the output folder holds no file
    yet (issue 39: ``corrugate design`` prints it before the slow files); the run then writes
    the whole set, ``design.json`` listing every file."""
    from corrugate.workflow import Events

    out = tmp_path / "out"
    heard: list[tuple[Run, list[str]]] = []

    def answered(answer: Run) -> None:
        present = sorted(p.name for p in out.iterdir()) if out.exists() else []
        heard.append((answer, present))

    done = run(_request(output=Output(out, output_options())), Events(answered=answered))
    assert len(heard) == 1
    told, present = heard[0]
    assert present == [] and told.files == ()  # nothing of the set on disk yet
    assert told.solution is done.solution and told.payload == done.payload
    record = json.loads((out / "design.json").read_text(encoding="utf-8"))
    assert sorted(record["files"]) == sorted(p.name for p in done.files)
    assert "report.html" in record["files"]


def test_a_part_too_large_is_an_error_before_the_answer_is_told(tmp_path: Path) -> None:
    """The sheet plan is made before the answer is told: a part too large for the machine (the
    square of at least 20 mm on a 25 x 25 mm bed with 5 mm margins) stops the run with nothing
    told and nothing written."""
    from corrugate.workflow import Events

    heard: list[Run] = []
    options = output_options(get_machine("laser:25x25"))
    with pytest.raises(PartTooLargeError):
        run(_request(output=Output(tmp_path / "cli", options)), Events(answered=heard.append))
    assert heard == []
    assert not (tmp_path / "cli").exists() or not any((tmp_path / "cli").iterdir())


def test_without_files_the_answer_is_told_once() -> None:
    from corrugate.workflow import Events

    heard: list[Run] = []
    done = run(_request(), Events(answered=heard.append))
    assert len(heard) == 1 and heard[0].solution is done.solution and done.files == ()
