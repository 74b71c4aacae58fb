"""Spans shorter than the panel in CalculiX (docs/fea.md 2.1, "Spans shorter than the panel"):
the structured mesh's moved node lines against the gmsh mesh with the stations as element
edges (a second discretisation), the cantilever clamped inside a longer panel against the
shorter panel (the same free part: an identity) and three-point bending of an overhanging panel
against the panel cut at its supports (beam theory: the overhangs carry no moment)."""

from __future__ import annotations

from dataclasses import replace

import pytest

from corrugate import Assembly, Layer, get_material
from corrugate.fea.assembly import AssemblyMesh, solve_assembly
from corrugate.geometry.layouts import Rectangle

pytestmark = [pytest.mark.fea, pytest.mark.slow]

DL = get_material("dura-lar")
#: layer 2 runs along eta = 0 (its chord along y): 8 facets of pitch 3.06 mm, 24.5 mm
A = Assembly(
    Layer(W=5.0, n=5, alpha_deg=84.0, material=DL, t=0.125),
    Layer(W=4.0, n=7, alpha_deg=100.0, material=DL, t=0.125),
    Rectangle(),
)


def _k(a: Assembly, test: str, **kw: object) -> float:
    r = solve_assembly(a, test, AssemblyMesh(4), 0.0, **kw)  # type: ignore[arg-type]
    return r.force / r.displacement


@pytest.mark.parametrize("test", ["three-point", "four-point", "cantilever"])
def test_the_structured_span_agrees_with_the_gmsh_span(ccx: str, test: str) -> None:
    """A span of 0.8 L (supports and, for four-point, load lines inside facets): P / delta on
    the structured mesh with moved node lines and on the gmsh mesh with the stations as element
    edges, 4 per facet, within 2 % (the tolerance of the two meshers at full span,
    test_gmsh_mesher_matches_the_structured_mesh_at_eta_0)."""
    s = 0.8 * A.Ly
    structured = _k(A, test, span=s)
    gmsh = _k(A, test, span=s, mesher="gmsh")
    assert structured == pytest.approx(gmsh, rel=0.02)


def test_a_cantilever_clamped_inside_the_panel_is_the_shorter_panel(ccx: str) -> None:
    """The clamp holds the panel from its root end to L - span: the free part is the panel two
    facets shorter (layer 2 n - 2, the same zig-zag from a valley), clamped at its end. With the
    band both meshes put their node lines at the same places, so P / delta agrees to 1e-4, not
    a mesh tolerance (measured: 13.06499 against 13.06524 N/mm, 2e-5)."""
    short = replace(A, layer2=replace(A.layer2, n=A.layer2.n - 2))
    assert A.Ly - short.Ly == pytest.approx(2 * A.layer2.pitch)
    inside = _k(A, "cantilever", span=short.Ly, connectors=True)
    alone = _k(short, "cantilever", connectors=True)
    assert inside == pytest.approx(alone, rel=1e-4)


def test_three_point_over_a_span_inside_the_panel_is_the_simply_supported_span(ccx: str) -> None:
    """Limit case, beam theory: the overhangs beyond the supports carry no moment, so the
    deflection under the load is the simply supported span's. A slender panel (24 facets of
    layer 2 along the span, 73.5 mm, span over depth 16.6) with its supports on the valleys two
    facets in from each end (span 61.3 mm) against the panel four facets shorter over its
    length, 2 per facet: within 1 % (measured 0.27 %, 0.31 % at 4 per facet), and the overhangs
    can only stiffen. (On a stubby panel, span over depth 3.3, they stiffen the support lines
    by 16 %: the local term, docs/load_cases.md 2.)"""
    long = replace(A, layer2=replace(A.layer2, n=23))
    short = replace(A, layer2=replace(A.layer2, n=19))
    r = solve_assembly(long, "three-point", AssemblyMesh(2), 0.0, span=short.Ly)
    alone = solve_assembly(short, "three-point", AssemblyMesh(2), 0.0)
    over_k, alone_k = r.force / r.displacement, alone.force / alone.displacement
    assert r.span == pytest.approx(short.Ly)
    assert over_k == pytest.approx(alone_k, rel=0.01)
    assert over_k >= alone_k
