"""``corrugate pattern``: every file of a design, parsed back; bad options leave nothing behind."""

from __future__ import annotations

import json
import math
import xml.etree.ElementTree as ET
from pathlib import Path
from typing import TYPE_CHECKING

import ezdxf
import pytest

from corrugate import Assembly, Layer, analyze, get_material
from corrugate.fabrication.build import build_pattern

if TYPE_CHECKING:
    from conftest import CliRun

SVG = "{http://www.w3.org/2000/svg}"


CASE1 = ["pattern", "--W", "8", "--n", "8", "--alpha", "84", "--material", "dura-lar"]


@pytest.mark.slow
def test_case1_files(tmp_path: Path, cli: CliRun) -> None:
    code, _, err = cli([*CASE1, "--out", str(tmp_path)])
    assert code == 0, err
    names = {p.name for p in tmp_path.iterdir()}
    assert {
        "sheet-1.svg",
        "cut-1.dxf",
        "pattern.pdf",
        "layer1.fold",
        "layer2.fold",
        "assembly.glb",
        "assembly.stl",
        "ASSEMBLY.md",
        "assembly.png",
        "design.json",
    } <= names
    assert [n for n in names if n.startswith(".")] == [".corrugate-set.json"]  # no temp file
    record = json.loads((tmp_path / "design.json").read_text())
    a = Assembly.identical(Layer(8, 8, 84, get_material("dura-lar")))
    expected = analyze(a).mass
    parts_mass = sum(p["mass_g"] for p in record["cut_parts"])
    assert parts_mass == pytest.approx(expected.total, rel=5e-3)
    assert record["mass_breakdown_g"]["connectors_g"] == pytest.approx(expected.connectors)
    assert set(record["files"]) <= names

    # every crease of the design is in the SVG exactly once, with Origami Simulator's colours
    root = ET.parse(tmp_path / "sheet-1.svg").getroot()
    creases = [e for e in root.iter(f"{SVG}line") if e.get("data-crease")]
    keys = [e.get("data-crease") for e in creases]
    assert len(keys) == len(set(keys))
    pattern = build_pattern(a)
    assert len(keys) == sum(len(p.creases()) for p in pattern.parts)
    for e in creases:
        assert e.get("stroke") in ("#ff0000", "#0000ff")
        assert 0 < float(e.get("opacity", "0")) <= 1
    layer_creases = [e for e in creases if e.get("data-crease", "").startswith("L1:")]
    assert len(layer_creases) == 8
    assert {round(float(e.get("opacity", "0")), 4) for e in layer_creases} == {round(96 / 180, 4)}

    # the Cameo's cut file (the default machine): outlines and slits, and by default the
    # creases and the band's marks as operations the machine performs, the part names drawn by
    # the pen, with a legend
    doc = ezdxf.readfile(tmp_path / "cut-1.dxf")
    assert not doc.audit().has_errors
    assert doc.header["$INSUNITS"] == 4
    msp = doc.modelspace()
    assert {e.dxf.layer for e in msp} == {
        "CUT",
        "MOUNTAIN-PERFORATE",
        "VALLEY-CUT-SCORE",
        "MARK-PEN",
        "LABEL",
        "LEGEND",
    }
    assert len(msp.query('LWPOLYLINE[layer=="CUT"]')) == len(pattern.parts)
    assert not (tmp_path / "cut-1.svg").exists()  # Silhouette Studio basic reads DXF


@pytest.mark.slow
def test_circle_and_polygon_patterns(tmp_path: Path, cli: CliRun) -> None:
    for name, extra in (
        ("circle", ["--layout", "circle"]),
        ("triangle", ["--layout", "polygon", "--vertices", "0,0 1,0 0.5,1"]),
    ):
        out = tmp_path / name
        code, _, err = cli(
            [
                *CASE1,
                "--out",
                str(out),
                "--fold-style",
                "perforated",
                "--cut",
                "1",
                "--gap",
                "0.5",
                *extra,
            ],
        )
        assert code == 0, err
        record = json.loads((out / "design.json").read_text())
        assert record["layout"]["shape"] in ("circle", "polygon")
        assert sum(p["mass_g"] for p in record["cut_parts"]) == pytest.approx(
            record["mass_g"], rel=5e-3
        )
        doc = ezdxf.readfile(out / "cut-1.dxf")
        assert not doc.audit().has_errors
        assert len(doc.modelspace().query('LINE[layer=="MOUNTAIN-PERFORATE"]')) > 0
        assert len(doc.modelspace().query('LINE[layer=="VALLEY-PERFORATE"]')) > 0


#: 17 small circles on a 2 mm grid, and a 257-gon of radius 40 mm: one past each cap of
#: corrugate.core.limits.MAX_COUNTS
HOLES_17 = json.dumps(
    [
        {"shape": "circle", "diameter": 0.5, "center": [2.0 * (i % 5), 2.0 * (i // 5)]}
        for i in range(17)
    ]
)
POLYGON_257 = " ".join(
    f"{40 * math.cos(2 * math.pi * k / 257):.4f},{40 * math.sin(2 * math.pi * k / 257):.4f}"
    for k in range(257)
)


@pytest.mark.parametrize(
    ("extra", "message"),
    [
        (["--fold-style", "perforated", "--cut", "60", "--gap", "1"], "longer than the crease"),
        (["--cutter", "laser:40x40"], "does not fit on the sheet"),
        (["--cutter", "plotter-9000"], "cutter = 'plotter-9000' is unknown"),
        (["--fold-style", "dotted"], "fold-line style = 'dotted' is unknown"),
        (["--alpha", "200"], "alpha = 200 deg is out of range"),
        # as many holes or outline vertices as a spec may have (400 holes ran past 2 minutes and
        # 4 GB before the cap)
        (["--holes", HOLES_17], "holes = 17 holes has too many items: allowed at most 16 holes"),
        (["--layout", "polygon", "--vertices", POLYGON_257], "at most 256 vertices"),
    ],
)
def test_bad_options_leave_no_file(
    tmp_path: Path, cli: CliRun, extra: list[str], message: str
) -> None:
    out = tmp_path / "out"
    out.mkdir()
    (out / "keep.txt").write_text("an earlier file")
    code, stdout, err = cli([*CASE1, "--out", str(out), *extra])
    assert stdout == ""
    assert code == 2
    assert message in err
    assert len(err.strip().splitlines()) == 1
    assert sorted(p.name for p in out.iterdir()) == ["keep.txt"]
    assert (out / "keep.txt").read_text() == "an earlier file"
