"""Text from a user or a file made safe to print: control characters removed, long values cut.

A name read from a spec, a ``design.json`` or a command-line argument can hold terminal escape
sequences (``ESC [ 31 m``), a bell, a backspace or a carriage return that rewrites what the line
already shows; printed as it is, it takes over the user's terminal. :func:`printable` removes
every such character (Unicode category ``Cc``: C0, DEL and C1, and the bidirectional controls
that reorder text, U+202A-U+202E and U+2066-U+2069). :func:`clipped` keeps a value shown in a
one-line error short: the first :data:`SHOWN_CHARS` characters and how long the value was.
:func:`foreign_digits` finds the digits Python's ``int`` and
``float`` read besides 0-9 (``int("８")`` is 8: full-width, Arabic-Indic, Devanagari, ...), which
the command line, the spec and the web API refuse in a number (one line naming the key).
"""

from __future__ import annotations

import unicodedata

__all__ = ["CLIP_CHARS", "SHOWN_CHARS", "clipped", "foreign_digits", "printable"]

#: Longest value an error shows whole (characters); a longer one is cut to SHOWN_CHARS.
CLIP_CHARS = 100
SHOWN_CHARS = 60

#: The bidirectional embedding, override and isolate controls (category Cf, not Cc).
_BIDI = frozenset("\u202a\u202b\u202c\u202d\u202e\u2066\u2067\u2068\u2069")


def printable(text: object, limit: int | None = None) -> str:
    """``str(text)`` without control characters (Unicode ``Cc``) and bidirectional controls,
    cut to ``limit`` characters with an ellipsis when ``limit`` is given."""
    out = str(text)
    if not out.isprintable():  # the common case is printable: nothing to remove
        out = "".join(ch for ch in out if unicodedata.category(ch) != "Cc" and ch not in _BIDI)
    return out if limit is None or len(out) <= limit else out[: limit - 3] + "..."


def clipped(text: str, limit: int = CLIP_CHARS, *, tail: bool = False) -> str:
    """``text`` if at most ``limit`` characters long, else its first :data:`SHOWN_CHARS`
    characters, ``...`` and its length (``'laser:99999...' (4010 characters)``); with ``tail``
    (a field: a long path whose end names the key) its first 20 and last 40 characters around
    ``...``, so the key stays in the line."""
    if len(text) <= limit:
        return text
    if tail:
        return f"{text[:20]}...{text[-(SHOWN_CHARS - 20) :]}"
    return f"{text[:SHOWN_CHARS]}... ({len(text)} characters)"


def foreign_digits(text: str) -> bool:
    """Whether ``text`` holds a decimal digit other than ASCII 0-9 (Unicode ``Nd``)."""
    return not text.isascii() and any(ch.isdecimal() and not ch.isascii() for ch in text)
