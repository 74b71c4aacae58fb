"""Something done just before and just after a module's first import in this process.

The command line's process sets up two libraries as they load rather than when it starts, so
that a command that never imports them (``corrugate --help``) pays nothing: numpy's BLAS threads
(:mod:`corrugate.core.blas`) and pydantic's plugins (:mod:`corrugate.core.plugins`). A finder
first on :data:`sys.meta_path` waits for the module's name, lets the other finders find it, and
wraps its loader's ``exec_module`` with the two steps; it then leaves :data:`sys.meta_path`.
"""

from __future__ import annotations

import sys
from collections.abc import Callable, Sequence
from types import ModuleType
from typing import TYPE_CHECKING

if TYPE_CHECKING:
    from importlib.machinery import ModuleSpec

__all__ = ["around_first_import", "waiting_for"]


class _Around:
    """A finder waiting for the module ``name``. A plain class, not
    ``importlib.abc.MetaPathFinder``: that module imports ``importlib.resources`` and
    ``tempfile`` (3.8 ms in ``python -X importtime``) for nothing."""

    def __init__(self, name: str, before: Callable[[], None], after: Callable[[], None]) -> None:
        self.name = name
        self.before = before
        self.after = after

    def find_spec(
        self, name: str, path: Sequence[str] | None = None, target: ModuleType | None = None
    ) -> ModuleSpec | None:
        if name != self.name:
            return None
        sys.meta_path.remove(self)
        spec: ModuleSpec | None = None
        for finder in sys.meta_path:
            find = getattr(finder, "find_spec", None)
            spec = find(name, path, target) if find is not None else None
            if spec is not None:
                break
        run = getattr(spec.loader, "exec_module", None) if spec is not None else None
        if spec is None or run is None:
            return spec
        before, after = self.before, self.after

        def exec_module(module: ModuleType) -> None:
            before()
            try:
                run(module)
            finally:
                after()

        setattr(spec.loader, "exec_module", exec_module)  # noqa: B010 (the loader's own method)
        return spec


def waiting_for(name: str) -> bool:
    """Whether a step waits for the first import of ``name`` (:func:`around_first_import`)."""
    return any(isinstance(f, _Around) and f.name == name for f in sys.meta_path)


def around_first_import(name: str, before: Callable[[], None], after: Callable[[], None]) -> None:
    """Run ``before`` just before the module ``name`` is first executed in this process and
    ``after`` just after (also when it fails). Nothing when ``name`` is imported already or a
    step waits for it; neither runs when it is never imported or cannot be found."""
    if name in sys.modules or waiting_for(name):
        return
    sys.meta_path.insert(0, _Around(name, before, after))
