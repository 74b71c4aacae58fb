"""Process CPU time of corrugate's commands, start-up included (issue 13, "Start-up and files").

Run by hand (about a minute with the defaults, two with ``--base``)::

    .venv/bin/python benchmarks/pipeline.py [--repeats 5] [--base main] [--src src] [--src /tmp/x/src]

Each command runs as a fresh process (``python -m corrugate ...`` with ``PYTHONPATH`` set to a
source tree) and is charged the user + system CPU time of that child
(``resource.getrusage(RUSAGE_CHILDREN)`` before and after it): CPU, not wall-clock, because the
machine is shared and noisy. The commands are interleaved (floor, --help, analyze, design, design --out,
floor, ...) ``--repeats`` times and the median of each is printed, with its ratio to the floor (a bare
``python -c pass``) and to its target:

* ``corrugate --help``: <= 0.3 s;
* ``corrugate analyze --W 8 --n 8 --alpha 84 --material dura-lar``: <= 0.4 s;
* ``corrugate design examples/blimp_gripper.toml``: <= 0.25 s (the answer alone; issue 39);
* ``corrugate design examples/blimp_gripper.toml --out <new tmpdir>``: <= 1.0 s (issue 39; 1.5 s
  before it).

With two or more trees the trees are interleaved too, and each command's median is printed per tree
with the ratio to the first: ``--base REF`` puts a ``git archive`` of ``REF`` (e.g. ``main``),
unpacked under a temporary folder, first and this checkout's ``src`` second (the before and after
of a change in one run); ``--src`` names trees by hand. The last lines put each tree's
``design --out`` and ``design`` medians beside the import floors measured in the same run (what
importing their libraries costs, which no code of ours can remove). The floors import numpy as a
command does, with one BLAS thread, and not pydantic's plugin loader (issue 39:
``corrugate.core.blas``, ``corrugate.core.plugins``); a tree from before that change pays for
both, so its distance to the floor includes them. A floor is those bare
imports, exit included: ``design`` itself skips three parts of it, the interpreter's collection
at exit (``corrugate.cli.main`` freezes the collector's objects then), the execution of
fontTools' subsetter, which matplotlib's PDF backend imports but uses only for Type 42 fonts
(``corrugate.core.plotting.pdf_pages``), and the help text of matplotlib's artists' ``set``
methods (``corrugate.core.plotting.lean_import``, 0.08 s; issue 39). So "above the floor"
understates ``design``'s own work by what those cost in the floor's process: its exit collection
(the floor with ``gc.freeze()`` as its last statement took 0.2-0.4 s less in three runs of issue
24's session), the subsetter's import (0.13-0.18 s) and that help text.

Bytecode: this environment sets ``PYTHONDONTWRITEBYTECODE``, which would charge every run for
compiling the sources again; the trees and the interpreter's site-packages are compiled once with
:mod:`compileall` first, as an installed package has them.
"""

from __future__ import annotations

import argparse
import os
import resource
import statistics
import subprocess
import sys
import sysconfig
import tarfile
import tempfile
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
BLIMP = ROOT / "examples" / "blimp_gripper.toml"

#: How a command's process imports numpy (issue 39): its BLAS with one thread
#: (``corrugate.core.blas``); a floor imports it so too, or it charges the floor for threads the
#: command never starts.
ONE_BLAS_THREAD = "import os; os.environ['OPENBLAS_NUM_THREADS'] = '1'; "
ANALYZE_LIBS = ONE_BLAS_THREAD + "import numpy, typer, rich.console, rich.table"
#: The import floor of ``design`` without files (issue 39): its libraries and pydantic's model
#: machinery, without the plugin loader (a command's process never imports it:
#: ``corrugate.core.plugins``).
ANSWER_LIBS = ONE_BLAS_THREAD + (
    "import numpy, typer, rich.console, rich.table, pydantic.main, pydantic.fields, tomllib"
)
#: The import floor of ``design --out`` (issue 24): every library it draws and writes with.
DESIGN_LIBS = ONE_BLAS_THREAD + (
    "import numpy, pydantic.main, pydantic.fields, typer, rich.console, rich.table, "
    "matplotlib.figure, matplotlib.backends.backend_agg, matplotlib.backends.backend_pdf, "
    "mpl_toolkits.mplot3d, ezdxf"
)

#: (label, arguments after ``python``, target CPU seconds or None); "{out}" is a new empty folder.
COMMANDS: list[tuple[str, list[str], float | None]] = [
    ("python -c pass (floor)", ["-c", "pass"], None),
    ("corrugate --help", ["-m", "corrugate", "--help"], 0.3),
    (
        "corrugate analyze --W 8 --n 8 --alpha 84 --material dura-lar",
        [
            *("-m", "corrugate", "analyze", "--W", "8", "--n", "8", "--alpha", "84"),
            "--material",
            "dura-lar",
        ],
        0.4,
    ),
    (
        "corrugate design examples/blimp_gripper.toml",
        ["-m", "corrugate", "design", str(BLIMP)],
        0.25,
    ),
    (
        "corrugate design examples/blimp_gripper.toml --out DIR",
        ["-m", "corrugate", "design", str(BLIMP), "--out", "{out}"],
        1.0,
    ),
    # What the libraries alone cost, so the targets can be read against what no code of ours
    # can remove: the imports `analyze` and `design --out` need, and nothing else.
    ("import numpy (1 BLAS thread), typer, rich (analyze's libraries)", ["-c", ANALYZE_LIBS], None),
    ("import numpy (1 BLAS thread), pydantic, typer, matplotlib, ezdxf", ["-c", DESIGN_LIBS], None),
    ("import numpy (1 BLAS thread), typer, rich, pydantic's models", ["-c", ANSWER_LIBS], None),
]
#: Indices in COMMANDS of ``design --out`` and of its import floor, of ``design`` and of its.
DESIGN, DESIGN_FLOOR = 4, 6
ANSWER, ANSWER_FLOOR = 3, 7


def child_cpu(argv: list[str], env: dict[str, str]) -> float:
    """Run ``argv`` to its end; its user + system CPU time (s). Raises if it fails."""
    before = resource.getrusage(resource.RUSAGE_CHILDREN)
    done = subprocess.run(argv, env=env, stdout=subprocess.DEVNULL, stderr=subprocess.PIPE)
    after = resource.getrusage(resource.RUSAGE_CHILDREN)
    if done.returncode != 0:
        raise RuntimeError(f"{argv} exited {done.returncode}: {done.stderr.decode()[-2000:]}")
    return (after.ru_utime - before.ru_utime) + (after.ru_stime - before.ru_stime)


def archive(ref: str, into: Path) -> Path:
    """The ``src`` tree of the commit ``ref`` of this checkout, unpacked into ``into``."""
    tar = into / "base.tar"
    subprocess.run(
        ["git", "-C", str(ROOT), "archive", "--format=tar", "-o", str(tar), ref, "src"], check=True
    )
    with tarfile.open(tar) as t:
        t.extractall(into / "base", filter="data")
    return into / "base" / "src"


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.split("\n", 1)[0])
    parser.add_argument("--repeats", type=int, default=5, help="runs of each command (median)")
    parser.add_argument(
        "--src",
        action="append",
        type=Path,
        help="source tree(s) put on PYTHONPATH (default: this checkout's src)",
    )
    parser.add_argument(
        "--base",
        metavar="REF",
        help="also time a git archive of REF (e.g. main), first, beside this checkout's src",
    )
    args = parser.parse_args()
    with tempfile.TemporaryDirectory(prefix="corrugate-bench-") as tmp:
        trees = [p.resolve() for p in (args.src or [ROOT / "src"])]
        if args.base:
            trees.insert(0, archive(args.base, Path(tmp)))
        run(trees, args.repeats, Path(tmp))


def run(trees: list[Path], repeats: int, tmp: Path) -> None:
    """Time every command on every tree, interleaved, ``repeats`` times; print the medians."""
    site = sysconfig.get_paths()["purelib"]
    for tree in [*trees, Path(site)]:  # bytecode once, as an installed package has it
        subprocess.run([sys.executable, "-m", "compileall", "-q", str(tree)], check=True)
    times: dict[tuple[int, int], list[float]] = {}
    for k in range(repeats):
        for c, (_, tail, _) in enumerate(COMMANDS):
            for t, tree in enumerate(trees):
                env = {**os.environ, "PYTHONPATH": str(tree)}
                out = tmp / f"out-{k}-{c}-{t}"
                argv = [sys.executable, *(a.replace("{out}", str(out)) for a in tail)]
                times.setdefault((c, t), []).append(child_cpu(argv, env))
        print(f"run {k + 1}/{repeats} done", file=sys.stderr)
    print(f"process CPU time (user + sys), median of {repeats} interleaved runs")
    for t, tree in enumerate(trees):
        floor = statistics.median(times[(0, t)])
        print(f"\nsource tree {tree}")
        for c, (label, _, target) in enumerate(COMMANDS):
            median = statistics.median(times[(c, t)])
            spread = f"[{min(times[(c, t)]):.3f}-{max(times[(c, t)]):.3f}]"
            line = f"  {label:<62} {median:7.3f} s {spread:>15}  x{median / floor:6.1f} floor"
            if target is not None:
                verdict = "meets" if median <= target else "misses"
                line += f"  target <= {target:g} s: {verdict} ({median / target:.2f} x target)"
            print(line)
    if len(trees) > 1:
        print(f"\nratio to {trees[0]}")
        for c, (label, _, _) in enumerate(COMMANDS):
            first = statistics.median(times[(c, 0)])
            ratios = ", ".join(
                f"{statistics.median(times[(c, t)]) / first:.2f}" for t in range(1, len(trees))
            )
            print(f"  {label:<62} {ratios}")
    for name, (command, lower) in {
        "design --out": (DESIGN, DESIGN_FLOOR),
        "design": (ANSWER, ANSWER_FLOOR),
    }.items():
        print(f"\n{name} beside its import floor (same run)")
        for t, tree in enumerate(trees):
            value = statistics.median(times[(command, t)])
            floor = statistics.median(times[(lower, t)])
            print(
                f"  {tree!s:<62} {value:.3f} s, floor {floor:.3f} s, {value - floor:.3f} s above it"
            )


if __name__ == "__main__":
    main()
