"""A spec as the TOML file the command line reads, and a TOML file back into a spec's keys.

The web page saves its form as a spec file (``POST /api/spec/toml``) and loads one into the form
(``POST /api/spec/parse``); both go through :func:`corrugate.spec.schema.parse_spec`, the rules
``corrugate design FILE.toml`` applies, so a file the page saves is a file the CLI reads with the
same answer, and a file the page cannot read is refused with the CLI's one-line error naming the
key (the endpoints: :mod:`corrugate.web.app`).

:func:`spec_toml` writes a spec's keys (the JSON object of the page, the keys of the TOML file:
values with their units as the user wrote them, ``"80 mN*m^2"``) as TOML: top-level values, then
one ``[table]`` per top-level table whose own tables and arrays are inline
(``W = { min = "1 mm", max = "30 mm" }``, ``flexural_rigidity = [{ min = "80 mN*m^2" }]``), as
``examples/*.toml`` are written. A ``None`` value is left out (TOML has no null: the key's default
applies, as when the form leaves a field empty).
"""

from __future__ import annotations

import json
import math
import re
import tomllib
from collections.abc import Mapping, Sequence
from typing import Any

from corrugate.spec.schema import Spec, parse_spec, parse_spec_text

__all__ = ["read_spec_toml", "spec_toml", "toml_value"]

_BARE_KEY = re.compile(r"^[A-Za-z0-9_-]+$")


def _key(key: str) -> str:
    """A TOML key: bare when it may be, else a quoted basic string."""
    return key if _BARE_KEY.match(key) else _string(key)


def _string(text: str) -> str:
    """A TOML basic string: JSON's escapes (all TOML's too) and DEL escaped, which TOML forbids
    raw; no surrogate pairs (``ensure_ascii=False`` keeps every other character as it is)."""
    return json.dumps(text, ensure_ascii=False).replace("\x7f", "\\u007f")


def toml_value(value: Any) -> str:
    """One value as inline TOML: a string, a bool, an integer, a finite float, an array or an
    inline table (its ``None`` entries left out). Raises ``ValueError`` for anything else (a
    non-finite float, ``None`` itself, another type)."""
    if isinstance(value, bool):
        return "true" if value else "false"
    if isinstance(value, int):
        return str(value)
    if isinstance(value, float):
        if not math.isfinite(value):
            raise ValueError(f"{value!r} has no TOML form the spec accepts")
        return repr(value)
    if isinstance(value, str):
        return _string(value)
    if isinstance(value, Mapping):
        items = [f"{_key(str(k))} = {toml_value(v)}" for k, v in value.items() if v is not None]
        return "{ " + ", ".join(items) + " }" if items else "{}"
    if isinstance(value, Sequence):
        return "[" + ", ".join(toml_value(v) for v in value) + "]"
    raise ValueError(f"a {type(value).__name__} has no TOML form")


def spec_toml(data: Mapping[str, Any], comments: Sequence[str] = ()) -> str:
    """The TOML text of a spec's keys ``data`` (module docstring), after ``comments`` (lines
    written as ``# ...`` at the top). ``data`` is validated first by
    :func:`~corrugate.spec.schema.parse_spec`: a bad value raises its
    :class:`~corrugate.spec.schema.SpecError` naming the key, and nothing is written."""
    parse_spec(dict(data))
    lines = [f"# {c}" if c else "#" for c in comments]
    tables = [(k, v) for k, v in data.items() if isinstance(v, Mapping)]
    for key, value in data.items():
        if value is not None and not isinstance(value, Mapping):
            lines.append(f"{_key(key)} = {toml_value(value)}")
    for key, table in tables:
        lines += ["", f"[{_key(key)}]"]
        lines += [f"{_key(str(k))} = {toml_value(v)}" for k, v in table.items() if v is not None]
    return "\n".join(lines).lstrip("\n") + "\n"


def read_spec_toml(text: str, shown: str = "<text>") -> tuple[Spec, dict[str, Any]]:
    """A spec file's text read as ``corrugate design`` reads it
    (:func:`~corrugate.spec.schema.parse_spec_text`: ``shown`` names it in errors): the validated
    spec and its keys as written (the values with their units, for a form); a byte-order mark
    at its start is not part of the text."""
    text = text.removeprefix("\ufeff")
    spec = parse_spec_text(text, shown)
    return spec, tomllib.loads(text)
