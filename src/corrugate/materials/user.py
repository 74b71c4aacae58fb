"""The user's own materials files: a calibrated sheet, or a library entry extended.

Two files are read, in the library's format (``data/materials.toml``, one table per material):

- ``corrugate-materials.toml`` beside a spec (:data:`SPEC_FILE`): the materials of the specs in
  that folder (:func:`spec_materials`);
- ``materials.toml`` in the user's config folder (:func:`config_dir`: ``$CORRUGATE_CONFIG_DIR``
  when set, else platformdirs' user config folder for ``corrugate`` when platformdirs is
  installed, else ``~/.config/corrugate``): every command's (:func:`user_materials`).

A table may extend a library entry (``extends = "dura-lar"``: every key not given is the
library's). The spec's file wins over the config folder's, which wins over the library
(:func:`corrugate.materials.library.get_material`). ``corrugate calibrate fit --save`` writes
its fit there (:func:`write_entry`, docs/calibration.md section 6).
"""

from __future__ import annotations

import os
from collections.abc import Mapping
from functools import lru_cache
from pathlib import Path
from typing import Any

from corrugate.core.errors import InputError
from corrugate.materials.library import Material, library_entries, material_from_entry

__all__ = [
    "CONFIG_FILE",
    "SPEC_FILE",
    "config_dir",
    "entry_text",
    "existing_text",
    "read_materials",
    "spec_materials",
    "user_materials",
    "write_entry",
]

#: The materials file beside a spec.
SPEC_FILE = "corrugate-materials.toml"
#: The materials file in the user's config folder.
CONFIG_FILE = "materials.toml"
#: The largest materials file read (bytes).
MAX_BYTES = 1 << 20


def config_dir() -> Path:
    """The user's config folder for corrugate (module docstring)."""
    env = os.environ.get("CORRUGATE_CONFIG_DIR")
    if env:
        return Path(env)
    try:
        import platformdirs
    except ImportError:
        return Path.home() / ".config" / "corrugate"
    return Path(platformdirs.user_config_dir("corrugate"))


def _entries(text: str, shown: str) -> dict[str, Any]:
    from corrugate.core.fileio import parse_toml_input
    from corrugate.core.limits import MAX_NAME_CHARS, check_text

    data = parse_toml_input(text, "materials file", shown)
    for key, entry in data.items():
        check_text(f"{shown} [{key[:MAX_NAME_CHARS]}]", key)  # a material id: at most 200 chars
        if not isinstance(entry, dict):
            raise InputError(f"{shown} [{key}]", repr(entry)[:40], "a table of a material")
    return data


def _material(key: str, entry: dict[str, Any], shown: str) -> Material:
    base = entry.get("extends")
    if base is not None:
        lib = library_entries()
        if str(base).lower() not in lib:
            raise InputError(
                f"{shown} [{key}].extends",
                repr(base),
                "a library material id: " + ", ".join(sorted(lib)),
            )
        merged = dict(lib[str(base).lower()])
        merged.pop("aliases", None)  # a variant of a PET film is not itself "pet"
        merged.update({k: v for k, v in entry.items() if k != "extends"})
        entry = merged
    return material_from_entry(key.strip().lower(), entry, shown)


@lru_cache(maxsize=16)
def _read(path: str, stamp: tuple[int, int]) -> dict[str, Material]:
    from corrugate.core.fileio import read_input_text

    p = Path(path)
    # a regular file only, size-capped, strict UTF-8 (read as untrusted input)
    text = read_input_text(p, "materials file", MAX_BYTES)
    return {k.strip().lower(): _material(k, e, p.name) for k, e in _entries(text, p.name).items()}


def read_materials(path: str | os.PathLike[str]) -> dict[str, Material]:
    """The materials of the file ``path`` by id ({} when it does not exist); read again only when
    the file changes."""
    p = Path(path)
    try:
        st = p.stat()
    except OSError:
        return {}
    if not p.is_file():
        return {}
    return dict(_read(str(p), (st.st_mtime_ns, st.st_size)))


def user_materials() -> dict[str, Material]:
    """The materials of the user's config folder (``materials.toml`` there; {} without one)."""
    return read_materials(config_dir() / CONFIG_FILE)


def spec_materials(spec_dir: str | os.PathLike[str] | None) -> dict[str, Material]:
    """A spec's own materials: the config folder's, with those of ``corrugate-materials.toml``
    in ``spec_dir`` (the spec's folder; None: none) over them."""
    found = user_materials()
    if spec_dir is not None:
        found.update(read_materials(Path(spec_dir) / SPEC_FILE))
    return found


def _toml_value(v: Any) -> str:
    if isinstance(v, bool):
        return "true" if v else "false"
    if isinstance(v, int | float):
        return repr(v)
    if isinstance(v, list | tuple):
        return "[" + ", ".join(_toml_value(x) for x in v) + "]"
    if isinstance(v, Mapping):
        return "{ " + ", ".join(f"{_key(k)} = {_toml_value(x)}" for k, x in v.items()) + " }"
    text = str(v).replace("\\", "\\\\").replace('"', '\\"').replace("\n", " ")
    return f'"{text}"'


def _key(k: str) -> str:
    return k if k and all(c.isalnum() or c in "-_" for c in k) else _toml_value(k)


def entry_text(key: str, entry: Mapping[str, Any]) -> str:
    """The TOML table ``[key]`` of ``entry`` (values: text, numbers, lists, tables of those;
    nested tables as ``[key.sub]``)."""
    lines = [f"[{_key(key)}]"]
    subs = {k: v for k, v in entry.items() if isinstance(v, Mapping)}
    lines += [f"{_key(k)} = {_toml_value(v)}" for k, v in entry.items() if k not in subs]
    for sub, table in subs.items():
        lines += ["", f"[{_key(key)}.{_key(sub)}]"]
        lines += [f"{_key(k)} = {_toml_value(v)}" for k, v in table.items()]
    return "\n".join(lines) + "\n"


def write_entry(
    path: str | os.PathLike[str],
    key: str,
    entry: Mapping[str, Any],
    field: str = "materials file",
) -> Path:
    """Put the material ``[key]`` (``entry``: the library's keys, and any others) into the
    materials file ``path`` (created with its folder if missing): appended, or, when the file
    has a table of that id already, the file written again with every other table as it reads
    (its comments are not kept) and this one last. The whole text is checked before it is
    written, all or nothing; a file that cannot be read or written (a folder, a FIFO, not UTF-8,
    a name too long, a folder of ``/proc``) is one error line naming ``field``."""
    from corrugate.core.fileio import atomic_write

    p = Path(path)
    old = existing_text(p, field)
    data = _entries(old, p.name) if old.strip() else {}
    if key in data:
        old = _HEADER + "\n".join(entry_text(k, v) for k, v in data.items() if k != key)
    elif not old.strip():
        old = _HEADER
    text = old.rstrip("\n") + "\n\n" + entry_text(key, entry)
    for k, e in _entries(text, p.name).items():
        _material(k, e, p.name)
    return atomic_write(p, text, field)


def existing_text(path: Path, field: str) -> str:
    """The text of the materials file ``path`` that :func:`write_entry` adds to ("" when there
    is none), read as untrusted input (a regular UTF-8 file of at most 1 MiB), its tables
    checked; one :class:`~corrugate.core.errors.InputError` line naming ``field`` otherwise.
    Called before a fit too, so that a bad target is named before the work."""
    from corrugate.core.fileio import read_input_text

    try:
        os.lstat(path)
    except FileNotFoundError:
        return ""  # made by write_entry
    except (OSError, ValueError):  # a name too long, a file on the way: read_input names why
        pass
    text = read_input_text(path, field, MAX_BYTES)
    for k, e in (_entries(text, path.name) if text.strip() else {}).items():
        _material(k, e, path.name)
    return text


_HEADER = (
    "# corrugate: the user's own materials, in the library's format (corrugate docs calibration).\n"
    "# A spec names one by its id as any library material.\n"
)
