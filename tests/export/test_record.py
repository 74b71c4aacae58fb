"""design.json: the typed record's one writer and one reader, and the pipeline's output options."""

from __future__ import annotations

import json
from pathlib import Path

import pytest

from corrugate import Assembly, InputError, Layer, analyze, get_material, make_layout
from corrugate.export.record import LayerRecord, read_record, write_record
from corrugate.fabrication.linestyle import StyleKind
from corrugate.geometry.holes import Hole
from corrugate.workflow import output_options, write_design_files

DURALAR = get_material("dura-lar")


@pytest.mark.slow
def test_the_files_record_reads_back_typed(tmp_path: Path) -> None:
    hole = Hole("circle", (2.0, -1.0), diameter=6.0)
    layer1 = Layer(8.0, 8, 84.0, DURALAR)
    layer2 = Layer(7.0, 9, 90.0, DURALAR, t=0.1)
    a = Assembly(layer1, layer2, make_layout("rectangle", holes=(hole,)))
    written = write_design_files(analyze(a, "refined", (0.0,)), tmp_path)
    record = read_record(tmp_path)  # the folder or the file
    assert read_record(tmp_path / "design.json") == record
    assert record.shape == "rectangle"
    assert record.holes == (hole,)
    stored = DURALAR.as_dict()  # every property of the material, JSON's way
    assert record.layers == (
        LayerRecord(8.0, 8, 84.0, "dura-lar", DURALAR.default_thickness, stored),
        LayerRecord(7.0, 9, 90.0, "dura-lar", 0.1, stored),
    )
    assert record.assembly() == a
    assert record.layers[0].material_of(0) == DURALAR  # the library's, creep table and all
    assert record.content["files"] == [p.name for p in written]
    assert json.loads((tmp_path / "design.json").read_text()) == record.content


def test_a_record_without_a_design_has_no_layers_and_no_assembly(tmp_path: Path) -> None:
    path = write_record({"name": "x", "status": "infeasible", "design": None}, tmp_path)
    record = read_record(path)
    assert record.layers == () and record.shape is None
    assert record.content["status"] == "infeasible"
    with pytest.raises(InputError, match=r"layout\.shape = None"):
        record.assembly()


def test_the_writer_refuses_what_the_reader_could_not_read(tmp_path: Path) -> None:
    with pytest.raises(InputError, match=r"layers = \? is missing or malformed"):
        write_record({"layers": [{"W_mm": 1}]}, tmp_path)
    with pytest.raises(InputError, match=r"layers\[0\]\.n = None is missing"):
        write_record({"layers": [{"W_mm": 1}, {}]}, tmp_path)
    assert list(tmp_path.iterdir()) == []  # nothing written
    bad = tmp_path / "design.json"
    bad.write_text("{not json")
    with pytest.raises(InputError, match="is not JSON"):
        read_record(bad)
    with pytest.raises(InputError, match="cannot be read"):
        read_record(tmp_path / "missing.json")


def test_output_options_read_user_strings_and_name_the_callers_fields() -> None:
    opts = output_options("maker-12x24", "perforated", "1.5", "0.04 in", spacing="0.5 cm")
    assert opts.cutter == "maker-12x24"
    assert opts.style.kind is StyleKind.PERFORATED
    assert opts.style.gap == pytest.approx(1.016)
    assert opts.spacing == pytest.approx(5.0)
    with pytest.raises(InputError, match=r"^gap = None is missing"):
        output_options(fold_style="perforated", cut="1")
    with pytest.raises(InputError, match=r"^fold-line style = 'dotted' is unknown"):
        output_options(fold_style="dotted")
    with pytest.raises(InputError, match=r"^fold_style = 'dotted' is unknown"):
        output_options(fold_style="dotted", names={"fold-line style": "fold_style"})
    with pytest.raises(InputError, match=r"^cutter = 'plotter' is unknown"):
        output_options("plotter")


#: An inline material (no library id): issue 35's arm link's PET, with a yield strength.
PET = {
    "E": "4 GPa",
    "nu": 0.38,
    "density": "1.38 g/cm^3",
    "thickness": "0.25 mm",
    "yield_strength": "55 MPa",
}


@pytest.mark.slow
def test_an_inline_materials_design_reads_back_with_every_property(tmp_path: Path) -> None:
    """design.json of a design of an inline material stores E, nu, density, its thickness and
    yield strength (and creep table: none), and reads back to the same layers; a design.json
    written before the properties were stored reads back where it names a library material and
    is one line naming the field where it does not."""
    from dataclasses import replace

    from corrugate.materials.library import inline_material

    pet = replace(
        inline_material(PET["E"], PET["nu"], PET["density"], name="PET (generic)"),
        yield_strength=55.0,
    )
    a = Assembly.identical(Layer(6.0, 5, 90.0, pet, t=0.25))
    write_design_files(analyze(a, "refined", (0.0,)), tmp_path / "inline")
    record = read_record(tmp_path / "inline")
    props = record.layers[0].material_properties
    assert props is not None
    assert (props["E_MPa"], props["nu"], props["density_g_cm3"]) == (4000.0, 0.38, 1.38)
    assert props["yield_strength_MPa"] == 55.0 and props["creep"] is None
    back = record.assembly()
    assert back == a and back.layers[0].material == pet

    old = dict(record.content)  # as written before issue 35: no material_properties
    old["layers"] = [
        {k: v for k, v in lay.items() if k != "material_properties"} for lay in old["layers"]
    ]
    write_record(old, tmp_path / "old-inline")
    with pytest.raises(InputError, match=r"layers\[0\]\.material = 'PET \(generic\)'"):
        read_record(tmp_path / "old-inline").assembly()
    library = dict(old)
    library["layers"] = [{**lay, "material": "dura-lar", "t_mm": 0.125} for lay in old["layers"]]
    write_record(library, tmp_path / "old-library")
    assert read_record(tmp_path / "old-library").assembly().layers[0].material == DURALAR


def test_stored_material_properties_are_checked_as_a_specs() -> None:
    """A stored property out of range or missing is one error naming its key."""
    from corrugate.materials.library import material_from_dict

    good = DURALAR.as_dict()
    assert material_from_dict(good) == DURALAR
    for key, value, word in (
        ("nu", 0.7, "nu"),
        ("E_MPa", None, "E_MPa"),
        ("yield_strength_MPa", 1e6, "yield_strength_MPa"),
        ("creep", {"hours": [1.0], "E_MPa": [1e6]}, "creep"),
    ):
        with pytest.raises(InputError, match=rf"m\.{word}"):
            material_from_dict({**good, key: value}, "m")
