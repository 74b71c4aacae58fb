"""The schema of ``design.json`` as a reader trusts it: a file a user may have edited by hand.

:func:`validate_record` checks the keys a design's folder is read back by (``corrugate verify``,
``corrugate validate --design``, the web app's verification) with the same limits as a spec
(:data:`corrugate.core.limits.LIMITS`): each layer's ``W_mm``, ``alpha_deg`` and ``t_mm`` finite
and in range, its ``n`` an integer in range (``11.5`` and a 400-digit ``n`` are refused, never
rounded or overflowed); each constraint's ``sense`` min or max, its ``bound`` and ``value`` finite
numbers (a behavioural bound positive), its ``quantity`` a key the registry reads
(``kcant@banana`` is refused, so is a direction, span or duration that is not a finite number),
its ``test`` a registered load case and the one its quantity names (``five-point`` is refused),
its ``load_N``, ``failure_loads_N`` and ``safety_factor`` positive and finite; the ``joint`` a known one. Every
integer has at most :data:`~corrugate.core.limits.MAX_INT_DIGITS` digits. Text is stripped of
control characters (:func:`corrugate.core.text.printable`: a constraint's name never sends an
escape sequence to the terminal). The first failure is one
:class:`~corrugate.core.errors.InputError` line naming the key (``design.json:
constraints[3].bound``), the value and what is allowed (docs/fea.md section 6: bad input is exit
2, before any CalculiX run).
"""

from __future__ import annotations

import math
from collections.abc import Callable, Mapping
from typing import Annotated, Any

from pydantic import BaseModel, BeforeValidator, ConfigDict, ValidationError, model_validator
from pydantic_core import PydanticCustomError

from corrugate.core.errors import InputError
from corrugate.core.limits import (
    LIMITS,
    MAX_INT_DIGITS,
    MAX_NAME_CHARS,
    MAX_TEXT_CHARS,
    abnormal_reason,
    integer_shown,
)
from corrugate.core.text import printable

__all__ = ["JOINTS", "MAX_CONSTRAINTS", "validate_record"]

#: The joints a design.json may name (:func:`corrugate.fea.verify.joint_options`).
JOINTS = ("none", "band-edges", "band-flanges")
#: Most constraints a design.json may list (a spec has at most 32 behavioural bounds and a few
#: dozen geometric and validity ones).
MAX_CONSTRAINTS = 1000


def _fail(reason: str, allowed: str) -> PydanticCustomError:
    return PydanticCustomError("record", "{reason}", {"reason": reason, "allowed": allowed})


def _real(x: Any, allowed: str) -> float:
    """``x`` as a finite float, or the validation error saying why it is not one."""
    if isinstance(x, bool) or not isinstance(x, int | float):
        raise _fail("is not a number", allowed)
    if isinstance(x, int) and abs(x) >= 10**MAX_INT_DIGITS:
        raise _fail(f"is too long (at most {MAX_INT_DIGITS} digits)", allowed)
    value = float(x)
    reason = abnormal_reason(value)
    if reason is not None:
        raise _fail(reason, allowed)
    return value


def _limited(key: str) -> Callable[[Any], float]:
    """A before-validator: a number within ``LIMITS[key]``."""
    lim = LIMITS[key]

    def check(x: Any) -> float:
        value = _real(x, lim.allowed)
        if not lim.contains(value):
            raise _fail("is out of range", lim.allowed)
        return value

    return check


def _finite(x: Any) -> float:
    return _real(x, "a finite number")


def _positive(x: Any) -> float:
    value = _real(x, "a finite number > 0")
    if value <= 0:
        raise _fail("is not positive", "a finite number > 0")
    return value


def _load(x: Any) -> float:
    """A load (N): > 0 and at most ``LIMITS["load"]``'s top (a zero load deflects nothing)."""
    hi = LIMITS["load"].hi
    allowed = f"0 < load_N <= {hi:g} N"
    value = _real(x, allowed)
    if not 0 < value <= hi:
        raise _fail("is out of range", allowed)
    return value


def _count(x: Any) -> int:
    lim = LIMITS["n"]
    if isinstance(x, bool) or not isinstance(x, int):
        raise _fail("is not an integer", f"an integer {lim.lo:g} <= n <= {lim.hi:g}")
    if not lim.lo <= x <= lim.hi:
        raise _fail("is out of range", f"an integer {lim.lo:g} <= n <= {lim.hi:g}")
    return x


def _text(limit: int) -> Callable[[Any], str]:
    def check(x: Any) -> str:
        if not isinstance(x, str):
            raise _fail("is not text", "a string")
        if len(x) > limit:
            raise _fail("is too long", f"at most {limit} characters")
        return printable(x, limit)

    return check


def _loads(x: Any) -> dict[str, float] | None:
    if x is None:
        return None
    if not isinstance(x, Mapping) or len(x) > 100:
        raise _fail("is malformed", "an object of failure modes and loads (N)")
    out = {}
    for k, v in x.items():
        out[printable(k, MAX_NAME_CHARS)] = _positive(v)
    return out


Text = Annotated[str, BeforeValidator(_text(MAX_TEXT_CHARS))]
Name = Annotated[str, BeforeValidator(_text(MAX_NAME_CHARS))]
Finite = Annotated[float, BeforeValidator(_finite)]
Positive = Annotated[float, BeforeValidator(_positive)]
Load = Annotated[float, BeforeValidator(_load)]


class _Layer(BaseModel):
    model_config = ConfigDict(extra="allow")

    W_mm: Annotated[float, BeforeValidator(_limited("W"))]
    n: Annotated[int, BeforeValidator(_count)]
    alpha_deg: Annotated[float, BeforeValidator(_limited("alpha"))]
    material: Name
    t_mm: Annotated[float, BeforeValidator(_limited("thickness"))]
    material_properties: dict[str, Any] | None = None


class _Constraint(BaseModel):
    model_config = ConfigDict(extra="allow")

    name: Text | None = None
    quantity: Name
    sense: Name = "min"
    unit: Name = ""
    bound: Finite | None = None
    value: Finite | None = None
    load_N: Load | None = None
    test: Name | None = None
    failure_loads_N: Annotated[dict[str, float] | None, BeforeValidator(_loads)] = None
    safety_factor: Positive | None = None

    @model_validator(mode="after")
    def _behavioural(self) -> _Constraint:
        if self.sense not in ("min", "max"):
            raise _at("sense", "is not min or max", "min or max")
        if "@" not in self.quantity:
            return self
        q = _quantity(self.quantity)
        if self.bound is None or self.bound <= 0:
            raise _at("bound", "is missing or not positive", "a finite number > 0")
        if q.kind == "k" and self.unit == "mm" and self.load_N is None:
            raise _at("load_N", "is missing", "the load of a deflection bound (N) > 0")
        if self.test is not None:
            from corrugate.mechanics.behaviours import load_cases, own_test

            names = [t.name for t in load_cases()]
            if self.test not in names:
                raise _at("test", "is unknown", "one of " + ", ".join(names))
            if self.test != (q.test or own_test().name):
                raise _at("test", "is not the test of its quantity", f"{q.test or own_test().name}")
        return self


def _at(key: str, reason: str, allowed: str) -> PydanticCustomError:
    return PydanticCustomError(
        "record", "{reason}", {"reason": reason, "allowed": allowed, "key": key}
    )


def _quantity(key: str) -> Any:
    """The quantity of a behavioural constraint's key, read strictly: a direction, span,
    duration and bearing that are finite numbers (span, duration, bearing positive)."""
    from corrugate.solver.quantity import Quantity

    allowed = "a quantity key such as EI@0 or k3pt@0/L=120"
    try:
        q = Quantity.parse(key)
    except (InputError, ValueError, OverflowError):
        raise _at("quantity", "is not a quantity key", allowed) from None
    eta = q.eta
    if eta is None or not math.isfinite(eta):
        raise _at("quantity", "has no finite direction", allowed)
    for part in (q.span, q.duration, q.bearing):
        if part is not None and not (math.isfinite(part) and 0 < part <= LIMITS["length"].hi):
            raise _at("quantity", "has a span, duration or bearing out of range", allowed)
    return q


class _Record(BaseModel):
    model_config = ConfigDict(extra="allow")

    layers: list[_Layer] | None = None
    constraints: list[_Constraint] | None = None
    joint: Name = "none"

    @model_validator(mode="after")
    def _joint(self) -> _Record:
        if self.joint not in JOINTS:
            raise _at("joint", "is unknown", ", ".join(JOINTS))
        if self.constraints is not None and len(self.constraints) > MAX_CONSTRAINTS:
            raise _at("constraints", "has too many items", f"at most {MAX_CONSTRAINTS}")
        return self


def validate_record(data: Mapping[str, Any], where: str = "design.json") -> dict[str, Any]:
    """``data`` (a design.json object) checked by the schema (module docstring), as the reader
    takes it: every key kept, the checked ones as read (text without control characters, numbers
    as floats, ``n`` an int); one :class:`InputError` line naming ``where: KEY`` otherwise."""
    try:
        model = _Record.model_validate(dict(data))
    except ValidationError as exc:
        raise _error(exc, data, where) from None
    out = dict(data)
    dumped = model.model_dump(exclude_unset=True)
    for key in ("layers", "constraints", "joint"):
        if key in dumped:
            out[key] = dumped[key]
    return out


def _error(exc: ValidationError, data: Mapping[str, Any], where: str) -> InputError:
    err = exc.errors()[0]
    loc = [p for p in err["loc"]]
    ctx = err.get("ctx") or {}
    if "key" in ctx:  # a check of the whole entry names its key
        loc.append(str(ctx["key"]))
        value = _lookup(data, loc)
    else:
        value = err.get("input")
    path = "".join(f"[{p}]" if isinstance(p, int) else f".{p}" for p in loc).lstrip(".")
    if isinstance(value, int) and not isinstance(value, bool):
        shown = integer_shown(value)
    else:
        shown = printable(repr(value), 60)
    allowed = str(ctx.get("allowed", "see docs/fea.md section 6"))
    reason = str(ctx.get("reason", str(err["msg"]).lower()))
    if err["type"] == "missing":
        shown, reason, allowed = "None", "is missing", "a value"
    return InputError(f"{where}: {path or 'design'}", shown, allowed, reason=reason)


def _lookup(data: Any, loc: list[Any]) -> Any:
    for p in loc:
        try:
            data = data[p]
        except (KeyError, IndexError, TypeError):
            return None
    return data
