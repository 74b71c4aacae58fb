"""The markers ``make test-fast`` selects on: registered in pyproject.toml (``--strict-markers``
refuses any other), and carried by every test that needs CalculiX or a browser. The check itself
is tests/conftest.py's collection hook (:func:`conftest.unmarked`), run on every collection before
``-m`` deselects anything; here it is shown to catch an unmarked test."""

from __future__ import annotations

import tomllib
from dataclasses import dataclass, field
from pathlib import Path

import pytest

from conftest import MARKED_FIXTURES, unmarked

ROOT = Path(__file__).resolve().parents[2]


@dataclass
class FakeItem:
    """What the check reads of a collected test: its id, fixtures and markers."""

    nodeid: str
    fixturenames: tuple[str, ...]
    markers: tuple[str, ...] = field(default=())

    def get_closest_marker(self, name: str) -> str | None:
        return name if name in self.markers else None


def test_the_markers_are_registered() -> None:
    config = tomllib.loads((ROOT / "pyproject.toml").read_text())["tool"]["pytest"]
    names = {m.split(":")[0].strip() for m in config["ini_options"]["markers"]}
    assert {"fea", "browser", "slow"} <= names
    assert "--strict-markers" in config["ini_options"]["addopts"]
    assert set(MARKED_FIXTURES.values()) <= names


def test_a_test_using_ccx_or_browser_without_its_marker_is_refused() -> None:
    items = [
        FakeItem("a.py::fe", ("ccx", "tmp_path"), ("fea",)),
        FakeItem("a.py::fe_unmarked", ("tmp_path", "ccx")),
        FakeItem("a.py::fe_marked_slow_only", ("ccx",), ("slow",)),
        FakeItem("b.py::page", ("browser", "live_server"), ("browser",)),
        FakeItem("b.py::page_unmarked", ("browser",)),
        FakeItem("c.py::plain", ("tmp_path",)),
    ]
    found = unmarked(items)  # type: ignore[arg-type]
    assert [line.split(" ")[0] for line in found] == [
        "a.py::fe_unmarked",
        "a.py::fe_marked_slow_only",
        "b.py::page_unmarked",
    ]
    assert "@pytest.mark.fea" in found[0] and "@pytest.mark.browser" in found[2]


def test_this_sessions_tests_pass_the_check(request: pytest.FixtureRequest) -> None:
    """The real items of this run (its selection): none lacks its marker, and each that uses
    ``ccx`` is marked fea."""
    items = request.session.items
    assert request.node in items
    assert unmarked(items) == []
    for item in items:
        if "ccx" in item.fixturenames:
            assert item.get_closest_marker("fea") is not None, item.nodeid
