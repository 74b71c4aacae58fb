"""User options -> Assembly (``corrugate.spec.inputs``), shared by ``corrugate analyze`` and the web API."""

from __future__ import annotations

import pytest

from corrugate import InputError, get_material
from corrugate.spec.inputs import (
    DEFAULT_ETAS,
    analysis_request,
    assembly_from_options,
    parse_etas,
    parse_int,
    parse_vertices,
)


def test_numbers_and_strings_with_units_give_the_same_assembly() -> None:
    a = assembly_from_options(W=8, n=8, alpha=84, material="dura-lar")
    b = assembly_from_options(W="8 mm", n="8", alpha="84 deg", material="dura-lar")
    c = assembly_from_options(W="0.8 cm", n=8.0, alpha=84.0)
    assert a == b == c
    assert a.layer1.t == a.layer2.t == 0.125


def test_layer2_defaults_and_overrides() -> None:
    a = assembly_from_options(
        W=8, n=8, alpha=84, thickness="0.25 mm", W2=6, n2=12, layout="rectangle"
    )
    assert (a.layer2.W, a.layer2.n, a.layer2.alpha_deg) == (6, 12, 84)
    assert a.layer2.t == 0.25  # layer 1's thickness carries over
    b = assembly_from_options(W=8, n=8, alpha=84, material2="kapton")
    assert b.layer2.material == get_material("kapton")
    assert b.layer2.t == get_material("kapton").default_thickness


@pytest.mark.parametrize(
    ("options", "field"),
    [
        ({"alpha": 190}, "alpha"),
        ({"alpha2": 190}, "alpha2"),
        ({"n2": "2.5"}, "n2"),
        ({"W2": "3 GPa"}, "W2"),
        ({"material2": "nope"}, "material2"),
        ({"material": "nope"}, "material"),
        ({"E": 2700, "nu": 0.4}, "density"),
        ({"E": 2700, "nu": 0.4, "density": 1.2}, "material"),  # conflicts with material below
        ({"n": True}, "n"),
    ],
)
def test_errors_name_the_field(options: dict[str, object], field: str) -> None:
    base: dict[str, object] = {"W": 8, "n": 8, "alpha": 84}
    if "E" in options and "density" in options:
        base["material"] = "dura-lar"
    with pytest.raises(InputError) as exc:
        assembly_from_options(**{**base, **options})  # type: ignore[arg-type]
    assert exc.value.field == field


def test_parse_int() -> None:
    assert parse_int("8", "n") == parse_int(8.0, "n") == parse_int(8, "n") == 8
    for bad in ("8.5", "eight", 8.5, None, False, float("inf")):
        with pytest.raises(InputError):
            parse_int(bad, "n")


def test_vertices_as_text_or_pairs() -> None:
    assert parse_vertices("0,0 1,0 0.5,1") == [(0, 0), (1, 0), (0.5, 1)]
    assert parse_vertices([[0, 0], (1, 0), [0.5, 1]]) == [(0, 0), (1, 0), (0.5, 1)]
    assert parse_vertices(None) is None
    for bad in ("0,0 1", [[0, 0, 0]], ["0,0"], [[True, 0]], 5):
        with pytest.raises(InputError) as exc:
            parse_vertices(bad)
        assert exc.value.field == "vertices"


def test_etas() -> None:
    assert parse_etas(None) == parse_etas([]) == DEFAULT_ETAS
    assert parse_etas([0, "45 deg", "1.5707963267948966 rad"]) == pytest.approx((0, 45, 90))
    for bad in (["nan"], [float("inf")], ["3 mm"]):
        with pytest.raises(InputError) as exc:
            parse_etas(bad)
        assert exc.value.field == "eta"


def test_analysis_request_runs_the_analysis() -> None:
    req = analysis_request(W=8, n=8, alpha=84, model="Paper", eta=[0])
    assert req.model == "paper" and req.eta_deg == (0.0,)
    ei_mNm2 = req.run().stiffness[0].EI / 1000
    assert ei_mNm2 == pytest.approx(87.84, abs=0.005)
    with pytest.raises(InputError) as exc:
        analysis_request(W=8, n=8, alpha=84, model="magic")
    assert exc.value.field == "model"
