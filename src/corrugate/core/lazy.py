"""A package's public names imported on first use (PEP 562).

A package lists where each of its public names lives; :func:`lazy_names` makes its module
``__getattr__``: the first use of a name imports that module and keeps the value among the
package's globals, so importing the package, or one of its submodules, costs nothing until a name
is used (issue 39: ``corrugate design`` imports only the modules its spec's path calls).
"""

from __future__ import annotations

from collections.abc import Callable, Mapping
from importlib import import_module
from typing import Any

__all__ = ["lazy_names"]


def lazy_names(
    package: str, where: Mapping[str, str], namespace: dict[str, Any]
) -> Callable[[str], Any]:
    """The module ``__getattr__`` of ``package`` (PEP 562): a name of ``where`` is the attribute
    of that name of the module ``where[name]`` (relative to ``package`` when it starts with a
    dot), imported on the name's first use and kept in ``namespace`` (the package's globals), so
    that later uses do not come back here; any other name raises :class:`AttributeError` as a
    module does."""

    def lookup(name: str) -> Any:
        module = where.get(name)
        if module is None:
            raise AttributeError(f"module {package!r} has no attribute {name!r}")
        value = getattr(import_module(module, package), name)
        namespace[name] = value
        return value

    return lookup
