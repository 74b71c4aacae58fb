"""The names of :mod:`corrugate.names` are the names the tables that implement them know (each
table is a second source: the moduli variants, the cutters, the layout factory, the supports, the
stiffness kinds of the spec, the fold styles, the papers, the file formats), its defaults are the
ones every surface applies, and it imports nothing of corrugate and no numpy."""

from __future__ import annotations

import ast
import inspect
import subprocess
import sys
import typing
from pathlib import Path

import pytest

from corrugate import names
from corrugate.core.errors import InputError, UnknownNameError

SRC = Path(__file__).resolve().parents[1] / "src" / "corrugate"


def test_names_imports_only_the_standard_library_typing() -> None:
    tree = ast.parse((SRC / "names.py").read_text(encoding="utf-8"))
    imported = {
        node.module if isinstance(node, ast.ImportFrom) else alias.name
        for node in ast.walk(tree)
        if isinstance(node, ast.Import | ast.ImportFrom)
        for alias in node.names
    }
    assert imported == {"__future__", "typing"}


def test_importing_names_loads_no_numpy_and_no_other_corrugate_module() -> None:
    code = (
        "import sys\n"
        "import corrugate.names\n"
        "print(sorted(m for m in sys.modules if m.startswith('corrugate') or m == 'numpy'))\n"
    )
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True)
    assert ast.literal_eval(out.stdout.strip()) == ["corrugate", "corrugate.names"]


@pytest.mark.parametrize(
    ("literal", "values"),
    [
        (names.ModelName, names.MODEL_NAMES),
        (names.Support, names.SUPPORTS),
        (names.LayoutShape, names.LAYOUT_SHAPES),
        (names.HoleShape, names.HOLE_SHAPES),
        (names.MachineName, names.MACHINE_NAMES),
        (names.CutFormat, names.CUT_FORMATS),
        (names.FileFormat, names.FILE_FORMATS),
        (names.StiffnessName, names.STIFFNESS_NAMES),
        (names.StiffnessSymbol, names.STIFFNESS_SYMBOLS),
        (names.FoldStyle, names.FOLD_STYLES),
        (names.FoldOpName, names.FOLD_OP_NAMES),
        (names.PaperName, names.PAPER_NAMES),
        (names.LoadCaseName, names.LOAD_CASES),
    ],
)
def test_each_tuple_is_its_literal(literal: object, values: tuple[str, ...]) -> None:
    assert values == typing.get_args(literal)
    assert len(set(values)) == len(values) > 1


def test_model_names_are_the_moduli_table() -> None:
    from corrugate.mechanics.moduli import MODELS, get_model

    assert tuple(MODELS) == names.MODEL_NAMES
    assert get_model(names.DEFAULT_MODEL).name == names.DEFAULT_MODEL


def test_load_case_names_are_the_behaviour_registrys_and_the_specs() -> None:
    """names.LOAD_CASES (the command line's ``analyze --test``, declared without numpy) are the
    registry's built-in load cases a deflection may name, and the spec's schema lists them."""
    from corrugate.mechanics.behaviours import deflection_tests, load_cases
    from corrugate.spec.schema import Spec

    registered = tuple(b.name for b in load_cases())
    assert registered == names.LOAD_CASES + names.STIFFNESS_ONLY_TESTS
    assert tuple(b.name for b in deflection_tests()) == names.LOAD_CASES
    assert tuple(b.name for b in load_cases() if b.stiffness_only) == names.STIFFNESS_ONLY_TESTS
    defs = Spec.model_json_schema()["$defs"]
    assert defs["DeflectionSpec"]["properties"]["test"]["enum"] == list(names.LOAD_CASES)
    assert defs["StrengthSpec"]["properties"]["test"]["enum"] == list(names.LOAD_CASES)
    stiffness = defs["RigiditySpec"]["properties"]["test"]["anyOf"][0]["enum"]
    assert stiffness == ["pure", *registered]


def test_machine_names_are_the_cutters_table_and_a_laser_is_named_by_its_bed() -> None:
    from corrugate.export.machines import get_machine
    from corrugate.fabrication.sheets import CUTTERS, get_cutter

    assert tuple(CUTTERS) == names.MACHINE_NAMES
    assert all(CUTTERS[k].name == k for k in CUTTERS)
    laser = get_cutter("laser:600x400")
    assert laser.name.startswith(names.LASER_PREFIX) and (laser.width, laser.height) == (600, 400)
    with pytest.raises(UnknownNameError) as info:
        get_cutter("plotter")
    assert info.value.allowed == "one of " + ", ".join(sorted((*names.MACHINE_NAMES, names.LASER)))
    assert get_machine().name == names.DEFAULT_MACHINE
    # every machine reads cut formats of the list, and each format is read by some machine
    formats = {f for k in (*names.MACHINE_NAMES, "laser:600x400") for f in get_machine(k).formats}
    assert formats == set(names.CUT_FORMATS)


def test_layout_shapes_are_what_the_layout_factory_builds() -> None:
    from corrugate.geometry.layouts import make_layout

    triangle = [(0, 0), (1, 0), (0.5, 1)]
    for shape in names.LAYOUT_SHAPES:
        layout = make_layout(shape, triangle if shape == "polygon" else None)
        assert layout.name == shape
    with pytest.raises(UnknownNameError) as info:
        make_layout("hexagon")
    assert info.value.allowed == "one of " + ", ".join(sorted(names.LAYOUT_SHAPES))
    assert set(names.RECTANGULAR_LAYOUTS) <= set(names.LAYOUT_SHAPES)
    assert names.DEFAULT_LAYOUT in names.LAYOUT_SHAPES


def test_rectangular_layouts_are_the_outlines_whose_plan_is_their_bounding_box() -> None:
    # a second source: the plan outline's area equals Lx * Ly exactly for a rectangle only
    from corrugate.geometry.layouts import make_layout
    from corrugate.geometry.planar import signed_area

    triangle = [(0, 0), (1, 0), (0.5, 1)]
    full = set()
    for shape in names.LAYOUT_SHAPES:
        outline = make_layout(shape, triangle if shape == "polygon" else None).plan_outline(
            30.0, 20.0
        )
        if abs(abs(signed_area(outline)) - 600.0) < 1e-9:
            full.add(shape)
    assert full == set(names.RECTANGULAR_LAYOUTS)


def test_hole_shapes_are_what_the_holes_parser_takes() -> None:
    from corrugate.geometry.holes import holes_from_data

    made = holes_from_data(
        [
            {"shape": "circle", "diameter": 4},
            {"shape": "polygon", "vertices": [[0, 0], [2, 0], [1, 2]], "center": [5, 0]},
            {"diameter": 3},  # no shape: the default
        ],
        "holes",
    )
    assert tuple(h.shape for h in made[:2]) == names.HOLE_SHAPES
    assert made[2].shape == names.DEFAULT_HOLE_SHAPE
    with pytest.raises(InputError):
        holes_from_data([{"shape": "square", "diameter": 3}], "holes")


def test_supports_are_the_registered_built_ins_and_the_spec_takes_each() -> None:
    """The built-in supports of the registry (mechanics/supports) are the names' ones; the spec's
    JSON Schema lists them (the registry may hold more, so the spec's type is checked at run time)."""
    from corrugate.mechanics import behaviours, offaxis
    from corrugate.spec.schema import Spec

    assert behaviours.support_names() == names.SUPPORTS
    assert behaviours.DEFAULT_SUPPORT == names.DEFAULT_SUPPORT
    assert typing.get_args(offaxis.Support) == names.SUPPORTS
    for s in names.SUPPORTS:
        assert offaxis.check_support(s) == s
    with pytest.raises(UnknownNameError):
        offaxis.check_support("glued")
    schema = Spec.model_json_schema()
    assert list(names.SUPPORTS) in [v.get("enum") for v in schema["$defs"].values()] + [
        schema["properties"]["support"].get("enum")
    ]
    assert Spec.model_fields["support"].default == names.DEFAULT_SUPPORT
    assert Spec.model_fields["model"].default == names.DEFAULT_MODEL


def test_stiffness_names_are_the_spec_kinds_and_their_symbols_the_solver_keys() -> None:
    from corrugate.solver.quantity import Quantity
    from corrugate.spec.schema import STIFFNESS_KINDS, ConstraintsSpec, ObjectiveSpec

    assert tuple(STIFFNESS_KINDS) == names.STIFFNESS_NAMES
    assert set(names.STIFFNESS_NAMES) <= set(ConstraintsSpec.model_fields)
    maximize = ObjectiveSpec.model_fields["maximize"].annotation
    assert set(typing.get_args(typing.get_args(maximize)[0])) == set(names.STIFFNESS_NAMES)
    for kind, symbol in names.STIFFNESS_SYMBOL.items():
        assert Quantity.stiffness(kind, 30.0).key == f"{symbol}@30"
        assert Quantity.stiffness(symbol, 30.0).key == f"{symbol}@30"
        assert Quantity.stiffness(kind, 30.0, "frame").key == f"{symbol}frame@30"
    # the units follow the symbols: EI in N mm^2, D in N mm, K in N/mm (docs/theory.md)
    units = {"EI": "N*mm^2", "D": "N*mm", "K": "N/mm"}
    assert {k: units[s] for k, s in names.STIFFNESS_SYMBOL.items()} == STIFFNESS_KINDS


def test_fold_styles_are_the_machine_default_and_the_line_styles() -> None:
    from corrugate.export.machines import get_machine
    from corrugate.export.operations import FoldOp, default_operations, style_operations
    from corrugate.fabrication.linestyle import StyleKind

    assert ("machine", *(k.value for k in StyleKind)) == names.FOLD_STYLES
    assert names.DEFAULT_FOLD_STYLE == "machine"
    for machine in names.MACHINE_NAMES:
        m = get_machine(machine)
        assert style_operations(names.DEFAULT_FOLD_STYLE, m, "dura-lar") == (
            default_operations(m, "dura-lar")
        )
    assert tuple(op.value for op in FoldOp) == names.FOLD_OP_NAMES


def test_paper_names_are_mat_and_the_tile_papers() -> None:
    from corrugate.export.pdf import PAPERS, check_paper

    assert ("mat", *PAPERS) == names.PAPER_NAMES
    for p in names.PAPER_NAMES:
        assert check_paper(p.upper()) == p
    with pytest.raises(UnknownNameError):
        check_paper("a3")


def test_file_formats_are_those_write_files_takes() -> None:
    from corrugate.export.files import FORMATS

    assert names.FILE_FORMATS == FORMATS


def test_the_output_defaults_are_the_same_on_the_command_line_the_web_and_the_library() -> None:
    # A second source for each default: the plain dataclass defaults of the writers, compared with
    # what the command line and the web app pass on when nothing is given.
    from corrugate.cli.pattern import pattern_cmd
    from corrugate.export.plan import OutputOptions
    from corrugate.fabrication.sheets import SheetPlan, plan_sheets
    from corrugate.geometry.fabrication_options import FabricationOptions
    from corrugate.web.app import _output_options
    from corrugate.web.schemas import OutputBody
    from corrugate.workflow import output_options

    library = OutputOptions()
    assert (library.cutter, library.paper) == (names.DEFAULT_MACHINE, names.DEFAULT_PAPER)
    assert (library.spacing, library.margin) == (
        names.DEFAULT_SPACING_MM,
        names.DEFAULT_MARGIN_MM,
    )
    assert FabricationOptions().tab_depth == names.DEFAULT_TAB_DEPTH_MM
    assert output_options() == library
    assert _output_options(OutputBody()) == library
    cli = {k: v.default for k, v in inspect.signature(pattern_cmd).parameters.items() if k != "out"}
    from_cli = output_options(
        cli["cutter"],
        cli["fold_style"],
        cli["cut"],
        cli["gap"],
        cli["spacing"],
        cli["margin"],
        cli["tab_depth"],
        cli["labels"],
        cli["paper"],
    )
    assert from_cli == library
    signature = inspect.signature(plan_sheets).parameters
    assert (signature["spacing"].default, signature["margin"].default) == (
        SheetPlan.__dataclass_fields__["spacing"].default,
        SheetPlan.__dataclass_fields__["margin"].default,
    )
    assert signature["cutter"].default == names.DEFAULT_MACHINE
