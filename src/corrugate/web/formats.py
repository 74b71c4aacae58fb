"""``GET /api/formats``: the writers registry (:mod:`corrugate.export.writers`) as the API lists it.

The page reads it once on load and orders its download buttons by ``order``; the result store
gives each file the media type of its entry. (The body lives here rather than in
:mod:`corrugate.web.schemas` only because it was added while that module was being reworked.)
"""

from __future__ import annotations

from pydantic import BaseModel, Field

from corrugate.export.writers import WRITERS

__all__ = ["FormatInfo", "format_list"]


class FormatInfo(BaseModel):
    """One kind of file a design's output folder holds (an entry of the writers registry)."""

    name: str = Field(description="The entry's name, e.g. 'cut-dxf'.")
    pattern: str = Field(
        description="Its file names: '{sheet}' is the sheet number from 1, '{layer}' the layer "
        "(1 or 2), '{paper}' a4 or letter; e.g. 'cut-{sheet}.dxf'."
    )
    media_type: str = Field(description="The media type its downloads are served with.")
    extra: str | None = Field(
        description="The package extra writing it needs ('fab'), or null for none."
    )
    description: str = Field(description="What the file is.")
    order: int = Field(description="Its place in the page's list of downloads (ascending).")


def format_list() -> list[FormatInfo]:
    """Every entry of the registry, in the order the files are written."""
    return [
        FormatInfo(
            name=w.name,
            pattern=w.pattern,
            media_type=w.media_type,
            extra=w.extra,
            description=w.description,
            order=w.order,
        )
        for w in WRITERS
    ]
