"""The command line runs a command from a group that holds it alone (``corrugate.cli._app_for``,
issue 24: typer builds the parameters of every command it holds on each run): checked against
the whole app (:data:`corrugate.cli.app`, the group every command is registered in), which must
print the same help and the same usage errors for every command."""

from __future__ import annotations

import subprocess
import sys

import pytest

from corrugate.cli import COMMAND_MODULES, COMMANDS, _app_for, app


def _run(group: object, args: list[str], capsys: pytest.CaptureFixture[str]) -> tuple[int, str]:
    with pytest.raises(SystemExit) as info:
        group(args=args)  # type: ignore[operator]
    out, err = capsys.readouterr()
    code = info.value.code
    return (0 if code is None else int(code)), out + err


NAMES = [name for module in COMMAND_MODULES for name in module.COMMANDS]


def test_the_table_of_command_modules_names_each_module_s_own_commands_in_order() -> None:
    """corrugate.cli.COMMANDS (which module a run imports) against each module's COMMANDS."""
    owners = [
        (name, module.__name__.rsplit(".", 1)[1])
        for module in COMMAND_MODULES
        for name in module.COMMANDS
    ]
    assert list(COMMANDS.items()) == owners
    assert len(COMMAND_MODULES) == 8


def test_a_command_imports_only_its_own_module() -> None:
    """A run of ``design`` loads corrugate.cli.design and none of the other command modules."""
    code = (
        "import sys; from corrugate.cli import _app_for; _app_for(['design']); "
        "print(sorted(m for m in sys.modules if m.startswith('corrugate.cli.')))"
    )
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True)
    loaded = {m.rsplit(".", 1)[1] for m in eval(out.stdout)}
    assert "design" in loaded
    assert not loaded & {"analyze", "pattern", "validate", "verify", "calibrate", "serve", "spec"}


@pytest.mark.parametrize("name", NAMES)
def test_a_command_alone_answers_as_in_the_whole_app(
    name: str, capsys: pytest.CaptureFixture[str]
) -> None:
    one = _app_for([name, "--help"])
    assert one is not app
    for args in ([name, "--help"], [name, "--no-such-option"]):
        alone = _run(one, args, capsys)
        whole = _run(app, args, capsys)
        assert alone == whole, args
        assert alone[0] == (0 if args[1] == "--help" else 2)
        assert name in alone[1]


def test_the_group_itself_and_unknown_names_use_the_whole_app() -> None:
    assert _app_for([]) is app
    assert _app_for(["--help"]) is app
    assert _app_for(["--version"]) is app
    assert _app_for(["desing"]) is app  # click's "No such command" with its suggestion
