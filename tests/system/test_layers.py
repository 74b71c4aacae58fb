"""The package's layers: each folder is one concept and one layer, and imports run one way.

Every import of every module under ``src/corrugate`` counts: module level, inside functions
(lazy), and under ``if TYPE_CHECKING:``; the files are parsed with :mod:`ast`, nothing is
imported. A module may import its own folder and the layers before it in :data:`ORDER`, never one
after it. docs/architecture.md describes the layers.
"""

from __future__ import annotations

import ast
from pathlib import Path

import pytest

SRC = Path(__file__).resolve().parents[2] / "src"
PACKAGE = SRC / "corrugate"

#: The layers, lowest first: the top-level module ``names`` and every folder.
ORDER = (
    "names",
    "core",
    "materials",
    "geometry",
    "mechanics",
    "analysis",
    "spec",
    "solver",
    "fea",
    "fabrication",
    "export",
    "report",
    "calibration",
    "workflow",
    "web",
    "cli",
    "__main__",
)

#: What the top-level package holds besides its layer folders and ``data/``.
TOP_LEVEL = {"__init__.py", "__main__.py", "names.py", "py.typed"}


def _module_name(path: Path, src: Path) -> tuple[str, bool]:
    parts = list(path.relative_to(src).with_suffix("").parts)
    is_package = parts[-1] == "__init__"
    if is_package:
        parts.pop()
    return ".".join(parts), is_package


def all_imports(path: Path, src: Path = SRC) -> list[tuple[int, str, list[str]]]:
    """(line, imported module, names) of every import statement in ``path`` (a file under
    ``src``), at any depth: module level, in functions, under ``if TYPE_CHECKING:``."""
    name, is_package = _module_name(path, src)
    here = name.split(".") if is_package else name.split(".")[:-1]
    found: list[tuple[int, str, list[str]]] = []
    for node in ast.walk(ast.parse(path.read_text(encoding="utf-8"), filename=str(path))):
        if isinstance(node, ast.Import):
            found += [(node.lineno, alias.name, []) for alias in node.names]
        elif isinstance(node, ast.ImportFrom):
            if node.level:
                base = here[: len(here) - (node.level - 1)] + ([node.module] if node.module else [])
                target = ".".join(base)
            else:
                target = node.module or ""
            found.append((node.lineno, target, [alias.name for alias in node.names]))
    return found


def layer_of(module: str) -> str | None:
    """The layer of a dotted module name (``corrugate.solver.bnb`` -> ``solver``); None for the
    package itself."""
    parts = module.split(".")
    return parts[1] if len(parts) > 1 else None


def upward_imports(src: Path = SRC) -> list[str]:
    """Every import of a later layer (or of an unknown one) in ``src/corrugate``, as
    ``file:line: a -> b (why)``."""
    bad: list[str] = []
    for path in sorted((src / "corrugate").rglob("*.py")):
        module, _ = _module_name(path, src)
        mine = layer_of(module)
        for line, target, names in all_imports(path, src):
            if target != "corrugate" and not target.startswith("corrugate."):
                continue
            theirs = layer_of(target)
            where = f"{path.relative_to(src)}:{line}: {module} -> {target}"
            if mine is None:  # the package's __init__: the public API, imported lazily
                continue
            if theirs is None:  # ``from corrugate import x``: only the version
                if set(names) - {"__version__"}:
                    bad.append(f"{where} {names} (import from the module that defines them)")
                continue
            if mine not in ORDER or theirs not in ORDER:
                bad.append(f"{where} (a layer missing from ORDER)")
            elif ORDER.index(theirs) > ORDER.index(mine):
                bad.append(f"{where} ({theirs} is above {mine})")
    return bad


def test_the_checker_sees_a_planted_upward_import(tmp_path: Path) -> None:
    root = tmp_path / "src" / "corrugate"
    (root / "core").mkdir(parents=True)
    (root / "core" / "bad.py").write_text(
        "def f():\n    from corrugate.solver.bnb import branch_and_bound\n", encoding="utf-8"
    )
    (root / "core" / "typed.py").write_text(
        "from typing import TYPE_CHECKING\nif TYPE_CHECKING:\n    from ..analysis import x\n",
        encoding="utf-8",
    )
    (root / "core" / "fine.py").write_text("from corrugate.names import MODEL_NAMES\n")
    found = upward_imports(tmp_path / "src")
    assert len(found) == 2, found
    assert "solver is above core" in found[0] or "solver is above core" in found[1]
    assert any("corrugate.analysis" in f for f in found)


def test_no_module_imports_a_layer_above_it() -> None:
    bad = upward_imports()
    if bad:
        pytest.fail("imports against the layer order:\n" + "\n".join(bad))


def test_every_folder_is_a_layer_and_the_top_level_holds_only_the_api() -> None:
    folders = {p.name for p in PACKAGE.iterdir() if p.is_dir() and p.name != "__pycache__"}
    assert folders - {"data"} <= set(ORDER), folders - set(ORDER)
    assert set(ORDER) - {"names", "__main__"} <= folders
    files = {p.name for p in PACKAGE.iterdir() if p.is_file()}
    assert files == TOP_LEVEL, files ^ TOP_LEVEL
    # every layer folder is a package with a docstring saying what it holds
    for folder in sorted(folders - {"data"}):
        init = PACKAGE / folder / "__init__.py"
        assert init.is_file(), init
        assert ast.get_docstring(ast.parse(init.read_text(encoding="utf-8"))), init


def test_names_imports_nothing_of_the_package() -> None:
    imported = [t for _, t, _ in all_imports(PACKAGE / "names.py")]
    assert not [t for t in imported if t.startswith("corrugate")], imported
    assert "numpy" not in imported
