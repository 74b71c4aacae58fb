"""SIGPIPE stays ignored in our process after a library resets it in C.

Python ignores SIGPIPE at start-up, so that a write to a closed pipe or socket raises
``BrokenPipeError`` in the writer instead of killing the process. ``gmsh.initialize()`` (gmsh 4)
sets it back to the default disposition in C, behind Python's back (``signal.getsignal`` still
answers ``SIG_IGN``): any later write to a closed pipe or socket, a browser's, a dask worker's,
a web client's, then ends the whole process with no traceback (exit 141). Measured: the
``SigIgn`` mask of ``/proc/self/status`` loses bit 13 across ``gmsh.initialize``.
"""

from __future__ import annotations

import ctypes
import signal
import threading

__all__ = ["reapply_sigpipe", "sigpipe_ignored"]

_SIG_IGN = 1  # the C value of SIG_IGN (<signal.h>)


def sigpipe_ignored() -> bool | None:
    """Whether the kernel ignores SIGPIPE for this process (``/proc/self/status``, Linux); None
    where that file does not exist."""
    try:
        with open("/proc/self/status", encoding="ascii") as fh:
            for line in fh:
                if line.startswith("SigIgn:"):
                    return bool(int(line.split()[1], 16) >> (signal.SIGPIPE - 1) & 1)
    except OSError:
        return None
    return None


def reapply_sigpipe() -> None:
    """Put SIGPIPE's disposition back to what Python holds it to be (``signal.getsignal``),
    after a C library changed it. From the main thread through :func:`signal.signal`; from
    another thread (where Python refuses ``signal.signal``) only the usual ``SIG_IGN``, through
    the C library's ``signal``."""
    wanted = signal.getsignal(signal.SIGPIPE)
    if threading.current_thread() is threading.main_thread():
        signal.signal(signal.SIGPIPE, wanted)
    elif wanted == signal.SIG_IGN:
        libc = ctypes.CDLL(None)
        libc.signal.restype = ctypes.c_void_p
        libc.signal.argtypes = (ctypes.c_int, ctypes.c_void_p)
        libc.signal(int(signal.SIGPIPE), ctypes.c_void_p(_SIG_IGN))
