"""The design and output options declared once (:func:`corrugate.cli.options.table_options`):
no command spells them again, their defaults are names.py's, and a toy command made with the same
declaration gets them as one :class:`TableValues` (what click parses and shows checked against
the table's entry). tests/core/test_parameters.py checks every command's options against the
table."""

from __future__ import annotations

import ast
from pathlib import Path
from typing import Any

import pytest
import typer
import typer.main
from typer.testing import CliRunner

from corrugate import names
from corrugate.cli import app
from corrugate.cli.options import TableValues, table_options
from corrugate.core.parameters import PARAMETERS

CLI = Path(__file__).resolve().parents[2] / "src" / "corrugate" / "cli"


def _params(command: str) -> dict[str, Any]:
    group: Any = typer.main.get_command(app)
    return {p.name: p for p in group.commands[command].params if p.name is not None}


def test_the_defaults_are_names_defaults() -> None:
    """A second source for the defaults the table gives the commands: names.py's
    (tests/core/test_parameters.py checks flags, help texts and defaults against the table)."""
    pattern = _params("pattern")
    assert pattern["cutter"].default == names.DEFAULT_MACHINE
    assert pattern["paper"].default == names.DEFAULT_PAPER
    assert pattern["fold_style"].default == names.DEFAULT_FOLD_STYLE
    assert float(str(pattern["spacing"].default)) == names.DEFAULT_SPACING_MM
    assert float(str(pattern["tab_depth"].default)) == names.DEFAULT_TAB_DEPTH_MM
    analyze = _params("analyze")
    assert analyze["model"].default == names.DEFAULT_MODEL
    assert analyze["layout"].default == names.DEFAULT_LAYOUT
    assert analyze["support"].default == names.DEFAULT_SUPPORT
    assert _params("design")["cutter"].default is None  # the spec's machine


def test_no_command_spells_a_table_parameter_again() -> None:
    """The commands' own signatures (parsed, not imported) declare none of the table's
    parameters: they come from the one declaration (``table_options``)."""
    spelt = []
    for path in sorted(CLI.glob("*.py")):
        for node in ast.walk(ast.parse(path.read_text(encoding="utf-8"))):
            if isinstance(node, ast.FunctionDef) and node.name.endswith("_cmd"):
                args = node.args.args + node.args.kwonlyargs
                spelt += [f"{path.name}:{node.name}:{a.arg}" for a in args if a.arg in PARAMETERS]
    assert spelt == []


def test_a_toy_command_gets_the_tables_options_as_one_value() -> None:
    got: list[tuple[TableValues, int]] = []

    @table_options("W", "extra", "paper", defaults={"paper": "a4"})
    def toy(table: TableValues, extra: int = 1) -> None:
        """A toy command."""
        got.append((table, extra))

    toy_app = typer.Typer(rich_markup_mode=None)
    toy_app.command()(toy)
    runner = CliRunner()
    result = runner.invoke(toy_app, ["--W", "8 mm", "--extra", "3"])
    assert result.exit_code == 0, result.output
    [(table, extra)] = got
    assert dict(table) == {"W": "8 mm", "paper": "a4"} and extra == 3
    help_text = runner.invoke(toy_app, ["--help"], terminal_width=200).output
    order = [help_text.index(flag) for flag in ("--W", "--extra", "--paper")]
    assert order == sorted(order)  # the options in the order declared
    assert f"--W {PARAMETERS['W'].metavar}" in help_text  # the table's metavar
    missing = runner.invoke(toy_app, ["--extra", "3"])
    assert missing.exit_code == 2 and "--W" in missing.output  # W is required in the table


def test_a_declaration_naming_no_parameter_is_refused() -> None:
    def no_table(extra: int = 1) -> None:
        pass

    with pytest.raises(TypeError, match="no parameter 'table'"):
        table_options("W")(no_table)

    def unknown(table: TableValues) -> None:
        pass

    with pytest.raises(TypeError, match="unknown"):
        table_options("no_such_option")(unknown)
