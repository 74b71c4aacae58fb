"""``validate --refine TOL`` decides convergence by :func:`corrugate.fea.extrapolate.judge`'s rule
(:func:`corrugate.fea.validation.settled`), not by the last relative change, which assumes an
order p >= 1. Checked on constructed series v(k) = L - c k^-p (k elements per facet) whose limit L
is known by construction (k -> infinity): no CalculiX."""

from __future__ import annotations

from dataclasses import dataclass

import pytest

from corrugate.fea.validation import _refine, settled

LIMIT = 100.0


def _series(p: float, meshes: tuple[int, ...] = (2, 4, 8, 16)) -> dict[int, float]:
    return {k: LIMIT - 50.0 * k**-p for k in meshes}


@dataclass(frozen=True)
class _Mesh:
    along: int

    def label(self) -> str:
        return f"{self.along}/facet"


def _study(p: float, tol: float, finest: int = 16) -> tuple[dict[str, float], _Mesh, bool, int]:
    history: list[tuple[str, dict[str, float]]] = []
    values, mesh, ok = _refine(
        "assembly",
        _Mesh(2),
        lambda m: _Mesh(2 * m.along),
        lambda m: m.along > finest,
        lambda m: {"K": LIMIT - 50.0 * m.along**-p, "D": 2 * LIMIT - 10.0 * m.along**-p},
        tol,
        history,
    )
    return values, mesh, ok, len(history)


def test_a_slow_series_is_not_called_converged() -> None:
    """p = 0.4: 62.1 / 71.3 / 78.2 / 83.5 at 2 / 4 / 8 / 16 per facet. The last change from 4 to
    8 is 9.7 % < 10 %, so the old rule stopped at 8 with 78.2, 22 % below the limit 100; the
    remaining error of a series of order p is the last step / (2^p - 1), 3.1 steps at p = 0.4.
    Judge's rule extrapolates 100 from both 2/4/8 and 4/8/16, and 83.5 is not within 10 % of it."""
    s = _series(0.4)
    assert s[8] / s[4] - 1 < 0.1  # what the old rule looked at
    j = settled(s, 0.1)
    assert j.verdict == "fails"  # the limit lies outside finest x (1 +- 10 %)
    assert j.value == pytest.approx(LIMIT, rel=1e-9)
    assert j.order == pytest.approx(0.4, rel=1e-9)
    values, mesh, converged, runs = _study(0.4, 0.1)
    assert (mesh.along, converged, runs) == (16, False, 4)  # refined to the finest allowed
    assert values["K"] == pytest.approx(s[16])
    # allowed finer, it goes on to the first mesh within 10 %: 100 <= 1.1 x (100 - 50 k^-0.4)
    # first at k = 128 (92.82 x 1.1 = 102.1; at 64, 90.53 x 1.1 = 99.58)
    values, mesh, converged, _ = _study(0.4, 0.1, finest=4096)
    assert converged and mesh.along == 128
    assert abs(values["K"] / LIMIT - 1) <= 0.1


def test_a_fast_series_settles_on_four_meshes() -> None:
    """p = 2: 87.5 / 96.875 / 99.219 / 99.805; 99.805 is within 1 % of the limit 100 that both
    extrapolations give, so it settles at 16 per facet, the first mesh with four behind it."""
    s = _series(2.0)
    assert settled(s, 0.01).verdict == "holds"
    assert settled({k: s[k] for k in (2, 4, 8)}, 0.01).verdict == "open"  # three meshes: not shown
    values, mesh, converged, runs = _study(2.0, 0.01, finest=64)
    assert (mesh.along, converged, runs) == (16, True, 4)
    assert abs(values["K"] / LIMIT - 1) <= 0.01


def test_a_mesh_independent_value_settles_when_its_steps_vanish() -> None:
    """A value that does not change with the mesh (a limit case: c = 0) settles on three meshes,
    the last two steps zero; one mesh alone is never settled."""
    flat = {2: 5.0, 4: 5.0, 8: 5.0}
    assert settled(flat, 1e-6).verdict == "holds"
    assert settled({2: 5.0}, 0.5).verdict == "open"
    history: list[tuple[str, dict[str, float]]] = []
    _, mesh, converged = _refine(
        "cell", _Mesh(2), lambda m: _Mesh(2 * m.along), lambda m: m.along > 16,
        lambda m: {"E": 5.0}, 1e-6, history,
    )  # fmt: skip
    assert (mesh.along, converged, len(history)) == (8, True, 3)
