"""Cut-ready files per machine, parsed back; and rendered by real third-party programs.

Every cut file is written to ``tmp_path`` and read back: it holds only the machine's operations
(no ``stroke-dasharray``, no text unless labels are asked), each perforated fold as separate dashes
of the set cut and gap, stopping short of the crease ends, parts from the top-left corner. Inkscape
renders every SVG and LibreCAD every DXF (``librecad dxf2pdf``, run headless with
``QT_QPA_PLATFORM=offscreen``); the extent of what they draw must equal the drawn extent within
0.5 mm. Without ``inkscape`` or ``librecad`` those tests are skipped, except on CI (``CI=true``),
where a missing program is a failure (``make system-deps`` installs both).
"""

from __future__ import annotations

import itertools
import math
import os
import re
import shutil
import subprocess
import xml.etree.ElementTree as ET
import zlib
from pathlib import Path
from typing import TYPE_CHECKING

import numpy as np
import pytest
from ezdxf.filemanagement import readfile
from PIL import Image

from corrugate import Assembly, Layer, get_material
from corrugate.export.files import write_files
from corrugate.export.machines import HAIRLINE_MM, OPERATIONS, get_machine
from corrugate.fabrication.build import build_pattern
from corrugate.fabrication.linestyle import SOLID, LineStyle, dash_layout, line_style
from corrugate.fabrication.model import Pattern, Point, Role
from corrugate.fabrication.sheets import SheetPlan, place, plan_sheets
from corrugate.geometry.layouts import Circle
from plan_readers import svg_mm_per_unit

if TYPE_CHECKING:
    from conftest import CliRun

SVG = "{http://www.w3.org/2000/svg}"
MACHINES = ["cameo4-12x12", "cameo4-12x24", "maker-12x12", "maker-12x24", "laser:400x300"]
STYLES: dict[str, LineStyle] = {
    "perforated": line_style("perforated", cut=2.0, gap=1.0),
    "scored": line_style("scored"),
    "solid": SOLID,
}
MARGIN = 5.0
TOL_DASH = 0.01  # mm: dash and gap lengths
TOL_RENDER = 0.5  # mm: rendered extent against drawn extent


def case1() -> Pattern:
    return build_pattern(Assembly.identical(Layer(8, 8, 84, get_material("dura-lar"))))


def circle() -> Pattern:
    layer = Layer(8, 8, 84, get_material("dura-lar"))
    return build_pattern(Assembly.identical(layer, Circle()))


@pytest.fixture(scope="module")
def patterns() -> dict[str, Pattern]:
    return {"case1": case1(), "circle": circle()}


# -- parsing the files back --------------------------------------------------------------------

Path2D = tuple[str, list[Point], bool]  # operation, points (sheet mm, y up), closed


def svg_paths(path: Path) -> tuple[list[Path2D], ET.Element]:
    """Every path of a cut SVG as (operation, points in sheet mm with y up, closed)."""
    root = ET.parse(path).getroot()
    H = float(root.attrib["viewBox"].split()[3])
    out: list[Path2D] = []
    for g in root.iter(f"{SVG}g"):
        op = g.attrib["id"]
        for e in g.iter(f"{SVG}path"):
            d = e.attrib["d"]
            nums = [float(v) for v in re.findall(r"-?\d+(?:\.\d+)?", d)]
            pts = [(nums[i], H - nums[i + 1]) for i in range(0, len(nums), 2)]
            out.append((op, pts, d.rstrip().endswith("Z")))
    return out, root


def dxf_paths(path: Path) -> list[Path2D]:
    doc = readfile(path)
    assert not doc.audit().has_errors
    assert doc.header["$INSUNITS"] == 4  # mm
    out: list[Path2D] = []
    for e in doc.modelspace():
        kind = e.dxftype()
        assert kind in ("LINE", "LWPOLYLINE"), kind  # no TEXT, MTEXT, INSERT, ...
        if kind == "LINE":
            out.append(
                (e.dxf.layer, [(e.dxf.start.x, e.dxf.start.y), (e.dxf.end.x, e.dxf.end.y)], False)
            )
        else:
            pts = [(float(x), float(y)) for x, y in e.get_points("xy")]
            out.append((e.dxf.layer, pts, bool(e.closed)))
    return out


def cut_files(plan: SheetPlan, out: Path, style: LineStyle, labels: bool | None) -> list[Path]:
    written = write_files(plan, out, style, formats=("cut",), labels=labels)
    return [p for p in written if p.name.startswith("cut-")]


def paths_of(path: Path) -> list[Path2D]:
    return svg_paths(path)[0] if path.suffix == ".svg" else dxf_paths(path)


def extent(paths: list[Path2D]) -> tuple[float, float, float, float]:
    pts = np.array([p for _, ps, _ in paths for p in ps])
    return (
        float(pts[:, 0].min()),
        float(pts[:, 1].min()),
        float(pts[:, 0].max()),
        float(pts[:, 1].max()),
    )


# -- what is in a cut file ---------------------------------------------------------------------


@pytest.mark.parametrize("machine", MACHINES)
@pytest.mark.parametrize("style_name", list(STYLES))
@pytest.mark.parametrize("labels", [None, True, False])
def test_cut_files_hold_only_the_machines_operations(
    patterns: dict[str, Pattern], tmp_path: Path, machine: str, style_name: str, labels: bool | None
) -> None:
    style = STYLES[style_name]
    m = get_machine(machine)
    plan = plan_sheets(patterns["case1"], machine, margin=MARGIN)
    files = cut_files(plan, tmp_path, style, labels)
    n = len(plan.sheets)
    expected = sorted(f"cut-{k}.{ext}" for k in range(1, n + 1) for ext in m.formats)
    assert sorted(p.name for p in files) == expected
    # Silhouette Studio (basic) reads DXF, Cricut Design Space SVG, a laser either
    family = machine.split("-")[0].split(":")[0]
    assert m.formats == {"cameo4": ("dxf",), "maker": ("svg",), "laser": ("svg", "dxf")}[family]
    made = {"perforated": "PERFORATE", "scored": "LASER" if family == "laser" else "SCORE"}
    crease_ops = (
        set()
        if style_name == "solid"
        else {f"MOUNTAIN-{made[style_name]}", f"VALLEY-{made[style_name]}"}
    )
    crease_ops = {op.replace("LASER", "CUT-SCORE") for op in crease_ops}  # a laser cannot press
    ops = {"CUT", "MARK-PEN", "LEGEND", *crease_ops}
    if labels is not False:  # on by default: the cut parts carry their names
        ops.add("LABEL")
    parts = patterns["case1"].parts
    mountains = sum(ln.role is Role.MOUNTAIN for p in parts for ln in p.lines)
    valleys = sum(ln.role is Role.VALLEY for p in parts for ln in p.lines)
    marks = sum(ln.role is Role.MARK for p in parts for ln in p.lines)
    for path in files:
        text = path.read_text(encoding="utf-8")
        assert "dasharray" not in text
        paths = paths_of(path)
        assert {op for op, _, _ in paths} == ops, path.name
        count = {op: sum(o == op for o, _, _ in paths) for op in ops}
        assert count["MARK-PEN"] == marks  # every band mark, drawn with the pen
        if style_name == "scored":
            one = "CUT-SCORE" if family == "laser" else "SCORE"
            assert count[f"MOUNTAIN-{one}"] == mountains
            assert count[f"VALLEY-{one}"] == valleys
        outlines = [p for p in paths if p[0] == "CUT" and p[2]]
        assert len(outlines) == len(parts)
        if path.suffix == ".svg":
            root = ET.fromstring(text)
            assert not list(root.iter(f"{SVG}text"))  # labels are pen strokes, never text
            assert root.attrib["width"] == f"{plan.cutter.width:.4f}".rstrip("0").rstrip(".") + "mm"
            for g in root.iter(f"{SVG}g"):
                op = OPERATIONS[g.attrib["id"]]
                assert g.attrib["stroke"] == op.colour  # one colour per layer
                assert float(g.attrib["stroke-width"]) == pytest.approx(m.stroke_mm)
                if machine.startswith("laser"):
                    assert float(g.attrib["stroke-width"]) == pytest.approx(0.0254)
                    assert pytest.approx(0.001 * 25.4) == HAIRLINE_MM
        else:
            doc = readfile(path)
            assert {layer.dxf.name for layer in doc.layers} >= ops
            for name in ops:
                assert doc.layers.get(name).dxf.color == OPERATIONS[name].aci
                if machine.startswith("laser"):
                    assert doc.layers.get(name).dxf.lineweight == 0  # hairline
            assert not doc.modelspace().query("TEXT MTEXT")
    # within a file one colour is one kind of line: the colours of the kinds differ
    kinds = {name.split("-")[0]: OPERATIONS[name].colour for name in OPERATIONS}
    assert len(set(kinds.values())) == len(kinds) - 1  # LABEL and LEGEND share the pen's grey


@pytest.mark.slow
@pytest.mark.parametrize("which", ["case1", "circle"])
@pytest.mark.parametrize(("cut", "gap"), [(2.0, 1.0), (1.3, 0.7)])
@pytest.mark.parametrize("machine", ["cameo4-12x12", "maker-12x12", "laser:400x300"])
def test_each_perforated_fold_is_separate_dashes_of_the_set_cut_and_gap(
    patterns: dict[str, Pattern], tmp_path: Path, which: str, cut: float, gap: float, machine: str
) -> None:
    style = line_style("perforated", cut=cut, gap=gap)
    plan = plan_sheets(patterns[which], machine, margin=MARGIN)
    for path in cut_files(plan, tmp_path / which, style, None):
        sheet = plan.sheets[int(path.stem.split("-")[1]) - 1]
        dashes = [ps for op, ps, closed in paths_of(path) if op.endswith("-PERFORATE")]
        assert all(len(ps) == 2 for ps in dashes)  # each dash its own two-point segment
        used = np.zeros(len(dashes), dtype=bool)
        a_pts = np.array([d[0] for d in dashes])
        b_pts = np.array([d[1] for d in dashes])
        total = 0
        for placement in sheet.placements:
            for ln in place(placement).lines:
                if ln.role not in (Role.MOUNTAIN, Role.VALLEY):
                    continue
                L = ln.length
                ux, uy = (ln.b[0] - ln.a[0]) / L, (ln.b[1] - ln.a[1]) / L
                along = []
                for k, (p, q) in enumerate(zip(a_pts, b_pts, strict=True)):
                    off = [(x - ln.a[0]) * uy - (y - ln.a[1]) * ux for x, y in (p, q)]
                    ts = sorted((x - ln.a[0]) * ux + (y - ln.a[1]) * uy for x, y in (p, q))
                    if max(map(abs, off)) < 1e-3 and ts[0] > -1e-3 and ts[1] < L + 1e-3:
                        along.append(ts)
                        assert not used[k]
                        used[k] = True
                along.sort()
                n = math.floor(L / (cut + gap) + 1e-9)
                assert len(along) == n == len(dash_layout(L, cut, gap))
                total += n
                for t0, t1 in along:
                    assert t1 - t0 == pytest.approx(cut, abs=TOL_DASH)
                for (_, e0), (s1, _) in itertools.pairwise(along):
                    assert s1 - e0 == pytest.approx(gap, abs=TOL_DASH)
                head, tail = along[0][0], L - along[-1][1]
                # stops short of the outline: at least half a gap free at each end, centred
                assert head >= gap / 2 - TOL_DASH and tail >= gap / 2 - TOL_DASH
                assert head == pytest.approx(tail, abs=TOL_DASH)
        assert used.all() and total == len(dashes)  # no stray dash


@pytest.mark.parametrize("machine", [*MACHINES, "laser:130x90"])
def test_parts_start_at_the_mats_top_left_corner(
    patterns: dict[str, Pattern], tmp_path: Path, machine: str
) -> None:
    small = machine == "laser:130x90"
    plan = plan_sheets(patterns["case1" if small else "circle"], machine, margin=MARGIN)
    files = cut_files(plan, tmp_path, STYLES["perforated"], None)
    if small:  # a small bed: several sheets, each filled from its top left
        assert len(plan.sheets) >= 2
        assert sorted(p.name for p in files) == sorted(
            f"cut-{k}.{ext}" for k in range(1, len(plan.sheets) + 1) for ext in ("svg", "dxf")
        )
    for path in files:
        x0, _, _, y1 = extent(paths_of(path))
        assert x0 == pytest.approx(MARGIN, abs=1e-3)
        assert y1 == pytest.approx(plan.cutter.height - MARGIN, abs=1e-3)  # y up: the top edge
        if path.suffix == ".svg":  # and in SVG's own coordinates (y down) at the top
            root = ET.parse(path).getroot()
            ys = [
                float(v)
                for e in root.iter(f"{SVG}path")
                for v in re.findall(r"-?\d+(?:\.\d+)?", e.attrib["d"])[1::2]
            ]
            assert min(ys) == pytest.approx(MARGIN, abs=1e-3)


# -- labels --------------------------------------------------------------------------------------


def _crosses(box: tuple[float, float, float, float], a: Point, b: Point) -> bool:
    """Whether segment a-b meets the box (x0, y0, x1, y1), by sampling it finely."""
    x0, y0, x1, y1 = box
    t = np.linspace(0.0, 1.0, 2001)
    xs = a[0] + t * (b[0] - a[0])
    ys = a[1] + t * (b[1] - a[1])
    return bool(np.any((xs >= x0) & (xs <= x1) & (ys >= y0) & (ys <= y1)))


def _segments(paths: list[Path2D]) -> list[tuple[Point, Point]]:
    segs = []
    for _, pts, closed in paths:
        ring = [*pts, pts[0]] if closed else pts
        segs.extend(itertools.pairwise(ring))
    return segs


@pytest.mark.parametrize("machine", ["cameo4-12x12", "maker-12x12", "laser:400x300"])
def test_labels_in_cut_files_by_default_as_pen_strokes_clear_of_every_line(
    patterns: dict[str, Pattern], tmp_path: Path, machine: str
) -> None:
    plan = plan_sheets(patterns["case1"], machine, margin=MARGIN)
    style = STYLES["scored"]
    for path in cut_files(plan, tmp_path / "off", style, False):
        assert "LABEL" not in {op for op, _, _ in paths_of(path)}
    for path in cut_files(plan, tmp_path / "on", style, None):
        paths = paths_of(path)
        glyphs = [p for p in paths if p[0] == "LABEL"]
        assert glyphs and not any(closed for _, _, closed in glyphs)  # strokes, drawn once
        lines = _segments([p for p in paths if p[0] not in ("LABEL", "LEGEND")])
        sheet = plan.sheets[int(path.stem.split("-")[1]) - 1]
        for placement in sheet.placements:
            x0, y0, x1, y1 = placement.bounds
            mine = [
                pts for _, pts, _ in glyphs if all(x0 <= x <= x1 and y0 <= y <= y1 for x, y in pts)
            ]
            assert mine, placement.part.name  # every part is labelled, inside its box
            pts = np.vstack(mine)
            box = (*pts.min(axis=0), *pts.max(axis=0))
            assert not any(_crosses(box, a, b) for a, b in lines), placement.part.name
            # and clear of the fold lines and marks too, which the cut file does not carry
            for ln in place(placement).lines:
                assert not _crosses(box, ln.a, ln.b), (placement.part.name, ln.role)


def test_fold_map_labels_are_clear_of_every_line(
    patterns: dict[str, Pattern], tmp_path: Path
) -> None:
    plan = plan_sheets(patterns["case1"], "cameo4-12x12", margin=MARGIN)
    (path,) = write_files(plan, tmp_path, STYLES["perforated"], formats=("svg",))
    root = ET.parse(path).getroot()
    H = plan.cutter.height
    (labels,) = (g for g in root.iter(f"{SVG}g") if g.attrib.get("id") == "labels")
    texts = list(labels.iter(f"{SVG}text"))
    assert len(texts) == len(plan.placements)  # labels are on in the fold map by default
    assert sorted(t.text.split(".")[0] for t in texts if t.text) == [
        str(k) for k in range(1, len(texts) + 1)
    ]  # each label starts with its step in the folding order
    segs: list[tuple[Point, Point]] = []
    for e in root.iter(f"{SVG}line"):
        a = (float(e.attrib["x1"]), H - float(e.attrib["y1"]))
        b = (float(e.attrib["x2"]), H - float(e.attrib["y2"]))
        segs.append((a, b))
    for e in root.iter(f"{SVG}polygon"):
        nums = [float(v) for v in re.split(r"[ ,]+", e.attrib["points"].strip())]
        ring = [(nums[i], H - nums[i + 1]) for i in range(0, len(nums), 2)]
        segs.extend(zip(ring, [*ring[1:], ring[0]], strict=True))
    for t in texts:
        x, y = float(t.attrib["x"]), H - float(t.attrib["y"])
        size, length = float(t.attrib["font-size"]), float(t.attrib["textLength"])
        half_l, half_h = length / 2, 0.6 * size
        if "rotate" in t.attrib.get("transform", ""):
            half_l, half_h = half_h, half_l
        box = (x - half_l, y - half_h, x + half_l, y + half_h)
        assert not any(_crosses(box, a, b) for a, b in segs), t.text
    # --no-labels: none at all
    (path,) = write_files(plan, tmp_path / "n", SOLID, formats=("svg",), labels=False)
    (legend,) = (g for g in ET.parse(path).getroot() if g.attrib.get("id") == "legend")
    assert len(list(ET.parse(path).getroot().iter(f"{SVG}text"))) == len(legend)  # legend only


# -- bad input -----------------------------------------------------------------------------------


@pytest.mark.parametrize("machine", ["maker-12x12", "cameo4-12x12", "laser:120x120"])
def test_part_larger_than_the_machine_is_one_line_exit_2_and_no_file(
    tmp_path: Path, cli: CliRun, machine: str
) -> None:
    out = tmp_path / "out"
    args = ["pattern", "--W", "30", "--n", "12", "--alpha", "84", "--material", "dura-lar"]
    code, _, err = cli([*args, "--out", str(out), "--machine", machine])
    assert code == 2
    lines = [ln for ln in err.strip().splitlines() if ln.strip()]
    assert len(lines) == 1, err
    assert "does not fit on the sheet" in lines[0] and machine in lines[0]
    assert "part 'L1'" in lines[0] or "part 'L2'" in lines[0] or "part 'B" in lines[0]
    assert not out.exists() or not list(out.iterdir())


def test_unknown_machine_is_one_line_exit_2(tmp_path: Path, cli: CliRun) -> None:
    args = ["pattern", "--W", "8", "--n", "8", "--alpha", "84", "--material", "dura-lar"]
    code, _, err = cli([*args, "--out", str(tmp_path / "o"), "--machine", "cameo3"])
    assert code == 2
    assert "cutter = 'cameo3' is unknown" in err and "maker-12x12" in err
    assert not (tmp_path / "o").exists()


@pytest.mark.slow
def test_machine_option_picks_the_files_and_labels_flag(tmp_path: Path, cli: CliRun) -> None:
    args = ["pattern", "--W", "8", "--n", "8", "--alpha", "84", "--material", "dura-lar"]
    for machine, names in (
        (None, {"cut-1.dxf"}),  # default: Silhouette Cameo 4, 12 x 12 in
        ("maker-12x24", {"cut-1.svg"}),
        ("laser:300x200", {"cut-1.svg", "cut-1.dxf"}),
    ):
        out = tmp_path / (machine or "default").replace(":", "_")
        extra = [] if machine is None else ["--machine", machine]
        code, _, err = cli([*args, "--out", str(out), *extra, "--labels", "--fold-style", "scored"])
        assert code == 0, err
        cut = {p.name for p in out.iterdir() if p.name.startswith("cut-")}
        assert cut == names
        for name in names:
            assert "LABEL" in {op for op, _, _ in paths_of(out / name)}
        assert (out / "sheet-1.svg").exists()  # the fold map, always


# -- rendered by third-party programs ------------------------------------------------------------


def need(program: str) -> str:
    """The path of ``program``; skip the test without it, or fail on CI (``CI=true``)."""
    found = shutil.which(program)
    if found is None:
        reason = f"{program} not found: run `make system-deps` as root"
        if os.environ.get("CI", "").strip().lower() in ("true", "1", "yes"):
            pytest.fail(f"{reason} (required in CI)")
        pytest.skip(reason)
    return found


@pytest.mark.parametrize(("ci", "outcome"), [("true", "fail"), ("", "skip")])
def test_a_missing_program_fails_in_ci_and_skips_elsewhere(
    monkeypatch: pytest.MonkeyPatch, ci: str, outcome: str
) -> None:
    monkeypatch.setenv("CI", ci)
    monkeypatch.setenv("PATH", "/nonexistent")
    expected = pytest.fail.Exception if outcome == "fail" else pytest.skip.Exception
    with pytest.raises(expected):
        need("inkscape")


def all_files(patterns: dict[str, Pattern], out: Path) -> list[tuple[Path, SheetPlan]]:
    """Every SVG and DXF (cut files with labels, fold maps) of both patterns on every machine."""
    found = []
    for which, pattern in patterns.items():
        for machine in MACHINES:
            plan = plan_sheets(pattern, machine, margin=MARGIN)
            folder = out / which / machine.replace(":", "_")
            style = STYLES["perforated"]
            for p in write_files(plan, folder, style, formats=("svg", "cut"), labels=True):
                found.append((p, plan))
    return found


def drawn_extent(path: Path) -> tuple[float, float, float, float]:
    """The extent (mm, sheet coordinates, y up) of the geometry written to ``path``."""
    if path.name.startswith("cut-"):
        return extent(paths_of(path))
    root = ET.parse(path).getroot()  # fold map: polygons and lines
    u = svg_mm_per_unit(root)
    H = u * float(root.attrib["viewBox"].split()[3])
    pts: list[Point] = []
    for e in root.iter(f"{SVG}polygon"):
        nums = [u * float(v) for v in re.split(r"[ ,]+", e.attrib["points"].strip())]
        pts.extend((nums[i], H - nums[i + 1]) for i in range(0, len(nums), 2))
    a = np.array(pts)
    return float(a[:, 0].min()), float(a[:, 1].min()), float(a[:, 0].max()), float(a[:, 1].max())


@pytest.mark.slow
def test_every_svg_renders_in_inkscape_at_its_drawn_extent(
    patterns: dict[str, Pattern], tmp_path: Path
) -> None:
    inkscape = need("inkscape")
    dpi = 254.0  # 10 px per mm
    checked = 0
    for path, plan in all_files(patterns, tmp_path):
        if path.suffix != ".svg":
            continue
        if path.name.startswith("sheet-"):  # the fold map's legend is text off the parts: the
            root = ET.parse(path).getroot()  # geometry is what must render at its extent
            for g in [g for g in root if g.attrib.get("id") == "legend"]:
                root.remove(g)
            ET.ElementTree(root).write(path)
        png = path.with_suffix(".png")
        subprocess.run(
            [
                inkscape,
                "--export-type=png",
                f"--export-dpi={dpi:g}",
                "--export-background=white",
                "--export-background-opacity=1",
                f"--export-filename={png}",
                str(path),
            ],
            check=True,
            capture_output=True,
            timeout=120,
        )
        img = np.asarray(Image.open(png).convert("L"))
        px = dpi / 25.4
        H = plan.cutter.height
        assert img.shape == (round(H * px), round(plan.cutter.width * px))  # the page is the sheet
        ink = np.argwhere(img < 250)
        assert len(ink), path
        r0, c0 = ink.min(axis=0)
        r1, c1 = ink.max(axis=0) + 1
        rendered = (c0 / px, H - r1 / px, c1 / px, H - r0 / px)
        drawn = drawn_extent(path)
        diff = max(abs(a - b) for a, b in zip(rendered, drawn, strict=True))
        assert diff <= TOL_RENDER, (path, rendered, drawn)
        checked += 1
    assert checked == 2 * (len(MACHINES) + 3)  # fold maps on 5 machines, cut SVGs on 3


def _pdf_extent(pdf: Path) -> tuple[float, float, float, float, float, float]:
    """Extent (mm from the page's lower-left corner) of the strokes in a PDF written by Qt, and
    the page size (mm): the content stream's ``cm`` matrix applied to every m/l/c point."""
    data = pdf.read_bytes()
    box = re.search(rb"/MediaBox \[([\d. ]+)\]", data)
    assert box is not None
    _, _, pw, ph = (float(v) for v in box.group(1).split())
    xs: list[float] = []
    ys: list[float] = []
    for raw in re.findall(rb"stream\r?\n(.*?)\r?\nendstream", data, re.S):
        try:
            text = zlib.decompress(raw).decode("latin-1")
        except zlib.error:
            continue
        cm = re.search(r"([-\d.]+) ([-\d.]+) ([-\d.]+) ([-\d.]+) ([-\d.]+) ([-\d.]+) cm", text)
        if cm is None:
            continue
        a, b, c, d, e, f = (float(v) for v in cm.groups())
        # only the drawn strokes: the clip rectangle (followed by W* n) is not ink
        body = text[cm.end() :]
        body = re.sub(r"[^\n]*\n[^\n]*\n[^\n]*\n[^\n]*\n[^\n]*\nh\nW\*? n", "", body, count=1)
        for x, y in re.findall(r"([-\d.]+) ([-\d.]+) [ml]\b", body):
            X, Y = float(x), float(y)
            xs.append(a * X + c * Y + e)
            ys.append(b * X + d * Y + f)
    assert xs, pdf
    mm = 25.4 / 72
    return min(xs) * mm, min(ys) * mm, max(xs) * mm, max(ys) * mm, pw * mm, ph * mm


@pytest.mark.slow
def test_every_dxf_renders_in_librecad_at_its_drawn_extent(
    patterns: dict[str, Pattern], tmp_path: Path
) -> None:
    librecad = need("librecad")
    env = {**os.environ, "QT_QPA_PLATFORM": "offscreen"}  # no display needed
    checked = 0
    for path, plan in all_files(patterns, tmp_path):
        if path.suffix != ".dxf":
            continue
        pdf = path.with_suffix(".pdf")  # dxf2pdf writes NAME.pdf beside NAME.dxf
        # LibreCAD 2.2's dxf2pdf takes no value for -o, -p or -s: the page size and the scale
        # come from the file (its paper-space page is the sheet, at 1:1)
        subprocess.run(
            [librecad, "dxf2pdf", str(path)],
            check=True,
            capture_output=True,
            timeout=120,
            env=env,
            cwd=path.parent,
        )
        x0, y0, x1, y1, pw, ph = _pdf_extent(pdf)
        assert pw == pytest.approx(plan.cutter.width, abs=0.5)  # the page is the sheet:
        assert ph == pytest.approx(plan.cutter.height, abs=0.5)  # nothing is cut off
        drawn = drawn_extent(path)
        # LibreCAD prints at 1:1 with the drawing's origin at the page's lower-left corner
        diff = max(abs(a - b) for a, b in zip((x0, y0, x1, y1), drawn, strict=True))
        assert diff <= TOL_RENDER, (path, (x0, y0, x1, y1), drawn)
        checked += 1
    assert checked == 2 * 3  # cut DXFs: two Cameo 4 mats and the laser, for both patterns
