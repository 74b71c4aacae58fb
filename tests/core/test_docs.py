"""The docs ship inside the package (``corrugate/data/docs``, linked to the repository's ``docs/``)
and ``corrugate docs [NAME]`` lists and prints them; every doc the package cites exists there."""

from __future__ import annotations

import re
from pathlib import Path
from typing import TYPE_CHECKING

import pytest

from corrugate.core.docs import CITATION, doc_names, doc_text, doc_title
from corrugate.core.errors import UnknownNameError

if TYPE_CHECKING:
    from conftest import CliRun

ROOT = Path(__file__).resolve().parents[2]
PACKAGE = ROOT / "src" / "corrugate"
#: Files of the package that may cite a doc: code, data, templates and the web page.
CITING = ("*.py", "*.toml", "*.html", "*.js")


def _citations() -> dict[str, set[str]]:
    """Every doc name cited anywhere in the package, with the files citing it."""
    found: dict[str, set[str]] = {}
    for pattern in CITING:
        for path in PACKAGE.rglob(pattern):
            if "vendor" in path.parts:
                continue
            for m in CITATION.finditer(path.read_text("utf-8")):
                name = m.group(1) or m.group(2)
                found.setdefault(name, set()).add(str(path.relative_to(ROOT)))
    return found


def test_the_package_cites_docs_and_every_cited_doc_is_shipped() -> None:
    cited = _citations()
    # the messages cite at least these (warnings, validate's legend, the report)
    assert {"fea", "offaxis", "validation/off_axis", "spec", "fabrication"} <= set(cited)
    missing = {name: files for name, files in cited.items() if name not in doc_names()}
    assert not missing, f"cited but not shipped: {missing}"


def test_user_facing_messages_cite_docs_by_command_not_by_repository_path() -> None:
    """Strings a user reads (warnings, help, the report, the template) say `corrugate docs NAME`;
    a repository path ``docs/X.md`` is left only in docstrings and comments of the source."""
    from corrugate.analysis.evaluate import analyze
    from corrugate.geometry.layer import Assembly, Layer
    from corrugate.materials.library import get_material

    layer = Layer(W=8.0, n=5, alpha_deg=84.0, material=get_material("dura-lar"), t=0.125)
    result = analyze(Assembly.identical(layer), "refined", [0.0, 30.0])
    texts = [w.message for w in result.warnings]
    assert any("corrugate docs offaxis" in t for t in texts)
    for text in texts:
        assert not re.search(r"docs/[a-z_/]+\.md", text), text
    template = (PACKAGE / "data" / "template.toml").read_text()
    assert "docs/spec.md" not in template and "corrugate docs spec" in template


def test_shipped_docs_are_the_repository_docs() -> None:
    names = doc_names()
    assert {"fea", "offaxis", "fabrication", "spec", "theory", "notebook", "calibration"} <= set(
        names
    )
    for name in names:
        assert doc_text(name) == (ROOT / "docs" / f"{name}.md").read_text("utf-8"), name
    # every Markdown doc of the repository (but the generated validation tables) is shipped
    top = {p.stem for p in (ROOT / "docs").glob("*.md")}
    assert top <= set(names)


def test_doc_names_accept_a_repository_path_and_reject_unknown_ones() -> None:
    assert doc_text("docs/fea.md") == doc_text("fea")
    assert doc_title("fea").startswith("Finite-element validation")
    with pytest.raises(UnknownNameError, match="offaxis"):
        doc_text("nope")


def test_docs_command_lists_and_prints(cli: CliRun) -> None:
    code, out, _ = cli(["docs"])
    assert code == 0
    listed = [line.split()[0] for line in out.splitlines()[:-1]]
    assert listed == doc_names()
    code, out, _ = cli(["docs", "offaxis"])
    assert code == 0 and out == doc_text("offaxis")
    code, out, err = cli(["docs", "feaa"])
    assert code == 2 and out == ""
    assert err.count("\n") == 1 and "'feaa'" in err and "fea" in err


def test_pyproject_ships_the_docs_folder() -> None:
    """The wheel's package data must include data/docs (and its validation/ subfolder)."""
    import tomllib

    data = tomllib.loads((ROOT / "pyproject.toml").read_text())
    globs = data["tool"]["setuptools"]["package-data"]["corrugate"]
    assert "data/docs/*.md" in globs and "data/docs/*/*.md" in globs
    for name in doc_names():
        depth = name.count("/")
        assert f"data/docs/{'*/' * depth}*.md" in globs, name
