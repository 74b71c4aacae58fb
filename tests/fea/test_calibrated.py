"""The part a calibrated certificate speaks of (corrugate.fea.calibrated), as ``verify`` meshes
it: E and the crease stiffness at their 90 % intervals' low ends, the folds at the angle cut plus
the springback end of lower model stiffness (docs/calibration.md 9)."""

from __future__ import annotations

import math
import re
from dataclasses import replace

import pytest

from corrugate.fea.assembly import AssemblyMesh, assembly_deck, solve_assembly
from corrugate.fea.calibrated import certified_part
from corrugate.fea.shells import STRIP_FRACTION, crease_strip
from corrugate.geometry.layer import Assembly, Layer
from corrugate.materials.calibrated import Calibration
from corrugate.materials.library import get_material

#: The walk-through's entry (docs/calibration.md 8 and 9): E 2738-2900 MPa, k 0.0949-0.103,
#: springback -6.2 deg (-6.9 to -5.5).
CAL = Calibration("2026-12-06", 40, ("F1", "C1"), 2738.0, 2900.0, 0.0949, 0.103, -6.2, -6.9, -5.5)


def _assembly(W: float = 9.0, n: int = 7, alpha: float = 93.0) -> Assembly:
    m = replace(get_material("dura-lar"), E=2818.0, crease_stiffness=0.0987, calibration=CAL)
    return Assembly.identical(Layer(W=W, n=n, alpha_deg=alpha, material=m, t=0.125))


def test_a_datasheet_sheet_is_meshed_as_cut() -> None:
    a = Assembly.identical(Layer(W=9, n=7, alpha_deg=93, material=get_material("dura-lar")))
    part = certified_part(a, "EI", 0.0, "free")
    assert part.assembly is a and not part.calibrated and part.words() == ""


def test_the_part_is_at_the_low_ends_and_the_folds_after_springback() -> None:
    """EI along layer 1's creases grows as the folds close (the section deepens: h = W cos(alpha
    / 2)), so its weaker end is the more open fold, 93 - 5.5 = 87.5 deg, the corner section 9
    names; E and k at 2738 MPa and 0.0949."""
    part = certified_part(_assembly(), "EI", 0.0, "free")
    for lay in part.assembly.layers:
        assert lay.alpha_deg == pytest.approx(87.5)
        assert lay.material.E == 2738.0
        assert lay.material.crease_stiffness == 0.0949
    assert lay.W == 9.0 and lay.n == 7  # the sizes stay as cut
    assert "folds at 87.5 deg (cut 93 deg, springback -5.5 deg" in part.words()


def test_the_deck_meshes_the_springback_angle_and_the_strips_at_the_low_k() -> None:
    """The deck's node heights: the zig-zag's height h = W cos(alpha / 2) at the folded angle
    (87.5 deg: 6.4917 mm for W 9; 6.1973 mm at the 93 deg cut); its strips' E across the
    crease that of k = 0.0949 on E 2738 MPa (crease_strip's closed form)."""
    part = certified_part(_assembly(), "EI", 0.0, "free")
    deck, _ = assembly_deck(part.assembly, "four-point", AssemblyMesh(along=2), 0.0)
    block = deck.split("*NODE", 1)[1].split("*", 1)[0]
    z = [float(r.split(",")[3]) for r in block.strip().splitlines()[1:] if r.count(",") == 3]
    h = 9.0 * math.cos(math.radians(87.5 / 2))
    assert max(z) - min(z) == pytest.approx(2 * h, rel=1e-9)  # two layers stacked
    Ea = crease_strip(0.125, 2738.0, 0.43, 0.0949, STRIP_FRACTION * 9.0, (0.0, 1.0), 9.0)
    cards = re.findall(r"\*ELASTIC,TYPE=ENGINEERING CONSTANTS\n([^\n]+)", deck)
    assert cards and all(float(c.split(",")[0]) == pytest.approx(Ea.E_across) for c in cards)
    assert all(float(c.split(",")[1]) == 2738.0 for c in cards)


def test_the_angle_end_follows_the_quantity() -> None:
    """Off the crease directions K is carried by the facets bending and the creases turning,
    and grows as the folds open (``analyze``: K(45) 0.27 N/mm at 86.1 deg, 0.32 at 93), the
    opposite of K along the creases (the panel's length grows as they open, its developed
    width does not): the weaker end at 45 deg is the more closed fold, 93 - 6.9 = 86.1 deg."""
    from corrugate.analysis.evaluate import analyze

    part = certified_part(_assembly(), "K", 45.0, "free")
    assert [lay.alpha_deg for lay in part.assembly.layers] == [pytest.approx(86.1)] * 2
    other = certified_part(_assembly(), "K", 0.0, "free").assembly
    assert other.layer1.alpha_deg == pytest.approx(87.5)
    k45 = [analyze(p, eta_deg=[45.0]).stiffness[0].K for p in (part.assembly, other)]
    assert k45[0] < k45[1]


@pytest.mark.fea
def test_verify_runs_the_certified_part(ccx: str) -> None:
    """verify's FE value of a calibrated design is that of the part built by hand at E 2738
    MPa, k 0.0949 and alpha 87.5 deg, and below the FE of the springback interval's other end
    (86.1 deg: the FE agrees with the model on which end is weaker), at 2 per facet."""
    from corrugate.fea.verify import verify_design

    a = _assembly(W=8, n=3)
    row = {"name": "EI", "quantity": "EI@0", "sense": "min", "unit": "N*mm^2"}
    v = verify_design(a, [{**row, "bound": 1.0, "value": 2.0}], meshes=(2,), max_mesh=2)
    r = v.rows[0]
    assert "meshed at the calibrated worst end" in r.note
    m = replace(a.layer1.material, E=2738.0, crease_stiffness=0.0949, calibration=None)
    hand = Assembly.identical(Layer(W=8, n=3, alpha_deg=87.5, material=m, t=0.125))
    fe = solve_assembly(hand, "four-point", AssemblyMesh(along=2), 0.0)
    assert r.fe_series[2] == pytest.approx(fe.EI, rel=1e-9)
    other = Assembly.identical(Layer(W=8, n=3, alpha_deg=86.1, material=m, t=0.125))
    assert r.fe_series[2] < solve_assembly(other, "four-point", AssemblyMesh(along=2), 0.0).EI
