"""The package's module-level imports form no cycle (imports inside functions are lazy and allowed).

Every module under ``src/corrugate`` is parsed with :mod:`ast` (nothing is imported); an edge
``a -> b`` is a module-level ``import``/``from ... import`` of ``b`` in ``a`` (``from .x import y``
counts ``x.y`` when that is a module, else ``x``). The implicit import of a module's own parent
packages is not an edge (every submodule has it; Python runs a package's ``__init__`` first). ``if TYPE_CHECKING:`` blocks are skipped: they
never run.

The last tests run a command in a fresh interpreter and list what it imported: ``design``'s
answer loads none of the writers' libraries (issue 39).
"""

from __future__ import annotations

import ast
import os
import subprocess
import sys
from pathlib import Path

import pytest

SRC = Path(__file__).resolve().parents[2] / "src"
PACKAGE = "corrugate"


def _modules() -> dict[str, Path]:
    """Dotted name -> file of every module of the package (a package by its ``__init__``)."""
    found: dict[str, Path] = {}
    for path in sorted((SRC / PACKAGE).rglob("*.py")):
        parts = list(path.relative_to(SRC).with_suffix("").parts)
        if parts[-1] == "__init__":
            parts.pop()
        found[".".join(parts)] = path
    return found


def _is_type_checking(test: ast.expr) -> bool:
    return (isinstance(test, ast.Name) and test.id == "TYPE_CHECKING") or (
        isinstance(test, ast.Attribute) and test.attr == "TYPE_CHECKING"
    )


def _top_level_imports(tree: ast.Module) -> list[ast.Import | ast.ImportFrom]:
    """The imports that run when the module is imported: the body, its try/if blocks (not
    functions, classes' methods or ``if TYPE_CHECKING:``)."""
    out: list[ast.Import | ast.ImportFrom] = []
    stack: list[ast.stmt] = list(tree.body)
    while stack:
        node = stack.pop()
        if isinstance(node, ast.Import | ast.ImportFrom):
            out.append(node)
        elif isinstance(node, ast.If):
            if not _is_type_checking(node.test):
                stack.extend(node.body)
            stack.extend(node.orelse)
        elif isinstance(node, ast.Try):
            stack.extend(node.body + node.orelse + node.finalbody)
            for handler in node.handlers:
                stack.extend(handler.body)
        elif isinstance(node, ast.With):
            stack.extend(node.body)
        elif isinstance(node, ast.ClassDef):
            stack.extend(n for n in node.body if not isinstance(n, ast.FunctionDef))
    return out


def import_graph() -> dict[str, set[str]]:
    """Module -> the package modules it imports at module level."""
    modules = _modules()
    graph: dict[str, set[str]] = {name: set() for name in modules}
    for name, path in modules.items():
        is_package = path.name == "__init__.py"
        here = name.split(".") if is_package else name.split(".")[:-1]
        tree = ast.parse(path.read_text(encoding="utf-8"), filename=str(path))
        for node in _top_level_imports(tree):
            targets: list[str] = []
            if isinstance(node, ast.Import):
                targets = [alias.name for alias in node.names]
            else:
                if node.level:
                    base_parts = here[: len(here) - (node.level - 1)]
                    base = ".".join(base_parts + ([node.module] if node.module else []))
                else:
                    base = node.module or ""
                # ``from .x import y``: the module x.y if there is one, else x (y is a name in it).
                targets = [
                    f"{base}.{alias.name}" if f"{base}.{alias.name}" in modules else base
                    for alias in node.names
                ]
            for target in targets:
                if target in modules and target != name:
                    graph[name].add(target)
    return graph


def find_cycle(graph: dict[str, set[str]]) -> list[str] | None:
    """One cycle of ``graph`` as a list of modules (first repeated at the end), or None."""
    state: dict[str, int] = {}  # 1: on the current path, 2: done
    path: list[str] = []

    def visit(node: str) -> list[str] | None:
        state[node] = 1
        path.append(node)
        for nxt in sorted(graph[node]):
            if state.get(nxt) == 1:
                return [*path[path.index(nxt) :], nxt]
            if nxt not in state:
                found = visit(nxt)
                if found:
                    return found
        path.pop()
        state[node] = 2
        return None

    for start in sorted(graph):
        if start not in state:
            found = visit(start)
            if found:
                return found
    return None


def test_the_graph_sees_the_package() -> None:
    graph = import_graph()
    assert "corrugate.analysis.evaluate" in graph and "corrugate.cli" in graph
    assert "corrugate.geometry.layer" in graph["corrugate.analysis.evaluate"]
    # A module-level import of a submodule through its package counts (solver/__init__ imports solve).
    assert "corrugate.solver.solve" in graph["corrugate.solver"]


def test_find_cycle_finds_a_planted_cycle() -> None:
    assert find_cycle({"a": {"b"}, "b": {"c"}, "c": {"a"}, "d": set()}) == ["a", "b", "c", "a"]
    assert find_cycle({"a": {"b"}, "b": set()}) is None


def test_package_imports_are_acyclic() -> None:
    cycle = find_cycle(import_graph())
    if cycle is not None:
        pytest.fail("import cycle: " + " -> ".join(cycle))


def test_the_command_line_loads_no_command_work_until_a_command_runs() -> None:
    """The CLI with every command registered (:data:`corrugate.cli.app`) loads none of the
    modules the commands work with: only the names, the core (errors) and the command modules
    themselves."""
    code = (
        "import sys, corrugate.cli\n"
        "corrugate.cli.app\n"
        "print(sorted(m for m in sys.modules if m.startswith('corrugate.')))\n"
    )
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True)
    loaded = set(ast.literal_eval(out.stdout.strip()))
    assert "corrugate.cli.validate" in loaded  # the command modules themselves are there
    light = ("names", "core", "cli")  # every other folder holds work a command does
    found = sorted(m for m in loaded if m.split(".")[1] not in light)
    assert found == [], found


#: What ``corrugate design`` of the case study must not import (issue 39: its answer within
#: 0.25 s of CPU): the file writers' libraries, the finite elements, the web app and calibration,
#: pydantic's plugin scan (``importlib.metadata``, with the email parser it imports), and the
#: modules only other specs' paths call: the FE step and the notebook's calls, the pattern's
#: classes, the layer-by-layer search of independent layers, the search by cells (continuous W
#: and alpha on independent layers) and its binding checks, the polish, the diagnosis of an
#: infeasible spec, a load case's capacity, a measured sheet's calibration, a layout's holes,
#: the profiles other than the zig-zag and the wheel test's factors.
_NOT_FOR_AN_ANSWER = (
    "corrugate.mechanics.wheel",
    "corrugate.mechanics.profiles.trapezoid",
    "corrugate.geometry.holes",
    "corrugate.materials.calibrated",
    "corrugate.workflow.fe",
    "corrugate.workflow.notebook",
    "corrugate.fabrication.model",
    "corrugate.solver.separable",
    "corrugate.solver.cells",
    "corrugate.solver.cell_checks",
    "corrugate.solver.polish",
    "corrugate.solver.diagnosis",
    "corrugate.mechanics.capacity",
    "matplotlib",
    "ezdxf",
    "PIL",
    "fontTools",
    "pyparsing",
    "dask",
    "gmsh",
    "importlib.metadata",
    "email",
    "corrugate.report",
    "corrugate.fea",
    "corrugate.web",
    "corrugate.calibration",
)


def _command_modules(*argv: str) -> tuple[set[str], int | None]:
    """The modules a fresh interpreter holds after ``corrugate ARGV`` (run by
    :func:`corrugate.cli.main`, its output discarded), and its threads then (``/proc``, Linux;
    None elsewhere)."""
    code = (
        "import contextlib, io, os, sys\n"
        "from corrugate.cli import main\n"
        "try:\n"
        "    with contextlib.redirect_stdout(io.StringIO()):\n"
        f"        main({list(argv)!r})\n"
        "except SystemExit as exc:\n"
        "    assert exc.code in (0, None), exc.code\n"
        "task = '/proc/self/task'\n"
        "threads = len(os.listdir(task)) if os.path.isdir(task) else None\n"
        "print(repr((sorted(sys.modules), threads)))\n"
    )
    env = {k: v for k, v in os.environ.items() if k not in ("OPENBLAS_NUM_THREADS",)}
    env.pop("PYDANTIC_DISABLE_PLUGINS", None)
    out = subprocess.run(
        [sys.executable, "-c", code],
        capture_output=True,
        text=True,
        check=True,
        cwd=SRC.parent,
        env=env,
    )
    modules, threads = ast.literal_eval(out.stdout.strip().splitlines()[-1])
    return set(modules), threads


def test_design_imports_what_its_answer_needs_and_nothing_else() -> None:
    modules, threads = _command_modules("design", "examples/blimp_gripper.toml")
    assert "numpy" in modules and "corrugate.solver" in modules  # it did run
    found = sorted(
        m for m in modules for name in _NOT_FOR_AN_ANSWER if m == name or m.startswith(name + ".")
    )
    assert found == [], found
    if threads is not None:
        assert threads == 1  # numpy's BLAS started no thread (corrugate.core.blas)


@pytest.mark.slow
def test_design_out_loads_no_subsetter_no_package_metadata() -> None:
    """``design --out`` draws and writes every file without pydantic's plugin scan
    (``importlib.metadata``: no library it draws or writes with imports it) and on one BLAS
    thread."""
    import tempfile

    with tempfile.TemporaryDirectory() as tmp:
        modules, threads = _command_modules(
            "design", "examples/blimp_gripper.toml", "--out", str(Path(tmp) / "set")
        )
    assert "matplotlib.figure" in modules and "ezdxf" in modules  # it did write
    assert not any(
        m == "importlib.metadata" or m.startswith("importlib.metadata.") for m in modules
    )
    if threads is not None:
        assert threads == 1
