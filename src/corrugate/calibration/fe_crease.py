"""The FE twin of the zig-zag strip pulled along its chord line, with compliant creases.

The strip of :mod:`corrugate.calibration.crease` as CalculiX shells: n creases, n + 1 full facets
of developed width W (mm) at the angle alpha (deg), b (mm) wide along the creases, meshed by
:func:`corrugate.fea.shells.layer_shell` (S8R, ``along`` elements across each facet, the crease
strips of :func:`corrugate.fea.shells.crease_strip` at a finite k). Each end edge is a rigid body
whose reference node lies on the chord line through the zig-zag's mid-height (the kit's tab):
one pinned (its rotation about the chord line held), the other pulled along the chord by F (N)
and held across it. Linear static step. The compliance C = delta / F (mm/N) by virtual work as in
docs/calibration.md section 4, for this strip (every crease and both end edges at the moment
F h / 2, h = W cos(alpha/2); the end edges are rigid):

    C = n e^2 / (k b) + (n + 1) e^2 W / (3 D b) + (n + 1) W sin^2(alpha/2) / (E b t),   e = h / 2,

with D = E t^3 / (12 (1 - nu^2)) the plate's rigidity (:func:`compliance`);
docs/offaxis.md, "Compliant creases", compares them.
"""

from __future__ import annotations

import math
import time
from dataclasses import dataclass, replace
from pathlib import Path

import numpy as np

from corrugate.materials.library import Material

__all__ = [
    "CreaseStripResult",
    "compliance",
    "crease_strip_compliance",
    "crease_strip_deck",
    "rigid_ends",
]


def compliance(
    k: float, E: float, nu: float, t: float, b: float, W: float, alpha_deg: float, n: int
) -> float:
    """C (mm/N) of the strip of the module docstring (k in N mm/(rad mm), inf: rigid; E MPa)."""
    half = math.radians(alpha_deg) / 2
    e = W * math.cos(half) / 2
    D = E * t**3 / (12 * (1 - nu * nu))
    hinge = 0.0 if math.isinf(k) else n * e * e / (k * b)
    return (
        hinge + (n + 1) * e * e * W / (3 * D * b) + (n + 1) * W * math.sin(half) ** 2 / (E * b * t)
    )


def rigid_ends(E: float, nu: float, t: float, b: float, W: float, alpha_deg: float) -> float:
    """The compliance (mm/N) the FE's rigid end zones take out of :func:`compliance`: each end
    facet's first strip element (:data:`corrugate.fea.shells.STRIP_FRACTION` W / 2 wide, a =
    W / 20, with the end edge's node lines) is part of the end's rigid body, so its bending,
    int_0^a (F e (1 - 2 x / W))^2 dx / (D b) = F e^2 (W / 6) (1 - (1 - 2 a / W)^3) / (D b)
    per end (F = 1), is not in the FE (the meshes with crease strips; rigid creases mesh no
    strip, and their end zone is W / along wide)."""
    from corrugate.fea.shells import STRIP_FRACTION

    e = W * math.cos(math.radians(alpha_deg) / 2) / 2
    D = E * t**3 / (12 * (1 - nu * nu))
    a = STRIP_FRACTION * W / 2
    return 2 * e * e * (W / 6) * (1 - (1 - 2 * a / W) ** 3) / (D * b)


def crease_strip_deck(
    material: Material, t: float, b: float, W: float, alpha_deg: float, n: int, along: int
) -> str:
    """The CalculiX deck of the strip (module docstring), pulled by 1 N; the material's
    ``crease_stiffness`` sets its creases."""
    from corrugate.fea.deck import mesh_lines, node_set
    from corrugate.fea.shells import layer_shell
    from corrugate.geometry.layer import Layer

    layer = Layer(W=W, n=n, alpha_deg=alpha_deg, material=material, t=t)
    across = max(2, 2 * math.ceil(b / (W / along) / 2))
    sh = layer_shell(layer, b, along, 1, 0, 0.0, nel_s=across)
    L = (n + 1) * layer.pitch
    tol = 1e-7 * max(L, b)
    x = sh.xyz[:, 0]
    # each end edge and the next line of corner nodes: CalculiX ties a shell node's translations
    # to a rigid body, not its rotation, so one line alone would be a hinge (a mechanism with
    # the pins); two lines make the end edge rigid, as the kit's tab is
    step = float(np.unique(np.round(x / tol))[2] * tol)
    ends = [
        [int(i) for i in sh.ids[x < step + tol]],
        [int(i) for i in sh.ids[x > L - step - tol]],
    ]
    lines, _ = mesh_lines([(1, sh)], "corrugate calibration zig-zag strip")
    top = int(sh.ids.max())
    refs = [(top + 1, top + 2, 0.0), (top + 3, top + 4, L)]
    lines.insert(lines.index("*NODE") + 1, f"{top + 1},0,{b / 2:.10g},{layer.height / 2:.10g}")
    lines.insert(lines.index("*NODE") + 2, f"{top + 2},0,{b / 2:.10g},{layer.height / 2:.10g}")
    lines.insert(
        lines.index("*NODE") + 3, f"{top + 3},{L:.10g},{b / 2:.10g},{layer.height / 2:.10g}"
    )
    lines.insert(
        lines.index("*NODE") + 4, f"{top + 4},{L:.10g},{b / 2:.10g},{layer.height / 2:.10g}"
    )
    for k, (nodes, (ref, rot, _)) in enumerate(zip(ends, refs, strict=True)):
        lines += node_set(f"END{k}", nodes)
        lines += [f"*RIGID BODY,NSET=END{k},REF NODE={ref},ROT NODE={rot}"]
    r0, q0, _ = refs[0]
    r1, _, _ = refs[1]
    lines += [
        "*NSET,NSET=PULLED",
        f"{r1}",
        "*BOUNDARY",
        f"{r0},1,3",
        f"{q0},1,1",  # the rotation about the chord line
        f"{r1},2,3",
        "*STEP",
        "*STATIC",
        "*CLOAD",
        f"{r1},1,1.",
        "*NODE PRINT,NSET=PULLED",
        "U",
        "*END STEP",
        "",
    ]
    return "\n".join(lines)


@dataclass(frozen=True, slots=True)
class CreaseStripResult:
    """The FE compliance C (mm/N) of one mesh (``along`` elements per facet), its ccx wall
    time (s) and node count."""

    along: int
    C: float
    seconds: float
    nodes: int


def crease_strip_compliance(
    material: Material,
    k: float,
    t: float,
    b: float,
    W: float,
    alpha_deg: float,
    n: int,
    along: int,
    folder: Path | None = None,
) -> CreaseStripResult:
    """Run :func:`crease_strip_deck` with creases of stiffness ``k`` (N mm/(rad mm), inf: rigid)
    in CalculiX and read the pulled end's displacement along the chord per newton (mm/N)."""
    from corrugate.fea.ccx import run_ccx, work_dir

    deck = crease_strip_deck(replace(material, crease_stiffness=k), t, b, W, alpha_deg, n, along)
    nodes = sum(1 for ln in deck.splitlines() if ln[:1].isdigit() and ln.count(",") == 3)
    start = time.monotonic()
    with work_dir(folder) as where:
        run = run_ccx(deck, where, job="zigzag")
    seconds = time.monotonic() - start
    last = run.last("displacements")
    (row,) = last.rows.values()
    return CreaseStripResult(along, float(row[0]), seconds, nodes)
