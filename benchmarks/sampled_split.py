"""Where a corrugate command's time goes, sampled: imports and work, by package (issue 39).

Run by hand (py-spy is not a dependency of the project: install it anywhere, e.g.
``python3 -m venv /tmp/spy && /tmp/spy/bin/pip install py-spy``)::

    .venv/bin/python benchmarks/sampled_split.py --py-spy /tmp/spy/bin/py-spy [--runs 8] \\
        -- design examples/blimp_gripper.toml --out {out}

The command runs ``--runs`` times as a fresh process (``python -m corrugate ...``, this checkout's
``src`` on ``PYTHONPATH``, bytecode compiled first) under ``py-spy record --nonblocking`` at 1000
samples per second of wall-clock time while the process is on a CPU (py-spy leaves out idle
samples). A sample is an *import* when its stack is inside an import (``_find_and_load``), charged
to the package of the module being executed (the innermost ``<module>`` frame); otherwise it is
*work*, charged to the package of the innermost frame (the leaf: where the CPU actually is) and to
the corrugate step that called into it (the frame below ``write_job`` for the files, else the
outermost corrugate frame past the CLI's). Sampling charges each function its share of the run
without the call overhead a deterministic profiler adds to code that makes many small calls
(ezdxf's, matplotlib's), which is why it is used here. The shares are of all samples; multiply
by a run's CPU time (``benchmarks/command_floor.py``) for seconds. ``{out}`` is replaced by a new
empty folder per run.
"""

from __future__ import annotations

import argparse
import collections
import os
import re
import subprocess
import sys
import sysconfig
import tempfile
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
_FRAME = re.compile(r"\((.*?):\d+\)$")
#: CLI and workflow frames every run passes through: a work sample is charged to the first frame
#: of ours past them.
_PLUMBING = ("corrugate/__main__.py", "corrugate/cli/__init__.py", "corrugate/cli/options.py")


def package(frame: str) -> str:
    """The package a py-spy frame ``function (path:line)`` runs in: ``ours:<subpackage>`` for
    corrugate's, the top folder of a site-packages path, else the file name (the standard
    library's, ``<frozen ...>``)."""
    m = _FRAME.search(frame)
    path = m.group(1) if m else frame
    if path.startswith("corrugate/"):
        return "ours:" + path.split("/")[1].removesuffix(".py")
    return path.split("/")[0]


def step(frames: list[str]) -> str:
    """The corrugate function a work sample is charged to (module docstring)."""
    ours = [f for f in frames if "(corrugate/" in f]
    for k, f in enumerate(ours):
        if f.startswith("write_job ("):
            return _FRAME.sub("", ours[k + 1] if k + 1 < len(ours) else f).strip()
    past = [f for f in ours if not any(p in f for p in _PLUMBING)]
    chosen = past[1] if len(past) > 1 else (past[0] if past else "(no frame of ours)")
    return _FRAME.sub("", chosen).strip()


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.split("\n", 1)[0])
    parser.add_argument("--py-spy", required=True, help="the py-spy executable")
    parser.add_argument("--runs", type=int, default=8, help="runs sampled (their samples summed)")
    parser.add_argument("--top", type=int, default=15, help="rows printed per table")
    parser.add_argument("command", nargs="+", help="corrugate's arguments (after --)")
    args = parser.parse_args()
    if not Path(args.py_spy).is_file():
        sys.exit(f"sampled_split.py: no py-spy at {args.py_spy} (see the module docstring)")
    src = ROOT / "src"
    for tree in (src, Path(sysconfig.get_paths()["purelib"])):  # bytecode once
        subprocess.run([sys.executable, "-m", "compileall", "-q", str(tree)], check=True)
    env = {**os.environ, "PYTHONPATH": str(src)}
    env.pop("PYTHONDONTWRITEBYTECODE", None)
    imports: collections.Counter[str] = collections.Counter()
    work: collections.Counter[str] = collections.Counter()
    leaves: collections.Counter[str] = collections.Counter()
    pairs: collections.Counter[tuple[str, str]] = collections.Counter()
    total = stackless = 0
    with tempfile.TemporaryDirectory(prefix="corrugate-sampled-") as tmp:
        for k in range(args.runs):
            raw = Path(tmp) / f"run-{k}.txt"
            command = [a.replace("{out}", str(Path(tmp) / f"out-{k}")) for a in args.command]
            spy = [
                args.py_spy,
                "record",
                "-r",
                "1000",
                "-f",
                "raw",
                "--nonblocking",
                "-o",
                str(raw),
            ]
            subprocess.run(
                [*spy, "--", sys.executable, "-m", "corrugate", *command],
                env=env,
                cwd=ROOT,
                stdout=subprocess.DEVNULL,
                stderr=subprocess.DEVNULL,
                check=True,
            )
            for line in raw.read_text(encoding="utf-8").splitlines():
                stack, count = line.rsplit(" ", 1)
                n = int(count)
                if not stack.strip():  # no Python frame: the interpreter's own start or exit,
                    stackless += n  # or a sample py-spy failed to read (--nonblocking)
                    continue
                total += n
                frames = stack.split(";")
                if any(f.startswith("_find_and_load ") for f in frames):
                    modules = [f for f in frames if f.startswith("<module> (")]
                    imports[package(modules[-1]) if modules else "?"] += n
                    continue
                leaf = package(frames[-1])
                leaf = "ours" if leaf.startswith("ours:") else leaf
                where = step(frames)
                work[where] += n
                leaves[leaf] += n
                pairs[(where, leaf)] += n
            print(f"run {k + 1}/{args.runs} sampled", file=sys.stderr)
    if total == 0:
        sys.exit("sampled_split.py: py-spy took no sample")
    share = sum(imports.values()) / total
    print(
        f"corrugate {' '.join(args.command)}: {total} samples with a Python stack in {args.runs} "
        f"runs (shares below are of those; {stackless} more had none)"
    )
    print(f"imports {share:.3f} of the samples, work {1 - share:.3f}")
    tables: list[tuple[str, collections.Counter[str] | collections.Counter[tuple[str, str]]]] = [
        ("imports, by the package of the module executed", imports),
        ("work, by the package where the CPU is (the leaf frame)", leaves),
        ("work, by the corrugate step that called", work),
        ("work, by step and leaf package", pairs),
    ]
    for title, counter in tables:
        print(f"== {title}")
        for key, n in counter.most_common(args.top):
            print(f"  {n / total:6.3f}  {key}")


if __name__ == "__main__":
    main()
