"""Shared fixtures: where the project's reference data lives (``../shared/reference``)."""

from __future__ import annotations

import os
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[1]


def reference_dir() -> Path:
    """``shared/reference`` beside the checkout (or ``$CORRUGATE_REFERENCE``)."""
    env = os.environ.get("CORRUGATE_REFERENCE")
    return Path(env) if env else ROOT.parent / "shared" / "reference"


@pytest.fixture(scope="session")
def reference() -> Path:
    path = reference_dir()
    if not path.is_dir():
        pytest.fail(f"reference data not found at {path} (set CORRUGATE_REFERENCE)")
    return path
