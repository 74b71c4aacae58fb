"""A command that needs an optional extra which is not installed says so in one line (exit 2)
before it solves or writes anything; the core commands work without the extras.

The extras are hidden from a child interpreter by setting their modules to None in
``sys.modules`` (Python's own way of making an import fail), so the test needs no second venv.
"""

from __future__ import annotations

import os
import re
import subprocess
import sys
import tomllib
from pathlib import Path

import pytest

from corrugate.core.extras import EXTRAS

ROOT = Path(__file__).resolve().parents[2]
EXAMPLE = ROOT / "examples" / "blimp_gripper.toml"
#: the case study's design as command-line options
CASE = ("--W", "8", "--n", "8", "--alpha", "84", "--material", "dura-lar")


def _run(hidden: tuple[str, ...], *args: str) -> subprocess.CompletedProcess[str]:
    code = (
        "import sys\n"
        f"for m in {hidden!r}: sys.modules[m] = None\n"
        "from corrugate.cli import main\n"
        f"main({list(args)!r})\n"
    )
    env = {**os.environ, "PYTHONPATH": str(ROOT / "src")}
    return subprocess.run(
        [sys.executable, "-c", code], capture_output=True, text=True, env=env, timeout=120
    )


def test_pyproject_extras_list_the_modules_the_checks_look_for() -> None:
    """EXTRAS lists pyproject.toml's extras (self-references aside)."""
    extras = tomllib.loads((ROOT / "pyproject.toml").read_text())["project"][
        "optional-dependencies"
    ]
    for extra, packages in EXTRAS.items():
        names = {re.split(r"[<>=!~\[ ]", r, maxsplit=1)[0] for r in extras[extra]}
        names.discard("corrugate")
        assert names == set(packages.values())
    # the web app writes every design's files, so its extra brings the writers' along
    assert "corrugate[fab]" in extras["web"]


@pytest.mark.parametrize(
    "args",
    [
        ("design", str(EXAMPLE), "--out", "{out}"),
        ("pattern", *CASE, "--out", "{out}"),
    ],
    ids=["design", "pattern"],
)
@pytest.mark.slow
@pytest.mark.parametrize("hidden", [("matplotlib",), ("ezdxf",), ("ezdxf", "matplotlib")])
def test_files_without_the_fab_extra_are_one_line_and_nothing_written(
    tmp_path: Path, args: tuple[str, ...], hidden: tuple[str, ...]
) -> None:
    out = tmp_path / "out"
    r = _run(hidden, *(a.format(out=out) for a in args))
    assert r.returncode == 2, r.stderr
    lines = r.stderr.strip().splitlines()
    assert len(lines) == 1, r.stderr
    assert "needs the 'fab' extra" in lines[0]
    assert f"({', '.join(hidden)} {'is' if len(hidden) == 1 else 'are'} missing)" in lines[0]
    assert "pip install 'corrugate[fab]'" in lines[0]
    assert r.stdout == ""  # nothing solved or printed before the check
    assert not out.exists()
    assert list(tmp_path.iterdir()) == []  # no staging folder left either


@pytest.mark.slow
def test_the_core_commands_work_without_the_fab_extra() -> None:
    r = _run(("ezdxf", "matplotlib"), "design", str(EXAMPLE), "-q")
    assert r.returncode == 0, r.stderr
    r = _run(("ezdxf", "matplotlib"), "analyze", *CASE, "--json")
    assert r.returncode == 0, r.stderr
    assert '"support": "free"' in r.stdout


@pytest.mark.parametrize(
    ("hidden", "extra", "named"),
    [
        (("uvicorn",), "web", "uvicorn"),
        (("multipart",), "web", "python-multipart"),
        (("ezdxf",), "fab", "ezdxf"),
    ],
)
def test_serve_without_its_extras_is_one_line(
    hidden: tuple[str, ...], extra: str, named: str
) -> None:
    """The message names the distribution to install (python-multipart, not its module)."""
    r = _run(hidden, "serve", "--port", "1")
    assert r.returncode == 2, r.stderr
    line = r.stderr.strip()
    assert "\n" not in line and line.startswith("corrugate: error: the web app")
    assert f"({named} is missing): pip install 'corrugate[{extra}]'" in line
