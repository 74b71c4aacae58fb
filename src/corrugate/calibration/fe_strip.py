"""The FE twin of a flat coupon: the strip's sag in CalculiX with geometric nonlinearity.

A strip of free length L, width b and thickness t (mm), clamped at x = 0 (every degree of freedom
of the edge's shell nodes) and free at x = L, meshed with ``nx`` x ``ny`` S8R shells (CalculiX
expands them to C3D20R bricks), loaded by its weight (``*DLOAD GRAV``: density rho, g = 9806.65
mm/s^2; units mm, N, tonne) and a dead load P (N) spread over the tip edge (the quadratic edge's
consistent weights 1/6, 2/3, 1/6), ramped in one ``*STATIC`` step with ``NLGEOM``. The sag is the
tip edge's mean downward displacement (mm): the quantity the elastica gives
(:mod:`corrugate.calibration.elastica`; docs/calibration.md section 7 compares them).
"""

from __future__ import annotations

from dataclasses import dataclass
from pathlib import Path

from corrugate.calibration.coupons import GRAVITY
from corrugate.materials.library import Material

__all__ = ["StripResult", "strip_deck", "strip_sag"]

#: Standard gravity in mm/s^2 (the deck's units: mm, N, tonne, s).
G_MM_S2 = 9806.65


def _nodes(L: float, b: float, nx: int, ny: int) -> dict[tuple[int, int], int]:
    """The S8R nodes on the (2 nx + 1) x (2 ny + 1) grid, without the elements' centres."""
    ids: dict[tuple[int, int], int] = {}
    for i in range(2 * nx + 1):
        for j in range(2 * ny + 1):
            if i % 2 == 1 and j % 2 == 1:
                continue
            ids[(i, j)] = len(ids) + 1
    return ids


def strip_deck(
    material: Material, E: float, t: float, b: float, L: float, tip_g: float, nx: int, ny: int = 2
) -> str:
    """The CalculiX deck of the strip (module docstring); E in MPa, lengths in mm, tip_g in g."""
    ids = _nodes(L, b, nx, ny)
    lines = ["*HEADING", "corrugate calibration strip", "*NODE"]
    for (i, j), n in ids.items():
        lines.append(f"{n}, {L * i / (2 * nx):.9g}, {b * j / (2 * ny) - b / 2:.9g}, 0")
    lines.append("*ELEMENT, TYPE=S8R, ELSET=EALL")
    e = 0
    for i in range(nx):
        for j in range(ny):
            x, y = 2 * i, 2 * j
            corners = [(x, y), (x + 2, y), (x + 2, y + 2), (x, y + 2)]
            mids = [(x + 1, y), (x + 2, y + 1), (x + 1, y + 2), (x, y + 1)]
            e += 1
            lines.append(f"{e}, " + ", ".join(str(ids[p]) for p in corners + mids))
    root = [n for (i, _), n in ids.items() if i == 0]
    tip = sorted(((j, n) for (i, j), n in ids.items() if i == 2 * nx))
    lines += ["*NSET, NSET=ROOT"] + [f"{n}," for n in root]
    lines += ["*NSET, NSET=TIP"] + [f"{n}," for _, n in tip]
    rho = material.density * 1e-6  # g/mm^3 -> tonne/mm^3
    lines += [
        "*MATERIAL, NAME=SHEET",
        "*ELASTIC",
        f"{E:.9g}, {material.nu:.9g}",
        "*DENSITY",
        f"{rho:.9g}",
        "*SHELL SECTION, ELSET=EALL, MATERIAL=SHEET",
        f"{t:.9g}",
        "*BOUNDARY",
        "ROOT, 1, 6, 0.",
        "*STEP, NLGEOM, INC=1000",
        "*STATIC",
        "0.05, 1., 1e-6, 0.1",
        "*DLOAD",
        f"EALL, GRAV, {G_MM_S2:.9g}, 0., 0., -1.",
    ]
    P = tip_g * GRAVITY
    if P > 0:
        lines.append("*CLOAD")
        for j, n in tip:
            weight = (1 / 6 if j in (0, 2 * ny) else 1 / 3) if j % 2 == 0 else 2 / 3
            lines.append(f"{n}, 3, {-P * weight / ny:.9g}")
    lines += ["*NODE PRINT, NSET=TIP", "U", "*END STEP", ""]
    return "\n".join(lines)


@dataclass(frozen=True, slots=True)
class StripResult:
    """The FE sag (mm) of one mesh (``nx`` x ``ny`` elements) and its ccx wall time (s)."""

    nx: int
    ny: int
    sag: float
    seconds: float


def strip_sag(
    material: Material,
    E: float,
    t: float,
    b: float,
    L: float,
    tip_g: float,
    nx: int,
    ny: int = 2,
    folder: Path | None = None,
) -> StripResult:
    """Run :func:`strip_deck` in CalculiX and read the tip edge's mean sag (mm) at the end of
    the ramp."""
    import time

    from corrugate.fea.ccx import run_ccx, work_dir

    deck = strip_deck(material, E, t, b, L, tip_g, nx, ny)
    start = time.monotonic()
    with work_dir(folder) as where:
        run = run_ccx(deck, where, job="strip")
    seconds = time.monotonic() - start
    last = run.last("displacements")
    sag = -sum(v[2] for v in last.rows.values()) / len(last.rows)
    return StripResult(nx, ny, sag, seconds)
