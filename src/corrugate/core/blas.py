"""numpy's BLAS started with one thread in a command's process.

numpy's wheels link OpenBLAS, which starts a thread per core when numpy is imported (it reads
``OPENBLAS_NUM_THREADS`` once, as the library loads) and keeps them for the process's life. A
command's arrays are small (the solver's boxes and the writers' paths are element-wise work; the
finite elements run in CalculiX, its own process), so those threads only cost their start: on a
2-core machine ``import numpy`` took 0.072 s of CPU with one thread against 0.103 s, and
``corrugate design examples/blimp_gripper.toml`` 0.279 s against 0.310 s, ``--out`` 1.089 s
against 1.129 s (``OPENBLAS_NUM_THREADS=1`` or not, medians of 15 and 7 interleaved runs; issue
39, docs/architecture.md section 1, ``core``). The answers and the files are the same
(``benchmarks/examples_before_after.sh``).
"""

from __future__ import annotations

import os

from corrugate.core.first_import import around_first_import

__all__ = ["BLAS_THREADS", "one_blas_thread"]

#: The variable OpenBLAS reads for its number of threads when it loads.
BLAS_THREADS = "OPENBLAS_NUM_THREADS"


def _one() -> None:
    os.environ[BLAS_THREADS] = "1"


def _given_back() -> None:
    os.environ.pop(BLAS_THREADS, None)


def one_blas_thread() -> None:
    """Have numpy's OpenBLAS, when numpy is first imported in this process, start one thread
    instead of one per core: :data:`BLAS_THREADS` is 1 while numpy's package runs (its BLAS
    loads) and removed after it (:func:`corrugate.core.first_import.around_first_import`), so
    the processes this one starts (CalculiX, workers) inherit the environment it was given.
    Nothing when numpy is imported already or the environment names :data:`BLAS_THREADS` (the
    user's choice stands). The command line calls this first (:func:`corrugate.cli.main`); a
    program importing the package keeps numpy's threads."""
    if BLAS_THREADS in os.environ:
        return
    around_first_import("numpy", _one, _given_back)
