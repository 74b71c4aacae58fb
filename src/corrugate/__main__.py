"""``python -m corrugate``: the command line.

The cyclic collector's thresholds are those of a command's process
(:data:`corrugate.cli.GC_THRESHOLDS`, repeated here: importing :mod:`corrugate.cli` is what they
should already apply to) before anything is imported: importing numpy, pydantic, typer and the
package allocates hundreds of thousands of objects, which at Python's default thresholds makes
the collector run some hundreds of times for nothing (0.025 s of CPU of a ``design`` run, median
of 11 interleaved runs, ``python -c 'import corrugate.cli, corrugate.solver, corrugate.workflow,
corrugate.export'`` with and without them; issue 39).
"""

import gc

gc.set_threshold(500_000, 20, 100)

from corrugate.cli import main  # noqa: E402  (after the thresholds: its imports are the point)

main()
