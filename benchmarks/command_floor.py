"""The import floor of one corrugate command: every module it imports, imported as it does.

Run by hand (about a minute)::

    .venv/bin/python benchmarks/command_floor.py [--repeats 11] -- design examples/blimp_gripper.toml --out {out}

First the command runs once in this checkout's tree (``corrugate.cli.main`` in a fresh
interpreter) to list the modules it leaves in ``sys.modules``, without those it holds as lazy
modules never executed (fontTools' subsetter: ``corrugate.core.plotting.pdf_pages``). Then, in
fresh processes interleaved ``--repeats`` times, it charges the user + system CPU time of (1) a
bare ``python -c pass``, (2) importing exactly those modules the way a command's process does
(``corrugate.cli.main``'s set-up: the collector's thresholds, numpy with one BLAS thread,
pydantic without its plugin scan, matplotlib leanly with the subsetter lazy, the objects frozen
at exit) and (3) the command itself, and prints their medians: what the command costs beyond its
imports (its work: solving, printing, drawing and writing) is (3) - (2), and (2) is the most any
change of import order or laziness inside the package could still save, short of importing fewer
modules (issue 39). ``benchmarks/pipeline.py``'s floors import each library bare instead (the
collector's default thresholds, matplotlib's full help, the subsetter executed), which costs more
than the command pays for the same libraries. ``{out}`` is replaced by a new empty folder.

Two more rows split (2): ``its library modules`` imports only the listed modules that are not
corrugate's, set up the same way (so with the few modules of the set-up itself:
:mod:`corrugate.cli`, whose import builds the typer app, and the small ``corrugate.core`` modules
it calls): what no change inside the package's other modules can remove, short of not using
those libraries; and ``frozen dataclasses of ours`` is the CPU time
:mod:`dataclasses` spends making corrugate's own value classes (``dataclasses._process_class``
clocked with :func:`time.process_time` in a fresh process that imports the listed modules; on
Python 3.11 each frozen dataclass compiles and executes five or six generated methods).
"""

from __future__ import annotations

import argparse
import os
import statistics
import subprocess
import sys
import sysconfig
import tempfile
from pathlib import Path

from pipeline import child_cpu  # type: ignore[import-not-found]  (benchmarks/, beside this)

ROOT = Path(__file__).resolve().parents[1]

#: Runs the command in process and prints the modules it left executed, one per line.
_LIST = r"""
import contextlib, importlib.util, io, sys
from corrugate.cli import main
try:
    with contextlib.redirect_stdout(io.StringIO()), contextlib.redirect_stderr(io.StringIO()):
        main(sys.argv[1:])
except SystemExit as exc:
    assert exc.code in (0, None), exc.code
lazy = importlib.util._LazyModule
print("\n".join(m for m, v in list(sys.modules.items())
                if v is not None and not isinstance(v, lazy) and m != "__main__"))
"""

#: Imports the modules listed in the file argv[1] as :data:`_IMPORT` does, with a clock around
#: the making of each dataclass; prints the seconds spent on corrugate's and their number.
_CLASSES = r"""
import dataclasses, sys, time
spent, made = [0.0], [0]
_process = dataclasses._process_class
def clocked(cls, *args):
    t = time.process_time()
    try:
        return _process(cls, *args)
    finally:
        if cls.__module__.startswith("corrugate"):
            spent[0] += time.process_time() - t
            made[0] += 1
dataclasses._process_class = clocked
exec(compile(open(sys.argv[2], encoding="utf-8").read(), "<import>", "exec"))
print(spent[0], made[0])
"""

#: Imports the modules listed in the file argv[1] as a command's process does.
_IMPORT = r"""
import gc, importlib, sys
from corrugate.cli import GC_THRESHOLDS
gc.set_threshold(*GC_THRESHOLDS)
from corrugate.core.blas import one_blas_thread
from corrugate.core.plotting import import_figure_module, lean_import, pdf_pages
from corrugate.core.plugins import without_pydantic_plugins
one_blas_thread(); without_pydantic_plugins(); lean_import()
names = open(sys.argv[1], encoding="utf-8").read().split()
if "matplotlib.figure" in names:
    import_figure_module()
if "matplotlib.backends.backend_pdf" in names:
    pdf_pages()
for name in names:
    if name not in sys.modules:
        try:
            importlib.import_module(name)
        except Exception:  # a module that only imports inside another's import
            pass
gc.freeze()
"""


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.split("\n", 1)[0])
    parser.add_argument("--repeats", type=int, default=11, help="runs of each (median)")
    parser.add_argument("command", nargs="+", help="corrugate's arguments (after --)")
    args = parser.parse_args()
    src = ROOT / "src"
    for tree in (src, Path(sysconfig.get_paths()["purelib"])):  # bytecode once
        subprocess.run([sys.executable, "-m", "compileall", "-q", str(tree)], check=True)
    env = {**os.environ, "PYTHONPATH": str(src)}
    with tempfile.TemporaryDirectory(prefix="corrugate-floor-") as tmp:
        listed = [a.replace("{out}", str(Path(tmp) / "list")) for a in args.command]
        names = subprocess.run(
            [sys.executable, "-c", _LIST, *listed],
            env=env,
            capture_output=True,
            text=True,
            check=True,
            cwd=ROOT,
        ).stdout.split()
        modules = Path(tmp) / "modules.txt"
        modules.write_text("\n".join(names), encoding="utf-8")
        libraries = Path(tmp) / "libraries.txt"
        theirs = [n for n in names if n != "corrugate" and not n.startswith("corrugate.")]
        libraries.write_text("\n".join(theirs), encoding="utf-8")
        importer = Path(tmp) / "import.py"
        importer.write_text(_IMPORT, encoding="utf-8")
        runs: dict[str, list[float]] = {"pass": [], "libraries": [], "imports": [], "command": []}
        classes: list[float] = []
        made = 0
        for k in range(args.repeats):
            command = [a.replace("{out}", str(Path(tmp) / f"out-{k}")) for a in args.command]
            argvs = {
                "pass": [sys.executable, "-c", "pass"],
                "libraries": [sys.executable, "-c", _IMPORT, str(libraries)],
                "imports": [sys.executable, "-c", _IMPORT, str(modules)],
                "command": [sys.executable, "-m", "corrugate", *command],
            }
            for label, argv in argvs.items():
                runs[label].append(child_cpu(argv, env))
            clock = subprocess.run(
                [sys.executable, "-c", _CLASSES, str(modules), str(importer)],
                env=env,
                capture_output=True,
                text=True,
                check=True,
            ).stdout.split()
            classes.append(float(clock[0]))
            made = int(clock[1])
            print(f"run {k + 1}/{args.repeats} done", file=sys.stderr)
    med = {label: statistics.median(v) for label, v in runs.items()}
    spread = {label: f"[{min(v):.3f}-{max(v):.3f}]" for label, v in runs.items()}
    print(f"corrugate {' '.join(args.command)}: CPU s, medians of {args.repeats} interleaved runs")
    print(f"  python -c pass                       {med['pass']:.3f} s {spread['pass']}")
    print(
        f"  its {len(theirs)} library modules (and set-up) {med['libraries']:.3f} s "
        f"{spread['libraries']}"
    )
    print(
        f"  its {len(names)} modules, imported as it does {med['imports']:.3f} s "
        f"{spread['imports']}"
    )
    print(f"  the command                          {med['command']:.3f} s {spread['command']}")
    print(f"  its work (command - imports)         {med['command'] - med['imports']:.3f} s")
    print(
        f"  of its imports, corrugate's others   {med['imports'] - med['libraries']:.3f} s, "
        f"of which making its {made} frozen dataclasses {statistics.median(classes):.3f} s "
        f"[{min(classes):.3f}-{max(classes):.3f}]"
    )


if __name__ == "__main__":
    main()
