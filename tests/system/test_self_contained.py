"""The repository tests itself: every file the tests read is inside the checkout, so a bare clone
runs them with nothing beside it. The ``reference`` fixture and its files resolve (links followed)
inside the repository, and no test's source reaches outside it (``parents[k]`` past the root, the
root's parent, or the shared reference folder the data was copied from)."""

from __future__ import annotations

import json
import re
from pathlib import Path

ROOT = Path(__file__).resolve().parents[2]
TESTS = ROOT / "tests"
#: The files the tests read from the ``reference`` fixture.
REFERENCE_FILES = ("unitcell_fe.csv", "xia2012_table5.json")
#: Spellings of a path outside the checkout, joined at run time so that neither this file nor
#: its bytecode contains them (the compiler folds "a" + "b" into one constant, and a search of
#: the tree for them found this test's .pyc).
OUTSIDE = tuple(
    "".join(parts)
    for parts in (
        ("/work/", "shared"),
        ("shared/", "reference"),
        ("CORRUGATE_", "REFERENCE"),
        ("../", "shared"),
        # the brief's reference folder by its files' names: the repository's copies are
        # docs/data/unitcell_fe.csv and tests/data/xia2012_table5.json
        ("reference/", "unitcell_fe"),
        ("reference/", "xia2012"),
    )
)
PARENTS = re.compile(r"Path\(__file__\)\.resolve\(\)\.parents\[(\d+)\]")
ROOT_PARENT = re.compile(r"\b[A-Z_]*ROOT\s*(\.parent\b|/\s*[\"']\.\.[\"'])")


def test_reference_data_resolves_inside_the_repository(reference: Path) -> None:
    assert reference.resolve().is_relative_to(ROOT)
    for name in REFERENCE_FILES:
        path = (reference / name).resolve()  # tests/data/unitcell_fe.csv links to docs/data
        assert path.is_file() and path.is_relative_to(ROOT), name


def test_each_reference_file_names_its_source(reference: Path) -> None:
    """The CSV's first comment line and the JSON's ``source`` key say where the data came from;
    the JSON's readers (tests/mechanics/test_profiles.py) take only ``input`` and ``expected``."""
    first = (reference / "unitcell_fe.csv").read_text().splitlines()[0]
    assert first.startswith("# Source: ") and "unitcell_fe.csv" in first
    data = json.loads((reference / "xia2012_table5.json").read_text())
    assert "xia2012_table5.json" in data["source"]
    assert {"input", "expected"} <= set(data)


def test_no_test_reads_a_path_outside_the_repository() -> None:
    offences: list[str] = []
    sources = sorted(TESTS.rglob("*.py"))
    assert len(sources) > 40
    for path in sources:
        rel = path.relative_to(ROOT)
        text = path.read_text("utf-8")
        for k in PARENTS.findall(text):
            # tests/<folder>/x.py: parents[2] is the root, parents[3] its parent
            if int(k) > len(rel.parts) - 1:
                offences.append(f"{rel}: parents[{k}] is outside the repository")
        if path.name != Path(__file__).name:
            offences += [f"{rel}: {word}" for word in OUTSIDE if word in text]
        offences += [f"{rel}: {m.group(0)}" for m in ROOT_PARENT.finditer(text)]
    assert offences == []


def test_no_code_names_a_path_outside_the_repository() -> None:
    """The package, the benchmarks and the docs name the repository's copies of the reference
    data, never the folder outside the checkout it was copied from."""
    sources = [
        *sorted((ROOT / "src").rglob("*.py")),
        *sorted((ROOT / "benchmarks").rglob("*.py")),
        *sorted((ROOT / "docs").rglob("*.md")),
        ROOT / "README.md",
        ROOT / "Makefile",
    ]
    offences = [
        f"{path.relative_to(ROOT)}: {word}"
        for path in sources
        if path.is_file() and not path.is_symlink()
        for word in OUTSIDE
        if word in path.read_text("utf-8")
    ]
    assert offences == []
