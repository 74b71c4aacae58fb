"""Ctrl-C: a design stopped by SIGINT exits with 130 and one line (corrugate.cli.INTERRUPTED),
and its output folder keeps the set an earlier run wrote, whole (subprocesses, files in
tmp_path, read back)."""

from __future__ import annotations

import json
import os
import signal
import subprocess
import sys
import time
from pathlib import Path

import pytest

from corrugate.cli import INTERRUPTED

ROOT = Path(__file__).resolve().parents[2]

#: A chassis plate with continuous W and alpha, every n, independent layers and eight
#: thicknesses: its solve takes tens of seconds (19.3 s CPU here; the fine-grid spec this test
#: had before takes about a second since the search builds its explanation from its own tree),
#: so SIGINT lands mid-solve.
LONG_SPEC = """
name = "long"
model = "refined"
layers = "independent"
[material]
name = "polypropylene"
thickness = ["0.2 mm", "0.25 mm", "0.3 mm", "0.35 mm", "0.4 mm", "0.45 mm", "0.5 mm", "0.55 mm"]
[layout]
shape = "rectangle"
[variables]
W = { min = "1 mm", max = "30 mm" }
n = { min = 1, max = 200 }
alpha = { min = "1 deg", max = "120 deg" }
[constraints]
side_x = { min = "78 mm", max = "82 mm" }
side_y = { min = "118 mm", max = "122 mm" }
thickness = { max = "15 mm" }
flexural_rigidity = [{ min = "360 mN*m^2", eta = "0 deg" }]
[fabrication]
machine = "maker-12x12"
[objective]
minimize = "mass"
"""


def _corrugate(*args: str) -> subprocess.Popen[str]:
    env = {**os.environ, "PYTHONPATH": str(ROOT / "src")}
    return subprocess.Popen(
        [sys.executable, "-m", "corrugate", *args],
        stdout=subprocess.PIPE,
        stderr=subprocess.PIPE,
        text=True,
        env=env,
        # a shell's background job ignores SIGINT; a user's foreground command does not
        preexec_fn=lambda: signal.signal(signal.SIGINT, signal.SIG_DFL),
    )


@pytest.mark.slow
def test_ctrl_c_mid_design_exits_130_with_one_line_and_keeps_the_earlier_set(
    tmp_path: Path,
) -> None:
    out = tmp_path / "out"
    first = _corrugate("design", str(ROOT / "examples" / "blimp_gripper.toml"), "--out", str(out))
    assert first.wait(timeout=300) == 0
    before = {p.name: p.read_bytes() for p in out.iterdir()}
    assert json.loads(before["design.json"])["name"] == "blimp-gripper"
    spec = tmp_path / "long.toml"
    spec.write_text(LONG_SPEC)
    run = _corrugate("design", str(spec), "--out", str(out))
    time.sleep(6.0)  # past the imports, inside the solve (which takes tens of seconds)
    assert run.poll() is None, "the design ended before it could be interrupted"
    run.send_signal(signal.SIGINT)
    stdout, stderr = run.communicate(timeout=120)
    assert run.returncode == 130, (stdout, stderr)
    # the one line, after the search's progress lines (stderr is not a terminal: a plain line
    # per stage and every few seconds, corrugate.cli.progress)
    *shown, last = stderr.splitlines()
    assert last == INTERRUPTED
    assert all(line.startswith(("corrugate: searching", "corrugate: explaining")) for line in shown)
    assert "Traceback" not in stdout + stderr and "NOT certified" not in stdout
    assert {p.name: p.read_bytes() for p in out.iterdir()} == before  # the earlier set, whole
    assert not [p for p in tmp_path.iterdir() if p.name.startswith(".")]  # no staging left
