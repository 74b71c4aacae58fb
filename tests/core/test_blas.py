"""corrugate.core.blas: numpy imported with one OpenBLAS thread, the environment given back
(issue 39).

Each check runs in a fresh interpreter (the test process has imported numpy already, and then
:func:`~corrugate.core.blas.one_blas_thread` does nothing). The threads are counted by the
kernel (``/proc/self/task``, one entry per thread of the process), not by asking OpenBLAS.
"""

from __future__ import annotations

import json
import os
import subprocess
import sys
import textwrap
from pathlib import Path

import pytest

from corrugate.core.blas import BLAS_THREADS

#: Prints, as JSON: the process's threads after numpy's import (and a product that BLAS
#: computes), the variable's value after it, and numpy's answer to a small product.
_CHILD = textwrap.dedent(
    """
    import json, os, sys
    from corrugate.core.blas import one_blas_thread
    if sys.argv[1] == "call":
        one_blas_thread()
    import numpy as np
    a = np.arange(40_000, dtype=float).reshape(200, 200) / 1e4
    product = float((a @ a).sum())
    print(json.dumps({
        "threads": len(os.listdir("/proc/self/task")),
        "variable": os.environ.get(sys.argv[2]),
        "product": product,
    }))
    """
)

_PROC = Path("/proc/self/task")


def _child(how: str, env: dict[str, str]) -> dict[str, object]:
    out = subprocess.run(
        [sys.executable, "-c", _CHILD, how, BLAS_THREADS],
        capture_output=True,
        text=True,
        check=True,
        env=env,
    )
    result: dict[str, object] = json.loads(out.stdout)
    return result


def _env(**extra: str) -> dict[str, str]:
    env = {k: v for k, v in os.environ.items() if k != BLAS_THREADS}
    return {**env, **extra}


@pytest.mark.skipif(not _PROC.is_dir(), reason="counts threads in /proc (Linux)")
def test_numpy_runs_on_one_thread_and_the_environment_is_given_back() -> None:
    done = _child("call", _env())
    assert done["threads"] == 1  # the interpreter's own thread, no BLAS thread
    assert done["variable"] is None  # set only while numpy was imported
    # The sum of the entries of a @ a, a_ij = (200 i + j) / 1e4, by hand: sum_j (column sum j of
    # a) (row sum j of a), the column sum (200 * 19900 + 200 j) / 1e4, the row sum
    # (40000 j + 19900) / 1e4.
    by_hand = sum((200 * 19900 + 200 * j) * (40000 * j + 19900) for j in range(200)) / 1e8
    assert done["product"] == pytest.approx(by_hand, rel=1e-12)


@pytest.mark.skipif(not _PROC.is_dir(), reason="counts threads in /proc (Linux)")
def test_the_users_setting_stands() -> None:
    """A variable the user set is neither replaced nor removed."""
    done = _child("call", _env(**{BLAS_THREADS: "1"}))
    assert done["variable"] == "1"
    assert done["threads"] == 1


def test_nothing_changes_once_numpy_is_imported() -> None:
    """The test process imported numpy (through this package): the call adds no finder and sets
    no variable."""
    import numpy  # noqa: F401

    from corrugate.core.blas import one_blas_thread

    before = list(sys.meta_path)
    had = os.environ.get(BLAS_THREADS)
    one_blas_thread()
    assert sys.meta_path == before
    assert os.environ.get(BLAS_THREADS) == had
