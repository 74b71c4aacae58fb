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
import sys
from collections.abc import Sequence
from types import ModuleType
from typing import TYPE_CHECKING

if TYPE_CHECKING:
    from importlib.machinery import ModuleSpec

__all__ = ["BLAS_THREADS", "one_blas_thread"]

#: The variable OpenBLAS reads for its number of threads when it loads.
BLAS_THREADS = "OPENBLAS_NUM_THREADS"


class _UntilNumpy:
    """First on :data:`sys.meta_path` until numpy is imported: lets the other finders find numpy
    and takes :data:`BLAS_THREADS` out of the environment again once numpy's package has run (its
    BLAS loaded), so that the processes this one starts after that (CalculiX, workers) inherit
    the environment it was given. A plain class, not ``importlib.abc.MetaPathFinder``: that
    module imports ``importlib.resources`` and ``tempfile`` (3.8 ms in ``python -X importtime``)."""

    def find_spec(
        self, name: str, path: Sequence[str] | None = None, target: ModuleType | None = None
    ) -> ModuleSpec | None:
        if name != "numpy":
            return None
        sys.meta_path.remove(self)
        spec: ModuleSpec | None = None
        for finder in sys.meta_path:
            find = getattr(finder, "find_spec", None)
            spec = find(name, path, target) if find is not None else None
            if spec is not None:
                break
        if spec is None:
            os.environ.pop(BLAS_THREADS, None)
            return None
        loader = spec.loader
        run = getattr(loader, "exec_module", None)
        if run is None:
            os.environ.pop(BLAS_THREADS, None)
            return spec

        def exec_module(module: ModuleType) -> None:
            try:
                run(module)
            finally:
                os.environ.pop(BLAS_THREADS, None)

        setattr(loader, "exec_module", exec_module)  # noqa: B010 (the loader's own method)
        return spec


def one_blas_thread() -> None:
    """Have numpy's OpenBLAS, when numpy is first imported in this process, start one thread
    instead of one per core. Nothing when numpy is imported already or the environment names
    :data:`BLAS_THREADS` (the user's choice stands). The variable is set only until numpy's
    package has run; the command line calls this first (:func:`corrugate.cli.main`), a program
    importing the package keeps numpy's threads."""
    if "numpy" in sys.modules or BLAS_THREADS in os.environ:
        return
    if any(isinstance(finder, _UntilNumpy) for finder in sys.meta_path):
        return
    os.environ[BLAS_THREADS] = "1"
    sys.meta_path.insert(0, _UntilNumpy())
