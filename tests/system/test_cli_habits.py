"""Command-line habits (issue 14): shell completion, exit codes in ``--help``, ``--quiet``, real
types in help, plain unwrapped output when piped, ``validate``'s progress and D4 legend, and the
hints where the next step is obvious."""

from __future__ import annotations

import io
import json
import re
from pathlib import Path
from typing import TYPE_CHECKING

import pytest
from rich.console import Console

from corrugate.cli import COMMAND_MODULES, app
from corrugate.spec.examples import example_text

if TYPE_CHECKING:
    from conftest import CliRun

ANALYZE = ["analyze", "--W", "8", "--n", "8", "--alpha", "84", "--material", "dura-lar"]


def _command_names() -> list[str]:
    return [name for module in COMMAND_MODULES for name in module.COMMANDS]


def _spec(tmp_path: Path, name: str) -> Path:
    path = tmp_path / f"{name}.toml"
    path.write_text(example_text(name))
    return path


# --- completion and the root help -------------------------------------------------------------


def test_root_help_offers_completion_and_documents_the_exit_codes(cli: CliRun) -> None:
    code, out, _ = cli(["--help"])
    assert code == 0
    flat = " ".join(out.split())  # the help may wrap; compare words
    assert "--install-completion" in flat and "--show-completion" in flat
    for text in ("0 an answer", "1 no design meets the spec", "2 bad input", "3 a bug"):
        assert text in flat, text


def test_show_completion_prints_a_bash_script(
    capsys: pytest.CaptureFixture[str], monkeypatch: pytest.MonkeyPatch
) -> None:
    # The shell is given, not detected: by default Typer reads it from the parent processes
    # (shellingham), so the test would depend on how pytest was launched (under sh: "Shell sh
    # not supported"). With detection off, --show-completion takes the shell as its value.
    monkeypatch.setenv("_TYPER_COMPLETE_TEST_DISABLE_SHELL_DETECTION", "1")
    with pytest.raises(SystemExit) as info:  # as the console script `corrugate` runs it
        app(args=["--show-completion", "bash"], prog_name="corrugate")
    assert info.value.code in (0, None)
    out = capsys.readouterr().out
    assert "complete -o default -F _corrugate_completion corrugate" in out
    assert "_CORRUGATE_COMPLETE=complete_bash" in out


@pytest.mark.parametrize(
    ("words", "cword", "expected"),
    [
        ("corrugate des", 1, {"design"}),
        ("corrugate analyze --mod", 2, {"--model"}),
        (
            "corrugate docs validation/",
            2,
            {
                "validation/capacity",
                "validation/load_cases",
                "validation/off_axis",
                "validation/ranges",
                "validation/strength",
            },
        ),
        ("corrugate analyze --model", 3, {"paper", "xia", "refined"}),
        ("corrugate analyze --material dura", 3, {"dura-lar"}),
        ("corrugate pattern --cutter maker", 3, {"maker-12x12", "maker-12x24"}),
        ("corrugate validate --support f", 3, {"free", "frame"}),
    ],
)
def test_bash_completion_completes_commands_options_and_values(
    words: str,
    cword: int,
    expected: set[str],
    monkeypatch: pytest.MonkeyPatch,
    capsys: pytest.CaptureFixture[str],
) -> None:
    monkeypatch.setenv("_CORRUGATE_COMPLETE", "complete_bash")
    monkeypatch.setenv("COMP_WORDS", words)
    monkeypatch.setenv("COMP_CWORD", str(cword))
    with pytest.raises(SystemExit) as info:
        app(args=[], prog_name="corrugate")
    assert info.value.code in (0, None)
    assert set(capsys.readouterr().out.split()) == expected


# --- real types in help ---------------------------------------------------------------------------


@pytest.mark.parametrize("command", _command_names())
def test_help_shows_real_types_never_str_or_text(command: str, cli: CliRun) -> None:
    code, out, _ = cli([command, "--help"])
    assert code == 0
    assert "<str>" not in out
    assert not re.search(r"\bTEXT\b", out), out


def test_help_shows_the_quantity_metavars(cli: CliRun, monkeypatch: pytest.MonkeyPatch) -> None:
    monkeypatch.setenv("COLUMNS", "250")  # one row per option
    monkeypatch.setenv("TERMINAL_WIDTH", "250")
    _, out, _ = cli(["analyze", "--help"])
    for metavar in ("LENGTH", "ANGLE", "INTEGER", "MATERIAL", "[paper|xia|refined]"):
        assert metavar in out, metavar


# --- plain, unwrapped output when piped -----------------------------------------------------------


def test_piped_output_keeps_a_long_sentence_on_one_line_without_colour(cli: CliRun) -> None:
    code, out, _ = cli([*ANALYZE, "--model", "paper"])
    assert code == 0
    assert "\x1b[" not in out  # no colour codes in a pipe
    lines = out.splitlines()
    warning = [line for line in lines if line.startswith("warning (paper-model)")]
    assert len(warning) == 1
    # the whole sentence, up to its last words, is on that one line
    assert warning[0].rstrip().endswith("use 'refined' for design")
    mass = [line for line in lines if line.startswith("layout square:")]
    assert len(mass) == 1 and "connectors" in mass[0] and mass[0].rstrip().endswith("g)")
    # the stiffness table's rows are whole: each eta with its four numbers on one line
    row0 = [line for line in lines if re.match(r"^\W*0 \W+ [\d.]+ \W+ [\d.]+", line)]
    assert row0 and len(re.findall(r"[\d.]+", row0[0])) == 5


def test_infeasible_diagnosis_lines_are_whole_and_end_with_a_hint(
    cli: CliRun, tmp_path: Path
) -> None:
    code, out, _ = cli(["design", str(_spec(tmp_path, "infeasible"))])
    assert code == 1
    items = [line for line in out.splitlines() if line.startswith("  - ")]
    assert len(items) >= 2
    for line in items:  # each diagnosis is one line, never broken mid-phrase, ending in its hint
        assert re.search(r"relaxing it alone makes the spec feasible: hint: \S+ = \"[0-9.]+ ", line)
        assert line.rstrip().endswith("%)")
    hint = out.splitlines()[-1]
    # the smallest relative change of the example: the flat blank, 250 -> 252 mm (0.8 %), written
    # as the spec takes it
    assert hint.startswith('hint: the smallest single change is constraints.sheet_max = "252 mm"')
    assert "instead of 250 mm (0.8 %)" in hint


# --- --quiet ----------------------------------------------------------------------------------------


@pytest.mark.slow
def test_design_quiet_prints_nothing_and_writes_the_files(cli: CliRun, tmp_path: Path) -> None:
    out_dir = tmp_path / "out"
    code, out, err = cli(
        ["design", str(_spec(tmp_path, "blimp_gripper")), "--out", str(out_dir), "-q"]
    )
    assert code == 0
    assert out == "" and err == ""
    record = json.loads((out_dir / "design.json").read_text())
    assert record["status"] == "optimal"
    assert list(out_dir.glob("cut-*.dxf"))  # the default cutter's files


def test_design_quiet_infeasible_keeps_exit_1_and_says_why_on_stderr(
    cli: CliRun, tmp_path: Path
) -> None:
    code, out, err = cli(["design", str(_spec(tmp_path, "infeasible")), "--quiet"])
    assert code == 1
    assert out == ""
    assert "infeasible" in err and "hint: the smallest single change" in err


def test_quiet_bad_input_still_one_line_exit_2(cli: CliRun) -> None:
    code, out, err = cli(["analyze", "--W", "-3", "--n", "8", "--alpha", "84", "-q"])
    assert code == 2
    assert out == ""
    assert len(err.strip().splitlines()) == 1 and err.startswith("corrugate: error:")


@pytest.mark.slow
def test_analyze_and_pattern_quiet(cli: CliRun, tmp_path: Path) -> None:
    code, out, err = cli([*ANALYZE, "--quiet"])
    assert (code, out, err) == (0, "", "")
    code, json_out, _ = cli([*ANALYZE, "--quiet", "--json"])  # --json is still printed
    assert code == 0 and json.loads(json_out)["model"] == "refined"
    folder = tmp_path / "pat"
    args = ["pattern", *ANALYZE[1:], "--out", str(folder), "-q"]
    code, out, err = cli(args)
    assert (code, out, err) == (0, "", "")
    record = json.loads((folder / "design.json").read_text())
    assert record["layers"][0]["n"] == 8
    loud_code, loud, _ = cli(["pattern", *ANALYZE[1:], "--out", str(tmp_path / "p2")])
    assert loud_code == 0 and "wrote" in loud  # without --quiet the same command speaks
    assert sorted(p.name for p in folder.iterdir()) == sorted(
        p.name for p in (tmp_path / "p2").iterdir()
    )


# --- tolerance hint -----------------------------------------------------------------------------


def test_tolerance_below_90_percent_points_to_robust(cli: CliRun, tmp_path: Path) -> None:
    spec = str(_spec(tmp_path, "blimp_gripper"))
    code, out, _ = cli(["tolerance", spec, "--samples", "300"])
    assert code == 0
    all_row = [line for line in out.splitlines() if re.match(r"^\W*all\W", line)]
    p_all = float(re.findall(r"([\d.]+) %", all_row[0])[0])
    assert p_all < 90
    hint = [line for line in out.splitlines() if line.startswith("hint:")]
    assert len(hint) == 1 and "[robust]" in hint[0] and "corrugate docs spec" in hint[0]
    # without tolerances the nominal design always meets the spec: no hint
    zero = ["--W-tol", "0", "--alpha-tol", "0", "--t-tol", "0", "--E-tol", "0"]
    code, out, _ = cli(["tolerance", spec, "--samples", "20", *zero])
    assert code == 0 and "100.0 %" in out and "hint:" not in out


# --- validate: progress, D4 legend, --quiet -------------------------------------------------------


def test_d4_legend_under_a_table_with_a_d4_row() -> None:
    from corrugate.cli.validate import D4_LEGEND, _print_result
    from corrugate.fea.validation import Case, CaseResult, closed_forms
    from corrugate.geometry.layer import Assembly, Layer
    from corrugate.materials.library import get_material

    layer = Layer(W=5.0, n=3, alpha_deg=120.0, material=get_material("dura-lar"), t=0.1)
    a = Assembly.identical(layer)
    models = closed_forms(a, (0.0,), "free")
    fe = {k: v for k, v in models["refined"].items() if k.endswith("@0")}
    assert "D4_Nmm@0" in fe
    buffer = io.StringIO()
    _print_result(
        CaseResult(Case("c", a), fe, models, {}, (), False), Console(file=buffer, width=300)
    )
    text = " ".join(buffer.getvalue().split())
    assert "D4(0) N mm" in text
    assert " ".join(D4_LEGEND.split()) in text
    assert "pure" in D4_LEGEND and "4-point" in D4_LEGEND and "corrugate docs fea" in D4_LEGEND
    without = {k: v for k, v in fe.items() if not k.startswith("D4")}
    buffer = io.StringIO()
    _print_result(
        CaseResult(Case("c", a), without, models, {}, (), False), Console(file=buffer, width=300)
    )
    assert "D4:" not in buffer.getvalue()


FE_SMALL = ["validate", "--W", "5", "--n", "3", "--alpha", "120", "--thickness", "0.1"]
FE_SMALL += ["--mesh", "2", "--cell-mesh", "10x1"]


@pytest.mark.fea
def test_validate_prints_a_line_per_calculix_run_on_stderr(ccx: str, cli: CliRun) -> None:
    code, out, err = cli(FE_SMALL)
    assert code == 0
    runs = [line for line in err.splitlines() if line.startswith("CalculiX run ")]
    # the platens, 3-point and 4-point bending of the assembly (each fixture's own label, as
    # verify prints it), then the unit cell
    assert len(runs) == 4, err
    assert "compression between platens" in runs[0] and "3-point bending" in runs[1]
    assert "4-point bending" in runs[2] and "unit cell of layer 1" in runs[3]
    assert "D4(0) N mm" in out and "D4: the bending stiffness from a 4-point" in out
    code, quiet_out, quiet_err = cli([*FE_SMALL, "--quiet"])
    assert (code, quiet_out, quiet_err) == (0, "", "")


def test_pareto_and_tolerance_quiet(cli: CliRun, tmp_path: Path) -> None:
    """--quiet on the last two commands that print: nothing on stdout or stderr, pareto's files
    still written (the same as without it), --json still printed, exit codes unchanged."""
    spec = str(_spec(tmp_path, "blimp_gripper"))
    quiet_dir, loud_dir = tmp_path / "pq", tmp_path / "pl"
    args = ["pareto", spec, "--vs", "flexural_rigidity", "--max-points", "5"]
    code, out, err = cli([*args, "--out", str(quiet_dir), "-q"])
    assert (code, out, err) == (0, "", "")
    loud_code, loud_out, loud_err = cli([*args, "--out", str(loud_dir)])
    assert loud_code == 0 and "wrote" in loud_out + loud_err
    assert (quiet_dir / "pareto.csv").read_text() == (loud_dir / "pareto.csv").read_text()
    code, csv_text, err = cli([*args, "-q"])  # no --out: the CSV on stdout is the answer
    assert code == 0 and err == "" and csv_text == (loud_dir / "pareto.csv").read_text()
    code, out, err = cli(["tolerance", spec, "--samples", "50", "-q"])
    assert (code, out, err) == (0, "", "")
    code, out, _ = cli(["tolerance", spec, "--samples", "50", "-q", "--json"])
    assert code == 0 and 0.0 <= json.loads(out)["probability_all_met"] <= 1.0
