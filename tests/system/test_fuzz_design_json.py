"""Fuzz of ``corrugate verify``'s reading and checking (issue 37, items 3 and 4): random mutations
of a real design.json (the blimp gripper's cantilever design, written by ``corrugate design``):
byte flips, deleted keys, values swapped for another type, huge numbers (a 400-digit integer, a
5000-digit one, 1e308, NaN). CalculiX is stubbed (``CORRUGATE_CCX`` a script that fails, the FE
runs replaced by fixed stiffnesses), so each case costs milliseconds.

Each mutated file ends in exit 2 with one line (bad input), or in a verdict's exit code
(0, 1, 5, 6: the same path as the unmodified file, which may give another verdict when a
mutation changed a bound); never exit 3 (a bug) and never a hang: each case runs under an alarm
of :data:`LIMIT_S` seconds. ``max_examples`` 60, derandomized (the same cases every run).
"""

from __future__ import annotations

import json
import shutil
import signal
from pathlib import Path
from types import SimpleNamespace
from typing import Any

import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from corrugate.cli import main
from corrugate.spec.examples import example_text

#: No case may take longer (a hang guard; a case takes about 0.1 s).
LIMIT_S = 20
#: The exit codes of a verdict (docs/fea.md section 6) and of bad input.
VERDICTS = {0, 1, 5, 6}

HUGE: list[Any] = [10**400, -(10**400), 1e308, -1e308, float("nan"), float("inf"), 2**63]
SWAPS: list[Any] = [None, True, "text", "", [], {}, [1, 2], {"a": 1}, 0, -1, 1.5, 11.5, *HUGE]


def _paths(obj: Any, prefix: tuple[Any, ...] = ()) -> list[tuple[Any, ...]]:
    """Every path to a value in ``obj`` (keys and list indices)."""
    out = [prefix] if prefix else []
    if isinstance(obj, dict):
        for k, v in obj.items():
            out += _paths(v, (*prefix, k))
    elif isinstance(obj, list):
        for i, v in enumerate(obj):
            out += _paths(v, (*prefix, i))
    return out


def _parent(obj: Any, path: tuple[Any, ...]) -> Any:
    for p in path[:-1]:
        obj = obj[p]
    return obj


@pytest.fixture(scope="module")
def original(tmp_path_factory: pytest.TempPathFactory) -> Path:
    folder = tmp_path_factory.mktemp("fuzz-design")
    spec = folder / "c.toml"
    spec.write_text(example_text("blimp_gripper_cantilever"))
    with pytest.raises(SystemExit) as info:
        main(["design", str(spec), "--out", str(folder / "d"), "-q"])
    assert info.value.code in (0, None)
    return folder / "d"


@pytest.fixture
def stubbed(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    from corrugate.fea import verify

    stub = tmp_path / "ccx"
    stub.write_text("#!/bin/sh\nexit 1\n")
    stub.chmod(0o755)
    monkeypatch.setenv("CORRUGATE_CCX", str(stub))

    def result(*args: Any, **kw: Any) -> SimpleNamespace:
        mesh = args[2] if len(args) > 2 else kw["mesh"]
        f = 1 + 1 / mesh.along
        return SimpleNamespace(
            EI=2e5 * f,
            K=50.0 * f,
            D=1e3 * f,
            force=1.0,
            displacement=0.1 * f,
            span=40.0,
            value=lambda: 3.0 * f,
        )

    def frame(*args: Any, **kw: Any) -> SimpleNamespace:
        return SimpleNamespace(K=lambda eta: 50.0)

    monkeypatch.setattr(verify, "solve_assembly", result)
    monkeypatch.setattr(verify, "solve_outline", result)
    monkeypatch.setattr(verify, "solve_frame", frame)


def _expired(signum: int, frame: object) -> None:
    raise TimeoutError(f"a case took more than {LIMIT_S} s")


def _verify(folder: Path, capsys: pytest.CaptureFixture[str]) -> tuple[int, str]:
    old = signal.signal(signal.SIGALRM, _expired)
    signal.alarm(LIMIT_S)
    try:
        with pytest.raises(SystemExit) as info:
            main(["verify", str(folder), "--no-first-failure", "-q", "--mesh", "2,4,8"])
    finally:
        signal.alarm(0)
        signal.signal(signal.SIGALRM, old)
    _, err = capsys.readouterr()
    code = info.value.code
    return (0 if code is None else int(code)), err


mutation = st.one_of(
    st.tuples(st.just("flip"), st.integers(0, 10**6), st.integers(0, 255)),
    st.tuples(st.just("delete"), st.integers(0, 10**6), st.just(0)),
    st.tuples(st.just("swap"), st.integers(0, 10**6), st.integers(0, len(SWAPS) - 1)),
    st.tuples(st.just("huge"), st.integers(0, 10**6), st.integers(0, len(HUGE))),
)


@settings(
    max_examples=60,
    deadline=None,
    derandomize=True,
    suppress_health_check=[HealthCheck.function_scoped_fixture, HealthCheck.too_slow],
)
@given(mutations=st.lists(mutation, min_size=1, max_size=3))
def test_a_mutated_design_json_is_exit_2_or_a_verdict_never_a_bug_or_a_hang(
    mutations: list[tuple[str, int, int]],
    original: Path,
    stubbed: None,
    tmp_path: Path,
    capsys: pytest.CaptureFixture[str],
) -> None:
    folder = tmp_path / "d"
    if folder.exists():
        shutil.rmtree(folder)
    shutil.copytree(original, folder)
    raw = (original / "design.json").read_bytes()
    data = json.loads(raw)
    for kind, where, what in mutations:
        if kind == "flip":
            raw = raw[: where % len(raw)] + bytes([what]) + raw[where % len(raw) + 1 :]
            continue
        paths = [p for p in _paths(data) if p]
        path = paths[where % len(paths)]
        parent = _parent(data, path)
        if kind == "delete":
            del parent[path[-1]]
        elif kind == "swap":
            parent[path[-1]] = SWAPS[what]
        elif what < len(HUGE):
            parent[path[-1]] = HUGE[what]
        raw = json.dumps(data).encode()
        if kind == "huge" and what == len(HUGE):  # beyond int()'s 4300 digits, in the text
            raw = raw.replace(b": 0.5", b": " + b"9" * 5000, 1)
    (folder / "design.json").write_bytes(raw)
    code, err = _verify(folder, capsys)
    assert code != 3, err
    assert code == 2 or code in VERDICTS, (code, err)
    if code == 2:
        lines = err.strip().splitlines()
        assert len(lines) == 1 and lines[0].startswith("corrugate: error:"), err
        assert "internal error" not in err and "Traceback" not in err


def test_the_unmodified_design_json_reaches_its_verdict(
    original: Path, stubbed: None, tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    """The fuzz's baseline: the file as written verifies (a verdict, not bad input)."""
    folder = tmp_path / "d"
    shutil.copytree(original, folder)
    code, err = _verify(folder, capsys)
    assert code in VERDICTS, err
