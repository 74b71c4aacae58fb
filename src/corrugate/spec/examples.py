"""The example specs shipped with the package, and the commented template of ``corrugate init``.

The examples live in ``corrugate/data/examples/`` (the repository's ``examples/`` folder points
there), so an installed package has them too.
"""

from __future__ import annotations

from importlib import resources

from corrugate.core.errors import UnknownNameError

__all__ = ["example_names", "example_text", "template_text"]


def _folder() -> resources.abc.Traversable:
    return resources.files("corrugate") / "data" / "examples"


def example_names() -> list[str]:
    """Names of the shipped example specs (file names without ``.toml``), sorted."""
    return sorted(p.name[:-5] for p in _folder().iterdir() if p.name.endswith(".toml"))


def example_text(name: str) -> str:
    """The TOML text of the example ``name`` (e.g. ``blimp_gripper``)."""
    names = example_names()
    if name not in names:
        raise UnknownNameError("example", name, names)
    return (_folder() / f"{name}.toml").read_text("utf-8")


def template_text() -> str:
    """A commented spec to start from (the case study, every section explained)."""
    return (resources.files("corrugate") / "data" / "template.toml").read_text("utf-8")
