"""`corrugate init`, `corrugate spec` and a spec read from standard input, as a user runs them:
in a real process, the files written to tmp_path and read back."""

from __future__ import annotations

import json
import subprocess
import sys
import tomllib
from pathlib import Path

import jsonschema
import pytest

from corrugate.spec.examples import template_text
from corrugate.spec.reference import reference_markdown

ROOT = Path(__file__).resolve().parents[2]


def corrugate(*args: str, stdin: str | None = None) -> subprocess.CompletedProcess[str]:
    return subprocess.run(
        [sys.executable, "-m", "corrugate", *args],
        input=stdin,
        capture_output=True,
        text=True,
        timeout=300,
        check=False,
    )


@pytest.mark.slow
def test_init_then_design_and_the_same_spec_from_stdin(tmp_path: Path) -> None:
    init = corrugate("init")
    assert init.returncode == 0 and init.stdout == template_text()
    spec = tmp_path / "s.toml"
    spec.write_text(init.stdout)
    from_file = corrugate("design", str(spec), "--json")
    assert from_file.returncode == 0, from_file.stderr
    from_stdin = corrugate(
        "design", "-", "--json", "--out", str(tmp_path / "out"), stdin=init.stdout
    )
    assert from_stdin.returncode == 0, from_stdin.stderr
    a, b = json.loads(from_file.stdout), json.loads(from_stdin.stdout)
    assert a["design"] == b["design"] and a["status"] == "optimal" and a["certified"]
    record = json.loads((tmp_path / "out" / "design.json").read_text())
    assert record["name"] == tomllib.loads(init.stdout)["name"]
    # the report shows the spec as it was piped in
    assert "name = &quot;my-panel&quot;" in (tmp_path / "out" / "report.html").read_text() or (
        'name = "my-panel"' in (tmp_path / "out" / "report.html").read_text()
    )


def test_bad_stdin_is_one_line_naming_stdin() -> None:
    r = corrugate("design", "-", stdin="name = [[[")
    assert r.returncode == 2
    assert r.stderr.count("\n") == 1 and "<stdin>" in r.stderr and "TOML" in r.stderr


def test_a_spec_saved_with_a_byte_order_mark_designs_as_without(tmp_path: Path) -> None:
    """A UTF-8 byte-order mark (as some editors save UTF-8) made tomllib say "Invalid statement
    (at line 1, column 1)" of a file that looks right in the editor: the file, and the same text
    on standard input, now give the answer the text without the mark gives, byte for byte."""
    text = "\ufeff" + corrugate("init").stdout
    path = tmp_path / "bom.toml"
    path.write_bytes(text.encode("utf-8"))
    assert path.read_bytes()[:3] == b"\xef\xbb\xbf"
    plain = tmp_path / "plain.toml"
    plain.write_text(text.removeprefix("\ufeff"), encoding="utf-8")
    expected = corrugate("design", str(plain), "--json")
    assert expected.returncode == 0, expected.stderr
    for r in (
        corrugate("design", str(path), "--json"),
        corrugate("design", "-", "--json", stdin=text),
    ):
        assert r.returncode == 0, r.stderr
        got, want = json.loads(r.stdout), json.loads(expected.stdout)
        for answer in (got, want):  # the solver's clocks: the keys that differ run to run
            solver = answer["solver"]
            for key in ("solve_seconds", "total_seconds"):
                del solver[key]
            del solver["budget"]["used_cpu_seconds"]
        assert got == want


def test_init_example_and_list() -> None:
    listed = corrugate("init", "--list").stdout.split()
    assert "wheel_circle" in listed
    wheel = corrugate("init", "--example", "wheel_circle")
    assert wheel.stdout == (ROOT / "examples" / "wheel_circle.toml").read_text()
    bad = corrugate("init", "--example", "nope")
    assert bad.returncode == 2 and "wheel_circle" in bad.stderr


@pytest.mark.slow
def test_spec_prints_the_reference_and_a_schema_the_examples_satisfy() -> None:
    assert corrugate("spec").stdout == reference_markdown()
    schema = json.loads(corrugate("spec", "--schema").stdout)
    data = tomllib.loads((ROOT / "examples" / "blimp_gripper.toml").read_text())
    jsonschema.Draft202012Validator(schema).validate(data)
