"""The CPU time of each import of one corrugate command, by module and by library (issue 39).

Run by hand (a few seconds per repeat)::

    PYTHONPATH=src .venv/bin/python benchmarks/import_cpu.py [--repeats 7] [--top 25] -- design examples/blimp_gripper.toml

``python -X importtime`` measures wall-clock time, which a shared machine's load inflates at
random; this runs the command (``corrugate.cli.main``, in process, its output discarded) in fresh
interpreters with a finder first on ``sys.meta_path`` that charges each module's execution the
process CPU time it took (:func:`time.process_time`), less that of the modules it imported
itself (its self time), and prints the median over ``--repeats`` runs: the command's whole CPU
in the interpreter, how much of it was imports, each library's self time (the package's own
subpackages one by one) and the ``--top`` modules. What no import accounts for is the
command's work (and the finder's own bookkeeping). Each run compiles nothing: the sources'
bytecode is written once first, as ``benchmarks/pipeline.py`` does. An ``{out}`` argument is
replaced by a new empty folder of each run.
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
from collections import defaultdict
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]

#: Runs in the child: the command under the CPU-charging finder; prints one JSON line.
_CHILD = r"""
import contextlib, gc, importlib.abc, io, json, sys, time
gc.set_threshold(500_000, 20, 100)  # python -m corrugate's thresholds (corrugate/__main__.py)
start = time.process_time()
stack, seen = [], {}


class Charging(importlib.abc.MetaPathFinder):
    def find_spec(self, name, path=None, target=None):
        for finder in sys.meta_path:
            if finder is self or not hasattr(finder, "find_spec"):
                continue
            spec = finder.find_spec(name, path, target)
            if spec is None:
                continue
            loader = spec.loader
            if loader is not None and hasattr(loader, "exec_module"):
                run = loader.exec_module

                def exec_module(module, run=run, name=name):
                    stack.append([time.process_time(), 0.0])
                    try:
                        run(module)
                    finally:
                        began, children = stack.pop()
                        spent = time.process_time() - began
                        seen[name] = spent - children
                        if stack:
                            stack[-1][1] += spent

                try:
                    loader.exec_module = exec_module
                except (AttributeError, TypeError):
                    pass
            return spec
        return None


sys.meta_path.insert(0, Charging())
from corrugate.cli import main

try:
    with contextlib.redirect_stdout(io.StringIO()), contextlib.redirect_stderr(io.StringIO()):
        main(sys.argv[1:])
except SystemExit as exc:
    assert exc.code in (0, None), exc.code
print(json.dumps({"start": start, "total": time.process_time(), "self": seen}))
"""


def library(module: str) -> str:
    """The library a module is charged to: its top-level package, or ``corrugate.X``."""
    parts = module.split(".")
    return ".".join(parts[:2]) if parts[0] == "corrugate" and len(parts) > 1 else parts[0]


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.split("\n", 1)[0])
    parser.add_argument("--repeats", type=int, default=7, help="runs (median)")
    parser.add_argument("--top", type=int, default=25, help="modules listed")
    parser.add_argument("command", nargs="+", help="corrugate's arguments (after --)")
    args = parser.parse_args()
    src = ROOT / "src"
    for tree in (src, Path(sysconfig.get_paths()["purelib"])):
        subprocess.run([sys.executable, "-m", "compileall", "-q", str(tree)], check=True)
    env = {**os.environ, "PYTHONPATH": str(src)}
    runs = []
    with tempfile.TemporaryDirectory(prefix="corrugate-imports-") as tmp:
        for k in range(args.repeats):
            argv = [a.replace("{out}", str(Path(tmp) / f"out-{k}")) for a in args.command]
            done = subprocess.run(
                [sys.executable, "-c", _CHILD, *argv],
                env=env,
                capture_output=True,
                text=True,
                check=True,
                cwd=ROOT,
            )
            runs.append(json.loads(done.stdout.splitlines()[-1]))
    med = statistics.median
    total = med(r["total"] for r in runs)
    modules = sorted({m for r in runs for m in r["self"]})
    own = {m: med(r["self"].get(m, 0.0) for r in runs) for m in modules}
    libraries: dict[str, float] = defaultdict(float)
    for m, spent in own.items():
        libraries[library(m)] += spent
    imports = sum(own.values())
    print(f"corrugate {' '.join(args.command)}: medians of {args.repeats} runs, CPU seconds")
    start = med(r["start"] for r in runs)
    print(f"  in the interpreter {total:.3f} s: start-up {start:.3f} s, imports {imports:.3f} s")
    print(f"  ({len(modules)} modules), the rest {total - start - imports:.3f} s (the work)")
    print("\nself time by library (those of 2 ms or more)")
    small = 0.0
    for name, spent in sorted(libraries.items(), key=lambda x: -x[1]):
        if spent >= 0.002:
            print(f"  {spent:7.3f} s  {name}")
        else:
            small += spent
    print(f"  {small:7.3f} s  the other {sum(v < 0.002 for v in libraries.values())} libraries")
    print(f"\nthe {args.top} modules of most self time")
    for m in sorted(own, key=lambda m: -own[m])[: args.top]:
        print(f"  {own[m]:7.4f} s  {m}")


if __name__ == "__main__":
    main()
