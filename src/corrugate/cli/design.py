"""``corrugate design``, ``pareto`` and ``tolerance``: certified designs from a spec, explained.

Registered by :mod:`corrugate.cli` (see :data:`COMMANDS`). Exit codes: 0 success, 1 the spec is
infeasible (the diagnosis says why) or a robust target is missed, 2 a user error (one line naming
the spec field, e.g. ``constraints.side.min``), 4 not certified within the work budget
(``--budget``; one line on stderr: the best design found so far and the proven gap); with
``--verify fe`` also verify's verdicts (:data:`corrugate.fea.verify.EXIT_CODES`): 1 a bound fails
in FE, 5 a series is not converged, 6 a bound has no FE twin (not checked).
"""

from __future__ import annotations

import math
import sys
from pathlib import Path
from typing import TYPE_CHECKING, Annotated

import typer

from corrugate.cli import options as o
from corrugate.cli.console import fmt, make_console
from corrugate.core.errors import InputError
from corrugate.core.limits import abnormal_reason, check, check_count, is_normal, require_finite
from corrugate.names import PAPER_NAMES, STIFFNESS_NAMES

if TYPE_CHECKING:
    from collections.abc import Callable

    from rich.console import Console

    from corrugate.solver import Problem, Solution
    from corrugate.solver.pareto import ParetoFront
    from corrugate.solver.robust import RobustResult
    from corrugate.workflow import DesignRequest, FeCheck, FeOptions, Run

#: ``--refine``'s cap on re-solves (:data:`corrugate.fea.refine.MAX_RESOLVES`, repeated here so
#: that ``corrugate --help`` does not import the FE; tests/cli check they agree).
MAX_RESOLVES = 4

__all__ = ["COMMANDS", "design_cmd", "pareto_cmd", "tolerance_cmd"]


def _print_solution(sol: Solution, console: Console, tightened: bool = False) -> None:
    from rich.markup import escape  # the spec's own text (its name, materials) is not markup
    from rich.table import Table

    p = sol.problem
    name = escape(p.name)
    cert = "certified" if sol.certified else "NOT certified"
    if sol.extrapolated:
        cert = "EXTRAPOLATED, not certified"
    if tightened:
        cert += " for the tightened bounds below"
    if sol.assembly is None and sol.status == "not-certified":
        console.print(
            f"[bold red]{name}: not certified[/bold red]: the search stopped before finding a "
            "design or proving that none exists."
        )
        return
    if sol.assembly is None:
        console.print(
            f"[bold red]{name}: {sol.status}[/bold red] ({cert}): no design meets every constraint."
        )
        for diag in sol.diagnosis:
            console.print(f"  - {diag.message}", markup=False)
        hint = relax_hint(sol)
        if hint:
            console.print(hint, markup=False)
        return
    assert sol.assembly is not None
    assert sol.analysis is not None
    gap = "exact (every variable on its grid)" if p.gridded else f"gap <= {sol.gap:.1e}"
    if not sol.certified and not tightened and not sol.extrapolated:
        gap = f"proven gap {_gap_text(sol.gap)}"
    head = "optimal" if sol.certified or sol.extrapolated else "best design found so far"
    console.print(
        f"[bold]{name}[/bold]: {head}, {cert}, {gap}; model {p.model}, layout {p.layout.name}"
    )
    console.print(sol.certificate, markup=False)
    t = Table(title="design", title_justify="left")
    for col in ("layer", "material", "t mm", "W mm", "n", "alpha deg"):
        t.add_column(col, justify="right")
    for i, layer in enumerate(sol.assembly.layers):
        t.add_row(
            str(i + 1),
            escape(layer.material.id),
            fmt(layer.t, 5),
            fmt(layer.W, 6),
            str(layer.n),
            fmt(layer.alpha_deg, 6),
        )
    console.print(t)
    a = sol.assembly
    console.print(
        f"extent {a.Lx:.2f} x {a.Ly:.2f} mm, folded thickness {a.thickness:.2f} mm, "
        f"mass {sol.analysis.mass.total:.4f} g"
    )
    s = Table(title="stiffness", title_justify="left")
    for col in ("eta deg", "K N/mm", "D N mm", "EI N mm^2", "EI mN m^2"):
        s.add_column(col, justify="right")
    for st in sol.analysis.stiffness:
        s.add_row(
            fmt(st.eta_deg, 5), fmt(st.K, 5), fmt(st.D, 5), fmt(st.EI, 5), f"{st.EI / 1000:.2f}"
        )
    console.print(s)
    c = Table(
        title="constraints (binding: relaxing it alone allows a better design)",
        title_justify="left",
    )
    # a name too long for its column folds over lines, never cut to an ellipsis: in an
    # 80-column terminal the case study's binding EI bound printed "constraints.flexural_rigi…"
    c.add_column("constraint", justify="right", overflow="fold")
    for col in ("value", "bound", "margin", "unit", "binding"):
        c.add_column(col, justify="right")
    for r in sol.constraints:
        op = ">=" if r.sense == "min" else "<="
        c.add_row(
            r.name,
            fmt(r.value, 5),
            f"{op} {fmt(r.bound, 5)}",
            fmt(r.margin, 3),
            r.unit,
            "yes" if r.binding else ("?" if r.binding is None else "no"),
        )
    console.print(c)
    if sol.runner_ups:
        u = Table(
            title=f"runner-ups (best for each n; {p.objective.sense}imise {p.objective.quantity.key})",
            title_justify="left",
        )
        for col in ("n", "W mm", "alpha deg", "objective"):
            u.add_column(col, justify="right")
        for ru in sol.runner_ups:
            lay = ru.layers[0]
            mark = " *" if ru.objective == sol.objective else ""
            u.add_row(
                str(ru.n),
                fmt(float(lay["W_mm"]), 6),  # type: ignore[arg-type]
                fmt(float(lay["alpha_deg"]), 6),  # type: ignore[arg-type]
                fmt(ru.objective, 6) + mark,
            )
        console.print(u)
    from rich.markup import escape  # a message's [[table]] is text, not markup

    for w in sol.warnings:
        console.print(f"[yellow]warning[/yellow] ({w['code']}): {escape(w['message'])}")
    for w in sol.notes:
        console.print(f"note ({w['code']}): {w['message']}", markup=False)


def _nothing() -> None:
    pass


def robust_lines(robust: RobustResult, problem: Problem) -> list[str]:
    """The answer's lines of a ``[robust]`` spec (:mod:`corrugate.solver.robust`): the
    probability that the design meets the spec's own bounds (the independent check's Monte Carlo
    estimate; the search's when the rounds ran out; none when no design meets the tightened
    bounds) against the target, and each bound tightened, from the spec's value to the one the
    certified design was solved for (N/mm for a deflection bound: its P/delta)."""
    met = "met" if robust.met else "NOT met"
    rounds = f"after {robust.rounds} round(s) of margin inflation"
    target = f"target {robust.target:g}, {met}"
    if robust.check is not None:
        head = f"P(spec holds) = {robust.check.p_all:.4g} ({target}) {rounds}"
    elif robust.solution.assembly is None:
        head = (
            f"no design meets the bounds tightened in round {robust.rounds} ({target}): "
            "P(spec holds) is not estimated"
        )
    elif robust.search is not None:
        head = (
            f"P(spec holds) = {robust.search.p_all:.4g} in the last round's search ({target}) "
            f"{rounds}, the most allowed"
        )
    else:  # pragma: no cover - robust_solve always searches a design it found
        head = f"P(spec holds) is not estimated ({target}) {rounds}"
    lines = [f"robust: {head}; not certified as the lightest robust design"]
    tightened = [c for c in problem.constraints if robust.factors.get(c.name, 1.0) != 1.0]
    if tightened:
        lines.append("robust: the bounds tightened from the spec's (the certificate is for these):")
    from corrugate.solver.robust import tighten

    for c in tightened:
        f = robust.factors[c.name]
        op = ">=" if c.sense == "min" else "<="
        new = tighten(c, f).bound
        unit = f" {c.unit}" if c.unit else ""
        lines.append(f"  {c.name}: {op} {fmt(c.bound, 5)} -> {fmt(new, 5)}{unit} (x{f:.4g})")
    if not tightened:
        lines.append("robust: no bound was tightened (the first round's design met the target)")
    return lines


def relax_hint(sol: Solution) -> str | None:
    """For an infeasible spec: the ``hint:`` line (:func:`corrugate.solver.diagnosis.best_hint`:
    a structural change that restores feasibility, else the smallest relative edit of one bound,
    else of a pair, else why no hint exists); None without a diagnosis."""
    return None if sol.hint is None else f"hint: {sol.hint}"


def _gap_text(gap: float) -> str:
    """A relative gap as a percentage, or ``none`` when nothing bounds it."""
    return f"{100 * gap:.3g} %" if math.isfinite(gap) else "none (no bound proven)"


def _budget_limit(budget: dict[str, object]) -> str:
    """What ran out of a spent budget (``solver.budget`` of ``design --json``): ``60 s`` or
    ``1000 boxes``."""
    if budget["stopped_by"] == "boxes":
        return f"{budget['boxes']} boxes"
    return f"{float(budget['cpu_seconds']):g} s"  # type: ignore[arg-type]


def not_certified_line(sol: Solution) -> str:
    """The one stderr line of exit code 4: what stopped the search (the budget, and what was
    used of it), the best design found so far and the proven gap."""
    budget = sol.stats.get("budget")
    if isinstance(budget, dict) and budget.get("stopped_by") is not None:
        limit = _budget_limit(budget)
        used = (
            f" (used {float(budget['used_cpu_seconds']):.3g} s of CPU time, "
            f"{budget['used_boxes']} boxes)"
        )
        head = f"not certified within the budget of {limit}{used}"
    else:
        head = "not certified: the search stopped at its iteration or box limit"
    if sol.analysis is None:
        return (
            f"corrugate: {head}: no design found so far and none proven impossible; "
            "run again with a larger --budget"
        )
    from corrugate.analysis.display import layers_text

    p = sol.problem
    return (
        f"corrugate: {head}: best design found so far {layers_text(sol.analysis)}, "
        f"{p.objective.quantity.key} {sol.objective:.6g}; proven gap {_gap_text(sol.gap)}; "
        "run again with a larger --budget"
    )


def _print_failure(sol: Solution, robust: object, console: Console) -> None:
    """With --quiet: why the exit code is 1 (infeasible, robust target missed)."""
    if sol.status == "infeasible":
        _print_solution(sol, console)
    elif robust is not None:
        console.print(f"{sol.problem.name}: the robust target is not met", markup=False)


#: ``design``'s output options: the table's but the sheet layout's (spacing, margin, tabs).
_DESIGN_OUTPUT = tuple(n for n in o.OUTPUT if n not in ("spacing", "margin", "tab_depth"))


@o.table_options(
    "spec",
    "as_json",
    "out",
    *_DESIGN_OUTPUT,
    # not given: the spec's [fabrication] machine (or the default); given, it overrides it
    defaults={"cutter": None},
)
def design_cmd(
    table: o.TableValues,
    spec: Annotated[
        Path,
        typer.Argument(
            metavar="SPEC",
            help="Spec file (TOML), or - to read it from standard input; start from "
            "`corrugate init`, every key in `corrugate spec`.",
        ),
    ],
    as_json: Annotated[bool, typer.Option("--json", help="Print one JSON object.")] = False,
    out: Annotated[
        Path | None,
        typer.Option(
            "--out",
            metavar="DIR",
            help="Folder for design.json and, for a design, every cut file.",
        ),
    ] = None,
    budget: o.SolverBudget = None,
    verify: Annotated[
        str | None,
        typer.Option(
            "--verify",
            metavar="fe",
            help="fe: check every behavioural bound of the answer by its FE twin (CalculiX; "
            "as `corrugate verify`) and add the table to the answer; exit 1 when one fails, 5 when "
            "one is not converged, 6 when one has no FE twin.",
        ),
    ] = None,
    refine: Annotated[
        bool,
        typer.Option(
            "--refine",
            help="With --verify fe: correct each model bound the FE contradicts by the measured "
            f"ratio and re-solve (at most {MAX_RESOLVES} times); the answer is the lightest "
            "design the FE verifies.",
        ),
    ] = False,
    verify_meshes: Annotated[
        str,
        typer.Option(
            "--verify-meshes",
            metavar="N,N,...",
            help="Mesh series of --verify (elements per facet).",
        ),
    ] = "2,4,8",
    verify_shifts: Annotated[
        str,
        typer.Option(
            "--verify-shifts",
            metavar="S,S,...",
            help="Coupon positions of --verify off the crease directions (fractions of the "
            "pitch); the worst counts.",
        ),
    ] = "0,0.25,0.5,0.75",
    verify_max_mesh: Annotated[
        int,
        typer.Option(
            "--verify-max-mesh",
            parser=o.ASCII_INT,
            metavar="N",
            help="With --verify fe: refine a series not yet shown asymptotic against its bound "
            "by doubling its finest mesh, up to N elements per facet (0: 16; a 16-per-facet run "
            "may take minutes and up to ~8 GB); still open there: not converged (exit 5).",
        ),
    ] = 0,
    quiet: o.Quiet = False,
) -> None:
    """The certified lightest OADLC design that meets a spec, with its explanation.

    Example: corrugate design examples/blimp_gripper.toml --out out/blimp_gripper
    (--verify fe [--refine]: its FE verification, docs/fea.md section 6)
    """
    from corrugate.cli.progress import show_progress, solve_progress
    from corrugate.workflow import Events, run

    seconds = None if budget is None else check("budget", budget, "--budget")
    fe = _fe_options(verify, refine, verify_meshes, verify_shifts, verify_max_mesh)
    request = _request(spec, out, table, seconds, fe)
    fe_quiet = quiet or (as_json and not sys.stderr.isatty())
    unit = request.problem.objective.quantity.unit
    console = None if as_json or quiet else make_console()

    def answered(answer: Run) -> None:
        """The answer, printed as soon as it is final: before its files are written."""
        sol, robust, checked = answer.solution, answer.robust, answer.fe
        failed = sol.status == "infeasible" or (robust is not None and not robust.met)
        if as_json:
            import json  # --json only

            typer.echo(json.dumps(answer.payload, indent=2))
        elif quiet:
            if failed:
                _print_failure(sol, robust, make_console(stderr=True))
        else:
            assert console is not None
            _print_solution(sol, console, tightened=robust is not None)
            if checked is not None:
                _print_fe(checked, console)
            if robust is not None:
                for line in robust_lines(robust, request.problem):
                    console.print(line, markup=False)
        sys.stdout.flush()  # shown now, through a pipe too, not when the files are written

    with solve_progress(show_progress(quiet, as_json), unit) as shown:
        events = Events(
            fe_progress=lambda: _fe_progress(fe_quiet),
            solved=_nothing if shown is None else shown.stop,
            answered=answered,
        )
        answer = run(request, events)
    sol, robust, checked = answer.solution, answer.robust, answer.fe
    stopped = sol.status == "not-certified"
    failed = sol.status == "infeasible" or (robust is not None and not robust.met)
    if console is not None:
        for path in answer.files:
            console.print(f"wrote {path}", markup=False)
    if stopped:  # exit 4 (before 1: a robust target cannot be judged on an unfinished search)
        typer.echo(not_certified_line(sol), err=True)
        raise typer.Exit(4)
    if failed:
        raise typer.Exit(1)
    if checked is not None and checked.verification.verdict != "holds":
        if quiet:
            typer.echo(f"corrugate: {checked.statement}", err=True)
        raise typer.Exit(checked.verification.exit_code)


def _request(
    spec: Path,
    out: Path | None,
    table: o.TableValues,
    budget: float | None,
    fe: FeOptions | None,
) -> DesignRequest:
    """``corrugate design``'s arguments (its output options in ``table``) read into one request
    (``budget``, CPU seconds, and ``fe`` already checked), in the command's order of checks (each
    error one line naming the option or the spec's key, exit 2): the output folder, the paper
    and the machine before the spec is read; CalculiX and the layout's FE fixtures before
    solving."""
    cutter, paper = table["cutter"], table["paper"]
    from corrugate.core.parameters import PARAMETERS
    from corrugate.solver import Problem
    from corrugate.spec.schema import load_spec_text
    from corrugate.workflow import DesignRequest, Output, made_for, output_options, resolve_machine

    if out is not None:  # too long, the root, a system folder, home, the working folder
        from corrugate.core.fileio import check_output_folder

        check_output_folder(out)  # before solving, and before out.exists() asks the OS
    if out is not None and out.exists() and not out.is_dir():
        raise InputError("--out", str(out), "a directory", reason="is a file")
    if paper.strip().lower() not in PAPER_NAMES:  # checked with or without --out; the writers
        from corrugate.export.pdf import check_paper  # (export) only for its message: not --json's

        check_paper(paper)
    given = None  # --machine, checked before the spec is read, and before solving
    if cutter is not None:
        given = resolve_machine(cutter, PARAMETERS["cutter"].flag)
    loaded, spec_text = load_spec_text(spec)
    made = made_for(
        loaded, cutter, mountain=table["mountain"], valley=table["valley"], marks=table["marks"]
    )
    parsed = made.spec
    if fe is not None:
        from corrugate.fea.ccx import find_ccx
        from corrugate.fea.verify import check_layout

        check_layout(parsed.layout.shape)  # an unknown layout name has no FE fixtures
        find_ccx()  # one clear line when CalculiX is missing, before solving
    # the machine given, else the spec's (a checked name) or the default: looked up once
    machine = given if given is not None else resolve_machine(made.cutter)
    output = None
    if out is not None:
        options = output_options(
            machine,
            table["fold_style"],
            table["cut"],
            table["gap"],
            labels=table["labels"],
            paper=paper,
            mountain=made.mountain,
            valley=made.valley,
            marks=made.marks,
        )
        output = Output(out, options)
    problem = Problem.from_spec(parsed)
    return DesignRequest(parsed, spec_text, problem, machine, budget, output, fe)


def _fe_options(
    verify: str | None, refine: bool, meshes: str, shifts: str, max_mesh: int = 0
) -> FeOptions | None:
    """``--verify``, ``--refine``, ``--verify-meshes``, ``--verify-shifts`` and
    ``--verify-max-mesh`` checked before the spec is read (one line naming the option, exit 2).
    The FE package is imported only with ``--verify`` (``design --json`` does without it)."""
    if verify is None:
        if refine:
            raise InputError("--refine", "given", "only with --verify fe", reason="needs --verify")
        if meshes != "2,4,8" or shifts != "0,0.25,0.5,0.75" or max_mesh:
            raise InputError(
                "--verify-meshes"
                if meshes != "2,4,8"
                else "--verify-shifts"
                if shifts != "0,0.25,0.5,0.75"
                else "--verify-max-mesh",
                "given",
                "only with --verify fe",
                reason="needs --verify",
            )
        return None
    if verify != "fe":
        raise InputError("--verify", repr(verify), "fe (the FE twin of every behavioural bound)")
    from corrugate.fea.verify import parse_max_mesh, parse_meshes, parse_shifts
    from corrugate.workflow import FeOptions

    try:
        m = parse_meshes(meshes)
    except InputError as exc:
        raise InputError("--verify-meshes", exc.value, exc.allowed, reason=exc.reason) from None
    try:
        sh = parse_shifts(shifts)
    except InputError as exc:
        raise InputError("--verify-shifts", exc.value, exc.allowed, reason=exc.reason) from None
    return FeOptions(m, sh, refine, parse_max_mesh(max_mesh, "--verify-max-mesh"))


def _fe_progress(quiet: bool) -> Callable[[str], None]:
    from corrugate.cli.validate import progress_lines

    return progress_lines(quiet)


def _print_fe(checked: FeCheck, console: Console) -> None:
    """The FE table of the answer's design, the loop's attempts with --refine, and both
    statements."""
    from rich.table import Table

    from corrugate.cli.verify import print_table
    from corrugate.export.record import design_label

    sol = checked.run.solution
    assert sol.assembly is not None
    r = checked.refined
    if r is not None:
        t = Table(
            title=f"--refine: {r.resolves} re-solve(s) (at most {MAX_RESOLVES}); stopped: "
            f"{r.stopped}",
            title_justify="left",
        )
        for col in ("attempt", "design", "mass g", "model bounds", "FE holds"):
            t.add_column(col, justify="left" if col in ("design", "model bounds") else "right")
        for i, a in enumerate(r.attempts):
            design = (
                "; ".join(
                    dict.fromkeys(
                        f"{x.material.id} {x.t:g} W {x.W:g} n {x.n} a {x.alpha_deg:g}"
                        for x in a.layers
                    )
                )
                or a.solution.status
            )
            bounds = ", ".join(
                f"{k.removeprefix('constraints.')} {b:.4g}" for k, b in a.bounds.items()
            )
            mark = " *" if i == r.chosen else ""
            holds = "-" if a.verification is None else ("yes" if a.verification.holds else "no")
            t.add_row(
                f"{i}{mark}",
                design,
                "-" if a.solution.mass is None else f"{a.solution.mass:.4f}",
                bounds,
                holds,
            )
        console.print(t)
        if r.chosen is None:
            console.print(
                "[red]no attempt is verified by FE[/red]: the answer is the spec's own design"
            )
    print_table(checked.verification, design_label(sol.assembly), console)
    console.print(str(checked.run.payload.get("certificate", "")), markup=False)
    console.print(checked.statement, markup=False)


def _plot(front: ParetoFront, title: str, path: Path) -> bool:
    """Write the front as a PNG (mass against stiffness); False if matplotlib is missing."""
    try:
        import matplotlib  # noqa: F401
    except ImportError:
        return False
    from corrugate.core.fileio import staged
    from corrugate.core.plotting import new_figure

    fig = new_figure((6, 4))
    ax = fig.subplots()
    s = [p.stiffness for p in front.points]
    m = [p.mass for p in front.points]
    if front.exact:
        ax.step(s, m, where="pre", color="0.6", lw=1)
    else:
        ax.plot(s, m, color="0.6", lw=1)
    ax.plot(s, m, "o", ms=3)
    ax.set_xlabel(f"{front.quantity.key} [{front.unit}]")
    ax.set_ylabel("lightest mass [g]")
    ax.set_title(title)
    ax.grid(True, alpha=0.3)
    fig.tight_layout()
    with staged() as st:
        fig.savefig(st.path(path), dpi=120, format="png")
    return True


def pareto_cmd(
    spec: Annotated[
        Path,
        typer.Argument(
            metavar="SPEC",
            help="Spec file (TOML), or - to read it from standard input; start from "
            "`corrugate init`, every key in `corrugate spec`.",
        ),
    ],
    vs: Annotated[
        str,
        typer.Option(
            "--vs",
            metavar="QUANTITY",
            help=" | ".join(STIFFNESS_NAMES),
        ),
    ] = STIFFNESS_NAMES[0],
    eta: Annotated[
        str, typer.Option(metavar=o.ANGLE, help="Direction of the stiffness (deg).")
    ] = "0",
    points: Annotated[
        int, typer.Option(parser=o.ASCII_INT, help="Points on a continuous front.")
    ] = 25,
    max_points: Annotated[
        int, typer.Option(parser=o.ASCII_INT, help="Cap on a gridded (exact) front.")
    ] = 500,
    out: Annotated[
        Path | None,
        typer.Option("--out", metavar="DIR", help="Directory for pareto.csv and pareto.png."),
    ] = None,
    budget: o.SolverBudget = None,
    quiet: o.Quiet = False,
) -> None:
    """The exact mass-versus-stiffness Pareto front of a spec (each point a certified optimum).

    Example: corrugate pareto examples/blimp_gripper.toml --vs flexural_rigidity --out out/p
    """
    from rich.progress import BarColumn, MofNCompleteColumn, Progress, TextColumn, TimeElapsedColumn

    from corrugate.core.fileio import check_output_folder, write_set
    from corrugate.core.units import parse_quantity

    if out is not None:
        check_output_folder(out)
    from corrugate.solver import Problem
    from corrugate.solver.pareto import pareto_front
    from corrugate.spec.schema import load_spec

    if vs not in STIFFNESS_NAMES:
        raise InputError(
            "--vs", repr(vs), "one of " + ", ".join(STIFFNESS_NAMES), reason="is unknown"
        )
    check_count("points", points, "--points")
    check_count("points", max_points, "--max-points")
    seconds = None if budget is None else check("budget", budget, "--budget")
    eta_deg = parse_quantity(eta, "deg", "--eta")
    reason = abnormal_reason(eta_deg)
    if reason is not None:
        raise InputError("--eta", f"{eta_deg:g} deg", "a finite angle in deg", reason=reason)
    problem = Problem.from_spec(load_spec(spec))
    console = make_console(stderr=True)
    with Progress(
        TextColumn("Pareto front"),
        BarColumn(),
        MofNCompleteColumn(),
        TimeElapsedColumn(),
        console=console,
        transient=True,
        disable=quiet,
    ) as bar:
        task = bar.add_task("solve", total=None)

        def tick(done: int, total: int | None) -> None:
            bar.update(task, completed=done, total=total)

        front = pareto_front(
            problem,
            vs,
            eta_deg,
            points=points,
            max_points=max_points,
            progress=tick,
            budget=seconds,
        )
    require_finite(
        [[p.level, p.stiffness, p.mass, *p.layers] for p in front.points], "Pareto front"
    )
    text = front.csv()
    if out is None:
        typer.echo(text, nl=False)
    else:
        if out.exists() and not out.is_dir():
            raise InputError("--out", str(out), "a directory", reason="is a file")
        write_set(out, {"pareto.csv": text}, kind="pareto")
        plotted = _plot(front, f"{problem.name}: Pareto front", out / "pareto.png")
        if not quiet:
            console.print(f"wrote {out / 'pareto.csv'}", markup=False)
            if plotted:
                console.print(f"wrote {out / 'pareto.png'}", markup=False)
            else:
                console.print(
                    "[yellow]warning[/yellow]: matplotlib is not installed (extra 'fab'); "
                    "no plot written"
                )
    kind = "exact staircase" if front.exact else f"{len(front.points)} sampled levels"
    note = " (truncated at --max-points)" if front.truncated else ""
    summary = f"{len(front.points)} points, {kind}{note}, every point certified: {front.certified}"
    failed = not front.points or not front.certified
    if not quiet or failed:  # with --quiet, only why the exit code is 1 or 4 (on stderr)
        console.print(summary)
    if front.stopped is not None and front.budget is not None:
        typer.echo(
            f"corrugate: not certified within the budget of {_budget_limit(front.budget)}: "
            "the front ends at the "
            f"{len(front.points)} point(s) found so far; run again with a larger --budget",
            err=True,
        )
        raise typer.Exit(4)
    if failed:
        raise typer.Exit(1)


def _relative(value: str, field: str) -> float:
    """'5%' or '0.05' -> 0.05."""
    text = value.strip()
    try:
        x = float(text[:-1]) / 100 if text.endswith("%") else float(text)
    except ValueError:
        raise InputError(
            field,
            repr(value),
            "a fraction such as 0.05 or a percentage such as '5%'",
            reason="cannot be read",
        ) from None
    if not 0 <= x < 1 or not is_normal(x):
        raise InputError(field, value, "0 <= tolerance < 100 %")
    return x


def tolerance_cmd(
    spec: Annotated[
        Path, typer.Argument(metavar="SPEC", help="Spec file (TOML); its optimum is analysed.")
    ],
    samples: Annotated[int, typer.Option(parser=o.ASCII_INT, help="Monte Carlo samples.")] = 10_000,
    seed: Annotated[int, typer.Option(parser=o.ASCII_INT, help="Random seed.")] = 0,
    W_tol: Annotated[
        str, typer.Option("--W-tol", metavar=o.LENGTH, help="1-sigma error of W (mm).")
    ] = "0.1 mm",
    alpha_tol: Annotated[
        str, typer.Option("--alpha-tol", metavar=o.ANGLE, help="1-sigma error of alpha (deg).")
    ] = "2 deg",
    t_tol: Annotated[
        str, typer.Option("--t-tol", metavar="FRACTION", help="1-sigma relative error of t.")
    ] = "5%",
    E_tol: Annotated[
        str, typer.Option("--E-tol", metavar="FRACTION", help="1-sigma relative error of E.")
    ] = "10%",
    as_json: Annotated[bool, typer.Option("--json", help="Print one JSON object.")] = False,
    budget: o.SolverBudget = None,
    quiet: o.Quiet = False,
) -> None:
    """Monte Carlo of the certified design of a spec over manufacturing and material tolerances:
    stiffness distribution and the probability that the spec is still met.

    Example: corrugate tolerance examples/blimp_gripper.toml --alpha-tol "2 deg" --E-tol 10%
    """
    from rich.table import Table

    from corrugate.cli.progress import show_progress, solve_progress
    from corrugate.core.units import parse_quantity
    from corrugate.solver import Problem, solve
    from corrugate.solver.tolerance import Tolerances, monte_carlo
    from corrugate.spec.schema import load_spec

    check_count("samples", samples, "--samples")
    check_count("seed", seed, "--seed")
    seconds = None if budget is None else check("budget", budget, "--budget")
    tol = Tolerances(
        W=check("W_tol", parse_quantity(W_tol, "mm", "--W-tol"), "--W-tol"),
        alpha=check("alpha_tol", parse_quantity(alpha_tol, "deg", "--alpha-tol"), "--alpha-tol"),
        t_rel=_relative(t_tol, "--t-tol"),
        E_rel=_relative(E_tol, "--E-tol"),
    )
    problem = Problem.from_spec(load_spec(spec))
    with solve_progress(show_progress(quiet, as_json), problem.objective.quantity.unit):
        sol = solve(problem, explain=False, budget=seconds)
    if sol.status == "not-certified":  # no Monte Carlo of a design that may not be the optimum
        typer.echo(not_certified_line(sol), err=True)
        raise typer.Exit(4)
    if sol.assembly is None:
        raise InputError("spec", str(spec), "a feasible spec", reason=f"is {sol.status}")
    report = monte_carlo(problem, sol.assembly, tol, samples, seed)
    payload = {"design": sol.to_dict()["design"], **report.as_dict()}
    require_finite(payload, "tolerance")
    if as_json:
        import json

        typer.echo(json.dumps(payload, indent=2))
        return
    if quiet:
        return
    from rich.markup import escape

    console = make_console()
    lay = sol.assembly.layer1
    console.print(
        f"[bold]{escape(problem.name)}[/bold]: certified design W = {lay.W:.6g} mm, n = "
        f"{lay.n}, alpha = {lay.alpha_deg:.6g} deg; {samples} samples, 1-sigma "
        f"W {tol.W:g} mm, alpha {tol.alpha:g} deg, t {100 * tol.t_rel:g} %, "
        f"E {100 * tol.E_rel:g} %"
    )
    t = Table(title="quantities", title_justify="left")
    for col in ("quantity", "unit", "nominal", "mean", "sd", "5 %", "50 %", "95 %"):
        t.add_column(col, justify="right")
    for s in report.stats:
        t.add_row(
            s.quantity.key,
            s.unit,
            *(fmt(v, 5) for v in (s.nominal, s.mean, s.sd, s.q05, s.q50, s.q95)),
        )
    console.print(t)
    c = Table(title="probability that each constraint holds", title_justify="left")
    c.add_column("constraint")
    c.add_column("P", justify="right")
    for name, p in report.probabilities:
        c.add_row(name, f"{100 * p:.1f} %")
    c.add_row("[bold]all[/bold]", f"[bold]{100 * report.p_all:.1f} %[/bold]")
    console.print(c)
    if report.p_all < ROBUST_HINT_BELOW:
        console.print(robust_hint(report.p_all), markup=False)


#: ``tolerance`` suggests a ``[robust]`` section below this probability of meeting the spec.
ROBUST_HINT_BELOW = 0.9


def robust_hint(p_all: float) -> str:
    """The hint ``tolerance`` prints when the spec holds with probability ``p_all`` < 0.9."""
    return (
        f"hint: the spec holds in only {100 * p_all:.1f} % of the samples; add a [robust] "
        "section to the spec (e.g. `[robust]` then `probability = 0.9`) and `corrugate design` "
        "inflates the margins until that probability is met (`corrugate docs spec`, section "
        "robust)"
    )


#: The commands of this module, by name (registered by :mod:`corrugate.cli`).
COMMANDS = {"design": design_cmd, "pareto": pareto_cmd, "tolerance": tolerance_cmd}
