"""Every command the README and docs/ show with its output runs here, and prints what they show.

A shown command is a line ``$ corrugate ...`` in a fenced block; the lines after it, up to the next
``$`` line or the block's end, are its output. Each command runs in-process (``corrugate.cli.main``,
as the ``cli`` fixture does), in a folder of its own per document (``tmp_path``, holding a link to
the repository's ``examples/``), so ``--out out/x`` writes there and a document's commands see the
files its earlier ones wrote. A block preceded by ``<!-- file: NAME -->`` is written to ``NAME``
in that folder first (the README's walk-through spec). The output compared is stdout followed by
stderr, normalised only where it legitimately varies:

* trailing blanks of each line and blank lines at the end are dropped;
* the progress lines of a solve on stderr (``corrugate: searching: 3 s, 17 iterations ...``): how
  many there are and their figures depend on the machine's speed;
* a line ``...`` in the document stands for any number of lines left out (doctest's ELLIPSIS).

A block that is not run (a finite-element run, a benchmark figure: minutes of CalculiX, or a
machine's timing) must say so, and when and how it was measured, on the line before it:
``<!-- not run: FE, measured 2026-12-06 -->``; the test checks every ``$`` block carries such a
mark or runs. Python examples written as ``>>>`` sessions in these files run with :mod:`doctest`
(ELLIPSIS, NORMALIZE_WHITESPACE) in the same kind of folder.
"""

from __future__ import annotations

import doctest
import re
import shlex
from dataclasses import dataclass
from pathlib import Path

import pytest

from corrugate.cli import main

ROOT = Path(__file__).resolve().parents[2]
#: The documents whose shown commands run: the README and every Markdown file under docs/.
DOCUMENTS = [ROOT / "README.md", *sorted((ROOT / "docs").rglob("*.md"))]

NOT_RUN = re.compile(r"<!-- not run: (?P<why>[^,]+), measured (?P<date>\d{4}-\d{2}-\d{2})\b.*-->")
FILE = re.compile(r"<!-- file: (?P<name>[\w.-]+) -->")
#: A solve's progress line on stderr (corrugate.cli.progress): stage, seconds, iterations.
PROGRESS = re.compile(r"^corrugate: [a-z][^\n]*: \d+ s, \d+ iterations? in \d+ runs?\b.*$")


@dataclass(frozen=True)
class Shown:
    """One ``$`` line of a document and the output it shows."""

    document: str
    line: int
    command: str
    output: tuple[str, ...]


@dataclass(frozen=True)
class Block:
    """A fenced block: its first line number, the line before its fence, its lines."""

    line: int
    before: str
    lines: tuple[str, ...]


def blocks(text: str) -> list[Block]:
    """The fenced blocks of a Markdown text (```...```), in order."""
    found: list[Block] = []
    lines = text.splitlines()
    i = 0
    while i < len(lines):
        if lines[i].startswith("```"):
            before = next((s for s in reversed(lines[:i]) if s.strip()), "")
            j = i + 1
            while j < len(lines) and not lines[j].startswith("```"):
                j += 1
            found.append(Block(i + 1, before.strip(), tuple(lines[i + 1 : j])))
            i = j + 1
        else:
            i += 1
    return found


def shown(path: Path) -> tuple[list[Shown], dict[str, str], list[str]]:
    """The commands of ``path`` that run (with their output), the files to write first, and the
    blocks with a ``$`` line that are marked not run (their marks)."""
    doc = str(path.relative_to(ROOT))
    runs: list[Shown] = []
    files: dict[str, str] = {}
    unrun: list[str] = []
    for block in blocks(path.read_text("utf-8")):
        if m := FILE.fullmatch(block.before):
            files[m["name"]] = "\n".join(block.lines) + "\n"
            continue
        if not any(line.startswith("$ ") for line in block.lines):
            continue
        if "not run:" in block.before:
            unrun.append(f"{doc}:{block.line}: {block.before}")
            continue
        current: list[str] | None = None
        command, start = "", 0
        for k, line in enumerate(block.lines):
            if line.startswith("$ "):
                if current is not None:
                    runs.append(Shown(doc, start, command, tuple(current)))
                command, current, start = line[2:], [], block.line + 1 + k
            elif current is not None:
                current.append(line)
        if current is not None:
            runs.append(Shown(doc, start, command, tuple(current)))
    return runs, files, unrun


def _normalise(text: str) -> list[str]:
    lines = [line.rstrip() for line in text.splitlines() if not PROGRESS.match(line)]
    while lines and not lines[-1]:
        lines.pop()
    return lines


def matches(expected: tuple[str, ...], actual: str) -> bool:
    """Whether ``actual`` (normalised) is ``expected``, a ``...`` line standing for any lines."""
    want = list(expected)
    while want and not want[-1].strip():
        want.pop()
    pattern = "".join(
        r"(?:[^\n]*\n)*?" if line.strip() == "..." else re.escape(line.rstrip()) + r"\n"
        for line in want
    )
    got = "".join(line + "\n" for line in _normalise(actual))
    return re.fullmatch(pattern, got) is not None


def _folder(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> Path:
    (tmp_path / "examples").symlink_to(ROOT / "examples", target_is_directory=True)
    monkeypatch.chdir(tmp_path)
    return tmp_path


COLLECTED = {path: shown(path) for path in DOCUMENTS}


def _param(path: Path, slow: bool) -> object:
    """A document as a test parameter; ``slow`` when it writes files or solves in Python (a second
    or more on a 2-core machine: the README's walk-through takes about 2 s)."""
    marks = [pytest.mark.slow] if slow else []
    return pytest.param(path, marks=marks, id=str(path.relative_to(ROOT)))


RUN = [
    _param(path, any("--out" in s.command for s in runs))
    for path, (runs, _, _) in COLLECTED.items()
    if runs
]


def test_the_readme_and_docs_show_commands_with_output() -> None:
    """The README's walk-through and the docs' examples are found (a parser that finds nothing
    would pass every document)."""
    readme = COLLECTED[ROOT / "README.md"][0]
    assert any(s.command.startswith("corrugate design stiffener.toml") for s in readme)
    assert "stiffener.toml" in COLLECTED[ROOT / "README.md"][1]
    commands = [s.command for runs, _, _ in COLLECTED.values() for s in runs]
    assert sum(c.startswith("corrugate analyze") for c in commands) >= 4
    assert any(c.startswith("corrugate design examples/") for c in commands)


def test_every_unrun_block_names_why_and_when() -> None:
    """A ``$`` block that does not run says why (FE, benchmark) and the date it was measured."""
    for _, _, unrun in COLLECTED.values():
        for mark in unrun:
            before = mark.split(": ", 1)[1]
            assert NOT_RUN.fullmatch(before), (
                f"{mark}: expected <!-- not run: WHY, measured DATE -->"
            )


def test_the_not_run_mark_needs_a_reason_and_a_date() -> None:
    assert NOT_RUN.fullmatch("<!-- not run: FE, measured 2026-12-06 -->")
    assert NOT_RUN.fullmatch("<!-- not run: benchmark, measured 2026-12-06 on 2 cores -->")
    assert not NOT_RUN.fullmatch("<!-- not run: FE -->")
    assert not NOT_RUN.fullmatch("<!-- not run -->")


def test_every_shown_command_is_a_corrugate_command() -> None:
    """Only ``corrugate`` runs in-process; another program's output would need a mark."""
    for runs, _, _ in COLLECTED.values():
        for s in runs:
            assert s.command.startswith("corrugate "), f"{s.document}:{s.line}: {s.command}"


@pytest.mark.parametrize("path", RUN)
def test_shown_commands_print_what_the_document_shows(
    path: Path,
    tmp_path: Path,
    monkeypatch: pytest.MonkeyPatch,
    capsys: pytest.CaptureFixture[str],
) -> None:
    runs, files, _ = COLLECTED[path]
    folder = _folder(tmp_path, monkeypatch)
    for name, text in files.items():
        (folder / name).write_text(text, "utf-8")
    failures = []
    for s in runs:
        args = shlex.split(s.command, comments=True)[1:]
        with pytest.raises(SystemExit):
            main(args)
        out, err = capsys.readouterr()
        if not matches(s.output, out + err):
            got = "\n".join(_normalise(out + err))
            failures.append(
                f"{s.document}:{s.line}: $ {s.command}\n--- shown:\n"
                + "\n".join(s.output)
                + f"\n--- printed:\n{got}\n"
            )
    assert not failures, "\n".join(failures)


def test_matches_reads_ellipsis_and_drops_progress_but_nothing_else() -> None:
    """The comparison itself: a changed figure fails, a left-out run of lines and the progress
    lines do not."""
    printed = "a 1\nb 2\nc 3\ncorrugate: searching: 3 s, 17 iterations in 1 run, gap 1 %\n"
    assert matches(("a 1", "...", "c 3"), printed)
    assert matches(("a 1", "b 2", "c 3", ""), printed)
    assert not matches(("a 1", "b 2.0", "c 3"), printed)
    assert not matches(("a 1", "c 3"), printed)
    assert not matches(("a 1", "...", "c 3", "d 4"), printed)


def sessions(path: Path) -> str:
    """The ``>>>`` sessions of ``path``'s fenced blocks, in order, as one doctest text."""
    return "\n\n".join(
        "\n".join(b.lines)
        for b in blocks(path.read_text("utf-8"))
        if b.lines and b.lines[0].startswith(">>> ")
    )


PYTHON = [_param(path, True) for path in DOCUMENTS if sessions(path)]


@pytest.mark.parametrize("path", PYTHON)
def test_python_sessions_in_the_docs_print_what_they_show(
    path: Path, tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    _folder(tmp_path, monkeypatch)
    name = str(path.relative_to(ROOT))
    test = doctest.DocTestParser().get_doctest(sessions(path), {}, name, name, 0)
    runner = doctest.DocTestRunner(optionflags=doctest.ELLIPSIS | doctest.NORMALIZE_WHITESPACE)
    out: list[str] = []
    result = runner.run(test, out=out.append)
    assert result.attempted > 0
    assert result.failed == 0, "".join(out)


LINK = re.compile(r"\]\(([^)\s]+)\)")


def test_links_of_the_readme_and_docs_reach_files_of_the_repository() -> None:
    """The reference moved out of the README into docs/: every relative link of either (a page, an
    image, an example) names a file that exists, and every ``corrugate docs NAME`` they cite is a
    shipped doc."""
    from corrugate.core.docs import CITATION, doc_names

    names = set(doc_names())
    broken, unknown = [], []
    for path in DOCUMENTS:
        text = path.read_text("utf-8")
        for m in LINK.finditer(text):
            target = m.group(1).split("#")[0]
            external = target.startswith(("http://", "https://", "mailto:"))
            if target and not external and not (path.parent / target).exists():
                broken.append(f"{path.relative_to(ROOT)}: {m.group(1)}")
        for m in CITATION.finditer(text):
            if m.group(1) and m.group(1) not in names:
                unknown.append(f"{path.relative_to(ROOT)}: corrugate docs {m.group(1)}")
    assert not broken, broken
    assert not unknown, unknown
    readme = (ROOT / "README.md").read_text("utf-8")
    for name in ("design", "analyze", "models", "python", "web", "validate", "cli", "development"):
        assert f"(docs/{name}.md)" in readme, name
