"""FE runs as tasks of a ``concurrent.futures`` executor: a local process pool or a dask cluster.

One mechanism serves ``corrugate validate --sweep`` (:func:`corrugate.fea.series.run_sweep`) and
``corrugate verify`` (:func:`corrugate.fea.verify.verify_design`,
:func:`corrugate.fea.first_failure.first_failures`); docs/fea.md section 4.

* :func:`dask_executor`: a dask.distributed cluster (the scheduler at an address, the optional
  ``dist`` extra) as an executor (``distributed.Client.get_executor``).
* :func:`run_tasks`: submits a function on every item to an executor (default: a process pool of
  ``jobs`` workers, made here) and yields ``(index, result)`` as each finishes; a task that
  raised, or whose worker died, yields its exception instead of a result, and the others go on.
  A worker that dies breaks a process pool: every task it took down is run again once, alone
  (:data:`RETRIES`), so that only the task that kills its worker is reported lost. SIGTERM ends the loop as SIGINT does, through the caller's
  cleanup (``finally``), and the pool's workers are terminated.

What is shipped to a worker is the task's function by its name (a worker imports it: corrugate
must be installed there, with ccx, docs/fea.md 4) and its arguments, pickled: frozen dataclasses
of numbers and names (an :class:`~corrugate.geometry.layer.Assembly`, a mesh, a fixture's name).
"""

from __future__ import annotations

import contextlib
import signal
import threading
from collections.abc import Callable, Generator, Hashable, Iterator, Sequence
from concurrent.futures import Executor, Future, ProcessPoolExecutor, as_completed
from concurrent.futures.process import BrokenProcessPool
from types import FrameType
from typing import Any, Generic, ParamSpec, TypeVar

from corrugate.core.errors import CorrugateError, InputError
from corrugate.core.limits import check_count

P = ParamSpec("P")
T = TypeVar("T")
A = TypeVar("A")
R = TypeVar("R")

__all__ = [
    "RETRIES",
    "Request",
    "Tasks",
    "dask_executor",
    "executor_for",
    "run_tasks",
    "worker_failure",
]

#: How often a task whose worker died (taking the process pool down) is run again.
RETRIES = 1


class _DaskExecutor(Executor):
    """A dask.distributed client as a ``concurrent.futures`` executor; shutdown closes it."""

    def __init__(self, address: str) -> None:
        import distributed

        client_cls: Any = distributed.Client  # untyped package
        self._client: Any = client_cls(address)
        self._executor: Any = self._client.get_executor()

    def submit(self, fn: Callable[P, T], /, *args: P.args, **kwargs: P.kwargs) -> Future[T]:
        future: Future[T] = self._executor.submit(fn, *args, **kwargs)
        return future

    def shutdown(self, wait: bool = True, *, cancel_futures: bool = False) -> None:
        self._executor.shutdown(wait=wait)
        self._client.close()


def dask_executor(address: str) -> Executor:
    """A ``concurrent.futures`` executor on the dask.distributed scheduler at ``address``
    (the optional ``dist`` extra); shut it down to close the connection."""
    try:
        import distributed  # noqa: F401
    except ImportError:
        raise InputError(
            "scheduler",
            address,
            "a dask.distributed address, with the `dist` extra installed "
            "(pip install 'corrugate[dist]')",
            reason="cannot be used",
        ) from None
    try:
        return _DaskExecutor(address)
    except (OSError, ValueError, TypeError) as exc:  # no scheduler there, or not an address
        raise InputError(
            "scheduler",
            address,
            "the address of a running dask scheduler, e.g. tcp://host:8786",
            reason=f"cannot be reached ({type(exc).__name__})",
        ) from None


def executor_for(scheduler: str | None, jobs: int | None) -> Executor | None:
    """The executor of the options ``--scheduler ADDRESS`` and ``--jobs N``: the dask cluster at
    ``scheduler``, else None (a process pool of ``jobs`` workers is then made by
    :func:`run_tasks`). Both given is refused (one line naming them)."""
    if jobs is not None:
        check_count("jobs", jobs, "jobs")
    if scheduler is not None and jobs is not None:
        raise InputError(
            "jobs", jobs, "--jobs or --scheduler, not both", reason="conflicts with --scheduler"
        )
    return dask_executor(scheduler) if scheduler is not None else None


@contextlib.contextmanager
def _terminate_as_exit() -> Iterator[None]:
    """SIGTERM raises SystemExit in the main thread while the block runs, so that its cleanup
    runs (SIGINT already raises KeyboardInterrupt)."""
    if threading.current_thread() is not threading.main_thread():
        yield
        return

    def on_term(signum: int, frame: FrameType | None) -> None:
        raise SystemExit(128 + signum)

    previous = signal.signal(signal.SIGTERM, on_term)
    try:
        yield
    finally:
        signal.signal(signal.SIGTERM, previous)


def _worker_init() -> None:
    """A worker ends on SIGTERM (its parent's handler, inherited by fork, would not let it)."""
    signal.signal(signal.SIGTERM, signal.SIG_DFL)


def _stop_pool(ex: ProcessPoolExecutor) -> None:
    """Shut a pool down now: cancel what has not started, terminate the workers."""
    processes = list(getattr(ex, "_processes", {}).values())
    ex.shutdown(wait=False, cancel_futures=True)
    for proc in processes:
        with contextlib.suppress(Exception):
            proc.terminate()
    for proc in processes:
        with contextlib.suppress(Exception):
            proc.join(5)


def worker_failure(exc: BaseException) -> str:
    """A task's exception that is not the task's own error (a worker killed, a pool broken, a
    dask ``KilledWorker``) in one line: ``worker failed: ...``."""
    msg = str(exc).splitlines()[0] if str(exc) else type(exc).__name__
    return f"worker failed: {msg}"


def run_tasks(
    fn: Callable[[A], R],
    items: Sequence[A],
    executor: Executor | None = None,
    *,
    jobs: int | None = None,
) -> Generator[tuple[int, R | Exception], None, None]:
    """``fn(item)`` for every item of ``items`` through ``executor`` (default: a process pool of
    ``jobs`` workers, all cores when None), yielding ``(index, result)`` as each finishes; every
    item yields exactly once. A task that raised yields its exception. With the own pool, a
    worker that dies breaks the pool and every task still in it is lost with it: once the others
    have finished, each lost task is run once more (:data:`RETRIES`) alone, in a pool of its own,
    so that only a task that kills its worker again yields the ``BrokenProcessPool``. ``fn`` must
    be picklable (a module-level function) and so must the items and results."""
    if jobs is not None:
        check_count("jobs", jobs, "jobs")
    own = executor is None
    tries = dict.fromkeys(range(len(items)), 0)
    todo = list(range(len(items)))
    ex: Executor | None = executor
    try:
        with _terminate_as_exit():
            while todo:
                alone = own and any(tries[i] for i in todo)  # the retries: one pool each
                batches = [[i] for i in todo] if alone else [todo]
                todo = []
                for batch in batches:
                    if own:
                        workers = 1 if alone else jobs
                        ex = ProcessPoolExecutor(max_workers=workers, initializer=_worker_init)
                    assert ex is not None
                    futures: dict[Future[R], int] = {ex.submit(fn, items[i]): i for i in batch}
                    broken = False
                    for fut in as_completed(futures):
                        i = futures[fut]
                        try:
                            result: R | Exception = fut.result()
                        except BrokenProcessPool as exc:
                            broken = True
                            tries[i] += 1
                            if own and tries[i] <= RETRIES:
                                todo.append(i)
                                continue
                            result = exc
                        except Exception as exc:  # the task's own error, or its worker's death
                            result = exc
                        yield i, result
                    if own and isinstance(ex, ProcessPoolExecutor):
                        if broken:
                            _stop_pool(ex)
                        else:
                            ex.shutdown()
                        ex = None
    finally:
        if own and isinstance(ex, ProcessPoolExecutor):
            _stop_pool(ex)


#: One run a plan asks for: its key (runs with equal keys are one run) and the task's item.
Request = tuple[Hashable, A]


class Tasks(Generic[A, R]):
    """Runs of ``fn`` on items, each key run once, in process or through an executor.

    A *plan* is a generator that yields lists of :data:`Request` (key, item) and, once resumed,
    reads their results from :attr:`results` (by key); its return value is what it computed (a
    row of a table). :meth:`drive` runs plans: in process (no ``executor`` and no ``jobs``) one
    plan after another, each request run in turn, ``progress`` called with ``line(item)`` before
    it (the order and the lines of a plain loop); otherwise in rounds, every plan's next requests
    submitted together (:func:`run_tasks`), ``progress`` called as each run finishes, so that
    plans that depend on what they read (a mesh series refined until it converges) still run
    their independent runs side by side. A task's ``CorrugateError`` is its result either way
    (returned, not raised); a task lost with its worker (killed, a pool broken, dask's
    ``KilledWorker``) has ``lost(item, exc)`` as its result. Runs are deterministic, so both ways
    give the same results."""

    def __init__(
        self,
        fn: Callable[[A], R],
        line: Callable[[A], str],
        lost: Callable[[A, Exception], R],
        progress: Callable[[str], None],
        executor: Executor | None = None,
        jobs: int | None = None,
    ) -> None:
        self.fn, self.line, self.lost, self.progress = fn, line, lost, progress
        self.executor, self.jobs = executor, jobs
        self.results: dict[Hashable, R] = {}

    @property
    def parallel(self) -> bool:
        """Whether runs go to an executor (``executor`` or ``jobs`` given)."""
        return self.executor is not None or self.jobs is not None

    def fulfil(self, requests: Sequence[Request[A]]) -> None:
        """Run every request whose key has no result yet."""
        todo = {k: item for k, item in requests if k not in self.results}
        if not self.parallel:
            for key, item in todo.items():
                self.progress(self.line(item))
                self.results[key] = self.fn(item)
            return
        keys, items = list(todo), list(todo.values())
        with contextlib.closing(run_tasks(self.fn, items, self.executor, jobs=self.jobs)) as done:
            for count, (i, r) in enumerate(done, start=1):
                result: R
                if isinstance(r, Exception) and not isinstance(r, CorrugateError):
                    result = self.lost(items[i], r)
                else:
                    result = r  # type: ignore[assignment]  # a CorrugateError is a task's result
                self.results[keys[i]] = result
                what = "failed" if isinstance(result, Exception) else "done"
                self.progress(f"{self.line(items[i])}: {what} ({count} of {len(items)})")

    def drive(self, plans: Sequence[Generator[list[Request[A]], None, T]]) -> list[T]:
        """Run ``plans`` (class docstring) and return what each returned, in order."""
        out: dict[int, T] = {}
        if not self.parallel:
            for i, plan in enumerate(plans):
                out[i] = self._finish(plan)
            return [out[i] for i in range(len(plans))]
        asked: dict[int, list[Request[A]]] = {}
        for i, plan in enumerate(plans):
            try:
                asked[i] = next(plan)
            except StopIteration as stop:
                out[i] = stop.value
        while asked:
            self.fulfil([r for i in sorted(asked) for r in asked[i]])
            for i in sorted(asked):
                try:
                    asked[i] = plans[i].send(None)
                except StopIteration as stop:
                    out[i] = stop.value
                    del asked[i]
        return [out[i] for i in range(len(plans))]

    def _finish(self, plan: Generator[list[Request[A]], None, T]) -> T:
        try:
            requests = next(plan)
            while True:
                self.fulfil(requests)
                requests = plan.send(None)
        except StopIteration as stop:
            return stop.value  # type: ignore[no-any-return]
