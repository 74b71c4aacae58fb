"""The one table of parameters is what every surface declares: the command line's options (flags,
metavar, help, default, required), the web API's fields (default, description), the spec
reference's texts of the same keys; its units and limit keys agree with the limits table; its help
texts' examples are values the parsers take; and it loads nothing heavy at start-up."""

from __future__ import annotations

import ast
import math
import subprocess
import sys
from pathlib import Path
from typing import Any

import pytest
import typer.main

from corrugate.core.errors import InputError
from corrugate.core.limits import LIMITS
from corrugate.core.parameters import (
    DESIGN_PARAMETERS,
    LOAD_CASE_PARAMETERS,
    OUTPUT_PARAMETERS,
    PARAMETERS,
    Parameter,
)

SRC = Path(__file__).resolve().parents[2] / "src" / "corrugate"

#: Which parameters each command takes (a second source: the commands' documented options).
COMMAND_PARAMETERS = {
    "analyze": [p.name for p in (*DESIGN_PARAMETERS, *LOAD_CASE_PARAMETERS)],
    "pattern": [p.name for p in (*DESIGN_PARAMETERS, *OUTPUT_PARAMETERS)],
    "validate": [p.name for p in DESIGN_PARAMETERS if p.name not in ("vertices", "holes", "model")],
    "design": ["cutter", "labels", "fold_style", "cut", "gap", "paper"],
}


def _click_params(command: str) -> dict[str, Any]:
    """The options of ``corrugate COMMAND`` as typer builds them (its click options)."""
    from corrugate.cli import app

    group: Any = typer.main.get_command(app)
    return {p.name: p for p in group.commands[command].params if hasattr(p, "secondary_opts")}


def test_parameters_loads_neither_numpy_nor_typer_nor_pydantic() -> None:
    code = (
        "import sys\n"
        "import corrugate.core.parameters\n"
        "print(sorted(m for m in sys.modules if m.startswith('corrugate')\n"
        "             or m in ('numpy', 'typer', 'pydantic', 'click')))\n"
    )
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True)
    loaded = ast.literal_eval(out.stdout.strip())
    assert loaded == ["corrugate", "corrugate.core", "corrugate.core.parameters", "corrugate.names"]


def test_names_flags_and_help_texts_are_unique_and_complete() -> None:
    assert len(PARAMETERS) == (
        len(DESIGN_PARAMETERS) + len(OUTPUT_PARAMETERS) + len(LOAD_CASE_PARAMETERS)
    )
    flags = [f for p in PARAMETERS.values() for f in p.flags]
    assert len(set(flags)) == len(flags)
    for p in PARAMETERS.values():
        assert p.help.endswith("."), p.name
        assert (p.metavar is None) == (p.kind == "flag"), p.name
        assert not (p.required and p.default is not None), p.name
        if p.kind == "name":  # a name without a default may be left out (--test)
            assert p.default is None or p.default in p.choices, p.name
            assert p.metavar in (None, "MACHINE") or p.metavar == "[" + "|".join(p.choices) + "]"


def test_design_parameters_are_the_assembly_options_then_model_and_support() -> None:
    from corrugate.spec.inputs import ASSEMBLY_OPTIONS

    assert tuple(p.name for p in DESIGN_PARAMETERS) == (*ASSEMBLY_OPTIONS, "model", "support")


@pytest.mark.parametrize("p", [p for p in PARAMETERS.values() if p.limits], ids=lambda p: p.name)
def test_limit_keys_exist_and_share_the_parameters_unit(p: Parameter) -> None:
    assert p.limits is not None
    assert LIMITS[p.limits].unit == p.unit


@pytest.mark.parametrize("command", sorted(COMMAND_PARAMETERS))
def test_the_command_line_declares_each_parameter_from_the_table(command: str) -> None:
    params = _click_params(command)
    for name in COMMAND_PARAMETERS[command]:
        p, opt = PARAMETERS[name], params[name]
        if p.kind == "flag":
            on, off = p.flags[0].split("/")
            assert (opt.opts, opt.secondary_opts) == ([on], [off])
        else:
            assert opt.opts == list(p.flags)
        if command == "validate" and name == "layout":  # the FE takes rectangles only
            assert opt.help == "square | rectangle (the FE tests need straight loaded edges)."
            assert opt.metavar == "[square|rectangle]"
        else:
            assert (opt.help, opt.metavar) == (p.help, p.metavar), name
        # validate reads W, n and alpha from --design too
        assert opt.required == (p.required and command != "validate"), name
        if command == "design" and name == "cutter":  # not given: the spec's [fabrication]
            assert opt.default is None
        else:
            assert opt.default == p.default, name


def test_every_table_flag_is_written_once_in_the_source() -> None:
    """Each option is declared in the table, not again beside it (``"--W2"`` once in src)."""
    texts = {path: path.read_text(encoding="utf-8") for path in SRC.rglob("*.py")}
    for p in PARAMETERS.values():
        for flag in p.flags:
            where = [path.name for path, text in texts.items() if f'"{flag}"' in text]
            assert where == ["parameters.py"], (flag, where)


def _web_fields() -> dict[str, Any]:
    from corrugate.web.schemas import PatternBody

    return dict(PatternBody.model_fields)


@pytest.mark.parametrize(
    "name",
    [p.name for p in DESIGN_PARAMETERS]
    + [
        p.name
        for p in OUTPUT_PARAMETERS
        if p.name in ("cutter", "fold_style", "cut", "gap", "paper")
    ],
)
def test_the_web_fields_take_the_tables_default_and_help(name: str) -> None:
    p, field = PARAMETERS[name], _web_fields()[name]
    assert field.description == p.help
    assert field.is_required() == p.required
    if not p.required:
        assert field.get_default() == p.default


def test_the_analyze_body_has_the_design_parameters_the_directions_and_a_load_case() -> None:
    from corrugate.web.schemas import AnalyzeBody

    assert list(AnalyzeBody.model_fields) == [
        *(p.name for p in DESIGN_PARAMETERS[:-1]),
        "eta",
        "support",
        *(p.name for p in LOAD_CASE_PARAMETERS),  # analyze --test --load --span
    ]


def test_the_spec_reference_describes_the_same_keys_with_the_same_text() -> None:
    from corrugate.spec.reference import KEYS, reference_markdown

    pairs = {"model": "model", "layout.shape": "layout"}
    for table in ("material", "materials[]"):
        pairs |= {f"{table}.{k}": k for k in ("E", "nu", "density")}
    for key, name in pairs.items():
        assert KEYS[key].text == PARAMETERS[name].help, key
        assert KEYS[key].unit == PARAMETERS[name].unit, key
    # every row of the reference is still five cells (no help text breaks the Markdown table)
    rows = [line for line in reference_markdown().splitlines() if line.startswith("| `")]
    assert len(rows) == len(KEYS)
    assert all(line.count("|") == 6 for line in rows)


def test_the_examples_in_the_help_texts_are_values_the_parsers_take() -> None:
    """What the help promises: W '0.3 in' is 7.62 mm, alpha '1.4 rad' is 80.21 deg, E '2.7GPa' is
    2700 MPa, nu strictly between -1 and 0.5, the vertices and holes examples parse."""
    import json

    from corrugate.core.units import parse_quantity
    from corrugate.materials.library import inline_material
    from corrugate.spec.inputs import parse_holes, parse_vertices

    assert parse_quantity("0.3 in", "mm", "W") == pytest.approx(0.3 * 25.4)
    assert parse_quantity("1.4 rad", "deg", "alpha") == pytest.approx(math.degrees(1.4))
    assert parse_quantity("2.7GPa", "MPa", "E") == pytest.approx(2700.0)
    assert inline_material(2700, 0.49, 1.39).nu == 0.49
    for nu in (0.5, -1.0):
        with pytest.raises(InputError):
            inline_material(2700, nu, 1.39)
    assert "'0,0 1,0 0.5,1'" in PARAMETERS["vertices"].help
    assert parse_vertices("0,0 1,0 0.5,1") == [(0, 0), (1, 0), (0.5, 1)]
    text = PARAMETERS["holes"].help
    example = text[text.index("'[") + 1 : text.rindex("]'") + 1]
    holes = parse_holes(example)
    assert json.loads(example)[0]["diameter"] == "6 mm"
    assert holes[0].shape == "circle" and holes[0].diameter == 6.0
