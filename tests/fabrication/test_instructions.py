"""ASSEMBLY.md's steps name what is on the parts: every part a step names is a cut part and is
named on the fold map; the overlap folds' angles are the outline's corners; the glue is the
sheet's; the figure's panels show the parts their titles name (written to tmp_path and read
back)."""

from __future__ import annotations

import re
import xml.etree.ElementTree as ET
from collections.abc import Callable
from pathlib import Path

import pytest
from HersheyFonts import HersheyFonts

from corrugate import Assembly, Layer, get_material, make_layout
from corrugate.fabrication.adhesives import ADHESIVES, adhesive_for
from corrugate.fabrication.build import build_pattern
from corrugate.fabrication.instructions import assembly_steps, instructions_figure
from corrugate.fabrication.palette import PALETTE

SVG = "http://www.w3.org/2000/svg"
CliRun = Callable[[list[str]], tuple[int, str, str]]


def _assembly(shape: str = "square", material: str = "dura-lar") -> Assembly:
    m = get_material(material)
    l1 = Layer(W=8.0, n=8, alpha_deg=84.0, material=m)
    l2 = Layer(W=8.0, n=14 if shape == "rectangle" else 8, alpha_deg=84.0, material=m)
    return Assembly(l1, l2, make_layout(shape))


@pytest.mark.parametrize("shape", ["square", "rectangle"])
def test_every_part_a_step_names_is_cut_and_named_on_the_fold_map(
    tmp_path: Path, shape: str, cli: CliRun
) -> None:
    a = _assembly(shape)
    pattern = build_pattern(a)
    steps = assembly_steps(a, pattern)
    named = set(re.findall(r"\b([LB]\d+)\b", " ".join(steps)))
    parts = {p.name for p in pattern.parts}
    assert named and named <= parts and parts <= named  # every part is named, none invented
    argv = ["pattern", "--W", "8", "--n", "8", "--alpha", "84", "--material", "dura-lar"]
    if shape == "rectangle":
        argv += ["--n2", "14", "--layout", "rectangle"]
    assert cli([*argv, "--out", str(tmp_path), "-q"])[0] == 0
    texts = set()
    for svg in tmp_path.glob("sheet-*.svg"):
        for el in ET.parse(svg).iter():
            if el.tag.endswith("text") and el.text:
                texts.add(el.text.strip())
    for name in named:  # "1. L1: layer 1: W 8 mm, ...", "3. B1: band 1/4: ..."
        assert any(re.search(rf"\b{name}\b", t) for t in texts), (name, texts)
    md = (tmp_path / "ASSEMBLY.md").read_text()
    assert "fold maps sheet-N.svg are for you, not the cutter" in md
    # the cut parts carry the same names by default: the Cricut file's LABEL strokes of each part
    # are the stroke font's strokes of its name, one pen path each
    cut = tmp_path / "cricut"
    assert cli([*argv, "--machine", "maker-12x12", "--out", str(cut), "-q"])[0] == 0
    strokes: dict[str, int] = {}
    for svg in cut.glob("cut-*.svg"):
        for g in ET.parse(svg).iter(f"{{{SVG}}}g"):
            if g.attrib.get("id") == "LABEL":
                for path in g.iter(f"{{{SVG}}}path"):
                    assert not path.attrib["d"].endswith("Z")  # an open stroke, drawn once
                    part = path.attrib["data-part"]
                    strokes[part] = strokes.get(part, 0) + 1
    font = HersheyFonts()
    font.load_default_font("futural")
    assert strokes == {
        name: sum(len(s) >= 2 for s in font.strokes_for_text(name)) for name in named
    }
    assert "printed face" not in md and "by its corner angle." not in md


def test_the_overlap_folds_are_the_outlines_corners_with_numbers() -> None:
    """A square and a rectangle turn by 90 deg at each corner: every band segment's overlap
    fold is a 90 deg valley; a circle's band has no corner, so no fold."""
    for shape in ("square", "rectangle"):
        a = _assembly(shape)
        step = assembly_steps(a, build_pattern(a))[2]
        bands = [p.name for p in build_pattern(a).parts if p.kind == "connector"]
        assert f"({', '.join(bands)}: valley 90 deg)" in step
    c = _assembly("circle")
    assert "a mark, not a fold" in assembly_steps(c, build_pattern(c))[2]


@pytest.mark.parametrize("material", sorted(ADHESIVES))
def test_the_glue_is_the_sheets(material: str) -> None:
    a = _assembly("square", material)
    step = assembly_steps(a, build_pattern(a))[3]
    assert f"Glue: {adhesive_for(material)}." in step


def test_each_3d_panel_draws_the_parts_its_title_names() -> None:
    """Panels 2-4 of assembly.png: a part the title names in the palette's colour name is drawn
    in that colour; the band is drawn exactly where the title names the band ring or the
    finished panel."""
    from matplotlib.colors import to_hex

    a = _assembly()
    fig = instructions_figure(a, build_pattern(a))
    axes = fig.axes[1:]
    assert len(axes) == 3
    c1, c2 = PALETTE.parts["L1"], PALETTE.parts["L2"]
    for ax in axes:
        title = ax.get_title()
        faces = {
            to_hex(coll.get_facecolor()[0]) for coll in ax.collections if len(coll.get_facecolor())
        }
        if f"L1 ({c1.name})" in title or "finished" in title:
            assert c1.hex.lower() in faces, title
        if "finished" in title:
            assert c2.hex.lower() in faces, title
        else:
            assert c2.hex.lower() not in faces, title  # L2 is named only as "alike"


@pytest.mark.parametrize("shape", ["square", "rectangle"])
def test_the_cut_panels_title_clears_the_parts_names(shape: str) -> None:
    """Panel 1 of assembly.png as drawn: its title's box overlaps no part name's box and every
    name stands above its part (the names were once placed in mm and the title at the axes' top,
    so on the case study the title was printed over "L1" and "L2")."""
    a = _assembly(shape)
    fig = instructions_figure(a, build_pattern(a))
    renderer = fig.canvas.get_renderer()
    fig.draw(renderer)
    ax0 = fig.axes[0]
    title = ax0.title.get_window_extent(renderer)
    names = [t for t in ax0.texts if re.fullmatch(r"[LB]\d+", t.get_text())]
    assert len(names) >= 3
    for name in names:
        box = name.get_window_extent(renderer)
        assert not box.overlaps(title), name.get_text()
        assert box.y0 >= ax0.transData.transform(name.xy)[1]  # above the part's top edge


@pytest.mark.parametrize(
    ("alpha1", "alpha2"), [(146.796875, 146.796875), (84.0, 84.0), (74.96, 119.52)]
)
def test_the_fold_step_gives_angles_a_protractor_reads(alpha1: float, alpha2: float) -> None:
    """Step 2's angles at a tenth of a degree at most (a continuous optimum's alpha of
    146.796875 deg was written "33.2031 deg (facets meet at 146.797 deg)"), each the design's own
    angle to within 0.05 deg: the fold 180 - alpha and, on identical layers, alpha itself."""
    m = get_material("polypropylene")
    a = Assembly(
        Layer(W=10.5, n=6, alpha_deg=alpha1, material=m),
        Layer(W=10.5, n=6, alpha_deg=alpha2, material=m),
        make_layout("circle" if alpha1 == alpha2 else "rectangle"),
    )
    step = assembly_steps(a, build_pattern(a))[1]
    shown = [float(x) for x in re.findall(r"(\d+(?:\.\d+)?) deg", step)]
    expected = [180 - alpha1, alpha1] if alpha1 == alpha2 else [180 - alpha1, 180 - alpha2]
    assert shown == pytest.approx(expected, abs=0.05), step
    for text in re.findall(r"(\d+(?:\.\d+)?) deg", step):
        assert len(text.partition(".")[2]) <= 1, step
