"""The gmsh plan mesher of the oblique coupons (corrugate.fea.planmesh), without ccx.

Properties for random directions, pitches and coupon sizes: the elements tile the coupon's plan
exactly (their plan areas sum to A x B), every element lies in one flat facet (its nodes, lifted,
are coplanar: no element straddles a crease), every node is on the folded surface, and the
fixture lines are made of element edges (nodes on them, none of the elements crossing them).
"""

from __future__ import annotations

import math

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from corrugate.fea.planmesh import Corrugation, plan_mesh


def _area(p: np.ndarray) -> float:
    """Plan area of a polygon given by its corners in order (shoelace)."""
    x, y = p[:, 0], p[:, 1]
    return 0.5 * float(np.sum(x * np.roll(y, -1) - np.roll(x, -1) * y))


@settings(max_examples=12, deadline=None)
@given(
    eta=st.floats(0.0, 90.0),
    pitch=st.floats(3.0, 8.0),
    height=st.floats(1.0, 6.0),
    side=st.floats(20.0, 45.0),
    offset=st.floats(-5.0, 5.0),
)
def test_plan_mesh_tiles_the_coupon_with_flat_elements(
    eta: float, pitch: float, height: float, side: float, offset: float
) -> None:
    e = math.radians(eta)
    corr = Corrugation((math.cos(e), math.sin(e)), offset, pitch, height, z0=1.0)
    lines = (side / 2, side / 4)
    m = plan_mesh(corr, side, side, 2, lines)
    xyz = m.xyz
    assert np.allclose(xyz[:, 2], corr.z(xyz[:, :2]))  # on the folded surface
    total = 0.0
    for name, rows in m.elements.items():
        corners = 4 if name == "S8R" else 3
        for r in rows:
            p = xyz[np.asarray(r)]
            a = _area(p[:corners, :2])
            assert a > 0  # normals up: counter-clockwise in plan
            total += a
            # coplanar: every node on the plane through three corners
            n = np.cross(p[1] - p[0], p[2] - p[0])
            n /= np.linalg.norm(n)
            # (1e-7 of the side: with gmsh 4.15.2 a node was 3.4e-8 of the side off its
            # element's plane and the area 2.5e-9 short, far below anything the FE resolves)
            assert np.max(np.abs((p - p[0]) @ n)) < 1e-7 * side
            # a fixture line is never crossed by an element (only touched along edges)
            for y in lines:
                assert not (p[:, 1].min() < y - 1e-9 and p[:, 1].max() > y + 1e-9)
    assert total == pytest.approx(side * side, rel=1e-7)
    for y in lines:
        assert np.sum(np.abs(xyz[:, 1] - y) < 1e-9) >= 3


_BROKEN_PIPE_AFTER_MESHING = """
import os, sys, threading
from corrugate.fea.planmesh import Corrugation, plan_mesh
corr = Corrugation((1.0, 0.0), 0.0, 5.0, 2.0, z0=1.0)
if sys.argv[1] == "thread":
    t = threading.Thread(target=plan_mesh, args=(corr, 20.0, 20.0, 2, (10.0, 5.0)))
    t.start(); t.join()
else:
    plan_mesh(corr, 20.0, 20.0, 2, (10.0, 5.0))
r, w = os.pipe()
os.close(r)
try:
    os.write(w, b"x")
except BrokenPipeError:
    print("BrokenPipeError")
"""


@pytest.mark.parametrize("where", ["main", "thread"])
def test_meshing_leaves_sigpipe_ignored_so_a_closed_pipe_raises(where: str) -> None:
    """gmsh.initialize() sets SIGPIPE to its default in C (the first assertion shows it on the
    bare library); after plan_mesh, from the main thread or another, a write to a closed pipe
    raises BrokenPipeError in a fresh process instead of killing it (exit -13, the death of
    the CI run of 2026-12-07 at 74 %)."""
    import subprocess
    import sys

    bare = subprocess.run(
        [
            sys.executable,
            "-c",
            "import gmsh; from corrugate.core.sigpipe import sigpipe_ignored as s; "
            "a = s(); gmsh.initialize(interruptible=False); print(a, s())",
        ],
        capture_output=True,
        text=True,
        timeout=120,
    )
    assert bare.stdout.split() == ["True", "False"], bare.stderr
    run = subprocess.run(
        [sys.executable, "-c", _BROKEN_PIPE_AFTER_MESHING, where],
        capture_output=True,
        text=True,
        timeout=120,
    )
    assert run.returncode == 0, (run.returncode, run.stderr[-2000:])
    assert run.stdout.strip() == "BrokenPipeError"
