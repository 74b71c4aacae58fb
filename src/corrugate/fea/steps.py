"""The analysis step of a deck: what CalculiX computes for a fixture (docs/fea.md section 2).

A fixture (:mod:`corrugate.fea.fixtures`) holds its supports and names the node sets that move
the load (each a :class:`Drive`: a set, the degree of freedom and the direction it is driven in);
the step decides how they are driven:

* :class:`Static`: a linear static step; every drive is a prescribed displacement of delta (mm)
  in its direction, and the reactions (``RF``) of the load sets are printed, from which the
  fixture reads its stiffness (force / delta);
* :class:`LinearBuckling`: a ``*BUCKLE`` step (linear eigenvalue buckling about the unloaded
  state). Every driven node is tied (``*EQUATION``) to one reference node in its driven degree of
  freedom, so the drives move together as the rigid load line or platen they model, and that node
  is loaded by 1 N in the drive's direction: ccx's buckling factors (the ``.dat`` file's
  ``BUCKLING FACTOR`` table, :func:`corrugate.fea.ccx.parse_buckling`) are then the loads (N)
  at which the fixture's load buckles the part, lowest first. ``modes`` factors are asked for at
  a relative ``accuracy`` (ccx's default is 1e-2). The load is a dead load: the drives are free
  to move in a mode (a weight on the part), so the first load is at or below that of a
  ``*BUCKLE`` step whose drives stay prescribed (a testing machine's head held in the mode);
  the two agree where the first mode leaves the drives still (tests/fea/test_buckling_step.py:
  the chassis example in three-point, 1.581 N both ways; a wheel's patch, 11.97 against 14.87 N).

* :class:`Nonlinear`: a geometrically nonlinear ``*STATIC`` step (``NLGEOM``), the drives tied
  to a reference node as for :class:`LinearBuckling` and that node loaded by a force ramped
  linearly from 0 to ``load`` (N) over the step's time 0-1, in increments of ``increment`` of it
  (ccx cuts them when an increment does not converge, down to ``min_increment``); the reference
  node's displacement (and that of the ``watch`` nodes) is printed to the ``.dat`` file at every
  increment, so the load-deflection curve is (time x ``load``, the reference node's travel).
  :mod:`corrugate.fea.nonlinear` runs it on a mesh perturbed by the first buckling mode.

Any fixture can be run with any step: a deck is mesh + fixture + step.
"""

from __future__ import annotations

from dataclasses import dataclass

__all__ = ["STATIC", "AnyStep", "Drive", "LinearBuckling", "Nonlinear", "Static", "Step"]


@dataclass(frozen=True, slots=True)
class Drive:
    """A node set ``nset`` (its ``nodes``) that moves the load: degree of freedom ``dof`` (1-3:
    x, y, z, in the nodes' own axes when a ``*TRANSFORM`` applies) driven by ``sign`` x delta
    (``sign`` -1: towards the part, e.g. a platen pushed along -y)."""

    nset: str
    dof: int
    nodes: tuple[int, ...]
    sign: float = -1.0


#: A boundary line, or a drive that the step writes its own way.
BoundaryItem = str | Drive


def _fortran(x: float) -> str:
    """``x`` as a Fortran-style real with the shortest mantissa: 1e-6 -> ``1.e-6``."""
    mantissa, exponent = f"{x:.6e}".split("e")
    return f"{mantissa.rstrip('0')}e{int(exponent)}"


@dataclass(frozen=True, slots=True)
class Static:
    """A linear static step: drives are prescribed displacements of delta (module docstring)."""

    name: str = "static"

    def describe(self, label: str, loading: str) -> str:
        """What a progress line calls the fixture under this step: its own ``label``."""
        return label

    @property
    def ties_parts(self) -> bool:
        """Whether the step couples the parts of a deck (then they cannot be solved apart)."""
        return False

    def lines(
        self,
        boundary: list[BoundaryItem],
        delta: float,
        reactions: list[str],
        displacements: list[str],
        *,
        stresses: bool = False,
        global_axes: bool = False,
    ) -> list[str]:
        """The step cards: every drive moved by its sign x ``delta`` (mm), the reactions of the
        sets ``reactions`` (``GLOBAL=YES`` with ``global_axes``: in global axes where a
        transform applies) and the displacements of ``displacements`` printed to the ``.dat``
        file, and with ``stresses`` the nodal stresses to the ``.frd`` file."""
        bc = [
            b if isinstance(b, str) else f"{b.nset},{b.dof},{b.dof},{b.sign * delta:.12g}"
            for b in boundary
        ]
        out = ["*STEP", "*STATIC", "*BOUNDARY", *bc]
        glob = ",GLOBAL=YES" if global_axes else ""
        for name in reactions:
            out += [f"*NODE PRINT,NSET={name}{glob}", "RF"]
        for name in displacements:
            out += [f"*NODE PRINT,NSET={name}", "U"]
        if stresses:
            out += ["*EL FILE", "S"]
        out.append("*END STEP")
        return out


@dataclass(frozen=True, slots=True)
class LinearBuckling:
    """A ``*BUCKLE`` step: ``modes`` buckling factors at relative ``accuracy``, the drives tied
    to a reference node loaded by 1 N, so each factor is a load in N (module docstring)."""

    modes: int = 3
    accuracy: float = 1e-6
    name: str = "buckle"

    def describe(self, label: str, loading: str) -> str:
        """What a progress line calls the fixture under this step: buckling under its
        ``loading``."""
        return f"buckling in {loading}"

    @property
    def ties_parts(self) -> bool:
        """The reference node ties the drives of every part: they are solved together."""
        return True

    def lines(
        self,
        boundary: list[BoundaryItem],
        reference: int,
        where: tuple[float, float, float],
    ) -> list[str]:
        """The reference node ``reference`` (at ``where``, mm; it carries no element), the
        equations that tie every driven node to it, and the step cards: the supports of
        ``boundary`` and 1 N on the reference node in the drives' direction."""
        out, dof, load = _tie(boundary, reference, where)
        out += ["*STEP", "*BUCKLE", f"{self.modes},{_fortran(self.accuracy)}", "*BOUNDARY"]
        out += [b for b in boundary if isinstance(b, str)]
        out += ["*CLOAD", f"{reference},{dof},{load}", "*END STEP"]
        return out


def _tie(
    boundary: list[BoundaryItem], reference: int, where: tuple[float, float, float]
) -> tuple[list[str], int, str]:
    """The reference node (at ``where``, mm) and the equations that tie every driven node of
    ``boundary`` to it; its driven degree of freedom and the sign of the load on it ("-1." or
    "1.": towards the part)."""
    drives = [b for b in boundary if isinstance(b, Drive)]
    if not drives:
        raise ValueError("a step with a reference node needs a fixture that drives a load")
    dof, sign = drives[0].dof, drives[0].sign
    out = ["*NODE", f"{reference},{where[0]:.10g},{where[1]:.10g},{where[2]:.10g}"]
    out.append("*EQUATION")
    for d in drives:  # u_dof(node) = u_dof(reference)
        for node in d.nodes:
            out += ["2", f"{node},{d.dof},1.,{reference},{dof},-1."]
    return out, dof, "-1." if sign < 0 else "1."


@dataclass(frozen=True, slots=True)
class Nonlinear:
    """A geometrically nonlinear static step (``*STEP,NLGEOM`` and ``*STATIC``): the drives tied
    to a reference node (as :class:`LinearBuckling`) loaded by a force ramped from 0 to ``load``
    (N); increments of ``increment`` of the ramp (also the largest allowed), cut by ccx down to
    ``min_increment`` where one does not converge; ``watch``: shell nodes whose displacement is
    printed at every increment beside the reference node's (module docstring)."""

    load: float
    increment: float = 0.05
    min_increment: float = 1e-3
    watch: tuple[int, ...] = ()
    name: str = "nonlinear"

    #: The node set whose displacements the step prints: the reference node and ``watch``.
    PRINTED = "NLPRINT"

    def describe(self, label: str, loading: str) -> str:
        """What a progress line calls the fixture under this step."""
        return f"nonlinear ramp in {loading}"

    @property
    def ties_parts(self) -> bool:
        """The reference node ties the drives of every part: they are solved together."""
        return True

    def lines(
        self,
        boundary: list[BoundaryItem],
        reference: int,
        where: tuple[float, float, float],
    ) -> list[str]:
        """The reference node, its equations and the step cards: the supports of ``boundary``,
        ``load`` N on the reference node in the drives' direction (ramped over the step), the
        displacements of the reference node and ``watch`` printed at every increment."""
        out, dof, sign = _tie(boundary, reference, where)
        inc = _fortran(self.increment)
        out += [f"*NSET,NSET={self.PRINTED}", ",".join(map(str, (reference, *self.watch)))]
        out += [
            "*STEP,NLGEOM,INC=10000",
            "*STATIC",
            f"{inc},1.,{_fortran(self.min_increment)},{inc}",
        ]
        out += ["*BOUNDARY", *(b for b in boundary if isinstance(b, str))]
        force = float(sign) * abs(self.load)
        out += ["*CLOAD", f"{reference},{dof},{force:.10g}"]
        out += [f"*NODE PRINT,NSET={self.PRINTED}", "U", "*END STEP"]
        return out


#: The static step every fixture runs unless told otherwise.
STATIC = Static()

#: The steps every fixture runs (:func:`corrugate.fea.assembly.solve_assembly`,
#: :func:`corrugate.fea.outline.solve_outline`).
Step = Static | LinearBuckling

#: Any step of an assembly deck (:func:`corrugate.fea.assembly.assembly_deck`), the nonlinear
#: ramp's included (run by :func:`corrugate.fea.nonlinear.ramp`).
AnyStep = Static | LinearBuckling | Nonlinear
