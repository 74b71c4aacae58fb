"""A path longer than the OS takes (a 300-character folder name: ENAMETOOLONG) given to
``--out`` or to ``verify DIR`` is one line naming the option, exit 2, before any work (an OS error
that named no option before: "aaa... cannot be used (File name too long)")."""

from __future__ import annotations

from pathlib import Path
from typing import TYPE_CHECKING

import pytest

from data_files import PAPER_CASE_STUDY

if TYPE_CHECKING:
    from conftest import CliRun

LONG = "a" * 300  # NAME_MAX is 255


@pytest.mark.parametrize(
    ("args", "field"),
    [
        (["design", str(PAPER_CASE_STUDY), "-q", "--out"], "--out"),
        (["pareto", str(PAPER_CASE_STUDY), "--vs", "flexural_rigidity", "-q", "--out"], "--out"),
        (["pattern", "--W", "8", "--n", "8", "--alpha", "84", "-q", "--out"], "--out"),
        (["verify"], "DIR"),
    ],
)
def test_a_name_longer_than_the_os_takes_is_one_line_naming_the_option(
    args: list[str], field: str, cli: CliRun, tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    monkeypatch.chdir(tmp_path)
    code, out, err = cli([*args, LONG])
    assert code == 2, err
    assert err.count("\n") == 1 and err.startswith(f"corrugate: error: {field} = aaaa"), err
    assert "too long" in err, err
    assert out == ""
    assert list(tmp_path.iterdir()) == []  # nothing made


def test_a_path_of_many_short_names_beyond_the_cap_is_refused(cli: CliRun, tmp_path: Path) -> None:
    deep = tmp_path.joinpath(*["b" * 150] * 30)  # 4530 characters, each name within NAME_MAX
    code, _, err = cli(["design", str(PAPER_CASE_STUDY), "-q", "--out", str(deep)])
    assert code == 2 and err.startswith("corrugate: error: --out = "), err
    assert "at most 4000 characters" in err, err
    assert not (tmp_path / ("b" * 150)).exists()
