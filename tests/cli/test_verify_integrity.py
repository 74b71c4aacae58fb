"""A folder never pairs one design with another design's verdict, and ``corrugate verify`` trusts
nothing it reads (issue 37, items 1, 3 and 4; docs/fea.md section 6).

CalculiX is a stand-in (``CORRUGATE_CCX`` a script that leaves a mark if it is ever run) and the
FE runs are replaced by a function returning EI(0) = 2e5 (1 + 1/mesh) N mm^2, whose extrapolation
is 2e5 against the blimp gripper's minimum of 8e4 (holds: exit 0), as in test_verify.py.
"""

from __future__ import annotations

import hashlib
import json
import os
import resource
import shutil
import signal
import subprocess
import sys
import time
from pathlib import Path
from types import SimpleNamespace
from typing import TYPE_CHECKING, Any

import pytest

import corrugate
from corrugate.core.fileio import MANIFEST, read_manifest, recover
from corrugate.spec.examples import example_text

if TYPE_CHECKING:
    from conftest import CliRun

SRC = Path(corrugate.__file__).resolve().parents[1]


def _one_error_line(err: str, *words: str) -> str:
    lines = err.strip().splitlines()
    assert len(lines) == 1, err
    assert lines[0].startswith("corrugate: error:"), err
    for w in words:
        assert w in lines[0], (w, err)
    return lines[0]


def _spec(tmp: Path, name: str, side_min: str) -> Path:
    """The blimp gripper's spec with another lower bound on the side (another design)."""
    text = example_text("blimp_gripper").replace('min = "48 mm"', f'min = "{side_min}"')
    path = tmp / f"{name}.toml"
    path.write_text(text)
    return path


@pytest.fixture(scope="module")
def specs(tmp_path_factory: pytest.TempPathFactory) -> tuple[Path, Path]:
    tmp = tmp_path_factory.mktemp("specs")
    return _spec(tmp, "a", "48 mm"), _spec(tmp, "b", "56 mm")


@pytest.fixture
def stub_fe(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> list[int]:
    """A CalculiX stand-in and FE runs replaced by EI(0) = 2e5 (1 + 1/mesh); returns the meshes
    run (each run appended), so a test can hook into a run or see that none was made."""
    from corrugate.fea import verify

    stub = tmp_path / "ccx"
    stub.write_text(f"#!/bin/sh\n: > {tmp_path / 'ccx-ran'}\nexit 1\n")
    stub.chmod(0o755)
    monkeypatch.setenv("CORRUGATE_CCX", str(stub))
    meshes: list[int] = []

    def fake(assembly, test, mesh, eta, **kw):  # type: ignore[no-untyped-def]
        meshes.append(mesh.along)
        return SimpleNamespace(EI=2.0e5 * (1 + 1 / mesh.along))

    monkeypatch.setattr(verify, "solve_assembly", fake)
    return meshes


def _design(cli: CliRun, spec: Path, out: Path) -> None:
    code, _, err = cli(["design", str(spec), "--out", str(out), "-q"])
    assert code == 0, err


def _sha(path: Path) -> str:
    return hashlib.sha256(path.read_bytes()).hexdigest()


def _layers(folder: Path) -> list[tuple[float, int, float]]:
    d = json.loads((folder / "design.json").read_text())
    return [(x["W_mm"], x["n"], x["alpha_deg"]) for x in d["layers"]]


def test_verify_json_names_its_design_and_a_new_design_drops_it(
    cli: CliRun, specs: tuple[Path, Path], tmp_path: Path, stub_fe: list[int]
) -> None:
    """design A, verify, design B into one folder: verify.json named A's design.json by its
    SHA-256 (computed here from the file's bytes); after B's commit there is no verify.json and
    the manifest lists the design set only."""
    out = tmp_path / "X"
    _design(cli, specs[0], out)
    code, _, err = cli(["verify", str(out), "--no-first-failure", "-q"])
    assert code == 0, err
    verdict = json.loads((out / "verify.json").read_text())
    assert verdict["design_sha256"] == _sha(out / "design.json")
    assert verdict["holds"] is True
    assert read_manifest(out)["verify"]["requires"] == {"design.json": _sha(out / "design.json")}
    a = _layers(out)
    _design(cli, specs[1], out)
    assert _layers(out) != a  # another design
    assert not (out / "verify.json").exists()
    assert set(read_manifest(out)) == {"design"}
    assert "verify" not in json.loads((out / MANIFEST).read_text())["sets"]
    # the same design written again keeps nothing stale either: a new verify names the new file
    code, _, err = cli(["verify", str(out), "--no-first-failure", "-q"])
    assert code == 0, err
    assert json.loads((out / "verify.json").read_text())["design_sha256"] == _sha(
        out / "design.json"
    )


def _child_env() -> dict[str, str]:
    env = dict(os.environ)
    env["PYTHONPATH"] = str(SRC)
    env["OPENBLAS_NUM_THREADS"] = env["OMP_NUM_THREADS"] = "1"
    return env


def test_a_verify_running_while_another_design_commits_drops_its_result(
    cli: CliRun,
    specs: tuple[Path, Path],
    tmp_path: Path,
    stub_fe: list[int],
    monkeypatch: pytest.MonkeyPatch,
) -> None:
    """The race of issue 37: while verify's first FE run is under way, another process commits
    design B into the folder (``corrugate design`` in a subprocess, waited for). verify then
    drops its result (exit 2, one line naming design.json): no verify.json, the manifest lists
    B's design only, and recover() finds nothing to undo."""
    from corrugate.fea import verify

    out = tmp_path / "X"
    _design(cli, specs[0], out)
    a = _layers(out)
    inner = verify.solve_assembly

    def racing(*args, **kw):  # type: ignore[no-untyped-def]
        if len(stub_fe) == 0:
            done = subprocess.run(
                [sys.executable, "-m", "corrugate", "design", str(specs[1]), "--out", str(out)],
                env=_child_env(),
                capture_output=True,
                text=True,
                timeout=300,
            )
            assert done.returncode == 0, done.stderr
        return inner(*args, **kw)

    monkeypatch.setattr(verify, "solve_assembly", racing)
    code, _, err = cli(["verify", str(out), "--no-first-failure", "-q"])
    assert code == 2
    _one_error_line(err, "design.json changed", str(out))
    assert stub_fe, "the FE ran"
    assert _layers(out) != a
    assert not (out / "verify.json").exists()
    assert set(read_manifest(out)) == {"design"}
    assert recover(out) is None


def test_recover_and_readers_drop_a_verdict_whose_design_json_changed(
    cli: CliRun, specs: tuple[Path, Path], tmp_path: Path, stub_fe: list[int]
) -> None:
    """A design.json edited by hand after verify: the manifest no longer lists the verdict, and
    recover() removes verify.json (it is the file the verify set wrote)."""
    out = tmp_path / "X"
    _design(cli, specs[0], out)
    code, _, err = cli(["verify", str(out), "--no-first-failure", "-q"])
    assert code == 0, err
    record = json.loads((out / "design.json").read_text())
    record["layers"][0]["W_mm"] = 9.0
    (out / "design.json").write_text(json.dumps(record))
    assert "verify" not in read_manifest(out)
    assert (out / "verify.json").exists()  # until the folder is settled
    assert recover(out) == "dropped verify (made of files that changed)"
    assert not (out / "verify.json").exists()
    assert "verify" not in json.loads((out / MANIFEST).read_text())["sets"]
    assert (out / "design.json").exists() and (out / "report.html").exists()


def test_a_verify_json_that_is_a_folder_is_refused_before_any_fe_run(
    cli: CliRun, specs: tuple[Path, Path], tmp_path: Path, stub_fe: list[int]
) -> None:
    out = tmp_path / "X"
    _design(cli, specs[0], out)
    (out / "verify.json").mkdir()
    code, _, err = cli(["verify", str(out), "--no-first-failure"])
    assert code == 2
    _one_error_line(err, "verify.json", "is a folder")
    assert stub_fe == []


# -- untrusted files: a subprocess under a time limit and an address-space cap ----------------

#: The address-space cap of the child (bytes): a /dev/zero read to the cap would fail with
#: MemoryError instead of the line naming the device.
_MEMORY = 2 << 30


def _limited() -> None:
    resource.setrlimit(resource.RLIMIT_AS, (_MEMORY, _MEMORY))
    signal.signal(signal.SIGINT, signal.SIG_DFL)


def _run_limited(args: list[str], cwd: Path) -> tuple[int, str, float]:
    """``corrugate ARGS`` in a child with a 2 GiB address space, stopped after 60 s (a FIFO
    that blocks fails the test by TimeoutExpired); its exit code, stderr and wall time."""
    start = time.monotonic()
    done = subprocess.run(
        [sys.executable, "-m", "corrugate", *args],
        env=_child_env(),
        cwd=cwd,
        capture_output=True,
        text=True,
        timeout=60,
        preexec_fn=_limited,
    )
    return done.returncode, done.stderr, time.monotonic() - start


@pytest.mark.slow
@pytest.mark.parametrize("kind", ["fifo", "dev-zero", "folder", "utf-16"])
def test_a_design_json_that_is_no_regular_utf8_file_is_one_line_at_once(
    kind: str, specs: tuple[Path, Path], tmp_path: Path
) -> None:
    """design.json as a FIFO (no writer: a blocking open or read would hang), a symlink to
    /dev/zero (a read without a cap would fill the memory), a folder, or UTF-16 text: exit 2
    with one line naming the file and why, in seconds, under the caps."""
    folder = tmp_path / "d"
    folder.mkdir()
    target = folder / "design.json"
    source = tmp_path / "ok.json"
    if kind == "fifo":
        os.mkfifo(target)
        why = "is a FIFO"
    elif kind == "dev-zero":
        target.symlink_to("/dev/zero")
        why = "is a device"
    elif kind == "folder":
        target.mkdir()
        why = "is a folder"
    else:
        source.write_text(json.dumps({"layout": {"shape": "square"}}))
        target.write_bytes(source.read_text().encode("utf-16"))
        why = "is UTF-16 text"
    code, err, wall = _run_limited(["verify", str(folder)], tmp_path)
    assert code == 2, err
    _one_error_line(err, "design.json", why)
    assert wall < 30


@pytest.mark.slow
@pytest.mark.parametrize("kind", ["fifo", "dev-zero"])
def test_a_spec_that_is_a_fifo_or_a_device_is_one_line_at_once(kind: str, tmp_path: Path) -> None:
    spec = tmp_path / "spec.toml"
    if kind == "fifo":
        os.mkfifo(spec)
    else:
        spec.symlink_to("/dev/zero")
    code, err, wall = _run_limited(["design", str(spec)], tmp_path)
    assert code == 2, err
    _one_error_line(err, "spec", "is a FIFO" if kind == "fifo" else "is a device")
    assert wall < 30


# -- hand-edited design.json: one line naming the key, exit 2, before any FE run ----------------


@pytest.fixture(scope="module")
def cantilever(tmp_path_factory: pytest.TempPathFactory) -> Path:
    """The folder of the blimp gripper's cantilever design (a deflection bound under load_N)."""
    from corrugate.cli import main

    folder = tmp_path_factory.mktemp("cantilever")
    spec = folder / "c.toml"
    spec.write_text(example_text("blimp_gripper_cantilever"))
    with pytest.raises(SystemExit) as info:
        main(["design", str(spec), "--out", str(folder / "d"), "-q"])
    assert info.value.code in (0, None)
    return folder / "d"


def _deflection(record: dict[str, Any]) -> dict[str, Any]:
    return next(c for c in record["constraints"] if c["quantity"].startswith("kcant@"))


def _set_n(r: dict[str, Any], v: object) -> None:
    r["layers"][0]["n"] = v


EDITS = {
    "n of 400 digits": (lambda r: _set_n(r, 10**400), "layers[0].n", "an integer of 401 digits"),
    "n 11.5": (lambda r: _set_n(r, 11.5), "layers[0].n", "not an integer"),
    "n as text": (lambda r: _set_n(r, "9"), "layers[0].n", "not an integer"),
    "kcant@banana": (
        lambda r: _deflection(r).update(quantity="kcant@banana"),
        ".quantity",
        "not a quantity key",
    ),
    "load_N -1": (lambda r: _deflection(r).update(load_N=-1), ".load_N", "out of range"),
    "load_N 0": (lambda r: _deflection(r).update(load_N=0), ".load_N", "out of range"),
    "NaN bound": (lambda r: _deflection(r).update(bound=float("nan")), ".bound", "NaN"),
    "five-point": (lambda r: _deflection(r).update(test="five-point"), ".test", "is unknown"),
    "joint glue": (lambda r: r.update(joint="glue"), "joint", "is unknown"),
    "alpha 180": (lambda r: r["layers"][1].update(alpha_deg=180), "layers[1].alpha_deg", "range"),
}


@pytest.mark.parametrize("case", list(EDITS))
def test_a_hand_edited_design_json_is_one_line_naming_the_key_before_any_run(
    case: str, cli: CliRun, cantilever: Path, tmp_path: Path, stub_fe: list[int]
) -> None:
    """Issue 37 item 3's cases: each gave exit 3, or exit 0 / 1 on a design that was not the
    file's (n 11.5 run as 11, load 0, a five-point test run as the cantilever); now exit 2 and
    one line naming the key, and no FE run."""
    edit, key, words = EDITS[case]
    folder = tmp_path / "d"
    shutil.copytree(cantilever, folder)
    record = json.loads((folder / "design.json").read_text())
    edit(record)
    (folder / "design.json").write_text(json.dumps(record))
    code, _, err = cli(["verify", str(folder)])
    assert code == 2, err
    _one_error_line(err, "design.json", key, words)
    assert stub_fe == [] and not (tmp_path / "ccx-ran").exists()


def test_an_integer_beyond_pythons_conversion_is_named_by_its_key(
    cli: CliRun, cantilever: Path, tmp_path: Path, stub_fe: list[int]
) -> None:
    """A 5000-digit integer (json.loads itself refuses it: ValueError, exit 3 before)."""
    folder = tmp_path / "d"
    shutil.copytree(cantilever, folder)
    text = (folder / "design.json").read_text()
    text = text.replace('"load_N": 0.5', '"load_N": ' + "9" * 5000, 1)
    (folder / "design.json").write_text(text)
    code, _, err = cli(["verify", str(folder)])
    assert code == 2, err
    _one_error_line(err, "load_N", "more than 4000 digits")


def test_control_characters_of_a_constraint_name_never_reach_the_terminal(
    cli: CliRun, specs: tuple[Path, Path], tmp_path: Path, stub_fe: list[int]
) -> None:
    """An ANSI escape (ESC [31m) and a carriage return in a constraint's name are stripped: the
    table shows the name's printable characters and no ESC or CR."""
    out = tmp_path / "X"
    _design(cli, specs[0], out)
    record = json.loads((out / "design.json").read_text())
    for c in record["constraints"]:
        if c["quantity"] == "EI@0":
            c["name"] = "\x1b[31mred\x1b[0m\rname"
    (out / "design.json").write_text(json.dumps(record))
    code, out_text, err = cli(["verify", str(out), "--no-first-failure"])
    assert code == 0, err
    assert "\x1b" not in out_text + err and "\r" not in out_text + err
    assert "[31mred[0mname" in out_text


def test_big_integers_of_the_command_line_are_named(cli: CliRun, tmp_path: Path) -> None:
    """--max-mesh of 400 digits was taken as a cap (the FE series ran); now one line."""
    code, _, err = cli(["verify", str(tmp_path), "--max-mesh", "1" + "0" * 400])
    assert code == 2
    _one_error_line(err, "--max-mesh", "an integer of 401 digits")
    code, _, err = cli(["verify", str(tmp_path), "--max-mesh", "65"])
    assert code == 2
    _one_error_line(err, "--max-mesh", "1 to 64")


def test_design_verify_fe_out_names_the_design_json_it_wrote(
    cli: CliRun, specs: tuple[Path, Path], tmp_path: Path, stub_fe: list[int]
) -> None:
    """``design --verify fe --out``: verify.json names the design.json committed just before it
    (SHA-256 of the file's bytes here) and requires it; the next design drops it."""
    out = tmp_path / "X"
    code, _, err = cli(["design", str(specs[0]), "--out", str(out), "-q", "--verify", "fe"])
    assert code == 0, err
    assert stub_fe, "the FE ran"
    digest = _sha(out / "design.json")
    assert json.loads((out / "verify.json").read_text())["design_sha256"] == digest
    assert read_manifest(out)["verify"]["requires"] == {"design.json": digest}
    _design(cli, specs[1], out)
    assert not (out / "verify.json").exists()
    assert set(read_manifest(out)) == {"design"}


def test_a_verdict_of_an_earlier_version_leaves_with_the_next_design(
    cli: CliRun, specs: tuple[Path, Path], tmp_path: Path, stub_fe: list[int]
) -> None:
    """A folder verified before issue 37 (verify.json without design_sha256, its set without
    ``requires``): design B written there removes it in its commit."""
    out = tmp_path / "X"
    _design(cli, specs[0], out)
    code, _, err = cli(["verify", str(out), "--no-first-failure", "-q"])
    assert code == 0, err
    manifest = json.loads((out / MANIFEST).read_text())
    del manifest["sets"]["verify"]["requires"]
    (out / MANIFEST).write_text(json.dumps(manifest))
    assert "verify" in read_manifest(out)
    _design(cli, specs[1], out)
    assert not (out / "verify.json").exists()
    assert set(read_manifest(out)) == {"design"}
