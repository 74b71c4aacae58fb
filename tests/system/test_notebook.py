"""docs/notebook.md runs: its Python blocks, in order, in one namespace, from the repository root
(each block's own asserts are the checks; a block that raises fails the test)."""

from __future__ import annotations

import re
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[2]


def blocks() -> list[str]:
    text = (ROOT / "docs" / "notebook.md").read_text()
    return re.findall(r"```python\n(.*?)```", text, flags=re.S)


@pytest.mark.slow
def test_the_notebook_page_runs(
    monkeypatch: pytest.MonkeyPatch, capsys: pytest.CaptureFixture[str]
) -> None:
    code = blocks()
    assert len(code) >= 5
    monkeypatch.chdir(ROOT)
    namespace: dict[str, object] = {}
    for i, block in enumerate(code):
        exec(compile(block, f"docs/notebook.md block {i + 1}", "exec"), namespace)
    shown = capsys.readouterr().out
    # what the page prints: the five-line repr of the answer, the constraint table, the files
    assert shown.startswith("Solution(optimal, certified=True")
    assert "cut-1.svg" in shown and "K(45): free" in shown
    assert all(len(repr(namespace[k]).splitlines()) <= 5 for k in ("result", "pad", "analysis"))
