"""One design request, read once at its boundary: the command line (``corrugate design``,
:mod:`corrugate.cli.design`), the web app (``POST /api/design`` and its job,
:mod:`corrugate.web.app`) and the notebook (:func:`corrugate.design`) each turn what the user gave
into a :class:`DesignRequest`, and :func:`corrugate.workflow.steps.run` runs it (docs/architecture.md,
``workflow``).

A request holds typed values only: the spec made for its machine and its solver
:class:`~corrugate.solver.problem.Problem`, the machine as its profile
(:class:`~corrugate.export.machines.Machine`, resolved once from its name), the solver's CPU
budget (s), the output folder and options (lengths in mm), the FE verification's options and how
the boundary names the errors the run may raise (:class:`Names`).
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from pathlib import Path
from typing import TYPE_CHECKING

from corrugate.core.errors import InputError

if TYPE_CHECKING:
    from corrugate.export.machines import Machine
    from corrugate.export.plan import OutputOptions
    from corrugate.solver.problem import Problem
    from corrugate.spec.schema import Spec

__all__ = [
    "DesignRequest",
    "FeOptions",
    "Names",
    "Output",
    "resolve_machine",
]


@dataclass(frozen=True)
class FeOptions:
    """``design --verify fe``'s options, checked (docs/fea.md section 6): the mesh series
    ``meshes`` (elements per facet), the coupon ``shifts`` (fractions of the pitch), whether to
    ``refine`` (the correction loop of :mod:`corrugate.fea.refine`) and the finest mesh a series
    may be extended to (``max_mesh``, elements per facet)."""

    meshes: tuple[int, ...]
    shifts: tuple[float, ...]
    refine: bool
    max_mesh: int = 16


@dataclass(frozen=True)
class Names:
    """What a boundary calls the options whose errors a run raises (None: the library's own
    name, the error as raised): ``machine``, the field a part too large for the machine is
    blamed on (the web's ``cutter``); ``cut`` and ``gap``, the fields of a perforation the fold
    lines cannot take."""

    machine: str | None = None
    cut: str | None = None
    gap: str | None = None


@dataclass(frozen=True)
class Output:
    """Where a design's files go (``folder``, created if missing), how they are drawn
    (:class:`~corrugate.export.plan.OutputOptions`, lengths in mm) and whether an infeasible spec
    leaves its ``design.json`` there (``record_infeasible``; the web app keeps no result for
    one)."""

    folder: Path
    options: OutputOptions
    record_infeasible: bool = True


@dataclass(frozen=True)
class DesignRequest:
    """A design request, read: the ``spec`` (made for its machine,
    :func:`corrugate.workflow.files.made_for`) and its ``text`` as the user wrote it (shown in
    the report), its solver ``problem``, the ``machine`` its files are for, the solver's
    ``budget`` (CPU seconds; None: the default 60 s), the ``output`` folder and options (None:
    no files), the FE verification (``fe``; None: none), ``strict_json`` (the answer's
    non-finite numbers as null, as the web API's JSON has no NaN) and the boundary's ``names``
    of the options a run's errors name."""

    spec: Spec
    text: str
    problem: Problem
    machine: Machine
    budget: float | None = None
    output: Output | None = None
    fe: FeOptions | None = None
    strict_json: bool = False
    names: Names = field(default_factory=Names)

    def __post_init__(self) -> None:
        """Refuse, before the search, an FE verification the FE cannot make: the connector band
        with compliant creases (its walls are meshed on the layers' rigid-crease edge nodes;
        docs/calibration.md 10)."""
        p = self.problem
        soft = [c.material.id for c in p.candidates if c.material.crease_stiffness < math.inf]
        if self.fe is not None and p.joint != "none" and soft:
            raise InputError(
                "joint",
                p.joint,
                "joint = 'none' with --verify fe, or rigid creases (the FE meshes the connector "
                "band with rigid creases only; `corrugate docs calibration`, section 10)",
                reason=f"cannot be verified in FE with the compliant creases of {soft[0]}",
            )


def resolve_machine(name: str, field_name: str | None = None) -> Machine:
    """The profile of the machine ``name`` (:func:`corrugate.export.machines.get_machine`), its
    error naming ``field_name`` (the boundary's name of the option: ``--machine``, ``cutter``)
    when given."""
    from corrugate.export.machines import get_machine

    try:
        return get_machine(name)
    except InputError as exc:
        if field_name is None:
            raise
        raise exc.renamed(field_name) from None
