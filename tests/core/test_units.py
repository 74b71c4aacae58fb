"""Quantities at the boundary: plain numbers in the default unit, strings with units read by the
unit grammar (pint given single names only)."""

from __future__ import annotations

import contextlib
import os
import re
import subprocess
import sys
import time
from pathlib import Path
from typing import Any

import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from corrugate.core.errors import InputError
from corrugate.core.units import parse_quantity


@pytest.mark.parametrize(
    ("value", "unit", "expected"),
    [
        (8, "mm", 8.0),
        ("8", "mm", 8.0),
        ("0.3 in", "mm", 7.62),
        ("5 mil", "mm", 0.127),  # sheet gauges: a mil is a thousandth of an inch
        ("2.7GPa", "MPa", 2700.0),
        ("1.39 g/cm^3", "g/cm^3", 1.39),
        ("1390 kg/m^3", "g/cm^3", 1.39),
        ("80 mN*m^2", "N*mm^2", 80_000.0),  # the paper's EI bound in internal units
        ("0.5 turn", "deg", 180.0),
    ],
)
def test_conversions(value: object, unit: str, expected: float) -> None:
    assert parse_quantity(value, unit, "x") == pytest.approx(expected)


@pytest.mark.parametrize(
    ("value", "reason"),
    [
        ("3 GPa", "wrong dimension"),
        ("5 percent", "wrong dimension"),
        ("5 bogons", "unknown unit"),
        ("1.2.3 mm", "cannot be read"),
        ("abc", "cannot be read"),
        (None, "is not a number"),
        (True, "is not a number"),
    ],
)
def test_rejections_name_the_field(value: object, reason: str) -> None:
    with pytest.raises(InputError, match=rf"^W = .* {reason}.*: allowed .*mm"):
        parse_quantity(value, "mm", "W")


def test_every_table_unit_is_pints() -> None:
    """The units read without pint: each entry's SI value and dimension are pint's own."""
    from corrugate.core.units import _TABLE, _table_key, ureg

    reg = ureg()
    base = {"[length]": 0, "[mass]": 1, "[time]": 2}
    for text, (factor, dims) in _TABLE.items():
        q = reg.Quantity(1.0, reg.Unit(text)).to_base_units()
        assert q.magnitude == pytest.approx(factor, rel=1e-12), text
        expected = [0, 0, 0]
        for name, power in q.dimensionality.items():
            expected[base[name]] = power
        assert tuple(expected) == dims[:3], text
        # the angle column: pint's radian is dimensionless, so an angle has dims (0, 0, 0, 1)
        assert dims[3] == (
            1
            if reg.Unit(text).is_compatible_with("radian")
            and text not in ("dimensionless", "percent")
            else 0
        ), text
        assert _table_key(text) == text


@pytest.mark.parametrize(
    ("value", "unit"),
    [
        ("80 mN * m ^ 2", "N*mm^2"),
        ("80 mN m**2", "N*mm^2"),
        ("3 ksi", "MPa"),
        ("12 lbf", "N"),
        ("1 turn", "deg"),
        ("2 oz", "g"),
        ("0.5 N*m", "N*mm"),
        ("250 N/m", "N/mm"),
        ("1 rad", "dimensionless"),  # an angle to a pure number: pint's rule (radian = 1)
        ("3 kg/m^3", "g/cm^3"),
    ],
)
def test_table_and_pint_agree(value: str, unit: str) -> None:
    """A quantity converts to the same number on the table's path and on pint's."""
    from corrugate.core.units import ureg

    reg = ureg()
    magnitude, text = value.split(" ", 1)
    expected = reg.Quantity(float(magnitude), reg.Unit(text)).to(reg.Unit(unit))
    assert parse_quantity(value, unit, "x") == pytest.approx(float(expected.magnitude), rel=1e-12)


@pytest.mark.slow
def test_a_spec_in_common_units_does_not_import_pint_or_dask(tmp_path: Path) -> None:
    """Start-up: a whole spec in the usual units is read without pint; a rarer unit brings pint in
    (from its disk cache) but not dask."""
    script = (
        "import sys\n"
        "from corrugate.spec.schema import load_spec\n"
        "load_spec(sys.argv[1])\n"
        "assert 'pint' not in sys.modules, 'pint'\n"
        "from corrugate.core.units import parse_quantity\n"
        "assert abs(parse_quantity('2 yard', 'mm', 'x') - 1828.8) < 1e-9\n"
        "assert 'pint' in sys.modules and 'dask' not in sys.modules, sorted(sys.modules)\n"
    )
    env = {**os.environ, "CORRUGATE_PINT_CACHE": str(tmp_path / "cache")}
    spec = Path(__file__).resolve().parents[2] / "examples" / "blimp_gripper.toml"
    for _ in range(2):  # the second run reads the cache the first wrote
        done = subprocess.run(
            [sys.executable, "-c", script, str(spec)], env=env, capture_output=True, text=True
        )
        assert done.returncode == 0, done.stderr
    assert any((tmp_path / "cache").iterdir())


# ---- the unit grammar (corrugate.core.unit_grammar): every accepted form, every hostile class ----


@pytest.mark.parametrize(
    ("value", "unit"),
    [
        ("0.3 in", "mm"),
        ("2.7GPa", "MPa"),
        ("84 deg", "deg"),
        ("1.4 rad", "deg"),
        ("80 mN*m^2", "N*mm^2"),
        ("80 mN m^2", "N*mm^2"),
        ("1.2 g/cm^3", "g/cm^3"),
        ("0.125 mm", "mm"),
        ("3 N/mm", "N/mm"),
        ("4 N*mm", "N*mm"),
        ("5 lbf/in", "N/mm"),
        ("6 kgf/mm^2", "MPa"),
        ("2 yard", "mm"),
        ("0.8 cm", "mm"),
        ("2 km", "mm"),
        ("7 N/mm m", "N"),  # pint's reading: left to right, (N / mm) * m
        ("2 (N/mm)^2", "N^2/mm^2"),
        ("3 N/mm/mm", "MPa"),
        ("4 1/mm", "1/mm"),
        ("5 N·mm", "N*mm"),
        ("6 mm²", "mm^2"),
        ("7 mm⁻²", "1/mm^2"),
        ("8 N per mm", "N/mm"),
        ("9 square mm", "mm^2"),
        ("2 sq in", "mm^2"),
        ("3 cubic cm", "mm^3"),
        ("4 mm squared", "mm^2"),
        ("5 cm cubed", "mm^3"),
        ("6 g per cubic cm", "g/cm^3"),
        ("3 µm", "mm"),
        ("30 °", "deg"),
        ("5 %", "dimensionless"),
        ("1 inch_Hg", "MPa"),
        ("2 mm^-1", "1/m"),
        ("3 ((((mm))))", "mm"),  # four levels: the deepest allowed
        ("4 lbf in", "N*mm"),
        ("  5   mN  *  m ^ 2 ", "N*mm^2"),
    ],
)
def test_accepted_forms_keep_pints_value(value: str, unit: str) -> None:
    """Each accepted form converts to the number pint's own parser gives for the same text (a
    second method: pint evaluates these harmless texts itself)."""
    from corrugate.core.units import ureg

    reg = ureg()
    magnitude, text = value.strip().split(maxsplit=1) if " " in value.strip() else (value, "")
    if not text:  # "2.7GPa": the number and the unit written together
        magnitude, text = value[:3], value[3:]
    expected = reg.Quantity(float(magnitude), reg.Unit(text)).to(reg.Unit(unit)).magnitude
    assert parse_quantity(value, unit, "x") == pytest.approx(float(expected), rel=1e-12)


@pytest.mark.parametrize(
    ("value", "unit", "expected"),
    [
        ("5 mil", "mm", 0.127),  # a mil (thou) is 0.0254 mm, not pint's milliradian
        ("0.3 in", "mm", 7.62),  # 0.3 * 25.4
        ("80 mN m^2", "N*mm^2", 80_000.0),  # 80e-3 N * 1e6 mm^2
        ("1.2 g/cm^3", "g/mm^3", 1.2e-3),  # 1 cm^3 = 1000 mm^3
        ("3 N/mm/mm", "MPa", 3.0),  # N/mm^2 is MPa
        ("2 (N/mm)^2", "N^2/m^2", 2e6),  # (1000 N/m)^2
        ("6 mm²", "cm^2", 0.06),
        ("1 kgf/mm^2", "MPa", 9.80665),  # standard gravity
        ("4 N per square mm", "MPa", 4.0),
    ],
)
def test_accepted_forms_by_hand(value: str, unit: str, expected: float) -> None:
    """The same forms against hand conversions (no pint on the expected side)."""
    assert parse_quantity(value, unit, "x") == pytest.approx(expected, rel=1e-12)


def test_a_zero_exponent_is_the_number_one() -> None:
    """``mm**-0`` and ``mm^0`` are read as dimensionless (mm^0 = 1): a pure number keeps its value,
    and a length field refuses them as the wrong dimension instead of reading them as mm."""
    assert parse_quantity("2 mm**-0", "dimensionless", "nu") == 2.0
    assert parse_quantity("3 mm^0 N", "N", "F") == 3.0
    for text in ("1 mm**-0", "1 mm^0"):
        with pytest.raises(InputError, match=r"^W = .* wrong dimension \(dimensionless\)"):
            parse_quantity(text, "mm", "W")


HOSTILE = [
    ("1 mm**9**9**9", "exponent of an exponent"),
    ("1 mm^9^9", "exponent of an exponent"),
    ("1 mm^2^2", "exponent of an exponent"),
    ("1 mm²^2", "exponent of an exponent"),
    ("1 mm**99", "exponent '\\*\\*99' that is too large"),
    ("1 mm^5", "too large"),
    ("1 mm^-5", "too large"),
    ("1 mm^99999999999999999999999999999", "too large"),
    ("1 mm**2.5", "not a whole number"),
    ("1 mm/0", "divides its unit by zero"),
    ("1 mm/0.0", "divides its unit by zero"),
    ("1 mm*2", "number '2' inside its unit"),
    ("1 mm/(0)", "number '0' inside its unit"),
    ("1 mm**(1/0)", "parenthesised exponent"),
    ("1 mm**(9**9)", "parenthesised exponent"),
    ("1 mm^(2)", "parenthesised exponent"),
    ("1 (mm", "unbalanced parenthesis"),
    ("1 mm)", "unbalanced parenthesis"),
    ("1 (mm))", "unbalanced parenthesis"),
    ("1 ((((mm)))", "unbalanced parenthesis"),
    ("1 (((((mm)))))", "nested more than 4 deep"),
    ("1 " + "(" * 1000 + "mm" + ")" * 1000, "longer than 64 characters"),
    ("1 " + "(" * 30 + "mm" + ")" * 30, "nested more than 4 deep"),
    ("1 " + "m" * 100_000, "longer than 64 characters"),
    ("1 " + "mm*" * 30 + "mm", "longer than 64 characters"),
    ("1 (((mm^4)^4)^4)", "power 64"),
    ("1 (mm^4)^4 mm", "power 17"),
    ("1 mm\x00", "unexpected character '\\\\x00'"),
    ("1 \x00", "unexpected character"),
    ("1 mm;import os", "unexpected character ';'"),
    ("1 mm.__class__", "unexpected character '\\.'"),
    ("1 mm[0]", "unexpected character '\\['"),
    ("1 mm-2", "unexpected '-'"),
    ("1 mm^", "no exponent"),
    ("1 mm^-", "no exponent"),
    ("1 mm*", "incomplete unit"),
    ("1 mm/", "incomplete unit"),
    ("1 /mm", "where a unit name belongs"),
    ("1 ()", "unit name missing before '\\)'"),
    ("1 mm²²", "exponent '²²' that is too large"),  # pint reads it as mm**22
    ("1 mm⁹", "too large"),
    ("1 ^2", "where a unit name belongs"),
    ("1 mm**", "no exponent"),
    ("1 degC*mm", "wrong dimension"),
    ("1 bogon^2", "unknown unit"),
    ("1 °9", "unknown unit"),
]


#: CPU seconds past which a parse counts as hung (an exponent tower: never ending). Not a speed
#: check (speed is measured in benchmarks): wall-clock 0.5 s, as before, failed a CI run on a
#: loaded 2-core machine at 0.52 s for "1 NNN".
HANG_CPU_S = 5.0


@pytest.mark.parametrize(("value", "reason"), HOSTILE)
def test_hostile_units_are_one_input_error_naming_the_field(value: str, reason: str) -> None:
    """Every hostile class is refused quickly with one InputError that names the field (an
    exponent tower once never ended: :data:`HANG_CPU_S` of CPU is a hang, not a slow machine)."""
    start = time.process_time()
    with pytest.raises(InputError, match=rf"^W = .*{reason}.*: allowed ") as exc:
        parse_quantity(value, "mm", "W")
    assert time.process_time() - start < HANG_CPU_S
    assert exc.value.field == "W"
    assert len(str(exc.value)) < 600  # one line, a long text cut short
    assert "\n" not in str(exc.value)


def _assert_float_or_input_error(text: str) -> None:
    """``parse_quantity(text)`` is a float or one InputError naming the field, within
    :data:`HANG_CPU_S` of CPU."""
    start = time.process_time()
    outcome: object
    try:
        outcome = parse_quantity(text, "mm", "W")
    except InputError as exc:
        outcome = exc
    assert time.process_time() - start < HANG_CPU_S, repr(text)
    if isinstance(outcome, InputError):
        assert outcome.field == "W", repr(text)
        assert str(outcome).startswith("W = "), repr(text)
    else:
        assert isinstance(outcome, float), repr(text)


def test_binary_junk_is_an_input_error() -> None:
    """Random bytes read as text (every code point 0-255, in a fixed shuffled order): an
    InputError or, for the rare readable text, a number; never another exception."""
    import random

    rng = random.Random(22)
    for _ in range(300):
        junk = bytes(rng.randrange(256) for _ in range(rng.randrange(1, 40))).decode("latin-1")
        for text in (junk, "1 " + junk, "1 mm" + junk):
            _assert_float_or_input_error(text)


_PIECES = ["mm", "m", "N", "mN", "in", "g", "cm", "deg", "%", "°", "µm", "per", "square", "squared"]
_ALPHABET = "mNgcinµ°% ()*/^·-+0123456789.²⁻\t"


@settings(max_examples=300, deadline=None, derandomize=True)
@given(
    st.text(alphabet=_ALPHABET, max_size=70)
    | st.lists(
        st.sampled_from([*_PIECES, *"()*/^·", "**", " ", "9", "-1", "0", "2"]), max_size=30
    ).map("".join)
)
def test_random_texts_of_the_grammar_are_a_float_or_an_input_error(unit_text: str) -> None:
    """Random texts over the grammar's alphabet (characters, or its pieces joined): each is a
    float or one InputError naming the field, within HANG_CPU_S of CPU."""
    from corrugate.core.units import ureg

    ureg()  # pint's registry loaded before the clock starts
    for text in (unit_text, "1 " + unit_text):
        _assert_float_or_input_error(text)


# ---- the same refusals at the command line and in a spec (subprocesses with a time limit) ----

TOWER = "1 mm**9**9**9"


def _corrugate(*args: str, timeout: float = 60) -> subprocess.CompletedProcess[str]:
    """``python -m corrugate ARGS`` in a fresh process, killed after ``timeout`` seconds (before
    the grammar, an exponent tower never ended)."""
    return subprocess.run(
        [sys.executable, "-m", "corrugate", *args],
        capture_output=True,
        text=True,
        timeout=timeout,
        env={**os.environ, "COLUMNS": "200"},
    )


@pytest.mark.slow
@pytest.mark.parametrize("text", [TOWER, "1 mm/0", "1 mm**(1/0)", "1 mm**-0", "1 (mm"])
def test_cli_option_with_a_hostile_unit_exits_2_naming_the_option(text: str) -> None:
    """``corrugate analyze --W TEXT``: exit 2 (bad input) with one line naming W, quickly."""
    start = time.perf_counter()
    done = _corrugate("analyze", "--W", text, "--n", "8", "--alpha", "84")
    assert time.perf_counter() - start < 30  # a fresh interpreter importing the package
    assert done.returncode == 2, done.stderr
    lines = done.stderr.strip().splitlines()
    assert len(lines) == 1, done.stderr
    assert lines[0].startswith("corrugate: error: W = ") and repr(text) in lines[0]
    assert done.stdout == ""


@pytest.mark.slow
def test_spec_quantity_with_an_exponent_tower_exits_2_naming_the_key(tmp_path: Path) -> None:
    """A TOML spec whose ``constraints.side.min`` is an exponent tower: ``corrugate design``
    exits 2 with one line naming the key, writes nothing, and does not hang."""
    example = Path(__file__).resolve().parents[2] / "examples" / "blimp_gripper.toml"
    text = example.read_text(encoding="utf-8")
    assert 'side = { min = "48 mm"' in text
    spec = tmp_path / "tower.toml"
    spec.write_text(text.replace('side = { min = "48 mm"', 'side = { min = "48 mm**9**9**9"'))
    out = tmp_path / "out"
    done = _corrugate("design", str(spec), "--out", str(out))
    assert done.returncode == 2, done.stderr
    lines = done.stderr.strip().splitlines()
    assert len(lines) == 1, done.stderr
    assert lines[0].startswith("corrugate: error: constraints.side.min = '48 mm**9**9**9' ")
    assert "exponent of an exponent" in lines[0]
    assert not out.exists()


def test_pint_is_given_single_unit_names_only(monkeypatch: pytest.MonkeyPatch) -> None:
    """Whatever the text, pint's parser sees one unit name at a time (plus the caller's own target
    unit): the expression itself is never handed to pint."""
    from corrugate.core.units import ureg

    reg = ureg()
    seen: list[object] = []
    unit_class = reg.Unit

    def recording(text: object) -> Any:
        seen.append(text)  # pint itself passes its parsed containers too (not texts)
        return unit_class(text)

    monkeypatch.setattr(reg, "Unit", recording)
    for text in ("2 yard/s^2", "3 (lbf/in)^2", "1 N per square ft", "4 inch_Hg·m³", "5 mm**9"):
        with contextlib.suppress(InputError):
            parse_quantity(text, "mm", "W")
    names = [t for t in seen if isinstance(t, str) and t not in ("mm", "dimensionless")]
    assert names and all(re.fullmatch(r"°?\w+|%", t) for t in names), seen
    assert {"yard", "s", "lbf", "in", "N", "ft", "inch_Hg", "m"} <= set(names)


def test_a_size_beyond_a_float_is_an_input_error() -> None:
    """(quettaparsec^4)^4 in mm^16 is about 1e793: beyond a float, refused as not convertible
    rather than an OverflowError."""
    with pytest.raises(InputError, match=r"^x = .* cannot be converted to mm\^16"):
        parse_quantity("1 (quettaparsec^4)^4", "mm^16", "x")
