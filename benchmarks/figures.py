"""CPU time of each figure ``corrugate design SPEC --out`` draws, in the command's own process.

Run by hand (about a minute with the defaults)::

    .venv/bin/python benchmarks/figures.py [--repeats 7] [--base main] [--src TREE] [--spec FILE]

Each run is a fresh interpreter with ``PYTHONPATH`` set to a source tree. It first imports the
modules the command imports, as a command's process does (``benchmarks/command_floor.py``'s
list and set-up), then runs ``corrugate.cli.main(["design", SPEC, "--out", DIR])`` in process
with a :func:`time.process_time` clock around each function that draws a figure: the assembly
figure (``instructions_png``: built and encoded), the report's load-case, design-space,
mass-against-n and polar figures (each built; ``png bytes (report)`` is the drawing and encoding
of all of them: PNG before issue 39, SVG since) and ``report_html`` in all (its figures included). ``command`` is the whole
command after those imports (the solve and every file). The clocks are wrappers put on the
package's own module attributes in the benchmark's process; the figures and files are the
command's. The trees are interleaved ``--repeats`` times and the median of each clock printed
per tree (``--base REF``: a ``git archive`` of REF first, then this checkout's ``src``, as in
``benchmarks/pipeline.py``). CPU time, not wall-clock: the machine is shared.
"""

from __future__ import annotations

import argparse
import json
import os
import statistics
import subprocess
import sys
import sysconfig
import tempfile
from pathlib import Path

from command_floor import _IMPORT, _LIST  # type: ignore[import-not-found]  (benchmarks/)
from pipeline import archive  # type: ignore[import-not-found]

ROOT = Path(__file__).resolve().parents[1]
BLIMP = ROOT / "examples" / "blimp_gripper.toml"

#: Runs in the child after ``_IMPORT``: argv[2] the spec, argv[3] the output folder; prints the
#: clocks (JSON).
_TIME = r"""
import contextlib, io, json, time
import corrugate.export.design_files as design_files
import corrugate.report as report
import corrugate.report.html as report_html
from corrugate.cli import main

clocks = {}

def clocked(module, name, label):
    inner = getattr(module, name)
    def timed(*args, **kwargs):
        start = time.process_time()
        try:
            return inner(*args, **kwargs)
        finally:
            clocks[label] = clocks.get(label, 0.0) + time.process_time() - start
    setattr(module, name, timed)

clocked(design_files, "instructions_png", "assembly.png (built, encoded)")
# the design space: design_space_figure before issue 39's key as text, design_space since
for name in ("load_case_figure", "design_space_figure", "design_space", "mass_by_n_figure",
             "polar_figure"):
    if hasattr(report_html, name):
        clocked(report_html, name, name.replace("_figure", "") + " (built)")
for name in ("png_bytes", "svg_text"):  # the report's plots: PNG before issue 39's SVG
    if hasattr(report_html, name):
        clocked(report_html, name, "report plots drawn, encoded (PNG or SVG)")
clocked(report, "report_html", "report_html (all)")
start = time.process_time()
try:
    with contextlib.redirect_stdout(io.StringIO()), contextlib.redirect_stderr(io.StringIO()):
        main(["design", sys.argv[2], "--out", sys.argv[3]])
except SystemExit as exc:
    assert exc.code in (0, None), exc.code
clocks["command (after its imports)"] = time.process_time() - start
print(json.dumps(clocks))
"""


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.split("\n", 1)[0])
    parser.add_argument("--repeats", type=int, default=7, help="runs of each tree (median)")
    parser.add_argument("--src", action="append", type=Path, help="source tree(s)")
    parser.add_argument("--base", metavar="REF", help="also time a git archive of REF, first")
    parser.add_argument("--spec", type=Path, default=BLIMP, help="the spec drawn")
    args = parser.parse_args()
    with tempfile.TemporaryDirectory(prefix="corrugate-figures-") as name:
        tmp = Path(name)
        trees = [p.resolve() for p in (args.src or [ROOT / "src"])]
        if args.base:
            trees.insert(0, archive(args.base, tmp))
        run(trees, args.repeats, args.spec.resolve(), tmp)


def run(trees: list[Path], repeats: int, spec: Path, tmp: Path) -> None:
    """Time every tree ``repeats`` times, interleaved; print the medians of each clock."""
    for tree in [*trees, Path(sysconfig.get_paths()["purelib"])]:  # bytecode once
        subprocess.run([sys.executable, "-m", "compileall", "-q", str(tree)], check=True)
    lists = []
    for t, tree in enumerate(trees):  # the modules the command imports, per tree
        env = {**os.environ, "PYTHONPATH": str(tree)}
        listed = subprocess.run(
            [sys.executable, "-c", _LIST, "design", str(spec), "--out", str(tmp / f"list-{t}")],
            env=env,
            capture_output=True,
            text=True,
            check=True,
        ).stdout
        lists.append(tmp / f"modules-{t}.txt")
        lists[-1].write_text(listed, encoding="utf-8")
    clocks: list[list[dict[str, float]]] = [[] for _ in trees]
    for k in range(repeats):
        for t, tree in enumerate(trees):
            env = {**os.environ, "PYTHONPATH": str(tree)}
            out = tmp / f"out-{k}-{t}"
            done = subprocess.run(
                [sys.executable, "-c", _IMPORT + _TIME, str(lists[t]), str(spec), str(out)],
                env=env,
                capture_output=True,
                text=True,
            )
            if done.returncode != 0:
                raise RuntimeError(f"{tree}: {done.stderr[-2000:]}")
            clocks[t].append(json.loads(done.stdout.splitlines()[-1]))
        print(f"run {k + 1}/{repeats} done", file=sys.stderr)
    labels = list(dict.fromkeys(label for runs in clocks for run in runs for label in run))
    print(f"{spec.name}: CPU s, medians of {repeats} interleaved runs per tree")
    for t, tree in enumerate(trees):
        print(f"  [{t}] {tree}")
    print(f"  {'':40}" + "".join(f"{f'[{t}]':>10}" for t in range(len(trees))))
    for label in labels:
        cells = [statistics.median(run.get(label, 0.0) for run in runs) for runs in clocks]
        print(f"  {label:40}" + "".join(f"{c:10.4f}" for c in cells))


if __name__ == "__main__":
    main()
