"""The parts of a CalculiX deck every fixture shares: the mesh cards and named node sets.

A deck is the mesh (this module: nodes, S8R / S6 elements, one material and shell section per
part, and one for the crease strips of compliant creases), the fixture's node sets and boundary conditions (:mod:`corrugate.fea.fixtures`) and the
analysis step (:mod:`corrugate.fea.steps`); docs/fea.md section 2. Units: mm, N, MPa.
"""

from __future__ import annotations

from dataclasses import dataclass

from corrugate.fea.shells import Shell, section_lines

__all__ = ["DeckInfo", "mesh_lines", "node_set"]


@dataclass(frozen=True, slots=True)
class DeckInfo:
    """Bookkeeping of an assembly deck: node sets whose reactions make the load (one per layer),
    span along the load axis (mm), prescribed displacement (mm), load axis (0 = x, 1 = y)."""

    sets: tuple[str, ...]  # one per part: layer 1, layer 2 (and the band)
    mid_sets: tuple[tuple[str, str], ...] | None  # (MIDk, GAUGEk) per part (four-point only)
    span: float
    delta: float
    axis: int
    nodes: int
    elements: int
    side_sets: tuple[str, ...] = ()  # far side platen of each part (the frame only)


def node_set(name: str, nodes: list[int]) -> list[str]:
    """The ``*NSET`` card of ``nodes`` named ``name``, twelve node numbers a line."""
    out = [f"*NSET,NSET={name}"]
    for k in range(0, len(nodes), 12):
        out.append(",".join(map(str, nodes[k : k + 12])))
    return out


def mesh_lines(parts: list[tuple[int, Shell]], heading: str) -> tuple[list[str], int]:
    """The ``*HEADING`` (``heading``), ``*NODE`` and ``*ELEMENT`` cards of ``parts`` (part number
    k, 1-based, and its shell: elements in set ``Lk``, numbered from 1 over all parts), and each
    part's material and shell section; returns the lines and the number of elements."""
    lines = ["*HEADING", heading, "*NODE"]
    for _, sh in parts:
        for n, (x, y, z) in zip(sh.ids, sh.xyz, strict=True):
            lines.append(f"{n},{x:.10g},{y:.10g},{z:.10g}")
    e_no = 1
    for k, sh in parts:
        for etype, elems, name in (
            ("S8R", sh.elements, "L"),
            ("S6", sh.triangles, "L"),
            ("S8R", sh.strip_elements, "C"),  # the crease strips (shells.crease_strip)
            ("S6", sh.strip_triangles, "C"),
        ):
            if not elems:
                continue
            lines.append(f"*ELEMENT,TYPE={etype},ELSET={name}{k}")
            for e in elems:
                lines.append(f"{e_no}," + ",".join(map(str, e)))
                e_no += 1
    lines += section_lines(parts)
    return lines, e_no - 1
