"""The writers registry, iterated: the files a design's output folder holds are exactly its
patterns expanded, in its order; each file is what its media type says (read back by its magic
bytes or a parser); the ``extra`` column is what writing each file needs."""

from __future__ import annotations

import json
import struct
import subprocess
import sys
import xml.etree.ElementTree as ET
from pathlib import Path
from typing import Any

import pytest
from ezdxf.filemanagement import readfile

from corrugate.cli import main
from corrugate.core.extras import EXTRAS
from corrugate.core.fileio import MANIFEST
from corrugate.export.files import FORMATS, write_files
from corrugate.export.machines import get_machine
from corrugate.export.plan import OutputOptions, cut_plan
from corrugate.export.writers import WRITERS, Writer, get_writer, writer_for
from corrugate.geometry.layer import Assembly, Layer
from corrugate.materials.library import get_material

EXAMPLES = Path(__file__).resolve().parents[2] / "examples"
CASE_STUDY = EXAMPLES / "blimp_gripper.toml"
#: Every entry's file with a laser (cut files in SVG and DXF) and --paper a4 (the tiles).
ALL_OPTIONS = ("--machine", "laser:600x400", "--paper", "a4")


def design_out(folder: Path, *options: str) -> Path:
    """``corrugate design`` of the case study with ``options`` into ``folder`` (in process)."""
    with pytest.raises(SystemExit) as info:
        main(["design", str(CASE_STUDY), "--out", str(folder), "--quiet", *options])
    assert info.value.code in (0, None)
    return folder


@pytest.fixture(scope="module")
def every_file(tmp_path_factory: pytest.TempPathFactory) -> Path:
    return design_out(tmp_path_factory.mktemp("design") / "out", *ALL_OPTIONS)


def expanded(writers: list[Writer], sheets: int, paper: str) -> list[str]:
    """The file names of ``writers`` for a design of ``sheets`` sheets (two layers), in order."""
    names: list[str] = []
    for w in writers:
        values: dict[str, list[object]] = {
            "sheet": list(range(1, sheets + 1)),
            "layer": [1, 2],
            "paper": [paper],
        }
        if not w.fields:
            names.append(w.file())
        else:
            (field,) = w.fields  # one field per pattern (checked below)
            names += [w.file(**{field: v}) for v in values[field]]
    return names


def listing(folder: Path) -> set[str]:
    return {p.name for p in folder.iterdir() if p.name != MANIFEST}


def test_the_registry_names_each_kind_of_file_once() -> None:
    names = [w.name for w in WRITERS]
    assert len(set(names)) == len(names)
    assert len({w.pattern for w in WRITERS}) == len(WRITERS)
    assert sorted(w.order for w in WRITERS) == list(range(1, len(WRITERS) + 1))
    for w in WRITERS:
        assert get_writer(w.name) is w
        assert len(w.fields) <= 1 and set(w.fields) <= {"sheet", "layer", "paper"}, w.pattern
        assert w.extra is None or w.extra in EXTRAS, w.name
        assert callable(w.step()), w.write
        assert w.format is None or w.format in FORMATS
        assert w.description and w.media_type.count("/") == 1
    # entries that share a step follow each other (the step runs once, where the first is)
    steps = [w.write for w in WRITERS]
    assert all(steps.index(s) == i or steps[i - 1] == s for i, s in enumerate(steps))
    assert FORMATS == ("svg", "cut", "pdf")
    # a pattern's field is one or more characters, and never a path
    fold = get_writer("fold")
    assert fold.matches("layer2.fold") and not fold.matches("layer.fold")
    assert not fold.matches("layer1.fold.tmp") and not fold.matches("../layer1.fold")
    assert not get_writer("fold-map").matches("sheet-1/x.svg")


@pytest.mark.parametrize(
    ("options", "missing"),
    [
        ((), {"cut-svg", "pattern-tiles"}),  # a Silhouette gets DXF only; no --paper, no tiles
        (ALL_OPTIONS, set()),
    ],
    ids=["defaults", "laser-a4"],
)
def test_a_design_writes_exactly_the_registry_patterns_expanded(
    options: tuple[str, ...],
    missing: set[str],
    every_file: Path,
    tmp_path: Path,
) -> None:
    out = every_file if options == ALL_OPTIONS else design_out(tmp_path / "out", *options)
    record = json.loads((out / "design.json").read_text(encoding="utf-8"))
    sheets = record["sheets"]["count"]
    assert sheets == len(list(out.glob("sheet-*.svg"))) >= 1
    writers = [w for w in WRITERS if w.name not in missing]
    expected = expanded(writers, sheets, "a4")
    assert listing(out) == set(expected)  # nothing else in the folder
    manifest = json.loads((out / MANIFEST).read_text(encoding="utf-8"))
    assert set(manifest["sets"]["design"]["files"]) == set(expected)
    assert record["files"] == expected  # the order written: the registry's
    for name in expected:  # each file is one entry's
        assert len([w for w in WRITERS if w.matches(name)]) == 1, name


def _is_svg(data: bytes) -> bool:
    return ET.fromstring(data).tag == "{http://www.w3.org/2000/svg}svg"


def _is_glb(data: bytes) -> bool:
    magic, version, length = struct.unpack_from("<4sII", data)
    return magic == b"glTF" and version == 2 and length == len(data)


def _is_binary_stl(data: bytes) -> bool:
    (count,) = struct.unpack_from("<I", data, 80)
    return count > 0 and len(data) == 84 + 50 * count


#: What a file of each media type starts with or parses as (the formats' own specifications:
#: SVG 1.1's namespace, PDF's header, RFC 8259 JSON, glTF 2.0's binary header, binary STL's
#: 84-byte header and 50-byte triangles, PNG's signature, an HTML document type, Markdown text).
CHECKS: dict[str, Any] = {
    "image/svg+xml": _is_svg,
    "application/pdf": lambda d: d.startswith(b"%PDF-") and b"%%EOF" in d[-1024:],
    "application/json": lambda d: isinstance(json.loads(d), dict),
    "model/gltf-binary": _is_glb,
    "model/stl": _is_binary_stl,
    "image/png": lambda d: d.startswith(b"\x89PNG\r\n\x1a\n"),
    "text/html": lambda d: d.decode("utf-8").lower().startswith("<!doctype html"),
    "text/markdown": lambda d: d.decode("utf-8").startswith("# "),
}


def test_every_file_is_what_its_media_type_says(every_file: Path) -> None:
    seen: set[str] = set()
    for name in sorted(listing(every_file)):
        w = writer_for(name)
        assert w is not None, name
        seen.add(w.name)
        data = (every_file / name).read_bytes()
        base, _, params = w.media_type.partition(";")
        if base == "image/vnd.dxf":
            assert not readfile(every_file / name).audit().has_errors, name
        else:
            assert CHECKS[base](data), (name, w.media_type)
        if base.startswith("text/"):  # a text type names its charset, and the file is in it
            assert params.strip() == "charset=utf-8", w.media_type
            data.decode("utf-8")
    assert seen == {w.name for w in WRITERS}  # every entry was checked on a file


def test_write_files_writes_the_entries_of_each_format(tmp_path: Path) -> None:
    layer = Layer(8.0, 8, 84.0, get_material("dura-lar"))
    cut = cut_plan(Assembly.identical(layer), OutputOptions(machine=get_machine("laser:600x400")))
    n = len(cut.plan.sheets)
    for fmt in FORMATS:
        out = tmp_path / fmt
        written = write_files(cut.plan, out, formats=(fmt,), paper="letter")
        entries = [w for w in WRITERS if w.format == fmt]
        assert [p.name for p in written] == expanded(entries, n, "letter")
        assert listing(out) == {p.name for p in written}


#: Writes each entry alone from the case study's design with ezdxf and matplotlib made
#: unimportable; prints {entry: [files] or "ImportError"}.
_BLOCKED = """
import json, sys, tempfile
from dataclasses import replace
from pathlib import Path
for m in ("ezdxf", "matplotlib", "HersheyFonts"):
    sys.modules[m] = None
from corrugate.export.files import plan_job
from corrugate.export.machines import get_machine
from corrugate.export.plan import OutputOptions, cut_plan
from corrugate.export.writers import WRITERS, write_job
from corrugate.report import report_html
from corrugate.workflow import design
result = design(sys.argv[1])
sol = result.solution
a = sol.analysis
cut = cut_plan(a.assembly, OutputOptions(machine=get_machine("laser:600x400"), labels=False, paper="a4"))
root = Path(tempfile.mkdtemp())
outcome = {}
for w in WRITERS:
    job = replace(
        plan_job(cut.plan, root / w.name, cut.style, labels=False, paper="a4"),
        assembly=a.assembly,
        pattern=cut.pattern,
        drawings=cut.drawings,
        report=lambda: report_html(sol, result.text, cut),
        record=a.to_dict(),
    )
    try:
        outcome[w.name] = [p.name for p in write_job(job, [w])]
    except ImportError:
        outcome[w.name] = "ImportError"
print(json.dumps(outcome))
"""


def test_the_extra_of_each_entry_is_what_writing_it_needs() -> None:
    """An entry without an extra is written with ezdxf, matplotlib and HersheyFonts unimportable; an entry
    that names ``fab`` cannot be (its step imports one of them)."""
    assert set(EXTRAS["fab"]) == {"ezdxf", "matplotlib", "HersheyFonts"}
    run = subprocess.run(
        [sys.executable, "-c", _BLOCKED, str(CASE_STUDY)],
        capture_output=True,
        text=True,
        check=True,
    )
    outcome = json.loads(run.stdout.strip().splitlines()[-1])
    assert set(outcome) == {w.name for w in WRITERS}
    for w in WRITERS:
        got = outcome[w.name]
        if w.extra is None:
            assert isinstance(got, list) and got, (w.name, got)
        else:
            assert got == "ImportError", (w.name, got)
    # a step writes its own entries' files and, sharing a step, its partner's (GLB and STL)
    for w in WRITERS:
        if isinstance(outcome[w.name], list):
            partners = [v for v in WRITERS if v.write == w.write]
            assert all(any(v.matches(f) for v in partners) for f in outcome[w.name]), w.name
            assert any(w.matches(f) for f in outcome[w.name]), w.name


def test_a_file_of_no_entry_has_no_writer() -> None:
    for name in ("notes.txt", "sheet-.svg", "pattern-.pdf", "cut-1.svg.bak", "design.JSON"):
        assert writer_for(name) is None, name
