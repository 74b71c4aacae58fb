"""Buckling mode shapes of a ``*BUCKLE`` run and where the first one lies (docs/fea.md section 2).

A buckling step (:class:`corrugate.fea.steps.LinearBuckling`) asked for ``*NODE FILE`` / ``U``
writes ``DISP`` blocks to the ``.frd`` file, each after a ``100CL`` line whose value is the
block's buckling factor: first the base state (the static solution under the reference load,
factor 0), then one block per mode (factor 1, 2, ...: the mode's displacement, normalised by ccx,
so only its shape counts) at every node, in the expanded 20-node bricks of the shells (new
node numbers on the shells' surfaces and mid-surfaces, as for the stresses,
:class:`corrugate.fea.ccx.FrdStresses`). :func:`parse_frd_mode` reads mode k's block with the
node coordinates (mm) and the material (part) of each node; :func:`mode_location` says where the
mode's largest displacement is: which part (layer 1, layer 2, the band), and where in the
panel's plan as fractions of its extents, the words of the validation table
(docs/validation/capacity.md).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from numpy.typing import NDArray

from corrugate.fea.ccx import SolverError

__all__ = ["NODE_FILE_U", "ModeShape", "mode_location", "parse_frd_mode", "with_mode_output"]

#: The cards that write every mode's displacements to the ``.frd`` file.
NODE_FILE_U = "*NODE FILE\nU"

#: The parts of an assembly deck, in the order of its ``*MATERIAL`` cards (material 1, 2, 3).
PARTS = ("layer 1", "layer 2", "the band")


def with_mode_output(deck: str) -> str:
    """``deck`` (one ``*BUCKLE`` step) with the mode shapes written to the ``.frd`` file."""
    head, sep, tail = deck.rpartition("*END STEP")
    if not sep:
        raise ValueError("the deck has no *END STEP card")
    return f"{head}{NODE_FILE_U}\n{sep}{tail}"


@dataclass(frozen=True, slots=True)
class ModeShape:
    """One mode of a ``.frd`` file: node ``ids``, their coordinates ``xyz`` (mm), the mode's
    displacement ``u`` (ccx's normalisation: a shape, no unit) and each node's ``material``
    (1-based part number of the first element using it; 0: none)."""

    ids: NDArray[np.int64]
    xyz: NDArray[np.float64]
    u: NDArray[np.float64]
    material: NDArray[np.int64]

    def largest(self) -> int:
        """The index of the node with the largest displacement magnitude."""
        return int(np.argmax(np.linalg.norm(self.u, axis=1)))


def _floats(line: str, count: int) -> list[float]:
    return [float(line[13 + 12 * k : 25 + 12 * k]) for k in range(count)]


def parse_frd_mode(text: str, mode: int = 1) -> ModeShape:
    """The ``DISP`` block of buckling mode ``mode`` (1: the first; the base state, whose
    ``100CL`` factor is 0, is not a mode) of an ASCII ``.frd`` file with the node coordinates
    and materials; :class:`SolverError` when the file has fewer modes."""
    coords: dict[int, tuple[float, ...]] = {}
    material: dict[int, int] = {}
    disp: dict[int, tuple[float, ...]] = {}
    state, current, seen, factor = "", 0, 0, 0.0
    for line in text.splitlines():
        head = line[:6]
        if line.startswith("  100CL"):
            factor = float(line[12:24])
            continue
        if head == "    2C":
            state = "nodes"
            continue
        if head == "    3C":
            state = "elements"
            continue
        if line.startswith(" -4"):
            if line.split()[1] == "DISP" and factor != 0.0:
                seen += 1
                state = "disp" if seen == mode else "other"
            else:
                state = "other"
            continue
        if line.startswith(" -3"):
            state = ""
            continue
        if state == "nodes" and line.startswith(" -1"):
            coords[int(line[3:13])] = tuple(_floats(line, 3))
        elif state == "elements":
            if line.startswith(" -1"):
                current = int(line.split()[4])
            elif line.startswith(" -2"):
                for node in line.split()[1:]:
                    material.setdefault(int(node), current)
        elif state == "disp" and line.startswith(" -1"):
            disp[int(line[3:13])] = tuple(_floats(line, 3))
    if not disp:
        raise SolverError(f"the .frd file holds no DISP block of mode {mode} (no *NODE FILE U?)")
    ids = np.array(sorted(i for i in disp if i in coords), dtype=np.int64)
    return ModeShape(
        ids,
        np.array([coords[i] for i in ids], dtype=np.float64).reshape(-1, 3),
        np.array([disp[i] for i in ids], dtype=np.float64).reshape(-1, 3),
        np.array([material.get(int(i), 0) for i in ids], dtype=np.int64),
    )


def mode_location(shape: ModeShape, span_axis: int, width: float, length: float) -> str:
    """Where ``shape``'s largest displacement is, in words: the part and its position along the
    span (``span_axis``: 0 for x, 1 for y; ``length`` mm the panel's extent that way) and across
    it (``width`` mm), each as a fraction of the extent from the panel's origin corner, e.g.
    ``"layer 1 at 0.50 of the span, 0.03 of the width"``."""
    i = shape.largest()
    m = int(shape.material[i])
    part = PARTS[m - 1] if 1 <= m <= len(PARTS) else f"part {m}"
    x = shape.xyz[i]
    # clipped to [0, 1]: the expanded shells' surface nodes lie up to t / 2 outside the panel
    along = min(max(float(x[span_axis]) / length, 0.0), 1.0)
    across = min(max(float(x[1 - span_axis]) / width, 0.0), 1.0)
    return f"{part} at {along:.2f} of the span, {across:.2f} of the width"
