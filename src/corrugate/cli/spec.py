"""``corrugate spec`` (the spec reference, or its JSON Schema), ``corrugate init`` (a spec to
start from: the commented template or one of the shipped examples) and ``corrugate docs`` (the
documentation shipped with the package, which messages cite as `corrugate docs NAME`)."""

from __future__ import annotations

import json
from typing import Annotated

import typer

__all__ = ["COMMANDS", "docs_cmd", "init_cmd", "spec_cmd"]


def spec_cmd(
    schema: Annotated[
        bool,
        typer.Option("--schema", help="Print a JSON Schema of spec files (for editors)."),
    ] = False,
) -> None:
    """Every key a spec file may hold, with its unit, default and meaning (`corrugate docs spec`).

    Example: corrugate spec --schema > corrugate-spec.schema.json
    """
    from corrugate.spec.reference import json_schema, reference_markdown

    if schema:
        typer.echo(json.dumps(json_schema(), indent=2))
    else:
        typer.echo(reference_markdown(), nl=False)


def init_cmd(
    example: Annotated[
        str | None,
        typer.Option(
            metavar="NAME",
            help="Print this shipped example instead of the template (see --list).",
        ),
    ] = None,
    list_: Annotated[bool, typer.Option("--list", help="List the shipped examples.")] = False,
) -> None:
    """Print a spec to start from: a commented template (the paper's case study).

    Example: corrugate init > my.toml && corrugate design my.toml
    """
    from corrugate.spec.examples import example_names, example_text, template_text

    if list_:
        for name in example_names():
            typer.echo(name)
    elif example is not None:
        typer.echo(example_text(example), nl=False)
    else:
        typer.echo(template_text(), nl=False)


def _complete_doc(incomplete: str) -> list[str]:
    """Shell completion of ``corrugate docs NAME``: the shipped doc names."""
    from corrugate.core.docs import doc_names

    return [n for n in doc_names() if n.startswith(incomplete)]


def _doc_name(value: str) -> str:
    """The doc name as given; :func:`corrugate.core.docs.doc_text` checks it (one line, exit 2)."""
    return value


_doc_name.__name__ = "name"  # ``--help`` shows the argument's type as <name>, not <str>


def docs_cmd(
    name: Annotated[
        str | None,
        typer.Argument(
            metavar="[NAME]",
            parser=_doc_name,
            autocompletion=_complete_doc,
            help="A doc to print (Markdown), e.g. fea or validation/off_axis; none: list them.",
        ),
    ] = None,
) -> None:
    """The documentation shipped with the package: list the docs, or print one.

    Messages cite these by name, e.g. "see `corrugate docs fea` (section 2.5)".

    Example: corrugate docs offaxis | less
    """
    from corrugate.core.docs import doc_names, doc_text, doc_title

    if name is None:
        names = doc_names()
        width = max(len(n) for n in names)
        for n in names:
            typer.echo(f"{n:<{width}}  {doc_title(n)}")
        typer.echo("Print one: corrugate docs NAME")
    else:
        typer.echo(doc_text(name), nl=False)


#: The commands of this module, by name (registered by :mod:`corrugate.cli`).
COMMANDS = {"spec": spec_cmd, "init": init_cmd, "docs": docs_cmd}
