"""``corrugate verify DIR``: the FE twin of every behavioural constraint of a design.

Registered by :mod:`corrugate.cli` (see :data:`COMMANDS`). Reads ``DIR/design.json`` (written by
``corrugate design SPEC --out DIR``), runs each constraint's FE twin on a mesh series and
extrapolates it (:mod:`corrugate.fea.verify`), prints the table, then each load case's first
buckling and first yield load in FE (:mod:`corrugate.fea.first_failure`; ``--no-first-failure``
skips them), with ``--nonlinear`` a geometrically nonlinear ramp of the first load case
(:mod:`corrugate.fea.nonlinear`), and writes ``DIR/verify.json`` (its ``first_failure`` list
beside ``constraints``, and its ``nonlinear`` block) and ``DIR/nonlinear.png`` (with
``--nonlinear``) as the folder's set of kind ``verify``. The FE subpackage is imported only
when the command runs. Exit codes (:data:`corrugate.fea.verify.EXIT_CODES`, the worst row's
verdict): 0 every constraint holds in FE, 1 one does not, 5 one is not converged (its mesh
series was not shown asymptotic up to --max-mesh, or a run failed), 6 one has no FE twin (not
checked), 2 bad input (a missing or malformed design.json, a folder that cannot be written, no
ccx) or a design.json that changed while the FE ran (another design written into DIR: the old
design's verdict is not written).

verify.json names the design it checked by ``design_sha256``, the SHA-256 of the design.json it
read, and is committed as a set that requires that design.json (:mod:`corrugate.core.fileio`): a
later design written into DIR drops it in the same commit, and a folder never lists one design's
verdict beside another design.

Example::

    corrugate design examples/blimp_gripper.toml --out out/gripper
    corrugate verify out/gripper --mesh 2,4,8
"""

from __future__ import annotations

import json
import os
import sys
from pathlib import Path
from typing import TYPE_CHECKING, Annotated

import typer

from corrugate.cli import options as o
from corrugate.cli.console import make_console
from corrugate.core.errors import InputError

if TYPE_CHECKING:
    from rich.console import Console

    from corrugate.fea.assembly import AssemblyMesh
    from corrugate.fea.first_failure import FailureRow
    from corrugate.fea.nonlinear import NonlinearResult
    from corrugate.fea.verify import Verification

__all__ = [
    "COMMANDS",
    "NONLINEAR_PNG",
    "print_failures",
    "print_nonlinear",
    "print_table",
    "summary",
    "verify_cmd",
]

Opt = typer.Option

#: The figure of ``--nonlinear``, beside verify.json.
NONLINEAR_PNG = "nonlinear.png"


def _writable(folder: Path) -> bool:
    """Whether verify.json can be written into ``folder`` (checked before any FE run)."""
    return os.access(folder, os.W_OK | os.X_OK)


def _fmt(v: float | None) -> str:
    return "-" if v is None else f"{v:.5g}"


def _nonlinear_mesh(n: int) -> AssemblyMesh:
    """``--nonlinear-mesh N``: the ramp's mesh (an even count >= 2)."""
    from corrugate.fea.assembly import AssemblyMesh

    try:
        return AssemblyMesh(n)
    except InputError as exc:
        raise exc.renamed("--nonlinear-mesh") from None


def print_table(v: Verification, label: str, console: Console) -> None:
    from rich.markup import escape
    from rich.table import Table

    off_axis = any(r.shift is not None for r in v.rows)
    where = (
        f"; off the crease directions the worst of coupon shifts "
        f"{' / '.join(f'{x:g}' for x in v.shifts)} pitch"
        if off_axis
        else ""
    )
    t = Table(
        title=f"{label}: FE twins (CalculiX), mesh series {' / '.join(map(str, v.meshes))} "
        f"elements per facet{where}",
        title_justify="left",
    )
    for col in ("constraint", "bound", "model", "FE series", "FE estimate", "holds"):
        t.add_column(col, justify="left" if col in ("constraint", "FE estimate") else "right")
    for r in v.rows:
        bound = ("<= " if r.sense == "max" else ">= ") + f"{r.bound:.5g} {r.unit}".rstrip()
        series = " / ".join(_fmt(x) for x in r.fe_series.values()) or "-"
        if r.fe_series and list(r.fe_series) != list(v.meshes):  # extended: say at which meshes
            series += f" (at {' / '.join(map(str, r.fe_series))})"
        est = escape(
            _fmt(r.fe) + (f" ({r.how})" if r.how else "") + (f"; {r.note}" if r.note else "")
        )
        t.add_row(
            escape(f"{r.name} [{r.quantity}]"),
            bound,
            f"{r.model:.5g}",
            series,
            est,
            _VERDICT_CELL[r.verdict],
        )
    console.print(t)
    console.print(summary(v))


#: The holds column of each verdict (corrugate.fea.verify.VERDICTS).
_VERDICT_CELL = {
    "holds": "yes",
    "fails": "[red]NO[/red]",
    "not converged": "[yellow]not converged[/yellow]",
    "not checked": "not checked",
}


def summary(v: Verification) -> str:
    """The line under the table: the design's verdict and its exit code (docs/fea.md 6;
    :attr:`corrugate.fea.verify.Verification.statement`, coloured)."""
    from rich.markup import escape

    text = escape(v.statement)
    colour = {"fails": "red", "not converged": "yellow"}.get(v.verdict)
    return f"[{colour}]{text}[/{colour}]" if colour and v.rows else text


def print_failures(rows: tuple[FailureRow, ...], console: Console) -> None:
    """The first-failure rows (:mod:`corrugate.fea.first_failure`): each load case's first
    buckling and first yield load in FE, beside the load its constraints are certified under
    and the model's first-failure load of a load capacity (no safety factor)."""
    from rich.markup import escape
    from rich.table import Table

    if not rows:
        return
    t = Table(
        title="first failure in FE (evidence beside the constraints, not part of their verdict)",
        title_justify="left",
    )
    cols = ("load case", "constraints", "load", "FE first failure", "load <= FE", "model <= FE")
    for col in cols:
        t.add_column(col, justify="left" if col in cols[:2] or col == cols[3] else "right")
    yes_no = {None: "-", True: "yes", False: "[red]NO[/red]"}

    def said(verdict: str | None, holds: bool | None) -> str:
        return "not converged" if verdict == "not converged" else yes_no[holds]

    for r in rows:
        model = (
            "-" if r.model is None else f"{r.model:.4g} N: {said(r.model_verdict, r.model_holds)}"
        )
        t.add_row(
            escape(r.test),
            escape(", ".join(r.constraints)),
            "-" if r.load is None else f"{r.load:.5g} N",
            escape(r.sentence + (f"; {r.note}" if r.note else "")),
            said(r.verdict, r.holds),
            model,
        )
    console.print(t)


def print_nonlinear(r: NonlinearResult | str, console: Console) -> None:
    """The nonlinear ramp (:mod:`corrugate.fea.nonlinear`) in a few lines, or why it did not
    run."""
    from rich.markup import escape

    if isinstance(r, str):
        console.print(escape(f"nonlinear ramp: {r}"))
        return
    console.print(escape(f"nonlinear ramp (NLGEOM, first mode as imperfection): {r.sentence}"))
    m = r.case.model
    if m is not None:
        verdict = {None: "-", True: "yes", False: "[red]NO[/red]"}[r.model_holds]
        at = r.knee_load if r.knee_load is not None else r.end_load
        console.print(
            f"model's first failure {m:.4g} N <= FE's {escape(r.compared_with)} ({at:.4g} N): "
            f"{verdict}"
        )


def verify_cmd(
    folder: Annotated[
        Path,
        typer.Argument(
            metavar="DIR", help="A design's folder, written by `corrugate design SPEC --out DIR`."
        ),
    ],
    mesh: Annotated[
        str,
        Opt(
            metavar="N,N,...",
            help="Mesh series: shell elements across each facet (even, increasing, each twice "
            "the one before for an extrapolation).",
        ),
    ] = "2,4,8",
    shifts: Annotated[
        str,
        Opt(
            metavar="S,S,...",
            help="Coupon positions off the crease directions (fractions of each layer's pitch, "
            "0 <= s < 1); the worst counts.",
        ),
    ] = "0,0.25,0.5,0.75",
    workdir: Annotated[
        Path | None,
        Opt(
            metavar="DIR",
            help="Parent folder of the ccx work folders (default: the system temporary "
            "folder); the folders there of runs that were killed (their process has ended) are "
            "removed first.",
        ),
    ] = None,
    timeout: Annotated[
        float, Opt(parser=o.ASCII_FLOAT, help="Time-out of one ccx run (s).")
    ] = 900.0,
    jobs: Annotated[
        int | None,
        Opt(
            parser=o.ASCII_INT,
            metavar="N",
            help="Run the FE runs side by side in a local pool of N worker processes (default: "
            "one after another, in this process).",
        ),
    ] = None,
    scheduler: Annotated[
        str | None,
        Opt(
            metavar="ADDRESS",
            help="Run the FE runs as tasks on the dask.distributed scheduler at ADDRESS, e.g. "
            "tcp://host:8786 (needs the `dist` extra; each worker needs corrugate and ccx; "
            "`corrugate docs fea`, section 4).",
        ),
    ] = None,
    max_mesh: Annotated[
        int,
        Opt(
            "--max-mesh",
            parser=o.ASCII_INT,
            metavar="N",
            help="Refine a series not yet shown asymptotic against its bound by doubling its "
            "finest mesh, up to N elements per facet (0: 16; a 16-per-facet run may take minutes "
            "and up to ~8 GB); a series still open there is 'not converged' (exit 5).",
        ),
    ] = 0,
    first_failure: Annotated[
        bool,
        Opt(
            "--first-failure/--no-first-failure",
            help="Also run each load case's fixture as a linear buckling analysis and with "
            "stresses: the load at the first buckling and at the first yield, on the same mesh "
            "series (evidence beside the constraints, not part of the verdict).",
        ),
    ] = True,
    nonlinear: Annotated[
        bool,
        Opt(
            "--nonlinear",
            help="Also run the first load case as a geometrically nonlinear ramp (NLGEOM) to "
            "1.5 x its predicted failure load, its first buckling mode (a buckling run first) as "
            "an imperfection of W/200: the load-deflection curve and where the stiffness falls, "
            "in verify.json and nonlinear.png. Costs one buckling run and 20 or more nonlinear "
            "increments, each a few linear solves: minutes at 4 per facet.",
        ),
    ] = False,
    nonlinear_mesh: Annotated[
        int,
        Opt(
            "--nonlinear-mesh",
            parser=o.ASCII_INT,
            metavar="N",
            help="Shell elements across each facet of the nonlinear ramp's mesh (even).",
        ),
    ] = 4,
    as_json: Annotated[
        bool,
        Opt(
            "--json", help='Print {"holds", "constraints": [...], "first_failure": [...]} as JSON.'
        ),
    ] = False,
    quiet: o.Quiet = False,
) -> None:
    """Check every behavioural constraint of a design by its FE twin, on a mesh series.

    Each stiffness, load-case and buckling bound of DIR/design.json runs in the FE fixture of
    its test (the runs of `corrugate validate`), at each mesh, Richardson-extrapolated; off the
    crease directions at each coupon position of --shifts, the worst counting; writes
    DIR/verify.json. A series counts only when shown asymptotic (four meshes, two successive
    extrapolations agreeing within a quarter of the bound's margin); otherwise it is refined up
    to --max-mesh. Exit 0 when every constraint holds in FE, 1 when one fails, 5 when one is not
    converged, 6 when one has no FE twin (not checked), 2 for bad input or a design.json that
    changed while the FE ran (nothing written) (the worst counts). Every layout: a circle's K runs in the wheel fixture (a ground
    patch against the hub), a polygon's constraints along its creases in the rectangle's
    fixtures on its cut outline (`corrugate docs fea`, 2.8); a row says how its test differs.

    Below them, each load case's first failure in FE: its fixture as a linear buckling
    analysis (a dead load) and its static run's peak stress against the yield strength, the
    loads (N) on the same mesh series (--no-first-failure: not run); they do not change the exit
    code. --nonlinear: the first load case's nonlinear ramp (curve, knee, peak) in verify.json
    and DIR/nonlinear.png; it does not change the exit code either.

    Example: corrugate verify out/gripper --mesh 2,4,8
    """
    from corrugate.core.fileio import write_set
    from corrugate.export.record import (
        RECORD_NAME,
        VERIFY_KIND,
        VERIFY_NAME,
        check_verify_target,
        design_label,
        read_design_file,
    )
    from corrugate.fea.ccx import find_ccx
    from corrugate.fea.series import check_sweep_options
    from corrugate.fea.tasks import executor_for
    from corrugate.fea.verify import parse_max_mesh, parse_meshes, parse_shifts, verify_design

    meshes = parse_meshes(mesh)
    positions = parse_shifts(shifts)
    cap = parse_max_mesh(max_mesh)
    nl_mesh = _nonlinear_mesh(nonlinear_mesh) if nonlinear else None
    check_sweep_options(jobs, timeout, workdir)
    if jobs is not None and scheduler is not None:
        raise InputError(
            "--jobs", jobs, "--jobs or --scheduler, not both", reason="conflicts with --scheduler"
        )
    design = read_design_file(folder)  # untrusted: one line and exit 2 before any FE run
    assembly, constraints, joint = design.assembly, design.constraints, design.joint
    check_verify_target(folder)  # a verify.json that is a folder: refused before any FE run
    if not _writable(folder):
        raise InputError(
            "DIR", str(folder), "a folder verify.json can be written to", reason="is not writable"
        )
    find_ccx()  # fail early, with one clear line, when CalculiX is missing
    from corrugate.fea.workdirs import sweep_stale

    sweep_stale(workdir)  # the work folders of runs killed before their end (owner gone)
    from corrugate.cli.validate import progress_lines

    progress = progress_lines(quiet or (as_json and not sys.stderr.isatty()))
    executor = executor_for(scheduler, jobs)  # None: in process, or a pool of --jobs
    from corrugate.core import memory

    try:
        result = verify_design(
            assembly,
            constraints,
            joint,
            meshes,
            shifts=positions,
            progress=progress,
            folder=workdir,
            timeout=timeout,
            max_mesh=cap,
            executor=executor,
            jobs=jobs,
            # an extending run estimated above the memory available now is not made: its
            # row is "not converged (memory)", as on the web (docs/fea.md 6)
            memory_bytes=memory.available_memory() if executor is None else None,
        )
        failures: tuple[FailureRow, ...] = ()
        if first_failure:
            from corrugate.fea.first_failure import first_failures

            failures = first_failures(
                assembly,
                constraints,
                joint,
                meshes,
                progress=progress,
                folder=workdir,
                timeout=timeout,
                done=result.rows,
                max_mesh=cap,
                executor=executor,
                jobs=jobs,
            )
    finally:
        if executor is not None:
            executor.shutdown()
    found = {**result.as_json(), "first_failure": [r.as_json() for r in failures]}
    files: dict[str, str | bytes] = {}
    ramp: NonlinearResult | str | None = None
    if nl_mesh is not None:
        from corrugate.fea.nonlinear import run_for_design
        from corrugate.fea.nonlinear_plot import nonlinear_png

        ramp = run_for_design(
            assembly,
            constraints,
            joint,
            nl_mesh,
            progress=progress,
            folder=workdir,
            timeout=timeout,
        )
        if isinstance(ramp, str):
            found["nonlinear"] = {"note": ramp}
        else:
            found["nonlinear"] = ramp.as_json()
            files[NONLINEAR_PNG] = nonlinear_png(ramp)
    data = {"design": design_label(assembly), "design_sha256": design.sha256, **found}
    text = json.dumps(data, indent=2, allow_nan=False)
    files = {VERIFY_NAME: text + "\n", **files}
    # the verdict of this design.json only: refused (exit 2, nothing written) when another
    # design was written there while the FE ran, dropped by the next design written there
    write_set(folder, files, field="DIR", kind=VERIFY_KIND, requires={RECORD_NAME: design.sha256})
    if as_json:
        typer.echo(json.dumps(found, indent=2, allow_nan=False))
    elif not quiet:
        console = make_console()
        print_table(result, design_label(assembly), console)
        print_failures(failures, console)
        if ramp is not None:
            print_nonlinear(ramp, console)
        for name in files:
            console.print(f"wrote {folder / name}", markup=False)
    if result.verdict != "holds":
        if quiet:
            others = [f"{r.name} ({r.verdict})" for r in result.rows if not r.holds]
            make_console(stderr=True).print(f"FE verdict {result.verdict}: " + ", ".join(others))
        raise typer.Exit(result.exit_code)


#: The commands of this module, by name (registered by :mod:`corrugate.cli`).
COMMANDS = {"verify": verify_cmd}
