"""A command's standard output whose reader may leave early (``corrugate design SPEC --out DIR |
head``): the command goes quiet and finishes.

Python raises ``BrokenPipeError`` at the first write after the reader closed the pipe; click
answers it with exit code 1 and rich with ``SystemExit(1)``, both before any file is written. The
command's work is its files and its exit code, not the lines nobody reads, so
:func:`pipe_safe_stdout` wraps ``sys.stdout``: at the first broken write the stream's descriptor
is pointed at the null device and every later write is dropped, and the command ends as it would
have (``tests/cli/test_closed_pipe.py``).
"""

from __future__ import annotations

import os
import sys
from typing import Any, TextIO

__all__ = ["pipe_safe_stdout"]


class _PipeSafe:
    """``stream`` with its writes and flushes made quiet once its reader has left."""

    def __init__(self, stream: TextIO) -> None:
        self._stream = stream
        self._gone = False

    def _leave(self) -> None:
        self._gone = True
        devnull = os.open(os.devnull, os.O_WRONLY)
        try:
            os.dup2(devnull, self._stream.fileno())
        finally:
            os.close(devnull)

    def write(self, text: str) -> int:
        if not self._gone:
            try:
                return self._stream.write(text)
            except BrokenPipeError:
                self._leave()
        return len(text)

    def flush(self) -> None:
        if not self._gone:
            try:
                self._stream.flush()
            except BrokenPipeError:
                self._leave()

    def __getattr__(self, name: str) -> Any:
        return getattr(self._stream, name)


def pipe_safe_stdout() -> None:
    """Wrap ``sys.stdout`` (module docstring), once; a stream without a file descriptor (a test
    runner's capture) is left as it is."""
    if isinstance(sys.stdout, _PipeSafe):
        return
    try:
        sys.stdout.fileno()
    except (AttributeError, OSError, ValueError):
        return
    sys.stdout = _PipeSafe(sys.stdout)
