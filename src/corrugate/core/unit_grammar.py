"""The grammar of unit texts: a unit expression read into unit names and small integer powers.

A quantity string is a number and a unit (:func:`corrugate.core.units.parse_quantity`); this module
reads the unit, with a grammar of its own instead of an expression evaluator, so that no text can
make the reader compute more than a few multiplications::

    unit     := term (op term)*                  op: "*", "/", "·" or a space (multiplication)
    term     := atom [exponent]
    atom     := NAME | "1" | "(" unit ")"        parentheses nested at most MAX_DEPTH deep
    exponent := ("^" | "**") [+-] DIGITS | SUPERSCRIPTS     |exponent| <= MAX_EXPONENT

``*``, ``/`` and implicit multiplication share one precedence and group from the left (pint's own
reading: ``N/mm m`` is N m / mm); pint's words are read as it reads them (``N per mm``,
``square mm``, ``sq mm``, ``cubic cm``, ``mm squared``, ``cm cubed``). A NAME is an identifier
without superscript digits (``mm``, ``mN``, ``inch_Hg``, ``µm``), ``°`` with an optional identifier
after it (``°``, ``°C``), or ``%``; it is looked up later as one name.
There is no exponent of an exponent (``mm^2^2``) and no parenthesised exponent (``mm^(1/2)``); a
number inside a unit is refused (``mm/0``: division by zero; ``mm*2``: a scaling factor) except
``1`` (``1/mm``); ``mm^0`` is the pure number 1 (dimensionless). The whole unit text has at most
:data:`MAX_LENGTH` characters and each name's power, summed over the expression, stays within
:data:`MAX_POWER`. Every refusal is an :class:`~corrugate.core.errors.InputError` naming the field.
"""

from __future__ import annotations

import re
from dataclasses import dataclass

from corrugate.core.errors import InputError

__all__ = ["MAX_DEPTH", "MAX_EXPONENT", "MAX_LENGTH", "MAX_POWER", "parse_unit"]

#: The longest unit text read (characters after the number).
MAX_LENGTH = 64
#: The largest absolute value of one written exponent (``mm^4``, ``mm**-4``).
MAX_EXPONENT = 4
#: The deepest nesting of parentheses.
MAX_DEPTH = 4
#: The largest absolute power one unit name reaches over the whole expression (``(mm^4)^4`` is 16).
MAX_POWER = 16

_SUPERSCRIPTS = str.maketrans("⁰¹²³⁴⁵⁶⁷⁸⁹⁺⁻", "0123456789+-")
_TOKEN = re.compile(
    r"""
    (?P<space>\s+)
  | (?P<name>(?:(?![⁰¹²³⁴⁵⁶⁷⁸⁹⁺⁻])[^\W\d]|°)(?:(?![⁰¹²³⁴⁵⁶⁷⁸⁹])\w)*|%)
  | (?P<number>\d+(?:\.\d*)?|\.\d+)
  | (?P<power>\*\*|\^)
  | (?P<times>[*·])
  | (?P<divide>/)
  | (?P<open>\()
  | (?P<close>\))
  | (?P<superscript>[⁺⁻]?[⁰¹²³⁴⁵⁶⁷⁸⁹]+)
  | (?P<sign>[-+])
    """,
    re.VERBOSE,
)
#: pint's words for exponents: before a name (``square mm``) and after a unit (``mm squared``).
_WORD_BEFORE = {"square": 2, "sq": 2, "cubic": 3}
_WORD_AFTER = {"squared": "²", "cubed": "³"}
_ALLOWED = (
    "unit names joined by '*', '/', '·' or a space, each with an optional whole exponent "
    f"'^n' or '**n' (|n| <= {MAX_EXPONENT}), parentheses at most {MAX_DEPTH} deep, "
    "such as 'N/mm^2' or 'mN m^2'"
)


def _shown(value: object, limit: int = 2 * MAX_LENGTH) -> str:
    """``repr(value)`` for a message, a long text cut short with its length said."""
    text = repr(value)
    return text if len(text) <= limit else f"{text[:limit]}... ({len(str(value))} characters)"


@dataclass(frozen=True)
class _Token:
    kind: str
    text: str
    space_before: bool


def _tokens(text: str, field: str, value: object) -> list[_Token]:
    """The tokens of ``text`` (spaces folded into the next token's ``space_before``)."""
    out: list[_Token] = []
    pos, space = 0, False
    while pos < len(text):
        m = _TOKEN.match(text, pos)
        if m is None:
            raise InputError(
                field,
                _shown(value),
                _ALLOWED,
                reason=f"has an unexpected character {text[pos]!r} in its unit",
            )
        kind = m.lastgroup or ""
        if kind == "space":
            space = True
        else:
            out.append(_Token(kind, m.group(), space))
            space = False
        pos = m.end()
    return out


class _Parser:
    """Recursive descent over the tokens; each method returns powers {name: exponent}."""

    def __init__(self, tokens: list[_Token], field: str, value: object) -> None:
        self.tokens = tokens
        self.i = 0
        self.field = field
        self.value = value

    def fail(self, reason: str, allowed: str = _ALLOWED) -> InputError:
        return InputError(self.field, _shown(self.value), allowed, reason=reason)

    def peek(self) -> _Token | None:
        return self.tokens[self.i] if self.i < len(self.tokens) else None

    def unit(self, depth: int) -> dict[str, int]:
        powers = self.term(depth)
        while (tok := self.peek()) is not None and tok.kind != "close":
            if tok.kind in ("times", "divide") or (tok.kind, tok.text) == ("name", "per"):
                self.i += 1
                sign = 1 if tok.kind == "times" else -1
            elif tok.kind in ("name", "number", "open"):
                sign = 1  # a unit right after a unit: implicit multiplication
            elif tok.kind in ("power", "superscript"):
                raise self.fail(
                    f"has an exponent of an exponent (at {tok.text!r})",
                    "one whole exponent per unit or parenthesis, such as 'mm^2' or '(N/mm)^2'",
                )
            else:
                raise self.fail(f"has an unexpected {tok.text!r} in its unit")
            nxt = self.peek()
            if sign < 0 and nxt is not None and nxt.kind == "number" and float(nxt.text) == 0:
                raise self.fail("divides its unit by zero")
            powers = self.combine(powers, self.term(depth), sign)
        return powers

    def term(self, depth: int) -> dict[str, int]:
        tok = self.peek()
        before = self.tokens[self.i + 1] if self.i + 1 < len(self.tokens) else None
        if tok is not None and tok.text in _WORD_BEFORE and before and before.kind == "name":
            self.i += 1  # "square mm", "cubic cm": pint's words for ^2 and ^3
            powers = self.combine({}, self.atom(depth), _WORD_BEFORE[tok.text])
        else:
            powers = self.atom(depth)
        tok = self.peek()
        if tok is not None and tok.kind == "name" and tok.text in _WORD_AFTER:
            self.i += 1  # "mm squared", "cm cubed"
            tok = _Token("superscript", _WORD_AFTER[tok.text], tok.space_before)
        elif tok is None or tok.kind not in ("power", "superscript"):
            return powers
        else:
            self.i += 1
        if tok.kind == "superscript":
            written = tok.text
            exponent_text = tok.text.translate(_SUPERSCRIPTS)
        else:
            exponent_text = self.exponent_after(tok)
            written = tok.text + exponent_text
        after = self.peek()
        if after is not None and after.kind in ("power", "superscript"):
            raise self.fail(
                f"has an exponent of an exponent ('{written}{after.text}...')",
                "one whole exponent per unit or parenthesis, such as 'mm^2' or '(N/mm)^2'",
            )
        exponent = int(exponent_text)
        if abs(exponent) > MAX_EXPONENT:
            raise self.fail(
                f"has an exponent {written!r} that is too large",
                f"a whole exponent from -{MAX_EXPONENT} to {MAX_EXPONENT}",
            )
        return self.combine({}, powers, exponent)

    def exponent_after(self, power: _Token) -> str:
        """The text of the whole exponent after ``power`` (``^`` or ``**``), sign included."""
        sign = ""
        tok = self.peek()
        if tok is not None and tok.kind == "sign":
            sign = "" if tok.text == "+" else "-"
            self.i += 1
            tok = self.peek()
        if tok is not None and tok.kind == "open":
            raise self.fail(
                f"has a parenthesised exponent after {power.text!r}",
                f"a whole exponent written as a plain number from -{MAX_EXPONENT} to "
                f"{MAX_EXPONENT}, such as 'mm^-2'",
            )
        if tok is None or tok.kind != "number":
            raise self.fail(f"has no exponent after {power.text!r}")
        if not tok.text.isdigit():
            raise self.fail(
                f"has an exponent {tok.text!r} that is not a whole number",
                f"a whole exponent from -{MAX_EXPONENT} to {MAX_EXPONENT}",
            )
        self.i += 1
        return sign + tok.text

    def atom(self, depth: int) -> dict[str, int]:
        tok = self.peek()
        if tok is None:
            raise self.fail("has an incomplete unit (a unit name is missing at the end)")
        self.i += 1
        if tok.kind == "name":
            return {tok.text: 1}
        if tok.kind == "number":
            if float(tok.text) != 1:
                raise self.fail(
                    f"has a number {tok.text!r} inside its unit",
                    "unit names after the number, such as '2 mm' (a unit has no scaling factor)",
                )
            return {}
        if tok.kind == "open":
            if depth >= MAX_DEPTH:
                raise self.fail(
                    f"has parentheses nested more than {MAX_DEPTH} deep in its unit",
                    f"parentheses at most {MAX_DEPTH} deep",
                )
            powers = self.unit(depth + 1)
            close = self.peek()
            if close is None or close.kind != "close":
                raise self.fail("has an unbalanced parenthesis in its unit ('(' not closed)")
            self.i += 1
            return powers
        if tok.kind == "close":
            if depth > 0:
                raise self.fail("has a unit name missing before ')'")
            raise self.fail("has an unbalanced parenthesis in its unit (')' not opened)")
        raise self.fail(f"has an unexpected {tok.text!r} where a unit name belongs")

    def combine(self, a: dict[str, int], b: dict[str, int], power: int) -> dict[str, int]:
        """``a`` times ``b`` to the ``power``, each name's total power checked."""
        out = dict(a)
        for name, p in b.items():
            total = out.get(name, 0) + p * power
            if abs(total) > MAX_POWER:
                raise self.fail(
                    f"raises {name!r} to the power {total} in its unit",
                    f"powers of a unit from -{MAX_POWER} to {MAX_POWER}",
                )
            out[name] = total
        return out


def parse_unit(text: str, field: str, value: object) -> tuple[tuple[str, int], ...]:
    """The unit names of ``text`` with their total integer powers, in order of first appearance
    (names whose powers cancel are left out: ``mm/mm`` and ``mm^0`` are ``()``, the number 1).

    Refuses, with an :class:`InputError` naming ``field`` and showing ``value``, every text outside
    the grammar of the module docstring (length, characters, exponents, parentheses, numbers).
    """
    if len(text) > MAX_LENGTH:
        raise InputError(
            field,
            _shown(value),
            f"a unit text of at most {MAX_LENGTH} characters",
            reason=f"has a unit text longer than {MAX_LENGTH} characters",
        )
    parser = _Parser(_tokens(text, field, value), field, value)
    if not parser.tokens:
        raise parser.fail("has no unit")
    powers = parser.unit(0)
    extra = parser.peek()
    if extra is not None:  # only a ')' stops unit() at depth 0
        raise parser.fail("has an unbalanced parenthesis in its unit (')' not opened)")
    return tuple((name, p) for name, p in powers.items() if p != 0)
