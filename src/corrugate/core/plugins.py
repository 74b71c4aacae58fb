"""pydantic without its plugins in a command's process, and without ``importlib.metadata``.

pydantic looks for plugins (packages that observe every validation, such as logfire) among the
installed packages' entry points the first time it builds a validator; its plugin loader
imports ``importlib.metadata`` to do so, with the email parser, zipfile, csv and socket it
imports. No plugin is part of corrugate, and a command's process (:func:`corrugate.cli.main`)
loads none: while pydantic's loader module is imported, ``importlib.metadata`` is a stand-in
whose ``entry_points`` finds no entry point (any other name loads the real module), so the
loader keeps an empty plugin table and the real module is never imported. 0.009 s of CPU less
for ``corrugate design examples/blimp_gripper.toml`` (0.261 s against 0.270 s, this function
called or not, medians of 21 interleaved runs on a 2-core machine at load 6-7; issue 39). A program importing the package keeps
pydantic's plugins; so does a process whose environment sets ``PYDANTIC_DISABLE_PLUGINS``
(pydantic's own switch: the user's choice stands).
"""

from __future__ import annotations

import importlib
import os
import sys
from types import ModuleType
from typing import Any

from corrugate.core.first_import import around_first_import

__all__ = ["LOADER", "METADATA", "without_pydantic_plugins"]

#: pydantic's plugin loader, and the module it finds the plugins with.
LOADER = "pydantic.plugin._loader"
METADATA = "importlib.metadata"


def _no_entry_points(**selection: Any) -> tuple[()]:
    """What the stand-in's ``entry_points`` finds: none (pydantic asks for its group)."""
    return ()


class _StandIn(ModuleType):
    """``importlib.metadata`` while pydantic's loader imports it: its ``entry_points`` finds
    none; any other public name imports the real module (the stand-in leaves ``sys.modules``
    first) and answers from it. A dunder name it does not have is missing (the import system
    asks for ``__path__``: a module, not a package)."""

    def __getattr__(self, name: str) -> Any:
        if name.startswith("__") and name.endswith("__"):
            raise AttributeError(name)
        if sys.modules.get(METADATA) is self:
            del sys.modules[METADATA]
        return getattr(importlib.import_module(METADATA), name)


def _stand_in() -> None:
    if METADATA in sys.modules:
        return
    module = _StandIn(METADATA)
    module.entry_points = _no_entry_points  # type: ignore[attr-defined]
    sys.modules[METADATA] = module


def _taken_away() -> None:
    if isinstance(sys.modules.get(METADATA), _StandIn):
        del sys.modules[METADATA]
    if isinstance(getattr(importlib, "metadata", None), _StandIn):
        delattr(importlib, "metadata")


def without_pydantic_plugins() -> None:
    """Have pydantic, when its plugin loader is first imported in this process, find no plugin
    without importing ``importlib.metadata`` (the module docstring). Nothing when the loader or
    ``importlib.metadata`` is imported already, or the environment sets
    ``PYDANTIC_DISABLE_PLUGINS``."""
    if "PYDANTIC_DISABLE_PLUGINS" in os.environ or METADATA in sys.modules:
        return
    around_first_import(LOADER, _stand_in, _taken_away)
