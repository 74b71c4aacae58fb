"""Readers shared by the tests of "one sheet plan": the report's sheet-plan table and the parts of
the written ``sheet-N.svg`` files, in sheet coordinates (mm)."""

from __future__ import annotations

import xml.etree.ElementTree as ET
from html.parser import HTMLParser
from pathlib import Path

__all__ = ["Tables", "sheet_rows", "svg_mm_per_unit", "svg_parts"]


class Tables(HTMLParser):
    """Every table of a page as rows of cell texts, and every image's (alt, src)."""

    def __init__(self) -> None:
        super().__init__()
        self.tables: list[list[list[str]]] = []
        self.images: list[tuple[str, str]] = []
        self._cell: list[str] | None = None

    def handle_starttag(self, tag: str, attrs: list[tuple[str, str | None]]) -> None:
        if tag == "table":
            self.tables.append([])
        elif tag == "tr":
            self.tables[-1].append([])
        elif tag in ("td", "th"):
            self._cell = []
        elif tag == "img":
            a = dict(attrs)
            self.images.append((str(a.get("alt")), str(a.get("src"))))

    def handle_endtag(self, tag: str) -> None:
        if tag in ("td", "th") and self._cell is not None:
            self.tables[-1][-1].append("".join(self._cell).strip())
            self._cell = None

    def handle_data(self, data: str) -> None:
        if self._cell is not None:
            self._cell.append(data)


def sheet_rows(text: str) -> list[tuple[int, str, float, float]]:
    """(sheet, part, x, y) of the report's sheet-plan table."""
    parsed = Tables()
    parsed.feed(text)
    (table,) = [t for t in parsed.tables if t and "turned 90 deg" in t[0]]
    return [(int(r[0]), r[1], float(r[2]), float(r[3])) for r in table[1:]]


def svg_mm_per_unit(root: ET.Element) -> float:
    """An SVG document's user unit in mm: its width (``...mm``) over its viewBox width (the fold
    maps use 0.01 mm units, the cut files 1 mm: a reader must not assume either)."""
    width = root.attrib["width"]
    assert width.endswith("mm"), width
    return float(width[:-2]) / float(root.attrib["viewBox"].split()[2])


def svg_parts(
    folder: Path,
) -> tuple[list[tuple[int, str, float, float]], list[tuple[float, float]]]:
    """(sheet, part, xmin, ymin) of every part outline in the cut files ``sheet-N.svg`` (sheet
    coordinates: y up from the sheet's lower edge, mm), and each sheet's size (mm)."""
    ns = "{http://www.w3.org/2000/svg}"
    parts: list[tuple[int, str, float, float]] = []
    sizes: list[tuple[float, float]] = []
    k = 1
    while (folder / f"sheet-{k}.svg").exists():
        root = ET.parse(folder / f"sheet-{k}.svg").getroot()
        u = svg_mm_per_unit(root)
        _, _, w, h = (u * float(v) for v in root.attrib["viewBox"].split())
        if "data-sheet-mm" in root.attrib:  # a legend strip below the sheet is not the sheet
            w, h = (float(v) for v in root.attrib["data-sheet-mm"].split())
        sizes.append((w, h))
        for g in root.iter(f"{ns}g"):
            name = g.attrib.get("data-part")
            if name is None:
                continue
            pts = [
                tuple(u * float(c) for c in pair.split(","))
                for el in g
                if el.attrib.get("stroke") == "#000000" and "points" in el.attrib
                for pair in el.attrib["points"].split()
            ]
            parts.append((k, name, min(p[0] for p in pts), h - max(p[1] for p in pts)))
        k += 1
    return sorted(parts), sizes
