"""Sweeps of FE validation cases through a ``concurrent.futures`` executor, and their reports.

* :func:`paper_cases`: the paper's validation sets (Liu, Yan and Mehta, Fig. 7; docs/theory.md 3.5):
  n = 11, alpha = 90 deg, W = 8/10/12/14 mm; W = 10 mm, alpha = 90 deg, n = 7/9/11/13; n = 11,
  W = 10 mm, alpha = 40/65/90/115 deg; Dura-Lar 0.125 mm, two identical layers on a square.
* :func:`run_sweep`: submits every case to an executor (a local process pool by default, or a
  dask.distributed cluster from :func:`corrugate.fea.tasks.dask_executor`, re-exported here)
  through :func:`corrugate.fea.tasks.run_tasks` and yields results as they finish; a case
  that fails is reported in its result and the others go on.
  A worker that dies (killed, out of memory) breaks a process pool: every case it took down is
  retried once, alone in a pool of its own; the rest go on. Work folders live under one private
  folder per sweep, removed at the end also after SIGINT or SIGTERM (unless ``keep``).
* :func:`write_table`, :func:`write_csv`: the table (Markdown) and the numbers (CSV) of a sweep;
  :func:`write_sweep_files`: the table, CSV and plot committed as one set.
* :func:`check_sweep_options`: jobs, time-out and work folder against :mod:`corrugate.core.limits`.
"""

from __future__ import annotations

import contextlib
import csv
import shutil
import tempfile
from collections.abc import Callable, Iterator, Sequence
from concurrent.futures import Executor
from dataclasses import replace
from pathlib import Path

from corrugate.core.errors import InputError
from corrugate.core.fileio import staged
from corrugate.core.limits import check, check_count
from corrugate.fea.tasks import dask_executor, run_tasks, worker_failure
from corrugate.fea.validation import Case, CaseResult, Refinement, run_case
from corrugate.geometry.layer import Assembly, Layer
from corrugate.materials.library import get_material
from corrugate.mechanics.moduli import MODELS

__all__ = [
    "SWEEPS",
    "check_sweep_options",
    "dask_executor",
    "paper_cases",
    "run_sweep",
    "write_csv",
    "write_sweep_files",
    "write_table",
]


def paper_cases(refinement: Refinement | None = None, unit_cell: bool = True) -> list[Case]:
    """The paper's validation sets (one case per set and value; the common design appears in
    each set)."""
    mat = get_material("dura-lar")
    sets: list[tuple[str, str, list[tuple[float, int, float]], list[float]]] = [
        ("W", "W mm", [(w, 11, 90.0) for w in (8.0, 10.0, 12.0, 14.0)], [8, 10, 12, 14]),
        ("n", "n", [(10.0, n, 90.0) for n in (7, 9, 11, 13)], [7, 9, 11, 13]),
        (
            "alpha",
            "alpha deg",
            [(10.0, 11, a) for a in (40.0, 65.0, 90.0, 115.0)],
            [40, 65, 90, 115],
        ),
    ]
    cases: list[Case] = []
    for group, param, designs, values in sets:
        for (W, n, alpha), v in zip(designs, values, strict=True):
            layer = Layer(W, n, alpha, mat, 0.125)
            cases.append(
                Case(
                    label=f"W={W:g} n={n} alpha={alpha:g}",
                    assembly=Assembly.identical(layer),
                    unit_cell=unit_cell,
                    refinement=refinement or Refinement(),
                    group=group,
                    parameter=param,
                    value=float(v),
                )
            )
    return cases


SWEEPS: dict[str, Callable[..., list[Case]]] = {"paper": paper_cases}


def _safe_run(case: Case) -> CaseResult:
    return run_case(case)


def check_sweep_options(
    jobs: int | None = None, timeout: float | None = None, workdir: Path | None = None
) -> None:
    """Raise :class:`InputError` for a number of jobs or a time-out outside
    :data:`corrugate.core.limits.LIMITS`, or a work folder that is not a folder or cannot be
    made (a name too long, a folder of ``/proc``, no permission): made here, before any FE work,
    as the first CalculiX run would make it."""
    if jobs is not None:
        check_count("jobs", jobs, "jobs")
    if timeout is not None:
        check("timeout", timeout, "timeout")
    if workdir is None:
        return
    try:
        if workdir.exists() and not workdir.is_dir():
            raise InputError("workdir", str(workdir), "a folder", reason="is a file")
        workdir.mkdir(parents=True, exist_ok=True)
    except OSError as exc:  # the OS's words, naming the option
        raise InputError(
            "workdir",
            str(workdir),
            "a folder this user may write in (made if missing)",
            reason=f"cannot be made ({exc.strerror or type(exc).__name__})",
        ) from None


def run_sweep(
    cases: Sequence[Case],
    executor: Executor | None = None,
    *,
    jobs: int | None = None,
    folder: Path | None = None,
    keep: bool = False,
    run: Callable[[Case], CaseResult] = _safe_run,
) -> Iterator[CaseResult]:
    """Run ``cases`` through ``executor`` (default: a process pool of ``jobs`` workers) and yield
    each result as it finishes; every case yields exactly one result
    (:func:`corrugate.fea.tasks.run_tasks`).

    With the own pool, a worker that dies breaks the pool: the cases lost with it are each
    retried once, alone (:data:`corrugate.fea.tasks.RETRIES`); a case lost again yields a result
    with ``error``. The ccx work folders go under one private folder (in
    ``folder`` if given), removed when the sweep ends, is interrupted (SIGINT) or terminated
    (SIGTERM), unless ``keep``. ``run`` is the function a worker runs on a case (a test may pass
    another)."""
    if jobs is not None:
        check_count("jobs", jobs, "jobs")
    if folder is not None:
        folder.mkdir(parents=True, exist_ok=True)
    root = Path(tempfile.mkdtemp(prefix="corrugate-sweep-", dir=folder))
    cases = [replace(c, folder=root, keep=keep or c.keep) for c in cases]
    try:
        with contextlib.closing(run_tasks(run, cases, executor, jobs=jobs)) as done:
            for i, r in done:
                yield _failed(cases[i], r) if isinstance(r, Exception) else r
    finally:
        if not keep:
            shutil.rmtree(root, ignore_errors=True)


def _failed(case: Case, exc: BaseException) -> CaseResult:
    return CaseResult(case, {}, {}, {}, (), False, worker_failure(exc))


def write_sweep_files(results: Sequence[CaseResult], out: Path, name: str) -> list[Path]:
    """The sweep's table (``sweep_NAME.md``), numbers (``.csv``) and plot (``.png``) in ``out``,
    committed as one set (:func:`corrugate.core.fileio.staged`): a failure or a kill leaves the old
    three files or the new three."""
    from corrugate.fea.plots import plot_sweep

    stem = f"sweep_{name}"
    paths = [out / f"{stem}.md", out / f"{stem}.csv", out / f"{stem}.png"]
    with staged(out, "--out", kind=stem) as st:
        write_table(results, st.path(paths[0]))
        write_csv(results, st.path(paths[1]))
        plot_sweep(results, st.path(paths[2]))
    return paths


def _order(r: CaseResult) -> tuple[int, float]:
    """Sweep sets in the paper's order (W, n, alpha), then by the swept value."""
    return ("Wnalpha".find(r.case.group), r.case.value)


def _rows(results: Sequence[CaseResult], eta: str) -> Iterator[dict[str, str]]:
    for r in sorted(results, key=_order):
        row = {"set": r.case.group, "case": r.case.label}
        if r.error:
            row["error"] = r.error
            yield row
            continue
        for q, unit in (("K", "N_per_mm"), ("D", "Nmm"), ("D4", "Nmm")):
            key = f"{q}_{unit}@{eta}"
            if key not in r.fe:
                continue
            row[f"{q} FE"] = f"{r.fe[key]:.4g}"
            for m in MODELS:
                row[f"{q} {m}"] = f"{r.models[m][key]:.4g}"
                row[f"{q} {m}/FE"] = f"{r.ratio(key, m):.3f}"
        row["mesh"] = ", ".join(f"{k} {v}" for k, v in r.meshes.items())
        row["converged"] = _converged(r)
        yield row


def _converged(r: CaseResult) -> str:
    """'yes' or 'no' for a refined case (did the change fall below the tolerance?), 'not
    refined' for a case run on one mesh."""
    if not r.refined:
        return "not refined"
    return "yes" if r.converged else "no"


def write_table(results: Sequence[CaseResult], path: Path, eta: str = "0") -> None:
    """A Markdown table: per case, FE and each model's K (N/mm), D (N mm, 3-point bending) and
    D4 (N mm, pure bending from the 4-point test) at ``eta``."""
    cols = ["set", "case", "K FE"]
    cols += [f"K {m}/FE" for m in MODELS]
    cols += ["D FE"] + [f"D {m}/FE" for m in MODELS]
    if any(f"D4_Nmm@{eta}" in r.fe for r in results):
        cols += ["D4 FE"] + [f"D4 {m}/FE" for m in MODELS]
    cols += ["mesh", "converged"]
    lines = ["| " + " | ".join(cols) + " |", "|" + "---|" * len(cols)]
    for row in _rows(results, eta):
        if "error" in row:
            lines.append(f"| {row['set']} | {row['case']} | failed: {row['error']} |")
            continue
        lines.append("| " + " | ".join(row.get(c, "") for c in cols) + " |")
    path.write_text("\n".join(lines) + "\n")


def write_csv(results: Sequence[CaseResult], path: Path) -> None:
    """Every number of every case (FE and each model), one row per case and quantity, cases in
    the order of the table (not of completion)."""
    with path.open("w", newline="") as fh:
        w = csv.writer(fh)
        w.writerow(
            [
                "set",
                "parameter",
                "value",
                "case",
                "quantity",
                "FE",
                *MODELS,
                "mesh",
                "converged",
                "error",
            ]
        )
        for r in sorted(results, key=_order):
            c = r.case
            mesh = "; ".join(f"{k} {v}" for k, v in r.meshes.items())
            if r.error:
                w.writerow(
                    [
                        c.group,
                        c.parameter,
                        c.value,
                        c.label,
                        "",
                        "",
                        *[""] * len(MODELS),
                        mesh,
                        "",
                        r.error,
                    ]
                )
                continue
            for key, v in r.fe.items():
                w.writerow(
                    [
                        c.group,
                        c.parameter,
                        c.value,
                        c.label,
                        key,
                        f"{v:.6g}",
                        *(f"{r.models[m][key]:.6g}" for m in MODELS),
                        mesh,
                        _converged(r),
                        "",
                    ]
                )
