"""The panel in a rigid frame: the FE counterpart of the paper's cos^2 rule for K(eta).

The rule K(eta) = K_y cos^2(eta) + K_x sin^2(eta) (docs/theory.md 3.3; eta from layer 1's creases, the
y axis) is the stiffness of two orthogonal springs whose common end moves along eta. On the panel
that is a rigid frame of four frictionless platens, one on each edge: the platen pair across y
moves by delta cos(eta), the pair across x by delta sin(eta), and the force along eta is
F = F_y cos(eta) + F_x sin(eta). The structure is linear, so two FE runs of the ``frame`` fixture
(:mod:`corrugate.fea.fixtures.frame`; one pair moving, the other held) give the 2 x 2 platen stiffness

    [F_x, F_y] = [[K_xx, K_xy], [K_yx, K_yy]] [d_x, d_y]

(K_xy = K_yx by reciprocity, which :class:`FrameStiffness` reports as a check), and then

    K_frame(eta) = K_yy cos^2 + K_xx sin^2 + (K_xy + K_yx) sin cos        (N/mm)

for every eta. The rule neglects K_xy and uses the free-sided K(0), K(90): this measures both.
Square and rectangular layouts (the layout's own edges).
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from pathlib import Path
from typing import TYPE_CHECKING

from corrugate.fea.assembly import AssemblyMesh, solve_assembly
from corrugate.geometry.layer import Assembly

if TYPE_CHECKING:
    from corrugate.fea.fixtures import Fixture

__all__ = ["FrameStiffness", "solve_frame"]


@dataclass(frozen=True, slots=True)
class FrameStiffness:
    """Platen stiffness (N/mm) of the panel in a rigid frame: ``Kxx`` (x pair moving, y pair
    held), ``Kyy``, and the coupling measured both ways, ``Kxy`` (force on the x pair per
    displacement of the y pair) and ``Kyx``."""

    Kxx: float
    Kyy: float
    Kxy: float
    Kyx: float

    def K(self, eta_deg: float) -> float:
        """Stiffness along eta (deg from layer 1's creases) of the panel in the frame, N/mm."""
        e = math.radians(eta_deg)
        s, c = math.sin(e), math.cos(e)
        return self.Kyy * c * c + self.Kxx * s * s + (self.Kxy + self.Kyx) * s * c


def solve_frame(
    assembly: Assembly,
    mesh: AssemblyMesh | None = None,
    *,
    fixture: str | Fixture = "frame",
    folder: Path | None = None,
    keep: bool = False,
    timeout: float = 600.0,
) -> FrameStiffness:
    """Run the ``frame`` fixture (or another of kind ``frame``, a support's own, named by its
    behaviour) twice (y pair moving at eta = 0, x pair at eta = 90)."""
    along_y, along_x = (
        solve_assembly(assembly, fixture, mesh, eta, folder=folder, keep=keep, timeout=timeout)
        for eta in (0.0, 90.0)
    )
    assert along_y.side_force is not None and along_x.side_force is not None
    return FrameStiffness(
        Kxx=along_x.value(),
        Kyy=along_y.value(),
        Kxy=along_y.side_force / along_y.displacement,
        Kyx=along_x.side_force / along_x.displacement,
    )
