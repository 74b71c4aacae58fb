"""The writers registry: every kind of file a design's output folder holds, in one table.

One :class:`Writer` per file pattern (:data:`WRITERS`, in the order the files are written): its
``name``, its file-name ``pattern`` (``cut-{sheet}.dxf``; a field in braces stands for one or more
characters other than ``/``: ``{sheet}`` the sheet number from 1, ``{layer}`` the layer 1 or 2,
``{paper}`` ``a4`` or ``letter``), its media type, the extra it needs (``fab``, see
:mod:`corrugate.core.extras`; None: the core dependencies only), what it is, its place in the web
page's list of downloads (``order``, ascending) and its ``write`` step. The table is used by the
output folder (:func:`corrugate.export.files.write_files` and
:func:`corrugate.workflow.write_design_files` write through :func:`write_job`), the web app's
result store (each file's media type, :func:`writer_for`) and the page (``GET /api/formats``
lists the table; the page orders its download buttons by it). docs/fabrication.md describes each
file.

A step is named as ``module:function`` and imported when it runs, so this module imports no
writer (the web store and the API read the table without them). A step takes the :class:`Job`,
checks and builds what it can before anything is written, and returns a :data:`Commit` that writes
its files into the output step's :class:`~corrugate.core.fileio.Staging` and returns their paths.
Entries written by one step (GLB and STL from one mesh; ``ASSEMBLY.md`` and its figure) follow
each other in the table and share their step, which runs once.
"""

from __future__ import annotations

import contextlib
import importlib
import re
from collections.abc import Callable, Iterable, Mapping, Sequence
from dataclasses import dataclass
from functools import cache
from pathlib import Path
from typing import TYPE_CHECKING, Any, cast

from corrugate.core.fileio import Staging, staged

if TYPE_CHECKING:
    from matplotlib.figure import Figure

    from corrugate.export.machines import Machine
    from corrugate.export.operations import FoldOperations
    from corrugate.export.plan import Drawings
    from corrugate.fabrication.linestyle import LineStyle
    from corrugate.fabrication.model import Pattern
    from corrugate.fabrication.sheets import SheetPlan
    from corrugate.geometry.layer import Assembly

__all__ = [
    "WRITERS",
    "Commit",
    "Job",
    "Step",
    "Writer",
    "get_writer",
    "write_job",
    "writer_for",
]

#: What a prepared step does: writes its files into the staging (``written``: the paths the
#: steps before it wrote) and returns their paths, in order.
Commit = Callable[[Staging, Sequence[Path]], list[Path]]
#: A write step: checks and builds what it writes from the job, returns what writes it.
Step = Callable[["Job"], Commit]


@dataclass(frozen=True, slots=True)
class Job:
    """Everything the steps write from, into the folder ``out``.

    The sheet plan's files need ``plan`` (mm), the fold-line ``style`` (fold map and PDF), the
    cut files' fold ``operations`` (None: the machine's default), the ``machine`` profile,
    ``labels`` (``None``: on the fold map and the PDF, not in the cut files; ``True``: everywhere;
    ``False``: nowhere), ``marks`` (assembly marks on the fold map), ``paper`` (``mat``, ``a4`` or
    ``letter``, checked), ``pdf_name`` (None: the registry's ``pattern.pdf``) and ``sheet_figures`` (the sheets' figures for the PDF, drawn
    already; None: drawn by the step). A design's files also need its ``assembly`` and its
    ``pattern``; ``drawings`` collects the figures drawn (:class:`~corrugate.export.plan.Drawings`,
    for the report), ``report`` makes the text of ``report.html`` when it is written (None, or
    None returned: no report) and ``record`` is the content of ``design.json`` (without ``files``,
    which the step adds).
    """

    out: Path
    plan: SheetPlan
    style: LineStyle
    machine: Machine
    operations: FoldOperations | None = None
    labels: bool | None = None
    marks: bool = True
    paper: str = "mat"
    pdf_name: str | None = None
    sheet_figures: Sequence[Figure] | None = None
    assembly: Assembly | None = None
    pattern: Pattern | None = None
    drawings: Drawings | None = None
    report: Callable[[], str | None] | None = None
    record: Mapping[str, Any] | None = None

    def design(self) -> tuple[Assembly, Pattern]:
        """The assembly and its pattern; a ``ValueError`` for a job of a sheet plan alone."""
        if self.assembly is None or self.pattern is None:
            raise ValueError("this output needs the design's assembly and pattern")
        return self.assembly, self.pattern


#: A field of a pattern: ``{sheet}``.
_FIELD = re.compile(r"\{([a-z]+)\}")


@dataclass(frozen=True, slots=True)
class Writer:
    """One kind of output file (see the module docstring).

    ``format`` is the group :func:`corrugate.export.files.write_files` selects it by (``svg``,
    ``cut``, ``pdf``: the files of a sheet plan alone), None for the files that need the design;
    ``write`` the step that writes it, as ``module:function``.
    """

    name: str
    pattern: str
    media_type: str
    extra: str | None
    description: str
    order: int
    format: str | None
    write: str

    @property
    def fields(self) -> tuple[str, ...]:
        """The fields of the pattern, in order (``('sheet',)``)."""
        return tuple(_FIELD.findall(self.pattern))

    def file(self, **values: object) -> str:
        """The file name of the pattern with its fields filled in (``file(sheet=2)``)."""
        return self.pattern.format(**values)

    def matches(self, name: str) -> bool:
        """Whether the file name ``name`` is one of this pattern's."""
        return _regex(self.pattern).fullmatch(name) is not None

    def step(self) -> Step:
        """The write step, imported."""
        module, _, function = self.write.partition(":")
        return cast("Step", getattr(importlib.import_module(module), function))


@cache
def _regex(pattern: str) -> re.Pattern[str]:
    parts = _FIELD.split(pattern)  # text, field, text, field, ..., text
    return re.compile("[^/]+".join(re.escape(text) for text in parts[::2]))


_FILES = "corrugate.export.files"
_DESIGN = "corrugate.export.design_files"

#: Every output file, in the order they are written.
WRITERS: tuple[Writer, ...] = (
    Writer(
        "fold-map",
        "sheet-{sheet}.svg",
        "image/svg+xml",
        None,
        "the fold map of the sheet, for people and Origami Simulator (not for the cutter)",
        1,
        "svg",
        f"{_FILES}:fold_maps",
    ),
    Writer(
        "cut-svg",
        "cut-{sheet}.svg",
        "image/svg+xml",
        "fab",
        "the machine's cut-ready file of the sheet, SVG (a Cricut, a laser)",
        2,
        "cut",
        f"{_FILES}:cut_svgs",
    ),
    Writer(
        "cut-dxf",
        "cut-{sheet}.dxf",
        "image/vnd.dxf",
        "fab",
        "the machine's cut-ready file of the sheet, DXF (a Silhouette, a laser)",
        3,
        "cut",
        f"{_FILES}:cut_dxfs",
    ),
    Writer(
        "pattern-pdf",
        "pattern.pdf",
        "application/pdf",
        "fab",
        "every sheet at 1:1, one page each, with a 10 mm check square",
        4,
        "pdf",
        f"{_FILES}:pattern_pdf",
    ),
    Writer(
        "pattern-tiles",
        "pattern-{paper}.pdf",
        "application/pdf",
        "fab",
        "every sheet at 1:1 on A4 or Letter pages to tape together (with --paper a4 or letter)",
        5,
        "pdf",
        f"{_FILES}:pattern_tiles",
    ),
    Writer(
        "fold",
        "layer{layer}.fold",
        "application/json",
        None,
        "FOLD 1.2 of the layer, with its folded frame (Origami Simulator)",
        6,
        None,
        f"{_DESIGN}:fold_files",
    ),
    Writer(
        "glb",
        "assembly.glb",
        "model/gltf-binary",
        None,
        "the folded assembly, one coloured mesh per layer and one for the band (mm)",
        7,
        None,
        f"{_DESIGN}:mesh_files",
    ),
    Writer(
        "stl",
        "assembly.stl",
        "model/stl",
        None,
        "the folded assembly, every triangle in one solid (mm)",
        8,
        None,
        f"{_DESIGN}:mesh_files",
    ),
    Writer(
        "steps",
        "ASSEMBLY.md",
        "text/markdown; charset=utf-8",
        "fab",
        "the numbered assembly steps",
        10,
        None,
        f"{_DESIGN}:assembly_steps",
    ),
    Writer(
        "steps-figure",
        "assembly.png",
        "image/png",
        "fab",
        "the figure of the assembly steps",
        11,
        None,
        f"{_DESIGN}:assembly_steps",
    ),
    Writer(
        "report",
        "report.html",
        "text/html; charset=utf-8",
        "fab",
        "the design report, one self-contained page (a design from a spec)",
        9,
        None,
        f"{_DESIGN}:report_file",
    ),
    Writer(
        "record",
        "design.json",
        "application/json",
        None,
        "the design's record: analysis, cut parts, sheets, machine and the files written",
        12,
        None,
        f"{_DESIGN}:record_file",
    ),
)

_BY_NAME: dict[str, Writer] = {w.name: w for w in WRITERS}


def get_writer(name: str) -> Writer:
    """The entry called ``name`` (a ``KeyError`` for another name: the table is the code's own)."""
    return _BY_NAME[name]


def writer_for(file_name: str) -> Writer | None:
    """The entry whose pattern the file name ``file_name`` is one of, or None."""
    return next((w for w in WRITERS if w.matches(file_name)), None)


def write_job(
    job: Job, writers: Iterable[Writer] = WRITERS, staging: Staging | None = None
) -> list[Path]:
    """Write the files of ``writers`` from ``job`` into ``job.out`` (created if missing), in the
    table's order; returns the paths written, in order.

    Every step is prepared first (options checked, documents built), then each writes its files.
    With ``staging`` they join that output step (committed with it); otherwise they are written
    all or nothing (:func:`corrugate.core.fileio.staged`).
    """
    wanted = set(writers)
    steps: dict[str, Writer] = {}  # each step once (entries of one step share it), in table order
    for w in WRITERS:
        if w in wanted:
            steps.setdefault(w.write, w)
    commits = [w.step()(job) for w in steps.values()]
    job.out.mkdir(parents=True, exist_ok=True)
    written: list[Path] = []
    with contextlib.nullcontext(staging) if staging is not None else staged() as st:
        for commit in commits:
            written += commit(st, tuple(written))
    return written
