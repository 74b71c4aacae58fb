"""corrugate.core.plugins and corrugate.core.first_import: pydantic validates without its
plugin scan and without importing ``importlib.metadata``, which stays importable (issue 39).

Each check runs in a fresh interpreter: the test process has imported pydantic already.
"""

from __future__ import annotations

import json
import os
import subprocess
import sys
import textwrap

import pytest

#: Validates with a new pydantic model after the call (or without it) and prints, as JSON: the
#: modules of importlib.metadata loaded then, the loader's plugin table, the validated value and
#: an invalid value's error, and pydantic's version read through the real importlib.metadata.
_CHILD = textwrap.dedent(
    """
    import json, sys
    from corrugate.core.plugins import without_pydantic_plugins
    if sys.argv[1] == "call":
        without_pydantic_plugins()
    from pydantic import BaseModel, ValidationError, Field
    class M(BaseModel):
        x: float = Field(gt=0)
    value = M(x="2.5").x
    try:
        M(x=-1)
        error = None
    except ValidationError as exc:
        error = exc.errors()[0]["type"]
    loaded = sorted(m for m in sys.modules if m.split(".")[:2] == ["importlib", "metadata"])
    import pydantic.plugin._loader as loader
    plugins = None if loader._plugins is None else sorted(loader._plugins)
    import importlib.metadata
    print(json.dumps({
        "loaded": loaded,
        "plugins": plugins,
        "value": value,
        "error": error,
        "version": importlib.metadata.version("pydantic"),
        "real": type(importlib.metadata).__name__,
    }))
    """
)


def _child(how: str, **extra: str) -> dict[str, object]:
    env = {k: v for k, v in os.environ.items() if k != "PYDANTIC_DISABLE_PLUGINS"}
    out = subprocess.run(
        [sys.executable, "-c", _CHILD, how],
        capture_output=True,
        text=True,
        check=True,
        env={**env, **extra},
    )
    result: dict[str, object] = json.loads(out.stdout)
    return result


def test_pydantic_validates_without_importing_importlib_metadata() -> None:
    import pydantic

    done = _child("call")
    assert done["loaded"] == []  # nothing of importlib.metadata until the test imports it
    assert done["plugins"] == []  # the loader looked, and found none
    assert done["value"] == 2.5 and done["error"] == "greater_than"  # pydantic's own checks
    assert done["version"] == pydantic.VERSION  # the real module, imported afterwards
    assert done["real"] == "module"


def test_without_the_call_pydantic_imports_it() -> None:
    """The control: the same program without the call imports importlib.metadata."""
    done = _child("plain")
    assert "importlib.metadata" in done["loaded"]
    assert done["value"] == 2.5 and done["error"] == "greater_than"


def test_pydantics_own_switch_stands() -> None:
    """``PYDANTIC_DISABLE_PLUGINS`` set: the call does nothing, pydantic decides."""
    done = _child("call", PYDANTIC_DISABLE_PLUGINS="some-plugin")
    assert "importlib.metadata" in done["loaded"]


def test_around_first_import_runs_its_steps_once_around_the_module() -> None:
    code = textwrap.dedent(
        """
        import sys
        from corrugate.core.first_import import around_first_import, waiting_for
        seen = []
        around_first_import("colorsys", lambda: seen.append(("before", "colorsys" in sys.modules)),
                            lambda: seen.append(("after", hasattr(sys.modules["colorsys"], "hls_to_rgb"))))
        around_first_import("colorsys", lambda: seen.append("twice"), lambda: seen.append("twice"))
        waiting = waiting_for("colorsys")
        import colorsys
        import colorsys
        print(waiting, waiting_for("colorsys"), seen)
        """
    )
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True)
    # before: the module is in sys.modules (being executed), after: its functions are defined
    assert out.stdout.strip() == "True False [('before', True), ('after', True)]"


@pytest.mark.parametrize("name", ["corrugate_no_such_module"])
def test_around_first_import_of_a_missing_module_leaves_the_import_error(name: str) -> None:
    code = (
        "import sys\n"
        "from corrugate.core.first_import import around_first_import, waiting_for\n"
        f"around_first_import({name!r}, lambda: print('before'), lambda: print('after'))\n"
        "try:\n"
        f"    import {name}\n"
        "except ModuleNotFoundError:\n"
        "    print('missing')\n"
        f"print(waiting_for({name!r}))\n"
    )
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True)
    assert out.stdout.split() == ["missing", "False"]
