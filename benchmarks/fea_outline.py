"""The outline fixtures of docs/fea.md section 2.8: their checks on a flat plate at finer meshes
than the tests run, and a design's wheel or corner series with time and memory.

    python benchmarks/fea_outline.py annulus 2,1,0.5         # flat annulus vs plane elasticity
    python benchmarks/fea_outline.py disc-annulus 2,1,0.5    # the same on the disc mesh
    python benchmarks/fea_outline.py strip 2,1,0.5           # narrow plate on 4 corners vs beam
    python benchmarks/fea_outline.py design DESIGN.json wheel 2,4,8,16 0,45

Runs that may exceed 3 GB (16 elements per facet on the wheel example: 4.3 GB) go under the
big-run lock, e.g. ``flock /work/notes/fe-big.lock prlimit --as=17000000000 python ...``.
Prints one line per run: the value (N/mm), the mesh's size, the wall time and the largest
resident set of a child process so far (ccx, MB).
"""

from __future__ import annotations

import resource
import sys
import time
from collections.abc import Callable
from dataclasses import replace

import numpy as np

from corrugate.fea.assembly import AssemblyMesh
from corrugate.fea.outline import (
    OutlineFixture,
    cut_outline,
    plate_shell,
    solve_outline,
    solve_shells,
)
from corrugate.fea.shells import Shell


def _child_rss_mb() -> float:
    return resource.getrusage(resource.RUSAGE_CHILDREN).ru_maxrss / 1024


def _disc(cx: float, cy: float, r: float) -> np.ndarray:
    th = np.arange(720) * 2 * np.pi / 720
    return np.column_stack([cx + r * np.cos(th), cy + r * np.sin(th)])


#: The annulus: E (MPa), nu, t (mm), its outer and inner radii a, b (mm).
ANNULUS = (1000.0, 0.3, 0.2, 20.0, 5.0)


def _sweep(sizes: list[float], mesh: Callable[[float], Shell]) -> None:
    """The annulus meshed by ``mesh`` at each element size (mm) in the wheel fixture with the
    whole rim the ground patch, at eta 0 and 30 deg, against plane elasticity (the closed form
    is tests/fea/test_outline.py's ``_annulus_K``)."""
    sys.path.insert(0, "tests/fea")
    from test_outline import _annulus_K

    E, nu, t, a, b = ANNULUS
    exact = _annulus_K(E, nu, t, a, b)
    outline, hole = _disc(a, a, a), _disc(a, a, b)
    print(f"plane elasticity: K = {exact:.6g} N/mm")
    for size in sizes:
        sh = mesh(size)
        count = len(sh.elements) + len(sh.triangles)
        for eta in (0.0, 30.0):
            t0 = time.time()
            k = solve_shells([sh], "wheel", outline, [hole], eta, OutlineFixture(patch_deg=180))[0]
            print(
                f"{size:g} mm, eta {eta:g}: K = {k:.6g} N/mm ({k / exact - 1:+.2%}), "
                f"{count} elements, {time.time() - t0:.1f} s, {_child_rss_mb():.0f} MB"
            )


def annulus(sizes: list[float]) -> None:
    """The annulus on the structured mesh of its box cut to a staircase (:func:`_sweep`)."""
    E, nu, t, a, b = ANNULUS
    outline, hole = _disc(a, a, a), _disc(a, a, b)

    def mesh(size: float) -> Shell:
        sh = cut_outline(plate_shell(2 * a, 2 * a, size, E, nu, t), outline)
        inner = {tuple(e) for e in cut_outline(sh, hole).elements}
        ring = [e for e in sh.elements if tuple(e) not in inner]
        used = np.isin(sh.ids, np.array([n for e in ring for n in e]))
        return replace(sh, ids=sh.ids[used], xyz=sh.xyz[used], elements=ring)

    _sweep(sizes, mesh)


def disc_annulus(sizes: list[float]) -> None:
    """The annulus on the disc mesh that conforms to its rim and hole
    (:func:`corrugate.fea.discmesh.disc_mesh`: a zig-zag of height 0, pitch 10 mm, 10 / size
    elements per pitch; :func:`_sweep`)."""
    from corrugate.fea.discmesh import Disc, disc_mesh
    from corrugate.fea.planmesh import Corrugation

    E, nu, t, a, b = ANNULUS

    def mesh(size: float) -> Shell:
        pm = disc_mesh(
            Corrugation((1.0, 0.0), 0.0, 10.0, 0.0), Disc((a, a), a, b), round(10 / size)
        )
        ids = np.arange(1, len(pm.xyz) + 1, dtype=np.int64)
        quads = [[int(ids[i]) for i in r] for r in pm.elements["S8R"]]
        tris = [[int(ids[i]) for i in r] for r in pm.elements["S6"]]
        return Shell(ids, pm.xyz, quads, t, E, nu, tris)

    _sweep(sizes, mesh)


def strip(sizes: list[float]) -> None:
    """100 x 10 x 1 mm, E 1000 MPa, nu 0, corner nodes pinned (or clamped), a point load at the
    centre, against 48 E I / L^3."""
    E, t, L, b = 1000.0, 1.0, 100.0, 10.0
    ring = np.array([[0.0, 0.0], [L, 0.0], [L, b], [0.0, b]])
    beam = 48 * E * (b * t**3 / 12) / L**3
    tiny = OutlineFixture(bolt_radius=1e-3, load_radius=1e-3)
    for size in sizes:
        sh = plate_shell(L, b, size, E, 0.0, t)
        for test in ("corners", "clamped-corners"):
            k = solve_shells([sh], test, ring, [], 0.0, tiny)[0]  # type: ignore[arg-type]
            print(f"{size:g} mm, {test}: P/delta = {k:.7g} N/mm, beam {beam:.7g}, {k / beam:.5f}")


def design(path: str, test: str, meshes: list[int], etas: list[float]) -> None:
    from corrugate.export.record import read_record

    a = read_record(path).assembly(any_layout=True)
    for along in meshes:
        for eta in etas:
            t0 = time.time()
            r = solve_outline(a, test, AssemblyMesh(along), eta, timeout=3000)  # type: ignore[arg-type]
            print(
                f"{test} {along}/facet eta {eta:g}: {r.value:.6g} N/mm, layers "
                f"{', '.join(f'{f:.5g}' for f in r.layer_forces)} N at {r.displacement:.4g} mm, "
                f"{r.nodes} nodes, {r.elements} elements, {time.time() - t0:.1f} s wall, "
                f"{_child_rss_mb():.0f} MB",
                flush=True,
            )


if __name__ == "__main__":
    kind = sys.argv[1]
    if kind == "annulus":
        annulus([float(v) for v in sys.argv[2].split(",")])
    elif kind == "disc-annulus":
        disc_annulus([float(v) for v in sys.argv[2].split(",")])
    elif kind == "strip":
        strip([float(v) for v in sys.argv[2].split(",")])
    else:
        design(
            sys.argv[2],
            sys.argv[3],
            [int(v) for v in sys.argv[4].split(",")],
            [float(v) for v in sys.argv[5].split(",")],
        )
