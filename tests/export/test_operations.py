"""Fold operations, legends and the one palette, checked on files written to ``tmp_path`` and parsed
back (ezdxf, ElementTree): every crease and band mark of the pattern reaches the machine as the
operation its profile says, counted against the pattern's own lines; each legend lies on a pen
layer, off every part; every writer takes its colours from the same palette object."""

from __future__ import annotations

import json
import math
import re
import xml.etree.ElementTree as ET
from pathlib import Path
from typing import TYPE_CHECKING

import pytest
from ezdxf.filemanagement import readfile

from corrugate import Assembly, Layer, get_material
from corrugate.core.errors import InputError, UnknownNameError
from corrugate.export import files3d, machines, svg
from corrugate.export.guidance import GUIDANCE, SILHOUETTE_BLADE_SOURCE, get_guidance
from corrugate.export.machines import OPERATIONS, get_machine
from corrugate.export.operations import FoldOp, default_operations, fold_operations
from corrugate.fabrication import instructions, palette
from corrugate.fabrication.build import build_pattern
from corrugate.fabrication.model import Pattern, Role
from corrugate.fabrication.sheets import plan_sheets
from corrugate.materials.library import library

if TYPE_CHECKING:
    from conftest import CliRun

SVG = "{http://www.w3.org/2000/svg}"
ROOT = Path(__file__).resolve().parents[2]
CASE1 = ["--W", "8", "--n", "8", "--alpha", "84", "--material", "dura-lar"]


def run(cli: CliRun, *args: str) -> tuple[int, str]:
    """``corrugate ARGS``: the exit code and everything it printed."""
    code, out, err = cli(list(args))
    return code, out + err


def case1() -> tuple[Assembly, Pattern]:
    a = Assembly.identical(Layer(8, 8, 84, get_material("dura-lar")))
    return a, build_pattern(a)


def expected_counts(pattern: Pattern, cut: float, gap: float) -> dict[str, int]:
    """Each kind's lines in the pattern, and the dashes a perforation of every mountain gives
    (floor(L / (cut + gap)) per crease, docs/fabrication.md)."""
    lines = [ln for p in pattern.parts for ln in p.lines]
    return {
        "mountain": sum(ln.role is Role.MOUNTAIN for ln in lines),
        "valley": sum(ln.role is Role.VALLEY for ln in lines),
        "marks": sum(ln.role is Role.MARK for ln in lines),
        "cuts": sum(ln.role is Role.CUT for ln in lines),
        "dashes": sum(
            math.floor(ln.length / (cut + gap) + 1e-9) for ln in lines if ln.role is Role.MOUNTAIN
        ),
    }


def dxf_layers(path: Path) -> dict[str, list[tuple[str, list[tuple[float, float]]]]]:
    doc = readfile(path)
    out: dict[str, list[tuple[str, list[tuple[float, float]]]]] = {}
    for e in doc.modelspace():
        if e.dxftype() == "LINE":
            pts = [(e.dxf.start.x, e.dxf.start.y), (e.dxf.end.x, e.dxf.end.y)]
        else:
            pts = [(float(x), float(y)) for x, y in e.get_points("xy")]
        out.setdefault(e.dxf.layer, []).append((e.dxftype(), pts))
    return out


def svg_layers(path: Path) -> dict[str, list[list[tuple[float, float]]]]:
    root = ET.parse(path).getroot()
    H = float(root.attrib["viewBox"].split()[3])
    out: dict[str, list[list[tuple[float, float]]]] = {}
    for g in root.iter(f"{SVG}g"):
        for e in g.iter(f"{SVG}path"):
            nums = [float(v) for v in re.findall(r"-?\d+(?:\.\d+)?", e.attrib["d"])]
            pts = [(nums[i], H - nums[i + 1]) for i in range(0, len(nums), 2)]
            out.setdefault(g.attrib["id"], []).append(pts)
    return out


def outside_every_part(points: list[tuple[float, float]], boxes: list[tuple[float, ...]]) -> bool:
    return all(not (b[0] <= x <= b[2] and b[1] <= y <= b[3]) for x, y in points for b in boxes)


# -- the default reaches the machine -----------------------------------------------------------


def test_design_default_silhouette_dxf_carries_every_crease_and_mark(
    tmp_path: Path, cli: CliRun
) -> None:
    out = tmp_path / "blimp"
    code, output = run(
        cli, "design", str(ROOT / "examples" / "blimp_gripper.toml"), "--out", str(out), "-q"
    )
    assert code == 0, output
    record = json.loads((out / "design.json").read_text())
    ops = record["fold_operations"]
    assert (ops["mountain"], ops["valley"], ops["marks"]) == ("perforate", "cut-score", "pen")
    # the material's perforation, from the guidance table
    assert (ops["perforation_cut_mm"], ops["perforation_gap_mm"]) == get_guidance(
        "dura-lar"
    ).perforation
    l1 = record["layers"][0]
    a = Assembly.identical(Layer(l1["W_mm"], l1["n"], l1["alpha_deg"], get_material("dura-lar")))
    want = expected_counts(build_pattern(a), *get_guidance("dura-lar").perforation)
    layers = dxf_layers(out / "cut-1.dxf")
    assert set(layers) == {
        "CUT",
        "MOUNTAIN-PERFORATE",
        "VALLEY-CUT-SCORE",
        "MARK-PEN",
        "LABEL",
        "LEGEND",
    }
    assert len(layers["MOUNTAIN-PERFORATE"]) == want["dashes"] > 0
    assert len(layers["VALLEY-CUT-SCORE"]) == want["valley"]
    assert len(layers["MARK-PEN"]) == want["marks"]
    assert sum(t == "LINE" for t, _ in layers["CUT"]) == want["cuts"]  # the slits
    doc = readfile(out / "cut-1.dxf")
    cameo = get_machine("cameo4-12x12")
    for name in layers:  # each layer's colour is its kind's, its description the action to set
        layer = doc.layers.get(name)
        assert layer.dxf.color == OPERATIONS[name].aci
        assert layer.description == cameo.action(name)
    assert cameo.action("LEGEND").startswith("Sketch") and cameo.action("MARK-PEN") == (
        cameo.action("LEGEND")
    )


@pytest.mark.parametrize(
    ("machine", "valley"),
    [("maker-12x12", "SCORE"), ("cameo4-12x12", "CUT-SCORE"), ("laser:400x300", "CUT-SCORE")],
)
def test_pattern_default_per_machine(
    tmp_path: Path, cli: CliRun, machine: str, valley: str
) -> None:
    out = tmp_path / "p"
    code, output = run(cli, "pattern", *CASE1, "--machine", machine, "--out", str(out), "-q")
    assert code == 0, output
    _, pattern = case1()
    want = expected_counts(pattern, *get_guidance("dura-lar").perforation)
    m = get_machine(machine)
    for fmt in m.formats:
        path = out / f"cut-1.{fmt}"
        got = {k: len(v) for k, v in (svg_layers if fmt == "svg" else dxf_layers)(path).items()}
        assert got["MOUNTAIN-PERFORATE"] == want["dashes"]
        assert got[f"VALLEY-{valley}"] == want["valley"]
        assert got["MARK-PEN"] == want["marks"]
        assert got["LEGEND"] > 0
    if "svg" in m.formats:  # Design Space: one group per layer, in its kind's colour
        root = ET.parse(out / "cut-1.svg").getroot()
        groups = {g.attrib["id"]: g.attrib["stroke"] for g in root.iter(f"{SVG}g")}
        assert groups["MOUNTAIN-PERFORATE"] == palette.LINES["mountain"].hex
        assert groups[f"VALLEY-{valley}"] == palette.LINES["valley"].hex
        assert groups["MARK-PEN"] == palette.LINES["mark"].hex
        assert groups["CUT"] == palette.LINES["cut"].hex
        (desc,) = root.iter(f"{SVG}desc")
        assert m.action(f"VALLEY-{valley}") in (desc.text or "")


def test_the_options_choose_each_kind(tmp_path: Path, cli: CliRun) -> None:
    out = tmp_path / "o"
    code, output = run(cli,
        "pattern", *CASE1, "--out", str(out), "-q",
        "--mountain", "cut-score", "--valley", "perforate", "--marks", "none",
        "--cut", "2", "--gap", "1",
    )  # fmt: skip
    assert code == 0, output
    _, pattern = case1()
    layers = dxf_layers(out / "cut-1.dxf")
    assert set(layers) == {"CUT", "MOUNTAIN-CUT-SCORE", "VALLEY-PERFORATE", "LABEL", "LEGEND"}
    want = expected_counts(pattern, 2.0, 1.0)
    assert len(layers["MOUNTAIN-CUT-SCORE"]) == want["mountain"]
    dashes = sum(
        math.floor(ln.length / 3.0 + 1e-9)
        for p in pattern.parts
        for ln in p.lines
        if ln.role is Role.VALLEY
    )
    assert len(layers["VALLEY-PERFORATE"]) == dashes
    # the shorthand still works: solid leaves the creases out, the marks stay
    code, output = run(
        cli, "pattern", *CASE1, "--out", str(tmp_path / "s"), "-q", "--fold-style", "solid"
    )
    assert code == 0, output
    assert set(dxf_layers(tmp_path / "s" / "cut-1.dxf")) == {"CUT", "MARK-PEN", "LABEL", "LEGEND"}


@pytest.mark.parametrize(
    ("args", "field"),
    [
        (["--machine", "maker-12x12", "--valley", "cut-score"], "valley"),
        (["--machine", "laser:400x300", "--mountain", "score"], "mountain"),
        (["--marks", "perforate"], "marks"),
        (["--valley", "glue"], "valley"),
    ],
)
def test_an_operation_the_machine_cannot_do_is_exit_2(
    tmp_path: Path, cli: CliRun, args: list[str], field: str
) -> None:
    out = tmp_path / "bad"
    code, output = run(cli, "pattern", *CASE1, *args, "--out", str(out))
    assert code == 2
    assert field in output and "Traceback" not in output
    assert len(output.strip().splitlines()) == 1  # one line
    assert not out.exists()


def test_fold_operations_is_the_one_entry_point() -> None:
    assert fold_operations(get_machine("cameo4-12x12"), "dura-lar") == default_operations(
        get_machine("cameo4-12x12"), "dura-lar"
    )
    card = fold_operations(get_machine("cameo4-12x12"), "cardstock")
    assert card.valley is FoldOp.SCORE  # card folds on a pressed line
    assert (card.cut, card.gap) == GUIDANCE["cardstock"].perforation
    assert fold_operations(get_machine("laser:100x100"), "cardstock").valley is FoldOp.CUT_SCORE
    assert fold_operations(get_machine("maker-12x12"), "dura-lar").valley is FoldOp.SCORE
    assert fold_operations(get_machine("maker-12x12"), style="scored").mountain is FoldOp.SCORE
    with pytest.raises(InputError, match="valley"):
        fold_operations(get_machine("maker-12x12"), valley="cut-score")
    with pytest.raises(UnknownNameError):
        fold_operations(get_machine("maker-12x12"), marks="staple")
    with pytest.raises(InputError, match="cut"):
        fold_operations(get_machine("cameo4-12x12"), cut=0.01)


# -- the guidance table --------------------------------------------------------------------------


def test_every_library_material_has_a_guidance_row_with_its_source() -> None:
    ids = set(library())
    assert set(GUIDANCE) == ids
    for g in GUIDANCE.values():
        assert "estimate" in g.source and SILHOUETTE_BLADE_SOURCE in g.source
        assert g.valley in {op.value for op in FoldOp}
        assert all(v > 0 for v in g.perforation)
    # the maker's own example: 0.3 mm card needs a blade of at least 3
    assert GUIDANCE["cardstock"].blade(0.3) == 3
    assert GUIDANCE["dura-lar"].blade(0.125) == 2


# -- legends -----------------------------------------------------------------------------------


@pytest.mark.parametrize("machine", ["cameo4-12x12", "maker-12x12", "laser:400x300"])
def test_legends_lie_off_every_part_on_a_pen_layer(
    tmp_path: Path, cli: CliRun, machine: str
) -> None:
    out = tmp_path / "l"
    assert run(cli, "pattern", *CASE1, "--machine", machine, "--out", str(out), "-q")[0] == 0
    _, pattern = case1()
    plan = plan_sheets(pattern, machine)
    boxes = [p.bounds for p in plan.sheets[0].placements]
    m = get_machine(machine)
    assert m.action("LEGEND") == m.action("MARK-PEN")  # the pen (engrave on a laser), never a cut
    assert "cut" not in m.action("LEGEND").lower()
    for fmt in m.formats:
        layers = (svg_layers if fmt == "svg" else dxf_layers)(out / f"cut-1.{fmt}")
        legend = layers["LEGEND"]
        pts = [p for item in legend for p in (item[1] if fmt == "dxf" else item)]
        assert pts and outside_every_part(pts, boxes)
        assert all(0 <= x <= plan.cutter.width and 0 <= y <= plan.cutter.height for x, y in pts)
    root = ET.parse(out / "sheet-1.svg").getroot()
    (g,) = (g for g in root if g.attrib.get("id") == "legend")
    rows = [t.text or "" for t in g]
    assert "for people, not the cutter" in rows[0]
    u = 0.01  # the fold map's user unit (mm)
    H = plan.cutter.height
    anchors = [(u * float(t.attrib["x"]), H - u * float(t.attrib["y"])) for t in g]
    assert outside_every_part(anchors, boxes)
    colours = {t.attrib["fill"] for t in g}
    assert {palette.LINES[k].hex for k in ("mountain", "valley", "mark")} <= colours
    assert any("red: mountain" in r for r in rows) and any("blue: valley" in r for r in rows)


# -- one palette ---------------------------------------------------------------------------------


def test_one_palette_in_fold_map_cut_file_assembly_figure_and_3d_view() -> None:
    # the same object everywhere
    assert svg.LINES is palette.LINES is machines.LINES is instructions.LINES
    assert instructions.PALETTE is palette.PALETTE
    assert svg.COLOURS[Role.MOUNTAIN] == OPERATIONS["MOUNTAIN-PERFORATE"].colour
    assert svg.COLOURS[Role.VALLEY] == OPERATIONS["VALLEY-SCORE"].colour
    assert svg.COLOURS[Role.MARK] == OPERATIONS["MARK-PEN"].colour
    assert OPERATIONS["CUT"].colour == svg.BOUNDARY
    assert {
        "layer 1": palette.rgba(palette.PARTS["L1"].hex),
        "layer 2": palette.rgba(palette.PARTS["L2"].hex),
        "band": palette.rgba(palette.PARTS["band"].hex),
    } == files3d.PART_COLOURS
    # the assembly figure draws with those colours: its 3D faces and its lines
    from matplotlib.colors import to_hex

    a, pattern = case1()
    fig = instructions.instructions_figure(a, pattern)
    faces = {
        to_hex(c, keep_alpha=False)
        for ax in fig.axes[1:]
        for coll in ax.collections
        for c in coll.get_facecolor()
    }
    assert faces == {palette.PARTS[k].hex for k in ("L1", "L2", "band")}
    lines = {to_hex(c) for coll in fig.axes[0].collections for c in coll.get_edgecolor()}
    assert lines == {palette.LINES[k].hex for k in ("cut", "slit", "mountain", "valley", "mark")}
    # the web page's fallbacks are the palette's part colours
    js = (ROOT / "src" / "corrugate" / "web" / "static" / "app.js").read_text()
    (body,) = re.findall(r"const PART_COLOURS = \{([^}]*)\}", js)
    found = dict(re.findall(r"'?([\w ]+)'?: 0x([0-9a-f]{6})", body))
    assert {k.strip(): "#" + v for k, v in found.items()} == {
        "layer 1": palette.PARTS["L1"].hex,
        "layer 2": palette.PARTS["L2"].hex,
        "band": palette.PARTS["band"].hex,
    }
