"""Design -> Pattern: every part to cut for an assembly (both layers and the connector band)."""

from __future__ import annotations

import numpy as np

from corrugate.fabrication.band import band_parts
from corrugate.fabrication.layers import layer_part
from corrugate.fabrication.model import Pattern
from corrugate.geometry.fabrication_options import DEFAULT_FABRICATION, FabricationOptions
from corrugate.geometry.holes import hole_rings
from corrugate.geometry.layer import Assembly

__all__ = ["build_pattern"]


def build_pattern(a: Assembly, opts: FabricationOptions = DEFAULT_FABRICATION) -> Pattern:
    """The cut parts of assembly ``a``: L1, L2 (layer blanks) and B1..Bk (band segments), in mm.

    Layer 1's plan outline is used in (x, y); layer 2's in (y, x), reversed to stay
    counter-clockwise, since its chordwise direction is y. The layout's holes are cut from both
    layers (inner rings of L1 and L2); the band does not meet them.
    """
    plan = a.layout.plan_outline(a.Lx, a.Ly)
    holes = hole_rings(a.layout.holes, a.Lx, a.Ly)
    l1 = layer_part(a.layer1, plan, 1, holes)
    swap = [np.ascontiguousarray(h[::-1, ::-1]) for h in holes]
    l2 = layer_part(a.layer2, np.ascontiguousarray(plan[::-1, ::-1]), 2, swap)
    m = a.layer1.material
    return Pattern(
        parts=(l1, l2, *band_parts(a, opts)),
        material_id=m.id,
        t=a.layer1.t,
        density=m.density,
    )
