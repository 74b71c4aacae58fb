"""LazyEvaluation (the solver's evaluation at points, each stiffness computed when read) against
the full :func:`corrugate.analysis.evaluate.evaluate` of the same arguments (the second method):
every column of K, D and EI, and the sizes, mass and springs, bit for bit, over layouts (with a
hole), supports, joints, scalar and several directions, identical and different layers."""

from __future__ import annotations

import numpy as np
import pytest

from corrugate import get_material
from corrugate.analysis.evaluate import LayerArrays, LazyEvaluation, evaluate
from corrugate.geometry.holes import Hole
from corrugate.geometry.layouts import make_layout

RNG = np.random.default_rng(39)
K = 40


def _layer(seed: int, mat: str = "dura-lar", t: float = 0.125) -> LayerArrays:
    rng = np.random.default_rng(seed)
    m = get_material(mat)
    W = rng.uniform(4.0, 16.0, K)[:, None]
    n = rng.integers(4, 30, K)[:, None]
    alpha = rng.uniform(40.0, 140.0, K)[:, None]
    return LayerArrays(m.E, m.nu, t, W, n, alpha, m.density)


LAYOUTS = {
    "rectangle": make_layout("rectangle"),
    "square": make_layout("square"),
    "circle": make_layout("circle"),
    "pentagon": make_layout("polygon", [(0, 0), (2, 0), (2.5, 1.2), (1, 2), (-0.4, 1.1)]),
    "rectangle-hole": make_layout("rectangle", holes=(Hole("circle", diameter=10.0),)),
}
ETAS = [0.0, 45.0, np.array([0.0, 90.0, 45.0]), np.array([30.0, 0.0, 90.0, 60.0, 45.0])]


@pytest.mark.parametrize("layout", list(LAYOUTS))
@pytest.mark.parametrize("support", ["free", "frame"])
@pytest.mark.parametrize("joint", ["none", "band-edges"])
@pytest.mark.parametrize("same", [True, False])
def test_lazy_columns_are_evaluate_bit_for_bit(
    layout: str, support: str, joint: str, same: bool
) -> None:
    lay = LAYOUTS[layout]
    l1 = _layer(1)
    l2 = l1 if same else _layer(2, "mylar", 0.1)
    for eta in ETAS:
        full = evaluate(l1, l2, lay, "refined", eta, support=support, joint=joint)
        lazy = LazyEvaluation(l1, l2, lay, "refined", eta, support=support, joint=joint)
        m = np.size(eta)
        # read in an order unlike evaluate's (EI before D, the last direction first)
        for j in reversed(range(m)):
            for kind in ("EI", "K", "D"):
                want = np.asarray(getattr(full, kind))[:, j]
                got = lazy.column(kind, j)
                assert got.shape == want.shape
                np.testing.assert_array_equal(got, want, err_msg=f"{kind} at {eta}[{j}]")
        for kind in ("K", "D", "EI"):
            np.testing.assert_array_equal(
                getattr(lazy, kind), np.broadcast_to(getattr(full, kind), (K, m))
            )
        for f in ("Lx", "Ly", "thickness", "mass", "mass_connectors"):
            np.testing.assert_array_equal(getattr(lazy, f), getattr(full, f), err_msg=f)
        for a, b in zip(lazy.springs, full.springs, strict=True):
            for f in ("K_C", "K_S", "D_C", "D_S"):
                np.testing.assert_array_equal(getattr(a, f), getattr(b, f))


def test_lazy_computes_only_what_is_read(monkeypatch: pytest.MonkeyPatch) -> None:
    """An off-axis D nobody reads is not computed (the point of the lazy path)."""
    import corrugate.analysis.evaluate as ev

    calls: list[tuple[str, float]] = []
    real = ev.assembly_directional

    def spy(kind, springs, eta, support="free", coupon=None):  # type: ignore[no-untyped-def]
        calls.append((kind, float(eta)))
        return real(kind, springs, eta, support, coupon)

    monkeypatch.setattr(ev, "assembly_directional", spy)
    l1 = _layer(3)
    lazy = LazyEvaluation(l1, l1, LAYOUTS["rectangle"], "refined", np.array([0.0, 90.0, 45.0]))
    lazy.column("EI", 0)
    lazy.column("EI", 1)
    lazy.column("K", 2)
    lazy.column("K", 2)  # kept
    assert sorted(calls) == [("D", 0.0), ("D", 90.0), ("K", 45.0)]
