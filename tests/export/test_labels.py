"""corrugate.export.labels: the stroke font of the cut files' labels."""

from __future__ import annotations

from HersheyFonts import HersheyFonts

from corrugate.export.labels import _font


def test_stroke_font_is_the_packages_futural() -> None:
    """The font loaded with one decompression of the package's archive (issue 39) has every
    glyph of the font as the package's own ``load_default_font("futural")`` reads it after
    checking the name against its list, and draws a label to the same strokes."""
    reference = HersheyFonts()
    assert "futural" in reference.default_font_names
    reference.load_default_font("futural")
    reference.normalize_rendering(1.0)
    ours = _font()
    mine = {c: g.strokes for c, g in ours.all_glyphs.items()}
    theirs = {c: g.strokes for c, g in reference.all_glyphs.items()}
    assert len(mine) == 96 and mine == theirs  # printable ASCII, 32-127
    text = "layer 1, part 12: W 8 mm, alpha 78 deg"
    assert list(ours.strokes_for_text(text)) == list(reference.strokes_for_text(text))
