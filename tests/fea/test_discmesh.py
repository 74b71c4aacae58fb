"""The disc mesh that conforms to the rim and the hole (docs/fea.md 2.8, issue 35): its geometry
by construction (the wheel fixture on it against plane elasticity: tests/fea/test_outline.py)."""

from __future__ import annotations

import math

import numpy as np
import pytest

from corrugate.fea.discmesh import Disc, disc_mesh
from corrugate.fea.fixtures.nodes import rim
from corrugate.fea.fixtures.wheel import patch_ends
from corrugate.fea.planmesh import Corrugation
from corrugate.fea.shells import Shell

DISC = Disc((35.0, 35.0), 35.0, 3.0)
PITCH = 10.0


def _shell(corr: Corrugation, disc: Disc, along: int, angles: tuple[float, ...]) -> Shell:
    pm = disc_mesh(corr, disc, along, angles)
    ids = np.arange(1, len(pm.xyz) + 1, dtype=np.int64)
    quads = [[int(ids[i]) for i in r] for r in pm.elements["S8R"]]
    tris = [[int(ids[i]) for i in r] for r in pm.elements["S6"]]
    return Shell(ids, pm.xyz, quads, 0.2, 1000.0, 0.3, tris)


@pytest.mark.parametrize("chord", [(1.0, 0.0), (0.0, 1.0)])
@pytest.mark.parametrize("along", [2, 4])
def test_the_rim_and_the_hole_are_circles_and_no_element_crosses_a_crease(
    chord: tuple[float, float], along: int
) -> None:
    """Every node on the mesh's edge lies on the rim (R = 35 mm) or on the hole (r = 3 mm) to
    1e-9 mm, corners and mid-side nodes alike (the staircase's lie up to an element off); the
    patch ends' angles (eta 45: 210 and 240 deg) are nodes of the rim; every element's corners
    lie in one facet (chordwise between two creases), so the lifted surface is exact."""
    corr = Corrugation(chord, 0.0, PITCH, 3.0)
    ends = patch_ends(45.0, 15.0)
    assert ends == pytest.approx((-150.0, -120.0))  # 210 and 240 deg
    sh = _shell(corr, DISC, along, ends)
    index = {int(n): i for i, n in enumerate(sh.ids)}
    edge = sh.xyz[[index[int(n)] for n in rim(sh)], :2] - np.array(DISC.centre)
    r = np.hypot(edge[:, 0], edge[:, 1])
    on = np.minimum(np.abs(r - DISC.R), np.abs(r - DISC.r))
    assert on.max() < 1e-9
    assert (np.abs(r - DISC.r) < 1e-9).sum() >= 8  # the hub exists at 2 per facet
    for a in ends:
        p = np.array(DISC.centre) + DISC.R * np.array(
            [math.cos(math.radians(a)), math.sin(math.radians(a))]
        )
        assert np.hypot(*(sh.xyz[:, :2] - p).T).min() < 1e-9
    u = sh.xyz[:, :2] @ np.array(chord)
    for e, k in [(e, 4) for e in sh.elements] + [(e, 3) for e in sh.triangles]:
        q = u[[index[n] for n in e[:k]]] / PITCH
        lo = math.floor(q.mean())
        assert q.min() >= lo - 1e-9 and q.max() <= lo + 1 + 1e-9
    # the lifted height is the zig-zag's: 0 at even creases, 3 mm at odd ones
    z = sh.xyz[:, 2]
    tri = np.abs((u / PITCH + 1.0) % 2.0 - 1.0)
    assert z == pytest.approx(3.0 * tri, abs=1e-12)
