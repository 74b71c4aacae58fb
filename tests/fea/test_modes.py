"""Reading a buckling run's mode shapes from ccx's ``.frd`` file (corrugate.fea.modes), on a
hand-written file laid out as ccx 2.20 writes a ``*BUCKLE`` step with ``*NODE FILE`` / ``U``:
the base state first (its ``100CL`` factor 0), then one block per mode."""

from __future__ import annotations

import pytest

from corrugate.fea.ccx import SolverError
from corrugate.fea.modes import mode_location, parse_frd_mode, with_mode_output


def _node(i: int, *v: float) -> str:
    return f" -1{i:10d}" + "".join(f"{x:12.5E}" for x in v)


def _block(factor: float, number: int, u: dict[int, tuple[float, float, float]]) -> list[str]:
    head = [
        f"  100CL  {100 + number:3d}{factor:12.5E}           3                     4{number:5d}",
        " -4  DISP        4    1",
        " -5  D1          1    2    1    0",
        " -5  D2          1    2    2    0",
        " -5  D3          1    2    3    0",
        " -5  ALL         1    2    0    0    1ALL",
    ]
    return [*head, *(_node(i, *v) for i, v in u.items()), " -3"]


#: Three nodes: 1 and 2 in an element of material 1 (layer 1), 3 in one of material 2.
FRD = "\n".join(
    [
        "    1C",
        "    2C                             3                                     1",
        _node(1, 0.0, 0.0, 0.0),
        _node(2, 10.0, 30.0, 1.0),
        _node(3, 40.0, 15.0, 5.0),
        " -3",
        "    3C                             2                                     1",
        " -1         1    4    0    1",
        " -2         1         2",
        " -1         2    4    0    2",
        " -2         3",
        " -3",
        # the base state: largest at node 3 (it must not be read as a mode)
        *_block(0.0, 1, {1: (0.0, 0.0, 0.0), 2: (0.0, 0.0, -0.1), 3: (0.0, 0.0, -9.0)}),
        *_block(0.745, 2, {1: (0.0, 0.0, 0.0), 2: (0.3, 0.0, 0.4), 3: (0.0, 0.1, 0.0)}),
        *_block(1.55, 3, {1: (0.0, 0.0, 0.0), 2: (0.0, 0.0, 0.1), 3: (0.0, 0.0, 2.0)}),
        "9999",
    ]
)


def test_the_first_mode_is_the_block_after_the_base_state() -> None:
    """Mode 1 is the block of factor 0.745, not the base state (factor 0) before it: its
    largest displacement is node 2's, |(0.3, 0, 0.4)| = 0.5, in layer 1 (material 1); mode 2's
    is node 3's (|u| = 2.0), in layer 2."""
    first = parse_frd_mode(FRD)
    assert list(first.ids) == [1, 2, 3]
    assert first.u[1].tolist() == pytest.approx([0.3, 0.0, 0.4])
    assert first.largest() == 1 and first.material.tolist() == [1, 1, 2]
    # node 2 at (10, 30): the span along y over 40 mm, the width along x over 50 mm
    assert mode_location(first, 1, 50.0, 40.0) == "layer 1 at 0.75 of the span, 0.20 of the width"
    second = parse_frd_mode(FRD, 2)
    assert second.largest() == 2
    assert mode_location(second, 0, 30.0, 40.0) == "layer 2 at 1.00 of the span, 0.50 of the width"
    with pytest.raises(SolverError, match="mode 3"):
        parse_frd_mode(FRD, 3)


def test_mode_output_goes_into_the_buckling_step() -> None:
    deck = "*NODE\n1,0,0,0\n*STEP\n*BUCKLE\n3,1.e-6\n*CLOAD\n1,3,-1.\n*END STEP\n"
    out = with_mode_output(deck)
    assert out.index("*NODE FILE\nU\n") > out.index("*CLOAD")
    assert out.endswith("*NODE FILE\nU\n*END STEP\n")
    with pytest.raises(ValueError, match="END STEP"):
        with_mode_output("*NODE\n")
