"""``corrugate verify``'s bad input (exit 2, one line naming it), before any CalculiX run."""

from __future__ import annotations

import json
from pathlib import Path
from typing import TYPE_CHECKING

import pytest

from corrugate.spec.examples import example_text

if TYPE_CHECKING:
    from conftest import CliRun


def _one_error_line(err: str, *words: str) -> None:
    lines = err.strip().splitlines()
    assert len(lines) == 1, err
    assert lines[0].startswith("corrugate: error:"), err
    for w in words:
        assert w in lines[0], (w, err)


def test_missing_folder_and_missing_or_garbled_design_json(cli: CliRun, tmp_path: Path) -> None:
    code, _, err = cli(["verify", str(tmp_path / "nowhere")])
    assert code == 2
    _one_error_line(err, "nowhere")
    code, _, err = cli(["verify", str(tmp_path)])
    assert code == 2
    _one_error_line(err, "design.json")
    (tmp_path / "design.json").write_text("{not json")
    code, _, err = cli(["verify", str(tmp_path)])
    assert code == 2
    _one_error_line(err, "design.json")


@pytest.fixture(scope="module")
def square(tmp_path_factory: pytest.TempPathFactory) -> Path:
    from corrugate.cli import main

    folder = tmp_path_factory.mktemp("verify-square")
    spec = folder / "blimp_gripper.toml"
    spec.write_text(example_text("blimp_gripper"))
    with pytest.raises(SystemExit) as info:
        main(["design", str(spec), "--out", str(folder / "d"), "-q"])
    assert info.value.code in (0, None)
    return folder / "d"


def test_garbled_constraints_and_bad_meshes(cli: CliRun, square: Path, tmp_path: Path) -> None:
    import shutil

    for mesh in ("3", "2,x", "4,2", "0"):
        code, _, err = cli(["verify", str(square), "--mesh", mesh])
        assert code == 2, mesh
        _one_error_line(err, "mesh")
    folder = tmp_path / "garbled"
    shutil.copytree(square, folder)
    record = json.loads((folder / "design.json").read_text())
    record["constraints"] = "EI"
    (folder / "design.json").write_text(json.dumps(record))
    code, _, err = cli(["verify", str(folder)])
    assert code == 2
    _one_error_line(err, "constraints")


def test_a_folder_that_cannot_be_written_is_refused(
    cli: CliRun, square: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    import corrugate.cli.verify as verify

    monkeypatch.setattr(verify, "_writable", lambda folder: False)
    code, _, err = cli(["verify", str(square)])
    assert code == 2
    _one_error_line(err, "DIR", "not writable")
    assert not (square / "verify.json").exists()


def test_missing_calculix_is_one_line(
    cli: CliRun, square: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    monkeypatch.setenv("PATH", "")
    monkeypatch.delenv("CORRUGATE_CCX", raising=False)
    code, _, err = cli(["verify", str(square)])
    assert code == 2
    _one_error_line(err, "ccx")
    assert not (square / "verify.json").exists()


def test_the_folder_of_an_infeasible_spec_holds_no_design(
    cli: CliRun, tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    from corrugate.cli import main

    spec = tmp_path / "infeasible.toml"
    spec.write_text(example_text("infeasible"))
    with pytest.raises(SystemExit):
        main(["design", str(spec), "--out", str(tmp_path / "x"), "-q"])
    capsys.readouterr()  # the design's diagnosis
    assert json.loads((tmp_path / "x" / "design.json").read_text())["design"] is None
    code, _, err = cli(["verify", str(tmp_path / "x")])
    assert code == 2
    _one_error_line(err, "holds no design", "infeasible")


def test_a_malformed_constraint_is_refused_before_any_run(
    cli: CliRun, square: Path, tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    """A bound that is not a number, or an unknown quantity key: exit 2, one line, no run."""
    import shutil

    # verify looks for ccx before it reads the constraints: a stand-in that leaves a mark if it
    # is ever run, so the test holds on a machine without CalculiX (make test-fast) too
    ran = tmp_path / "ccx-ran"
    stub = tmp_path / "ccx"
    stub.write_text(f"#!/bin/sh\n: > {ran}\nexit 1\n")
    stub.chmod(0o755)
    monkeypatch.setenv("CORRUGATE_CCX", str(stub))
    for change, word in ((("bound", "x"), "bound"), (("quantity", "EQ@0"), "quantity")):
        folder = tmp_path / word
        shutil.copytree(square, folder)
        record = json.loads((folder / "design.json").read_text())
        for c in record["constraints"]:
            if c["quantity"] == "EI@0":
                c[change[0]] = change[1]
        (folder / "design.json").write_text(json.dumps(record))
        code, _, err = cli(["verify", str(folder)])
        assert code == 2
        _one_error_line(err, word)
        assert "CalculiX run" not in err
        assert not ran.exists()


def test_an_extended_series_says_at_which_meshes() -> None:
    """A row whose series ran past the requested meshes shows them beside its values, and its
    reason in the estimate column; a row on the requested meshes shows none."""
    from io import StringIO

    from rich.console import Console

    from corrugate.cli.verify import print_table
    from corrugate.fea.verify import Row, Verification

    why = "extended to 16 per facet at shift 0.25 (reason)"
    rows = (
        Row(
            "k",
            "K@45",
            "min",
            "N/mm",
            1.0,
            1.0027,
            {2: 2.0, 4: 1.3, 8: 1.1, 16: 1.03},
            0.97,
            note=why,
            extended=why,
            shift=0.25,
        ),
        Row(
            "ei",
            "EI@0",
            "min",
            "N*mm^2",
            8e4,
            8.6e4,
            {2: None, 4: 8.55e4, 8: 8.59e4},
            8.59e4,
            holds=True,
        ),
    )
    out = StringIO()
    print_table(Verification(rows, (2, 4, 8), (0.25,)), "d", Console(file=out, width=400))
    text = out.getvalue()
    assert "1.03 (at 2 / 4 / 8 / 16)" in text and why in text
    assert text.count("(at ") == 1


def test_the_first_failure_table_states_each_load_case_against_its_load() -> None:
    """The rows below the constraints' table: the load case, its constraints, the load they are
    certified under and the FE first failure in words; a load above the FE estimate says NO,
    a stiffness bound (no load) says neither; no rows, no table."""
    from io import StringIO

    from rich.console import Console

    from corrugate.cli.verify import print_failures
    from corrugate.fea.first_failure import FailureRow

    rows = (
        FailureRow(
            "buckling in 3-point bending", "buckling", ("d",), 10.0, {2: 1.58}, 1.58, model=0.51
        ),
        FailureRow("3-point bending", "yield", ("k",), None, {2: 40.0, 4: 30.0}, 30.0),
        FailureRow(
            "cantilever",
            "buckling",
            ("c",),
            5.0,
            {2: 9.0, 4: 8.0, 8: 7.9},
            7.87,
            verdict="not converged",
        ),
    )
    buf = StringIO()
    print_failures(rows, Console(file=buf, width=300, no_color=True))
    text = buf.getvalue()
    assert "first buckling at 1.58 N (series 1.58)" in text
    assert "first yield at 30 N (series 40 / 30)" in text
    lines = [ln for ln in text.splitlines() if "first " in ln and "N (series" in ln]
    cells = [[c.strip() for c in ln.strip(" │").split("│")] for ln in lines]
    assert cells[0][-2:] == ["NO", "0.51 N: yes"] and cells[1][-2:] == ["-", "-"]
    # above the load at every mesh, but not shown asymptotic (corrugate.fea.extrapolate.judge)
    assert cells[2][-2:] == ["not converged", "-"]
    empty = StringIO()
    print_failures((), Console(file=empty))
    assert empty.getvalue() == ""


@pytest.mark.parametrize(
    ("case", "code", "verdict"),
    [
        ("holds", 0, "every constraint holds in FE"),
        ("fails", 1, "not every constraint holds in FE (exit 1)"),
        ("turns", 5, "not every FE series converged: not shown to hold (exit 5)"),
        ("no-twin", 6, "the others are not checked by FE"),
    ],
)
def test_each_verdict_has_its_exit_code(
    cli: CliRun,
    square: Path,
    tmp_path: Path,
    monkeypatch: pytest.MonkeyPatch,
    case: str,
    code: int,
    verdict: str,
) -> None:
    """docs/fea.md 6: verify exits with its worst row's verdict: 0 holds, 1 fails, 5 not
    converged, 6 not checked. A stand-in for CalculiX gives EI(0) (pure bending) per mesh:
    'holds' and 'fails' the exact series 2e5 (1 + 1 / mesh), whose extrapolations are 2e5 at
    2 / 4 / 8 / 16, against a minimum of 1e5 (holds) or 3e5 (fails from 2 / 4 / 8: below it and
    softening); 'turns' a series that never settles (refined to 16 and left not converged);
    'no-twin' adds EI(30), which has no FE twin, beside the EI(0) that holds."""
    import shutil
    from types import SimpleNamespace

    from corrugate.fea import verify

    stub = tmp_path / "ccx"
    stub.write_text("#!/bin/sh\nexit 1\n")
    stub.chmod(0o755)
    monkeypatch.setenv("CORRUGATE_CCX", str(stub))
    turning = {2: 2.0e5, 4: 1.8e5, 8: 1.9e5, 16: 1.85e5}
    alongs: list[int] = []

    def fake(assembly, test, mesh, eta, **kw):  # type: ignore[no-untyped-def]
        alongs.append(mesh.along)
        ei = turning[mesh.along] if case == "turns" else 2.0e5 * (1 + 1 / mesh.along)
        return SimpleNamespace(EI=ei)

    monkeypatch.setattr(verify, "solve_assembly", fake)
    folder = tmp_path / case
    shutil.copytree(square, folder)
    record = json.loads((folder / "design.json").read_text())
    ei = {"name": "ei0", "quantity": "EI@0", "sense": "min", "unit": "N*mm^2", "value": 2e5}
    rows = [{**ei, "bound": 3e5 if case == "fails" else 1e5}]
    if case == "no-twin":
        rows.append({**ei, "name": "ei30", "quantity": "EI@30", "bound": 1e5})
    record["constraints"] = rows
    (folder / "design.json").write_text(json.dumps(record))
    got, out, _ = cli(["verify", str(folder), "--no-first-failure"])
    assert got == code, out
    assert verdict in " ".join(out.split())
    got, out, _ = cli(["verify", str(folder), "--no-first-failure", "--json"])
    result = json.loads(out)
    assert got == code
    names = {0: "holds", 1: "fails", 5: "not converged", 6: "not checked"}
    assert result["verdict"] == names[code] and result["holds"] == (code == 0)
    assert max(alongs) == (8 if case == "fails" else 16)


def test_the_help_states_the_verdicts_exit_codes() -> None:
    """``corrugate --help``'s exit codes (written without importing the FE) name verify's."""
    from corrugate.cli import EXIT_CODES as HELP
    from corrugate.fea.verify import EXIT_CODES

    text = " ".join(HELP.split())
    assert EXIT_CODES == {"fails": 1, "not converged": 5, "not checked": 6, "holds": 0}
    assert (
        "5 (verify, design --verify fe) no constraint fails in FE but one is not converged" in text
    )
    assert "6 (verify, design --verify fe) every constraint with an FE twin holds" in text
    assert "(not checked)" in text


def test_an_old_design_json_of_an_inline_material_is_one_line(
    cli: CliRun, square: Path, tmp_path: Path
) -> None:
    """A design.json written before issue 35 (no material_properties) still verifies where it
    names a library material; where it names an inline one, exit 2 with one line naming
    layers[0].material and how to write it again (no CalculiX needed: it stops before)."""
    import shutil

    folder = tmp_path / "old"
    shutil.copytree(square, folder)
    record = json.loads((folder / "design.json").read_text())
    assert all("material_properties" in lay for lay in record["layers"])
    for lay in record["layers"]:
        del lay["material_properties"]
        lay["material"] = "PET (generic)"
    (folder / "design.json").write_text(json.dumps(record))
    code, _, err = cli(["verify", str(folder)])
    assert code == 2
    _one_error_line(err, "layers[0].material", "PET (generic)", "corrugate design SPEC --out DIR")


def test_jobs_and_scheduler_are_checked_before_any_run(cli: CliRun, square: Path) -> None:
    """``--jobs N`` (a local pool) and ``--scheduler ADDRESS`` (a dask cluster; docs/fea.md 4.1):
    a number of jobs outside its limits, or both options at once, is one line naming the option
    (exit 2) before the design is read or CalculiX looked for."""
    for jobs in ("0", "-1"):
        code, _, err = cli(["verify", str(square), "--jobs", jobs])
        assert code == 2, jobs
        _one_error_line(err, "jobs")
    code, _, err = cli(["verify", str(square), "--jobs", "2", "--scheduler", "tcp://127.0.0.1:1"])
    assert code == 2
    _one_error_line(err, "--jobs", "not both")


@pytest.mark.parametrize(
    ("workdir", "reason"),
    [
        ("/proc/corrugate-work", "No such file or directory"),  # /proc takes no folder
        ("a" * 300, "File name too long"),  # NAME_MAX is 255
        ("afile/work", "Not a directory"),  # under a file
    ],
)
def test_a_workdir_that_cannot_be_made_is_one_line_naming_it_before_any_run(
    cli: CliRun,
    square: Path,
    tmp_path: Path,
    monkeypatch: pytest.MonkeyPatch,
    workdir: str,
    reason: str,
) -> None:
    """The work folder was first made by the first CalculiX run: the OS error named no option
    ("/proc/corrugate-work cannot be used (No such file or directory)"), after the mesh was
    built; verify and validate now make it with their other checks."""
    monkeypatch.chdir(tmp_path)
    (tmp_path / "afile").write_text("")
    for args in (
        ["verify", str(square)],
        ["validate", "--W", "8", "--n", "8", "--alpha", "84", "--no-pure-bending"],
    ):
        code, _, err = cli([*args, "--workdir", workdir])
        assert code == 2, (args, err)
        _one_error_line(err, "error: workdir = ", f"cannot be made ({reason})")
