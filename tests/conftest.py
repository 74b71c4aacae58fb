"""Shared fixtures: the project's reference data (``tests/data``, inside the repository), the
CalculiX executable, and the command line run in-process; and the check that every test needing
CalculiX or a browser carries its marker (``fea``, ``browser``: ``make test-fast`` leaves them out)."""

from __future__ import annotations

import os
import signal
from collections.abc import Callable, Iterable, Iterator
from pathlib import Path

import pytest

from corrugate.cli import main
from corrugate.core.sigpipe import sigpipe_ignored

ROOT = Path(__file__).resolve().parents[1]
#: The reference data the tests read, each file with its source in its header: Xia et al.'s
#: Table 5 and the periodic unit-cell FE moduli (a link to docs/data/unitcell_fe.csv, the one copy
#: that docs/fea.md and the benchmarks cite).
DATA = ROOT / "tests" / "data"

#: The user's config folder (corrugate.materials.user.config_dir) during the tests: a folder of
#: the repository that does not exist, so that no test reads the user's own materials file.
os.environ["CORRUGATE_CONFIG_DIR"] = str(ROOT / "tests" / "data" / "no-user-config")

#: Fixtures that need something outside Python, and the marker their tests must carry.
MARKED_FIXTURES = {"ccx": "fea", "browser": "browser"}


def unmarked(items: Iterable[pytest.Item]) -> list[str]:
    """The ids of the tests that use a fixture of :data:`MARKED_FIXTURES` without its marker."""
    return [
        f"{item.nodeid} uses the {fixture!r} fixture without @pytest.mark.{marker}"
        for item in items
        for fixture, marker in MARKED_FIXTURES.items()
        if fixture in getattr(item, "fixturenames", ()) and item.get_closest_marker(marker) is None
    ]


@pytest.hookimpl(tryfirst=True)  # before -m deselects: every collected test is checked
def pytest_collection_modifyitems(items: list[pytest.Item]) -> None:
    missing = unmarked(items)
    if missing:
        raise pytest.UsageError("\n".join(missing))


@pytest.fixture(scope="session")
def reference() -> Path:
    """The folder of the reference data (:data:`DATA`)."""
    return DATA


@pytest.fixture(scope="session")
def ccx() -> str:
    """The CalculiX executable; a test that needs it skips without it, except on CI
    (``CI=true``), where it fails: there the finite-element tests must run."""
    from corrugate.fea.ccx import SolverNotFoundError, find_ccx

    try:
        return find_ccx()
    except SolverNotFoundError as exc:
        if os.environ.get("CI") == "true":
            pytest.fail(f"CI=true and CalculiX is missing: {exc}")
        pytest.skip(f"CalculiX not installed: {exc}")


CliRun = Callable[[list[str]], tuple[int, str, str]]


@pytest.fixture
def cli(capsys: pytest.CaptureFixture[str]) -> CliRun:
    """Run ``corrugate ARGS`` in-process: returns (exit code, stdout, stderr)."""

    def run(args: list[str]) -> tuple[int, str, str]:
        with pytest.raises(SystemExit) as info:  # the command line always ends in sys.exit
            main(args)
        out, err = capsys.readouterr()
        code = info.value.code
        return (0 if code is None else int(code)), out, err

    return run


@pytest.fixture(scope="module")
def dask_cluster() -> Iterator[str]:
    """The address of a dask.distributed ``LocalCluster`` of two worker processes with one
    thread each (the ``dist`` extra, which ``make test`` installs), shared by one module's tests
    and closed after them (a cluster left running for the rest of the session keeps its threads
    and sockets in the test process: the run of 2026-12-07 on 06fe4b4 died of SIGPIPE, exit 141,
    some 950 tests after the first dask module, with no traceback);
    without ``distributed`` a test skips, except on CI (``CI=true``), where it fails: there the
    scale-out tests must run."""
    try:
        import distributed
    except ImportError as exc:
        if os.environ.get("CI") == "true":
            pytest.fail(f"CI=true and dask.distributed is missing (the dist extra): {exc}")
        pytest.skip(f"dask.distributed not installed (the dist extra): {exc}")
    cluster = distributed.LocalCluster(
        n_workers=2, threads_per_worker=1, processes=True, dashboard_address=":0"
    )
    try:
        yield cluster.scheduler_address
    finally:
        cluster.close()


@pytest.fixture(autouse=True)
def _sigpipe_stays_ignored() -> Iterator[None]:
    """Python ignores SIGPIPE (a write to a closed pipe or socket raises BrokenPipeError); a test
    or library that sets it back to the default would let a later write kill the whole run with
    no traceback (exit 141): the test that changed it fails, named, and the default is put back."""
    yield
    # the kernel's disposition, not only Python's record of it: gmsh.initialize() changes the
    # first behind Python's back (corrugate.core.sigpipe; the CI run of 2026-12-07 on 31fc235
    # died of it, exit 141, at 74 %)
    if signal.getsignal(signal.SIGPIPE) != signal.SIG_IGN or sigpipe_ignored() is False:
        signal.signal(signal.SIGPIPE, signal.SIG_IGN)
        pytest.fail("SIGPIPE is no longer ignored after this test (put back to SIG_IGN)")
