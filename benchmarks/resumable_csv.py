"""A CSV of FE results that a killed run resumes (fea_offaxis.py, fea_offaxis_size.py): the keys
of the rows already in it are skipped, and each new row is appended and flushed as its case
returns."""

from __future__ import annotations

import csv
from collections.abc import Callable, Iterator, Sequence
from contextlib import contextmanager
from pathlib import Path


def done_keys(path: Path, key_fields: Sequence[str]) -> set[tuple[str, ...]]:
    """The ``key_fields`` values (strings) of every row already in ``path``."""
    if not path.exists():
        return set()
    with path.open() as f:
        rows = csv.DictReader(line for line in f if not line.startswith("#"))
        return {tuple(r[k] for k in key_fields) for r in rows}


@contextmanager
def appender(
    path: Path, fields: Sequence[str], preamble: Sequence[str] = ()
) -> Iterator[Callable[[Sequence[object]], None]]:
    """A function that appends one row (values in the order of ``fields``) and flushes it; the
    ``preamble`` (comment lines, each written after ``# ``: e.g. the command that makes the file)
    and the header are written when the file is new (:func:`done_keys` skips the comments)."""
    path.parent.mkdir(parents=True, exist_ok=True)
    new = not path.exists()
    with path.open("a", newline="") as f:
        writer = csv.DictWriter(f, fields)
        if new:
            for line in preamble:
                f.write(f"# {line}\n")
            writer.writeheader()

        def write(row: Sequence[object]) -> None:
            writer.writerow(dict(zip(fields, row, strict=True)))
            f.flush()

        yield write
