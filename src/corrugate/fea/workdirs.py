"""The CalculiX work folders a process owns, and the sweep of those whose owner is gone.

A ccx work folder (:func:`corrugate.fea.ccx.work_dir`) is named ``corrugate-ccx-PID-XXXXXXXX``:
``PID`` is the process that made it, so a folder left by a process that was killed (SIGKILL,
its ``finally`` never ran) can be told from one still in use. :func:`sweep_owned` removes the
folders of a process known to have ended (the web app's worker pool, when it kills or loses a
worker); :func:`sweep_stale` removes those whose owner no longer runs (``corrugate serve`` at
start-up, ``corrugate verify`` before its runs, in the folder its runs use). A folder kept on
purpose (``keep``) has no PID in its name and is never swept; nor is anything that is not a
directory of this user. docs/fea.md section 4.
"""

from __future__ import annotations

import os
import re
import shutil
import stat
import tempfile
import time
from pathlib import Path

__all__ = [
    "PREFIX",
    "owned_prefix",
    "owner",
    "owner_running",
    "sweep_owned",
    "sweep_stale",
]

#: The name every ccx work folder starts with.
PREFIX = "corrugate-ccx-"

#: An owned folder's name: the prefix, the owner's pid, and mkdtemp's random part (letters,
#: digits and underscores, never a hyphen).
_OWNED = re.compile(r"^corrugate-ccx-(\d{1,10})-[A-Za-z0-9_]+$")


def owned_prefix(pid: int | None = None) -> str:
    """The name prefix of a work folder owned by ``pid`` (None: this process)."""
    return f"{PREFIX}{os.getpid() if pid is None else pid}-"


def owner(path: Path) -> int | None:
    """The pid a work folder's name records, None for another name (a kept folder's)."""
    match = _OWNED.match(path.name)
    return None if match is None else int(match.group(1))


def _boot_time() -> float | None:
    """When the machine booted (s since the epoch), from ``/proc/stat``; None elsewhere."""
    try:
        with open("/proc/stat", encoding="ascii") as f:
            for line in f:
                if line.startswith("btime "):
                    return float(line.split()[1])
    except OSError:
        pass
    return None


def _started(pid: int) -> float | None:
    """When process ``pid`` started (s since the epoch), from ``/proc``; None if unknown."""
    boot = _boot_time()
    try:
        with open(f"/proc/{pid}/stat", encoding="ascii") as f:
            fields = f.read().rsplit(")", 1)[1].split()
    except (OSError, IndexError):
        return None
    if boot is None or len(fields) < 20:
        return None
    return boot + int(fields[19]) / os.sysconf("SC_CLK_TCK")


def owner_running(pid: int, made: float) -> bool:
    """Whether process ``pid`` runs and may be the one that made a folder at time ``made`` (s
    since the epoch): a process that started after the folder was made only reuses its pid. A
    process of another user counts as running (it cannot be signalled, but it exists)."""
    try:
        os.kill(pid, 0)
    except ProcessLookupError:
        return False
    except PermissionError:
        return True
    try:
        with open(f"/proc/{pid}/stat", encoding="ascii") as f:
            if f.read().rsplit(")", 1)[1].split()[0] == "Z":
                return False  # ended; its parent has not reaped it yet
    except (OSError, IndexError):
        pass
    started = _started(pid)
    return started is None or started <= made + 1.0  # clock ticks: a second's slack


def _ours(path: Path) -> os.stat_result | None:
    """The folder's status if it is a directory (not a link) of this user, else None."""
    try:
        status = path.lstat()
    except OSError:
        return None
    if not stat.S_ISDIR(status.st_mode) or status.st_uid != os.getuid():
        return None
    return status


def _candidates(parent: Path | None) -> list[Path]:
    root = Path(tempfile.gettempdir()) if parent is None else parent
    try:
        return [p for p in root.iterdir() if p.name.startswith(PREFIX)]
    except OSError:
        return []


def sweep_owned(pid: int, parent: Path | None = None) -> list[Path]:
    """Remove every work folder in ``parent`` (None: the system temporary folder) that process
    ``pid`` made; the caller knows that ``pid`` has ended. Returns the folders removed."""
    removed = []
    for path in _candidates(parent):
        if owner(path) == pid and _ours(path) is not None:
            shutil.rmtree(path, ignore_errors=True)
            removed.append(path)
    return removed


def sweep_stale(parent: Path | None = None, before: float | None = None) -> list[Path]:
    """Remove every work folder in ``parent`` (None: the system temporary folder) whose owner no
    longer runs (:func:`owner_running`) and that was last changed before ``before`` (s since
    the epoch; None: now). Folders without an owner in their name are left alone. Returns the
    folders removed."""
    limit = time.time() if before is None else before
    removed = []
    for path in _candidates(parent):
        pid = owner(path)
        status = _ours(path)
        if pid is None or status is None or pid == os.getpid():
            continue
        if status.st_mtime >= limit or owner_running(pid, status.st_mtime):
            continue
        shutil.rmtree(path, ignore_errors=True)
        removed.append(path)
    return removed
