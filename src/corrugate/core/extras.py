"""Which optional extras are installed, checked before work that needs them starts.

The core package needs only its dependencies; writing files (``fab``: ezdxf, matplotlib, Hershey-Fonts) and the
web app (``web``: FastAPI, uvicorn, python-multipart) need extras. A command that needs a
missing extra says so in one line (:class:`~corrugate.core.errors.MissingExtraError`) before it
computes or writes anything, instead of failing midway with an import error.
"""

from __future__ import annotations

import importlib.util

from corrugate.core.errors import MissingExtraError

__all__ = ["EXTRAS", "require_extra"]

#: Each extra's packages as pyproject.toml lists them: import name -> distribution name.
EXTRAS: dict[str, dict[str, str]] = {
    "fab": {"ezdxf": "ezdxf", "matplotlib": "matplotlib", "HersheyFonts": "Hershey-Fonts"},
    "web": {"fastapi": "fastapi", "uvicorn": "uvicorn", "multipart": "python-multipart"},
}


def _installed(module: str) -> bool:
    try:
        return importlib.util.find_spec(module) is not None
    except (ImportError, ValueError):  # a parent package missing, or a module set to None
        return False


def require_extra(extra: str, what: str) -> None:
    """Raise :class:`MissingExtraError` naming ``what`` (e.g. "writing a design's files") and the
    distributions missing if a module of ``extra`` (a key of :data:`EXTRAS`) cannot be imported;
    return quietly otherwise. Looks the modules up without importing them (no start-up cost)."""
    missing = [dist for module, dist in EXTRAS[extra].items() if not _installed(module)]
    if missing:
        raise MissingExtraError(what, extra, missing)
