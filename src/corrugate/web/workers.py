"""Killable worker processes for the web app's computations.

:class:`Runner` runs every computation of a request (parsing its quantities included) in a
worker process: killed at the time limit (:class:`ComputeTimeoutError`, 504), its address space
capped (``RLIMIT_AS``, :data:`WORKER_MEMORY_BYTES`: a job that needs more gets 422), replaced by
a fresh one; :class:`ServerBusyError` (503) when too many are queued. The event loop runs no
computation a request controls. Workers end with the server: killed at shutdown and on SIGTERM
or Ctrl-C (:meth:`Runner.kill_workers`), and by Linux when the server is killed
(``PR_SET_PDEATHSIG``).
"""

from __future__ import annotations

import asyncio
import contextlib
import ctypes
import gc
import logging
import multiprocessing
import os
import signal
import threading
import time
from collections import deque
from collections.abc import AsyncIterator, Callable, Iterator
from concurrent.futures import ThreadPoolExecutor
from dataclasses import dataclass
from multiprocessing.connection import Connection
from multiprocessing.process import BaseProcess
from typing import Any, TypeVar

__all__ = [
    "WORKER_MEMORY_BYTES",
    "ComputeTimeoutError",
    "Runner",
    "ServerBusyError",
    "Share",
    "WorkerLostError",
    "core_count",
    "memory_cap",
    "release_memory",
    "send_progress",
    "wants_progress",
]

_log = logging.getLogger("corrugate.web")

T = TypeVar("T")


class ServerBusyError(Exception):
    """Too many computations are in flight; try again later (HTTP 503, with ``Retry-After``
    ``retry_after_s`` seconds)."""

    def __init__(self, message: str, retry_after_s: int = 5) -> None:
        self.retry_after_s = retry_after_s
        super().__init__(message)


class Share:
    """A share of a runner's workers for one kind of computation: at most ``limit`` of them
    hold a worker at once (so the others always find one), at most ``max_waiting`` more wait
    for their turn, in order; past that :meth:`turn` raises :class:`ServerBusyError` at once.
    Lives on the event loop."""

    def __init__(self, limit: int, max_waiting: int) -> None:
        self.limit = max(1, limit)
        self.max_waiting = max_waiting
        self._turns = asyncio.Semaphore(self.limit)
        self._waiting = 0

    @contextlib.asynccontextmanager
    async def turn(self) -> AsyncIterator[None]:
        """The block runs while this kind holds at most ``limit`` turns."""
        if self._turns.locked() and self._waiting >= self.max_waiting:
            raise ServerBusyError("the server is busy with other computations; try again shortly")
        self._waiting += 1
        try:
            await self._turns.acquire()
        finally:
            self._waiting -= 1
        try:
            yield
        finally:
            self._turns.release()


class ComputeTimeoutError(Exception):
    """A computation did not finish within the time limit (HTTP 504)."""

    def __init__(self, seconds: float) -> None:
        self.seconds = seconds
        super().__init__(
            f"the computation did not finish within the time limit of {seconds:g} s and was stopped"
        )


def release_memory(full: bool = False) -> None:
    """Collect young garbage (all of it if ``full``: some 0.3 s) and hand freed heap pages back
    to the system (glibc ``malloc_trim``, microseconds), so that the memory a large computation
    needed does not stay resident."""
    gc.collect() if full else gc.collect(1)
    try:
        libc = ctypes.CDLL(None)
        libc.malloc_trim(0)
    except (OSError, AttributeError):
        pass


def core_count() -> int:
    """The cores this process may run on (at least 1)."""
    try:
        return max(1, len(os.sched_getaffinity(0)))
    except AttributeError:  # not on Linux
        return max(1, os.cpu_count() or 1)


#: What a new worker process imports before its first job (the web app, the solver and its
#: explanation, the writers, the report and the libraries they draw with: matplotlib's Agg and PDF
#: backends, ezdxf), so that no computation pays for it: a design's answer, then its files made on
#: demand (:mod:`corrugate.web.ondemand`). A module of an extra not installed is left out.
WORKER_PRELOAD = (
    "corrugate.web.app",
    "corrugate.workflow",
    "corrugate.solver",
    "corrugate.solver.diagnosis",
    "corrugate.solver.orientation",
    "corrugate.spec.written",
    "corrugate.mechanics.supports",
    "corrugate.export.plan",
    "corrugate.export.files",
    "corrugate.export.files3d",
    "corrugate.export.record",
    "corrugate.export.design_files",
    "corrugate.fabrication.instructions",
    "corrugate.report",
    "corrugate.report.figures",
    "matplotlib.backends.backend_agg",
    "matplotlib.backends.backend_pdf",
    "ezdxf",
)

#: The address space one worker process may map beyond what it maps once its modules are imported
#: (``RLIMIT_AS``): a computation that needs more fails with MemoryError in its worker, and its
#: request gets 422.
WORKER_MEMORY_BYTES = 2 * 1024**3

#: Longest wait for a new worker process to start and import :data:`WORKER_PRELOAD`.
_START_TIMEOUT_S = 300.0

#: ``prctl`` option: the signal a process gets when its parent ends.
_PR_SET_PDEATHSIG = 1


def _warm_up() -> None:
    """Import :data:`WORKER_PRELOAD` (in a worker process, before it takes jobs); a module of an
    extra that is not installed is skipped (its computations say which extra they need)."""
    import importlib

    for name in WORKER_PRELOAD:
        try:
            importlib.import_module(name)
        except ModuleNotFoundError as exc:  # a package of an extra; never one of ours
            if (exc.name or "corrugate").split(".")[0] == "corrugate":
                raise


def _die_with_parent() -> None:
    """Ask Linux to SIGKILL this process when its parent ends (``PR_SET_PDEATHSIG``): a worker's
    parent is the forkserver, which ends when the server ends, even by SIGKILL. Elsewhere, a
    no-op (the worker still ends when its pipe to the server closes, between jobs)."""
    try:
        libc = ctypes.CDLL(None, use_errno=True)
        libc.prctl(_PR_SET_PDEATHSIG, signal.SIGKILL, 0, 0, 0)
    except (OSError, AttributeError):
        pass


def _leave_forkserver() -> None:
    """Close this worker's copy of the forkserver's "alive" pipe (every child of a forkserver
    inherits one): the forkserver ends when the server ends, not when its last worker does, so
    that ``PR_SET_PDEATHSIG`` then kills the workers."""
    from multiprocessing import forkserver

    server = getattr(forkserver, "_forkserver", None)
    fd = getattr(server, "_forkserver_alive_fd", None)
    if isinstance(fd, int):
        with contextlib.suppress(OSError):
            os.close(fd)
        server._forkserver_alive_fd = None  # type: ignore[union-attr]


#: In a worker process, while it runs a job whose caller asked for progress: the function that
#: sends one progress event (a JSON-able dict) to the server; None otherwise.
_PROGRESS_SINK: Callable[[dict[str, Any]], None] | None = None


def wants_progress() -> bool:
    """Whether the job running in this process was asked for progress (:meth:`Runner.run` with
    ``on_progress``); False outside a worker."""
    return _PROGRESS_SINK is not None


def send_progress(event: dict[str, Any]) -> None:
    """Send ``event`` (a JSON-able dict) to the server as progress of the job running in this
    worker process, where its caller asked for progress; elsewhere, nothing. The job decides how
    often (a few events a second at most: each is a message on the worker's pipe)."""
    if _PROGRESS_SINK is not None:
        _PROGRESS_SINK(event)


def _own_process_group() -> None:
    """Make this worker the leader of a process group of its own, so that killing it
    (:meth:`Runner._kill`, ``killpg``) also kills the programs its job started (CalculiX)."""
    with contextlib.suppress(OSError, AttributeError):
        os.setpgid(0, 0)


#: In a worker process: what it had mapped when it was capped (bytes), for :func:`memory_cap`.
_MAPPED_AT_CAP: int | None = None


def _cap_memory(limit: int | None, ceiling: int | None = None) -> None:
    """Cap this process's address space (``RLIMIT_AS``) at what it has mapped now (its modules,
    thread stacks and arenas) plus ``limit`` bytes (None: no cap); the hard limit is that plus
    ``ceiling`` bytes when larger, up to which a job may raise it (:func:`memory_cap`)."""
    global _MAPPED_AT_CAP
    if limit is None:
        return
    try:
        import resource

        with open("/proc/self/statm", encoding="ascii") as f:
            mapped = int(f.read().split()[0]) * os.sysconf("SC_PAGE_SIZE")
        cap = mapped + limit
        hard = max(cap, mapped + (ceiling or 0))
        resource.setrlimit(resource.RLIMIT_AS, (cap, hard))
        _MAPPED_AT_CAP = mapped
    except (ImportError, ValueError, OSError):  # not on this system
        pass


@contextlib.contextmanager
def memory_cap(limit: int | None) -> Iterator[int | None]:
    """(In a worker process.) Within the block, the address-space cap is what the worker had
    mapped when it started plus ``limit`` bytes, at most the runner's ``ceiling_bytes`` (the
    worker's hard limit); the programs the block starts (CalculiX) inherit it. Yields the cap in
    bytes (None where there is none)."""
    try:
        import resource

        soft, hard = resource.getrlimit(resource.RLIMIT_AS)
    except (ImportError, ValueError, OSError):
        yield None
        return
    if limit is None or _MAPPED_AT_CAP is None or soft == resource.RLIM_INFINITY:
        yield None if soft == resource.RLIM_INFINITY else soft
        return
    wanted = _MAPPED_AT_CAP + limit
    cap = wanted if hard == resource.RLIM_INFINITY else min(wanted, hard)
    resource.setrlimit(resource.RLIMIT_AS, (cap, hard))
    try:
        yield cap
    finally:
        resource.setrlimit(resource.RLIMIT_AS, (soft, hard))


def _worker_main(
    conn: Connection, memory_bytes: int | None, ceiling_bytes: int | None = None
) -> None:
    """A worker process: import the modules, say "ready", then answer jobs ``(fn, args,
    progress)`` one at a time with ``("ok", result)``, ``("error", exception)`` or ``("memory", None)`` (after
    which it ends: a process that ran out of memory is not trusted with another job), preceded,
    for a job sent with ``progress`` true, by any number of ``("progress", event)``
    (:func:`send_progress`). It ends when the server closes its pipe."""
    global _PROGRESS_SINK
    _die_with_parent()
    _own_process_group()
    _leave_forkserver()
    signal.signal(signal.SIGINT, signal.SIG_IGN)  # Ctrl-C is the server's: it ends the workers
    _warm_up()
    _cap_memory(memory_bytes, ceiling_bytes)
    conn.send(("ready", os.getpid()))
    while True:
        reply: tuple[str, Any]
        progress = False
        try:
            fn, args, progress = conn.recv()
        except (EOFError, OSError):
            return
        except Exception as exc:  # a job this process cannot load
            fn, args = _raise, (exc,)
        if progress:
            _PROGRESS_SINK = lambda event: conn.send(("progress", event))  # noqa: E731
        try:
            reply = ("ok", fn(*args))
        except MemoryError:
            reply = ("memory", None)
        except BaseException as exc:
            reply = ("error", exc)
        finally:
            _PROGRESS_SINK = None
        release_memory()
        try:
            conn.send(reply)
        except MemoryError:
            conn.send(("memory", None))
        except (EOFError, OSError):
            return
        except Exception as exc:  # a result or an error that does not pickle
            from corrugate.core.errors import describe

            conn.send(("error", RuntimeError(describe(exc))))
        if reply[0] == "memory":
            return


def _raise(exc: BaseException) -> None:
    raise exc


@dataclass(eq=False)
class _Worker:
    """One worker process of a :class:`Runner` and the server's end of its pipe."""

    process: BaseProcess
    conn: Connection
    pid: int


class WorkerLostError(Exception):
    """The worker process of a computation ended under it (killed from outside, or the server is
    shutting down) (HTTP 503)."""


class Runner:
    """Run each computation of a request in a worker process that can be killed: ``processes``
    of them (None: one per core, at least 2), one job at a time each, jobs waiting in turn.

    * **Time limit**: ``timeout_s`` from when a worker takes the job (its wait in the queue does
      not count). Past it the worker is killed (SIGKILL), :class:`ComputeTimeoutError` is raised
      and a fresh worker takes its place.
    * **Memory**: each worker's address space is capped at ``memory_bytes`` beyond what it
      maps once its modules are imported (``RLIMIT_AS``); a
      job that needs more gets :class:`~corrugate.core.errors.InputError` naming the body (422),
      and its worker is replaced. A job may set its own cap, up to ``ceiling_bytes`` beyond that
      mapping (:func:`memory_cap`: the FE verification jobs, whose CalculiX runs inherit it).
    * **Load**: at most ``max_pending`` computations queued or running at once; past that
      :meth:`run` raises :class:`ServerBusyError` at once.
    * **Lifetime**: workers start from a fresh interpreter (``forkserver``; ``spawn`` where
      there is none), never as a fork of the server with its threads; each imports
      :data:`WORKER_PRELOAD` before it takes a job (that start is not part of a time limit).
      Each asks Linux to kill it when its parent ends, so a server killed with SIGKILL leaves no
      worker behind; :meth:`kill_workers` (on SIGTERM or Ctrl-C) and :meth:`shutdown` (at the
      app's end) kill them all. ``reap``, if given, is called with a worker's pid once that
      worker and its process group have ended (killed at a time limit, a cancel or shutdown, or
      dead of itself): what it left goes (the CalculiX work folders,
      :func:`corrugate.fea.workdirs.sweep_owned`).

    Jobs are module-level functions with picklable arguments and results; their exceptions
    come back as raised (corrugate's own errors with their fields).
    """

    def __init__(
        self,
        max_pending: int,
        timeout_s: float,
        processes: int | None = None,
        memory_bytes: int | None = WORKER_MEMORY_BYTES,
        ceiling_bytes: int | None = None,
        reap: Callable[[int], object] | None = None,
    ) -> None:
        self.timeout_s = timeout_s
        self.processes = max(2, core_count()) if processes is None else processes
        if self.processes < 1:
            raise ValueError(f"a runner needs at least one worker process, not {processes}")
        self.memory_bytes = memory_bytes
        self.ceiling_bytes = ceiling_bytes
        self._reap = reap
        self._reaping: list[threading.Thread] = []
        self._slots = threading.BoundedSemaphore(max_pending)
        self._lock = threading.Lock()
        self._idle: deque[_Worker] = deque()
        self._waiters: deque[tuple[asyncio.AbstractEventLoop, asyncio.Future[_Worker]]] = deque()
        self._workers: dict[int, _Worker] = {}  # every started worker, by pid
        self._pids: tuple[int, ...] = ()  # their pids, for kill_workers (read without the lock)
        self._starting = 0
        self._started = False
        self._closed = False
        # Threads that wait on the workers' pipes, and threads that start workers (never
        # computing themselves): one per worker, and a few for the killed ones still ending.
        self._io = ThreadPoolExecutor(
            max_workers=2 * self.processes + 2, thread_name_prefix="corrugate-web-io"
        )
        self._starter = ThreadPoolExecutor(
            max_workers=self.processes, thread_name_prefix="corrugate-web-start"
        )

    # -- worker life -------------------------------------------------------------------------

    def start_processes(self) -> None:
        """Start every worker process now (they import their modules in the background)."""
        with self._lock:
            if self._started or self._closed:
                return
            self._started = True
            self._starting += self.processes
        for _ in range(self.processes):
            self._starter.submit(self._start_one)

    def _start_one(self) -> None:
        """Start one worker, wait until it is ready, then hand it to a waiting job (a thread)."""
        worker: _Worker | None = None
        try:
            methods = multiprocessing.get_all_start_methods()
            context = multiprocessing.get_context(
                "forkserver" if "forkserver" in methods else "spawn"
            )
            if context.get_start_method() == "forkserver":
                # The forkserver imports them once (when this process starts it), so that a
                # worker that replaces a killed one is ready at once.
                context.set_forkserver_preload(list(WORKER_PRELOAD))
            ours, theirs = context.Pipe(duplex=True)
            process: BaseProcess = context.Process(  # type: ignore[attr-defined]
                target=_worker_main,
                args=(theirs, self.memory_bytes, self.ceiling_bytes),
                name="corrugate-web-worker",
                daemon=True,
            )
            if self._closed:
                raise WorkerLostError("the server is shutting down")
            process.start()
            theirs.close()
            assert process.pid is not None
            worker = _Worker(process, ours, process.pid)
            with self._lock:
                self._workers[worker.pid] = worker
                self._pids = tuple(self._workers)
            if self._closed:
                raise WorkerLostError("the server is shutting down")
            if not ours.poll(_START_TIMEOUT_S):
                raise TimeoutError("the worker process did not start")
            ours.recv()  # ("ready", pid)
        except Exception:
            if not self._closed:
                _log.exception("a worker process could not start")
            with self._lock:
                self._starting -= 1
            if worker is not None:
                self._kill(worker)
                worker.conn.close()
            self._fail_waiters_if_no_worker()
            return
        with self._lock:
            self._starting -= 1
        self._release(worker)

    def _replace(self, worker: _Worker) -> None:
        """Kill ``worker`` (if it still runs) and start another in its place."""
        self._kill(worker)
        with self._lock:
            if self._closed:
                return
            self._starting += 1
        self._starter.submit(self._start_one)

    def _kill(self, worker: _Worker) -> None:
        """SIGKILL ``worker`` and forget it (its parent, the forkserver, reaps it). Its pipe is
        closed by whoever holds it last: a thread may still be reading it (it reads EOF)."""
        with self._lock:
            known = self._workers.pop(worker.pid, None) is not None
            self._pids = tuple(self._workers)
        _kill_group(worker.pid)
        if known:
            self._reap_later(worker)

    def _reap_later(self, worker: _Worker) -> None:
        """Once ``worker`` and the programs it started have ended, call the runner's ``reap``
        with its pid (on a thread of its own: the sweep of what the worker left)."""
        if self._reap is None:
            return
        thread = threading.Thread(
            target=self._reap_when_ended, args=(worker,), name="corrugate-web-reap", daemon=True
        )
        with self._lock:  # started before shutdown can see it (and join it)
            thread.start()
            self._reaping = [t for t in self._reaping if t.is_alive()] + [thread]

    def _reap_when_ended(self, worker: _Worker) -> None:
        """Wait (at most some seconds) until ``worker`` and its process group have ended, then
        call ``reap`` with its pid."""
        if self._reap is None:
            return
        with contextlib.suppress(Exception):
            worker.process.join(_REAP_WAIT_S)
        _wait_group_ended(worker.pid, _REAP_WAIT_S)
        try:
            self._reap(worker.pid)
        except Exception:
            _log.exception("could not sweep what worker %d left", worker.pid)

    def _fail_waiters_if_no_worker(self) -> None:
        """When no worker runs or starts (they cannot start), the jobs waiting get 503."""
        with self._lock:
            if self._workers or self._starting:
                return
            waiters = list(self._waiters)
            self._waiters.clear()
        for loop, future in waiters:
            with contextlib.suppress(RuntimeError):  # its loop has ended
                loop.call_soon_threadsafe(_fail, future, "no worker process could start")

    def kill_workers(self) -> None:
        """Kill every worker now and take no more jobs (safe in a signal handler: no lock). The
        computations running get :class:`WorkerLostError` (503)."""
        self._closed = True
        for pid in self._pids:
            _kill_group(pid)

    def worker_pids(self) -> tuple[int, ...]:
        """The process ids of the workers started and not yet killed."""
        return self._pids

    def shutdown(self) -> None:
        """Kill every worker, fail the jobs waiting for one, and stop the runner's threads."""
        self.kill_workers()
        with self._lock:
            workers = list(self._workers.values())
            self._workers.clear()
            self._pids = ()
            self._idle.clear()
            waiters = list(self._waiters)
            self._waiters.clear()
        for loop, future in waiters:
            with contextlib.suppress(RuntimeError):  # its loop has ended
                loop.call_soon_threadsafe(_fail, future, "the server is shutting down")
        for worker in workers:
            worker.process.join(5)  # killed: the forkserver reports its end at once
        for worker in workers:
            self._reap_when_ended(worker)
        with self._lock:
            reaping, self._reaping = self._reaping, []
        for thread in reaping:
            thread.join(2 * _REAP_WAIT_S)
        self._io.shutdown(wait=False, cancel_futures=True)
        self._starter.shutdown(wait=False, cancel_futures=True)

    # -- jobs ----------------------------------------------------------------------------------

    def _release(self, worker: _Worker) -> None:
        """Give an idle ``worker`` to the first job waiting for one, or keep it idle."""
        with self._lock:
            if not self._closed:
                while self._waiters:
                    loop, future = self._waiters.popleft()
                    try:
                        loop.call_soon_threadsafe(self._hand, future, worker)
                    except RuntimeError:  # that job's loop has ended
                        continue
                    return
                self._idle.append(worker)
                return
        self._kill(worker)

    def _hand(self, future: asyncio.Future[_Worker], worker: _Worker) -> None:
        """(On the waiting job's loop.) Give it ``worker``, or pass it on if it stopped waiting."""
        if future.done():
            self._release(worker)
        else:
            future.set_result(worker)

    async def _take(self) -> _Worker:
        """An idle worker, waiting in turn for one."""
        self.start_processes()
        loop = asyncio.get_running_loop()
        with self._lock:
            if self._closed:
                raise WorkerLostError("the server is shutting down")
            if self._idle:
                return self._idle.popleft()
            if not self._workers and not self._starting:
                raise WorkerLostError("no worker process could start; see the server's log")
            future: asyncio.Future[_Worker] = loop.create_future()
            self._waiters.append((loop, future))
        try:
            while True:
                # kill_workers (a signal handler) cannot wake the waiting jobs: they look
                done, _ = await asyncio.wait({future}, timeout=0.5)
                if done:
                    return future.result()
                if self._closed:
                    raise WorkerLostError("the server is shutting down")
        except BaseException:  # stopped waiting (cancelled, or the server is stopping)
            if not future.cancel() and not future.cancelled() and future.exception() is None:
                self._release(future.result())  # handed over just now: pass it on
            raise

    @staticmethod
    def _exchange(
        worker: _Worker,
        fn: Callable[..., Any],
        args: tuple[Any, ...],
        on_progress: Callable[[dict[str, Any]], None] | None,
    ) -> Any:
        """(On a thread.) Send the job, pass its progress events to ``on_progress`` (called on
        this thread), return its answer; EOFError/OSError if the worker ends first."""
        worker.conn.send((fn, args, on_progress is not None))
        while True:
            kind, value = worker.conn.recv()
            if kind != "progress":
                return kind, value
            if on_progress is not None:
                on_progress(value)

    async def run(
        self,
        fn: Callable[..., T],
        *args: Any,
        timeout_s: float | None = None,
        on_progress: Callable[[dict[str, Any]], None] | None = None,
    ) -> T:
        """The result of ``fn(*args)``, computed in a worker process: ``fn`` must be a
        module-level function and ``args`` and the result picklable. Its exceptions propagate;
        see the class for the time limit (``timeout_s``: this job's own, instead of the runner's),
        the memory cap and the load limit. ``on_progress``: called (on a thread of the runner)
        with each event the job sends (:func:`send_progress`); the job is told that progress is
        wanted (:func:`wants_progress`). Cancelling the awaiting task kills the job's worker (and
        the programs it started) and starts another."""
        if not self._slots.acquire(blocking=False):
            raise ServerBusyError("the server is busy with other computations; try again shortly")
        try:
            worker = await self._take()
            limit = self.timeout_s if timeout_s is None else timeout_s
            return await self._run_on(worker, fn, args, limit, on_progress)  # type: ignore[no-any-return]
        finally:
            self._slots.release()

    async def _run_on(
        self,
        worker: _Worker,
        fn: Callable[..., Any],
        args: tuple[Any, ...],
        timeout_s: float,
        on_progress: Callable[[dict[str, Any]], None] | None,
    ) -> Any:
        loop = asyncio.get_running_loop()
        exchange = loop.run_in_executor(self._io, self._exchange, worker, fn, args, on_progress)
        try:
            kind, value = await asyncio.wait_for(asyncio.shield(exchange), timeout_s)
        except TimeoutError:
            _close_when_done(exchange, worker)
            self._replace(worker)
            raise ComputeTimeoutError(timeout_s) from None
        except (EOFError, OSError):
            worker.conn.close()
            self._replace(worker)
            if self._closed:
                raise WorkerLostError("the server is shutting down") from None
            await loop.run_in_executor(self._io, worker.process.join, 2)
            code = worker.process.exitcode
            how = f" (signal {-code})" if code is not None and code < 0 else ""
            raise WorkerLostError(
                f"the worker process computing this request ended{how}; try again"
            ) from None
        except BaseException:  # cancelled (the server is stopping): the job goes with its worker
            _close_when_done(exchange, worker)
            self._replace(worker)
            raise
        if kind == "memory":
            worker.conn.close()
            self._replace(worker)
            raise _memory_error(self.memory_bytes)
        self._release(worker)
        if kind == "error":
            raise value
        return value


def _close_when_done(exchange: asyncio.Future[Any], worker: _Worker) -> None:
    """Close the pipe of a killed worker once the thread reading it has seen its end."""

    def done(future: asyncio.Future[Any]) -> None:
        if not future.cancelled():
            future.exception()  # EOFError, expected: retrieved so that it is not logged
        worker.conn.close()

    exchange.add_done_callback(done)


def _kill_group(pid: int) -> None:
    """SIGKILL the worker ``pid`` and its process group (the programs its job started: each
    worker leads its own group, :func:`_own_process_group`); just the process if it has no group
    of its own yet."""
    try:
        if os.getpgid(pid) == pid:
            os.killpg(pid, signal.SIGKILL)
            return
    except (ProcessLookupError, PermissionError, OSError):
        pass
    with contextlib.suppress(ProcessLookupError, PermissionError):
        os.kill(pid, signal.SIGKILL)


#: Longest wait for a killed worker, then for its process group, before its sweep (s).
_REAP_WAIT_S = 5.0


def _wait_group_ended(pid: int, seconds: float) -> None:
    """Wait until no process of the group ``pid`` runs (a killed worker's CalculiX), at most
    ``seconds``."""
    deadline = time.monotonic() + seconds
    while time.monotonic() < deadline:
        try:
            os.killpg(pid, 0)
        except (ProcessLookupError, PermissionError, OSError):
            return
        time.sleep(0.02)


def _fail(future: asyncio.Future[Any], why: str) -> None:
    if not future.done():
        future.set_exception(WorkerLostError(why))


def _memory_error(limit: int | None) -> Exception:
    from corrugate.core.errors import InputError

    cap = "" if limit is None else f" of {limit / 1024**3:g} GiB"
    return InputError(
        "body",
        "the request",
        "inputs whose computation needs less (bound the sizes and counts, or use the CLI)",
        reason=f"needs more than the memory{cap} one request may use",
    )
