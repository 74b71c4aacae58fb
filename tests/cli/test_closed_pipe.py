"""A reader that leaves early (``corrugate design SPEC --out DIR | head``): the command goes
quiet and finishes, so the files are written and the exit code is the command's (rich's own
reaction to a closed pipe is to exit with 1 at the next write, before any file). Subprocesses
whose standard output is a pipe closed before they write; files in tmp_path, read back."""

from __future__ import annotations

import json
import os
import subprocess
import sys
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[2]


@pytest.mark.parametrize("extra", [[], ["--json"]])
def test_design_out_writes_its_files_when_the_reader_has_left(
    tmp_path: Path, extra: list[str]
) -> None:
    out = tmp_path / "design"
    env = {**os.environ, "PYTHONPATH": str(ROOT / "src")}
    read, write = os.pipe()
    os.close(read)  # the reader is gone before the first line: every write meets a closed pipe
    try:
        run = subprocess.run(
            [
                sys.executable,
                "-m",
                "corrugate",
                "design",
                str(ROOT / "examples" / "blimp_gripper.toml"),
                "--out",
                str(out),
                *extra,
            ],
            stdout=write,
            stderr=subprocess.PIPE,
            text=True,
            env=env,
            timeout=300,
            check=False,
        )
    finally:
        os.close(write)
    assert run.returncode == 0, run.stderr
    assert run.stderr == ""
    answer = json.loads((out / "design.json").read_text())
    assert answer["certified"] is True
    assert (out / "cut-1.dxf").stat().st_size > 0
    assert (out / "report.html").read_text().rstrip().endswith("</html>")
