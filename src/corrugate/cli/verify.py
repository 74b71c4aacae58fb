"""``corrugate verify DIR``: the FE twin of every behavioural constraint of a design.

Registered by :mod:`corrugate.cli` (see :data:`COMMANDS`). Reads ``DIR/design.json`` (written by
``corrugate design SPEC --out DIR``), runs each constraint's FE twin on a mesh series and
extrapolates it (:mod:`corrugate.fea.verify`), prints the table, and writes ``DIR/verify.json``
as the folder's set of kind ``verify``. The FE subpackage is imported only when the command
runs. Exit codes: 0 every constraint holds in FE, 1 one does not (or has no FE twin yet), 2 bad
input (a missing or malformed design.json, a folder that cannot be written, no ccx).

Example::

    corrugate design examples/blimp_gripper.toml --out out/gripper
    corrugate verify out/gripper --mesh 2,4,8
"""

from __future__ import annotations

import json
import os
import sys
from pathlib import Path
from typing import TYPE_CHECKING, Annotated, Any

import typer

from corrugate.cli import options as o
from corrugate.cli.console import make_console
from corrugate.core.errors import InputError

if TYPE_CHECKING:
    from rich.console import Console

    from corrugate.fea.verify import Verification

__all__ = [
    "COMMANDS",
    "VERIFY_KIND",
    "VERIFY_NAME",
    "check_layout",
    "parse_max_mesh",
    "parse_meshes",
    "parse_shifts",
    "print_table",
    "read_design",
    "verify_cmd",
]

Opt = typer.Option

#: The file verify writes into the design's folder, and its set kind in the folder's manifest.
VERIFY_NAME = "verify.json"
VERIFY_KIND = "verify"


def parse_meshes(text: str) -> tuple[int, ...]:
    """``--mesh 2,4,8``: even element counts >= 2, increasing, without repeats."""
    from corrugate.fea.assembly import AssemblyMesh

    try:
        values = tuple(int(v) for v in text.split(","))
    except ValueError:
        raise InputError(
            "mesh",
            repr(text),
            "even integers separated by commas, e.g. 2,4,8",
            reason="cannot be read",
        ) from None
    for v in values:
        AssemblyMesh(v)  # even, >= 2, within the limits
    if not values or list(values) != sorted(set(values)):
        raise InputError("mesh", repr(text), "increasing element counts, e.g. 2,4,8")
    return values


def parse_max_mesh(n: int, name: str = "--max-mesh") -> int:
    """``--max-mesh N``: the finest mesh a series may be extended to (elements per facet); 0 is
    the default cap (:data:`corrugate.fea.verify.DEFAULT_MAX_MESH`)."""
    from corrugate.fea.verify import DEFAULT_MAX_MESH

    if n < 0:
        raise InputError(name, str(n), "0 (the default, 16) or elements per facet >= 1")
    return n or DEFAULT_MAX_MESH


def parse_shifts(text: str) -> tuple[float, ...]:
    """``--shifts 0,0.25,0.5,0.75``: coupon positions, fractions of each layer's pitch in [0, 1),
    increasing, without repeats."""
    from corrugate.fea.shells import check_shift

    try:
        values = tuple(float(v) for v in text.split(","))
    except ValueError:
        raise InputError(
            "shifts",
            repr(text),
            "fractions of the pitch separated by commas, e.g. 0,0.25,0.5,0.75",
            reason="cannot be read",
        ) from None
    for v in values:
        try:
            check_shift(v)
        except InputError as exc:
            raise InputError("shifts", repr(text), exc.allowed) from None
    if not values or list(values) != sorted(set(values)):
        raise InputError("shifts", repr(text), "increasing fractions, e.g. 0,0.25,0.5,0.75")
    return values


def read_design(folder: Path) -> tuple[Any, list[dict[str, Any]], str]:
    """The assembly, the constraints and the joint of ``folder/design.json``; an InputError
    naming the file when it is missing, not JSON, or not a design record."""
    from corrugate.export.record import RECORD_NAME, read_record

    if not folder.is_dir():
        raise InputError(
            "DIR",
            str(folder),
            "a folder written by `corrugate design --out`",
            reason="is not a folder",
        )
    file = folder / RECORD_NAME
    record = read_record(file)  # one line naming the file when it is missing or not JSON
    data = json.loads(file.read_text(encoding="utf-8"))
    if data.get("design", {}) is None:
        raise InputError(
            "DIR",
            str(folder),
            "the folder of a design",
            reason=f"holds no design (its design.json: status {data.get('status')})",
        )
    constraints = data.get("constraints")
    if not isinstance(constraints, list) or not all(isinstance(c, dict) for c in constraints):
        raise InputError(
            f"{file}: constraints",
            type(constraints).__name__,
            "a list of constraint objects",
            reason="is malformed",
        )
    joint = data.get("joint", "none")
    if not isinstance(joint, str):
        raise InputError(
            f"{file}: joint", repr(joint), "a name such as none", reason="is malformed"
        )
    if record.shape is not None:  # a missing shape: record.assembly() names it
        check_layout(record.shape)
    # every layout: a circle's and a polygon's twins are the outline fixtures (docs/fea.md 2.8)
    return record.assembly(any_layout=True), constraints, joint


def check_layout(name: str) -> None:
    """Refuse a layout the FE has no fixtures for, naming what is missing. Every layout has
    them now (a circle: the wheel fixture; a polygon: the rectangle's fixtures cut to it;
    docs/fea.md 2.8), so only an unknown name is refused."""
    from corrugate.names import LAYOUT_SHAPES

    if name not in LAYOUT_SHAPES:
        raise InputError("layout", name, " or ".join(LAYOUT_SHAPES), reason="has no FE fixtures")


def _writable(folder: Path) -> bool:
    """Whether verify.json can be written into ``folder`` (checked before any FE run)."""
    return os.access(folder, os.W_OK | os.X_OK)


def _fmt(v: float | None) -> str:
    return "-" if v is None else f"{v:.5g}"


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
            "yes" if r.holds else "[red]NO[/red]",
        )
    console.print(t)
    if not v.rows:
        console.print("no behavioural constraint: nothing for the FE to check")
    console.print(
        "every constraint holds in FE" if v.holds else "[red]not every constraint holds in FE[/red]"
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
        Path | None, Opt(metavar="DIR", help="Parent folder of the ccx work folders.")
    ] = None,
    timeout: Annotated[float, Opt(help="Time-out of one ccx run (s).")] = 900.0,
    max_mesh: Annotated[
        int,
        Opt(
            "--max-mesh",
            metavar="N",
            help="Extend a series whose verdict could still flip (estimate within its own "
            "Richardson correction of the bound) by doubling its finest mesh, up to N elements "
            "per facet (0: 16; a 16-per-facet run may take minutes and up to ~8 GB).",
        ),
    ] = 0,
    as_json: Annotated[
        bool, Opt("--json", help='Print {"holds", "constraints": [...]} as JSON.')
    ] = False,
    quiet: o.Quiet = False,
) -> None:
    """Check every behavioural constraint of a design by its FE twin, on a mesh series.

    Each stiffness, load-case and buckling bound of DIR/design.json runs in the FE fixture of
    its test (the runs of `corrugate validate`), at each mesh, Richardson-extrapolated; off the
    crease directions at each coupon position of --shifts, the worst counting; writes
    DIR/verify.json. Exit 0 when every constraint holds in FE, 1 when one does not or has no FE
    twin yet, 2 for bad input. Every layout: a circle's K runs in the wheel fixture (a ground
    patch against the hub), a polygon's constraints along its creases in the rectangle's
    fixtures on its cut outline (`corrugate docs fea`, 2.8); a row says how its test differs.

    Example: corrugate verify out/gripper --mesh 2,4,8
    """
    from corrugate.core.fileio import write_set
    from corrugate.fea.ccx import find_ccx
    from corrugate.fea.series import check_sweep_options
    from corrugate.fea.verify import verify_design

    meshes = parse_meshes(mesh)
    positions = parse_shifts(shifts)
    cap = parse_max_mesh(max_mesh)
    check_sweep_options(None, timeout, workdir)
    assembly, constraints, joint = read_design(folder)
    if not _writable(folder):
        raise InputError(
            "DIR", str(folder), "a folder verify.json can be written to", reason="is not writable"
        )
    find_ccx()  # fail early, with one clear line, when CalculiX is missing
    from corrugate.cli.validate import design_label, progress_lines

    progress = progress_lines(quiet or (as_json and not sys.stderr.isatty()))
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
    )
    data = {"design": design_label(assembly), **result.as_json()}
    text = json.dumps(data, indent=2, allow_nan=False)
    write_set(folder, {VERIFY_NAME: text + "\n"}, field="DIR", kind=VERIFY_KIND)
    if as_json:
        typer.echo(json.dumps(result.as_json(), indent=2, allow_nan=False))
    elif not quiet:
        console = make_console()
        print_table(result, design_label(assembly), console)
        console.print(f"wrote {folder / VERIFY_NAME}")
    if not result.holds:
        if quiet:
            failing = [r.name for r in result.rows if not r.holds]
            make_console(stderr=True).print("does not hold in FE: " + ", ".join(failing))
        raise typer.Exit(1)


#: The commands of this module, by name (registered by :mod:`corrugate.cli`).
COMMANDS = {"verify": verify_cmd}
