"""The write steps of a design's files beyond its sheet plan: FOLD, GLB/STL, the assembly steps,
the report and ``design.json`` (entries of :data:`corrugate.export.writers.WRITERS`).

Each step does its work when it writes (inside the output step, after the sheet plan's files), in
the table's order: the assembly figure is drawn before the report, which shows it
(:class:`~corrugate.export.plan.Drawings`), and ``design.json`` comes last, listing every file
written before it and itself.
"""

from __future__ import annotations

from collections.abc import Sequence
from pathlib import Path

from corrugate.core.fileio import Staging
from corrugate.export.files3d import write_fold, write_mesh
from corrugate.export.record import RECORD_NAME, write_record
from corrugate.export.writers import Commit, Job, get_writer
from corrugate.fabrication.instructions import instructions_png, write_instructions

__all__ = ["assembly_steps", "fold_files", "mesh_files", "record_file", "report_file"]


def fold_files(job: Job) -> Commit:
    """``layer1.fold`` and ``layer2.fold`` (:func:`~corrugate.export.files3d.write_fold`)."""

    def commit(st: Staging, _: Sequence[Path]) -> list[Path]:
        return write_fold(*job.design(), job.out, st)

    return commit


def mesh_files(job: Job) -> Commit:
    """``assembly.glb`` and ``assembly.stl`` from one folded mesh
    (:func:`~corrugate.export.files3d.write_mesh`)."""

    def commit(st: Staging, _: Sequence[Path]) -> list[Path]:
        return write_mesh(*job.design(), job.out, st)

    return commit


def assembly_steps(job: Job) -> Commit:
    """``ASSEMBLY.md`` and ``assembly.png`` (:func:`~corrugate.fabrication.instructions.write_instructions`);
    the figure's PNG is kept in ``job.drawings`` for the report. The two are returned (and listed
    in ``design.json``) in the registry's order, the figure staged first (the set's manifest lists
    it first)."""

    def commit(st: Staging, _: Sequence[Path]) -> list[Path]:
        a, pattern = job.design()
        png = instructions_png(a, pattern)
        if job.drawings is not None:
            job.drawings.assembly_png = png
        return write_instructions(a, pattern, job.out, st, png=png)

    return commit


def report_file(job: Job) -> Commit:
    """``report.html``: the text ``job.report`` makes when it is written (nothing when there is no
    report)."""

    def commit(st: Staging, _: Sequence[Path]) -> list[Path]:
        text = None if job.report is None else job.report()
        if text is None:
            return []
        target = job.out / get_writer("report").pattern
        st.path(target).write_text(text, encoding="utf-8")
        return [target]

    return commit


def record_file(job: Job) -> Commit:
    """``design.json``: ``job.record`` with ``files``, the names of the files written before it and
    its own (:func:`~corrugate.export.record.write_record`); nothing without a record."""

    def commit(st: Staging, written: Sequence[Path]) -> list[Path]:
        if job.record is None:
            return []
        record = {**job.record, "files": [p.name for p in written] + [RECORD_NAME]}
        return [write_record(record, job.out, st)]

    return commit
