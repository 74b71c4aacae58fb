"""``corrugate spec`` (the spec reference, or its JSON Schema) and ``corrugate init`` (a spec to
start from: the commented template or one of the shipped examples)."""

from __future__ import annotations

import json
from typing import Annotated

import typer

__all__ = ["COMMANDS", "init_cmd", "spec_cmd"]


def spec_cmd(
    schema: Annotated[
        bool,
        typer.Option("--schema", help="Print a JSON Schema of spec files (for editors)."),
    ] = False,
) -> None:
    """Every key a spec file may hold, with its unit, default and meaning (docs/spec.md).

    Example: corrugate spec --schema > corrugate-spec.schema.json
    """
    from ..spec_reference import json_schema, reference_markdown

    if schema:
        typer.echo(json.dumps(json_schema(), indent=2))
    else:
        typer.echo(reference_markdown(), nl=False)


def init_cmd(
    example: Annotated[
        str | None,
        typer.Option(help="Print this shipped example instead of the template (see --list)."),
    ] = None,
    list_: Annotated[bool, typer.Option("--list", help="List the shipped examples.")] = False,
) -> None:
    """Print a spec to start from: a commented template (the paper's case study).

    Example: corrugate init > my.toml && corrugate design my.toml
    """
    from ..examples import example_names, example_text, template_text

    if list_:
        for name in example_names():
            typer.echo(name)
    elif example is not None:
        typer.echo(example_text(example), nl=False)
    else:
        typer.echo(template_text(), nl=False)


#: The commands of this module, by name (registered by :mod:`corrugate.cli`).
COMMANDS = {"spec": spec_cmd, "init": init_cmd}
