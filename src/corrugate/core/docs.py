"""The documentation shipped with the package, read by ``corrugate docs [NAME]``.

The Markdown files live in the repository's ``docs/`` folder; ``corrugate/data/docs/`` links to
them, so a built package (wheel, sdist) holds copies and an installed user can read what the
messages cite: a message says "see `corrugate docs fea` (section 2.5)" rather than a repository
path. A name is the file's path under ``docs/`` without ``.md``: ``fea``, ``validation/off_axis``.
"""

from __future__ import annotations

import re
from importlib import resources

from corrugate.core.errors import UnknownNameError

__all__ = ["CITATION", "doc_names", "doc_text", "doc_title"]

#: How the package cites a shipped doc: ```corrugate docs NAME``` or a repository path
#: ``docs/NAME.md``; group 1 (or 2) is the name.
CITATION = re.compile(r"corrugate docs ([a-z_]+(?:/[a-z_]+)?)|docs/([a-z_]+(?:/[a-z_]+)?)\.md")


def _folder() -> resources.abc.Traversable:
    return resources.files("corrugate") / "data" / "docs"


def doc_names() -> list[str]:
    """Names of the shipped docs (``fea``, ``validation/off_axis``, ...), sorted."""

    def walk(folder: resources.abc.Traversable, prefix: str) -> list[str]:
        out: list[str] = []
        for p in folder.iterdir():
            if p.is_dir():
                out += walk(p, f"{prefix}{p.name}/")
            elif p.name.endswith(".md"):
                out.append(prefix + p.name[:-3])
        return out

    return sorted(walk(_folder(), ""))


def doc_text(name: str) -> str:
    """The Markdown text of the shipped doc ``name`` (``.md`` and a leading ``docs/`` allowed)."""
    key = name.removeprefix("docs/").removesuffix(".md")
    names = doc_names()
    if key not in names:
        raise UnknownNameError("doc", name, names)
    path = _folder()
    *parents, last = key.split("/")
    for part in parents:
        path = path / part
    return (path / f"{last}.md").read_text("utf-8")


def doc_title(name: str) -> str:
    """The first heading of the doc ``name``, without the ``#``."""
    for line in doc_text(name).splitlines():
        if line.startswith("#"):
            return line.lstrip("#").strip()
    return name
