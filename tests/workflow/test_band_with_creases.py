"""A design asked to be verified in FE with the connector band on a sheet with compliant creases
is refused before the search, in one line naming ``joint`` (the FE meshes the band with rigid
creases only; docs/calibration.md 10); without --verify fe it is designed as before."""

from __future__ import annotations

import pytest

from corrugate.core.errors import InputError
from corrugate.export.machines import get_machine
from corrugate.solver.problem import Problem
from corrugate.spec.examples import example_text
from corrugate.spec.schema import parse_spec_text
from corrugate.workflow.request import DesignRequest, FeOptions

CREASE = (
    '[material]\nE = "2700 MPa"\nnu = 0.43\ndensity = "1.39 g/cm^3"\nthickness = "0.125 mm"\n'
    'crease_stiffness = "{k}"\n'
)


def _request(k: str, fe: FeOptions | None) -> DesignRequest:
    text = example_text("blimp_gripper")
    head, _, rest = text.partition("[material]\n")
    _, _, tail = rest.partition("\n\n")
    text = 'joint = "band-edges"\n' + head + CREASE.format(k=k) + "\n" + tail
    spec = parse_spec_text(text)
    machine = get_machine("cameo4-12x12")
    return DesignRequest(spec, text, Problem.from_spec(spec), machine, fe=fe)


def test_the_band_with_compliant_creases_and_fe_is_refused_in_one_line() -> None:
    with pytest.raises(InputError) as info:
        _request("0.1 N*mm/(rad*mm)", FeOptions((2,), (0.0,), False))
    assert info.value.field == "joint" and "compliant creases" in str(info.value)
    assert "\n" not in str(info.value)


def test_without_fe_or_with_rigid_creases_it_is_a_request() -> None:
    assert _request("0.1 N*mm/(rad*mm)", None).fe is None
    assert _request("inf", FeOptions((2,), (0.0,), False)).fe is not None
