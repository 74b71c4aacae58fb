"""The command line's progress on stderr (:mod:`corrugate.cli.progress`, issue 36 item 3): the
stages a solve goes through (searching; explaining: binding checks, runner-ups, diagnosis) reach
stderr as plain lines off a terminal and as a status line on one, stdout keeps the answer alone,
and ``--quiet`` or ``--json`` (off a terminal) print none.

The stages a solve must go through are those of docs/theory.md section 5: a feasible spec is
searched, then its binding checks and runner-ups are explained; an infeasible one is searched
(the proof that no design exists) and then diagnosed."""

from __future__ import annotations

import io
import json
import math
from pathlib import Path
from typing import TYPE_CHECKING

import pytest
from rich.console import Console

from corrugate.cli import progress
from corrugate.solver.progress import BINDING, DIAGNOSIS, RUNNER_UPS, SEARCHING, reporting, stage

if TYPE_CHECKING:
    from conftest import CliRun

EXAMPLES = Path(__file__).resolve().parents[2] / "examples"


@pytest.fixture
def eager(monkeypatch: pytest.MonkeyPatch) -> None:
    """Progress from the first instant, one line per stage (the examples solve in about a
    second: the thresholds of a real run would make the test depend on the machine's speed)."""
    monkeypatch.setattr(progress, "START_AFTER_S", 0.0)
    monkeypatch.setattr(progress, "PLAIN_INTERVAL_S", math.inf)


def _lines(err: str) -> list[str]:
    return [line for line in err.splitlines() if line.startswith("corrugate: ")]


def test_an_infeasible_spec_shows_its_search_then_its_diagnosis_on_stderr(
    cli: CliRun, eager: None
) -> None:
    code, out, err = cli(["design", str(EXAMPLES / "infeasible.toml")])
    assert code == 1
    lines = _lines(err)
    assert lines[0].startswith("corrugate: searching")
    assert any(line.startswith(f"corrugate: {DIAGNOSIS} (constraints.") for line in lines)
    # the search comes before its explanation, and each line says for how long it has run
    first_diag = next(i for i, line in enumerate(lines) if DIAGNOSIS in line)
    assert all(SEARCHING in line for line in lines[:first_diag])
    assert all(" s" in line.split(": ", 2)[-1] for line in lines)
    # stdout is the answer alone
    assert out.startswith("blimp-gripper-too-stiff: infeasible") and "corrugate: " not in out


def test_a_feasible_spec_explains_binding_checks_then_runner_ups(
    cli: CliRun, eager: None, monkeypatch: pytest.MonkeyPatch
) -> None:
    monkeypatch.setattr(progress, "PLAIN_INTERVAL_S", 0.0)  # a line at every iteration
    code, out, err = cli(["design", str(EXAMPLES / "blimp_gripper_continuous.toml")])
    assert code == 0
    text = "\n".join(_lines(err))
    assert text.index(SEARCHING) < text.index(BINDING) < text.index(RUNNER_UPS)
    # once the search has a design its line carries the gap and the best mass found
    found = [line for line in _lines(err) if line.startswith("corrugate: searching:")]
    assert found and all(", best " in line and line.endswith(" g") for line in found)
    assert out.startswith("blimp-gripper-continuous: optimal") and "corrugate: " not in out


def test_quiet_and_json_print_no_progress(cli: CliRun, eager: None) -> None:
    code, _, err = cli(["design", str(EXAMPLES / "infeasible.toml"), "-q"])
    assert code == 1 and not _lines(err) and "infeasible" in err  # only why the code is 1
    code, out, err = cli(["design", str(EXAMPLES / "infeasible.toml"), "--json"])
    assert code == 1 and not _lines(err)  # stderr is not a terminal here
    assert json.loads(out)["status"] == "infeasible"


def test_on_a_terminal_one_status_line_refreshes_and_is_removed() -> None:
    """The forced-terminal case: a rich status line (a spinner) with the stage and the search's
    numbers, drawn on the terminal and erased at the end (transient), never a plain line."""
    buf = io.StringIO()
    console = Console(file=buf, force_terminal=True, width=200)
    shown = progress.SolveProgress(console, live=True, unit="g")
    shown.t0 -= 10  # as if the solve had run 10 s
    with reporting(shown, shown.on_stage):
        stage(SEARCHING)
        shown(1, math.inf, None)
        shown(2, 0.25, 2.5)
        stage(DIAGNOSIS, "constraints.side.max")
    assert shown.text().startswith(
        f"{DIAGNOSIS} (constraints.side.max): 10 s, 2 iterations in 1 run"
    )
    shown.stop()
    drawn = buf.getvalue()
    assert "\x1b[" in drawn  # terminal control: the line is redrawn in place
    assert "corrugate: " not in drawn  # no plain lines on a terminal
    # after stop (the FE step prints its own lines) nothing more is drawn
    size = len(buf.getvalue())
    shown(3, 0.1, 2.4)
    assert len(buf.getvalue()) == size


def test_the_search_line_reads_gap_and_best_in_the_objective_unit() -> None:
    """A hand-made state: 1 run of 40 iterations, gap 0.5 %, best 2.162 g."""
    shown = progress.SolveProgress(Console(file=io.StringIO()), live=False, unit="g")
    for it in range(1, 41):
        shown(it, 0.005, 2.162)
    assert ", 40 iterations in 1 run, gap 0.5 %, best 2.162 g" in shown.text()
    fresh = progress.SolveProgress(Console(file=io.StringIO()), live=False, unit="g")
    fresh(1, math.inf, None)
    assert fresh.text().startswith("searching (no design found yet: proving infeasible")
