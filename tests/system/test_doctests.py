"""The docstring examples (``>>>``) of the package run as tests: every module under
src/corrugate whose source holds one, found by reading the files (a new example is picked up
without a list to update), imported and run with :mod:`doctest`."""

from __future__ import annotations

import doctest
import importlib
import io
from pathlib import Path

import pytest

import corrugate

PACKAGE = Path(corrugate.__file__).resolve().parent


def _modules_with_examples() -> list[str]:
    names = []
    for path in sorted(PACKAGE.rglob("*.py")):
        if ">>>" in path.read_text("utf-8"):
            rel = path.relative_to(PACKAGE.parent).with_suffix("")
            names.append(".".join(rel.parts).removesuffix(".__init__"))
    return names


MODULES = _modules_with_examples()


def test_the_package_has_examples() -> None:
    """At least analyze's (the paper's Table 1, case 1) and sweep's (the case study)."""
    assert {"corrugate.analysis.evaluate", "corrugate.analysis.sweep"} <= set(MODULES)


@pytest.mark.parametrize("name", MODULES)
def test_docstring_examples(name: str) -> None:
    try:
        module = importlib.import_module(name)
    except ImportError as exc:  # a module of an optional extra that is not installed
        pytest.skip(f"{name} needs an extra: {exc}")
    finder = doctest.DocTestFinder()
    runner = doctest.DocTestRunner(optionflags=doctest.ELLIPSIS | doctest.NORMALIZE_WHITESPACE)
    out = io.StringIO()
    tests = [t for t in finder.find(module, name) if t.examples]
    assert tests, f"{name} has '>>>' but no example doctest finds"
    for test in tests:
        runner.run(test, out=out.write)
    result = runner.summarize(verbose=False)
    assert result.failed == 0, out.getvalue()
    assert result.attempted > 0
