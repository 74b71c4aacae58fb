"""Compare two runs' output sets file by file: the check that a change left every file the same.

Usage::

    python benchmarks/compare_sets.py BEFORE AFTER

``BEFORE`` and ``AFTER`` are folders holding one output folder per case (the same names in both),
each written by ``corrugate design SPEC --out`` or ``corrugate pattern ... --out``, for example,
once on the old checkout and once on the new one::

    export PYTHONHASHSEED=0   # ezdxf orders two OBJECTS entries by hash: fix the seed
    for ex in examples/*.toml; do corrugate design "$ex" --out "BEFORE/$(basename "$ex" .toml)" -q; done
    corrugate pattern --W 8 --n 8 --alpha 84 --material dura-lar --out BEFORE/pattern -q

For each case it reads the two manifests (``.corrugate-set.json``, each file's SHA-256), compares
the file lists, and for every file whose hash differs compares the files again after dropping what
differs between any two runs of the same code: in a DXF, the ``$TDCREATE`` and ``$TDUPDATE`` dates,
the GUIDs and ezdxf's version-and-time stamp; in ``design.json``, the ``*_seconds`` timings. It
prints one line per case, a total, and each file that still differs; the exit code is 1 when one
does, else 0.
"""

from __future__ import annotations

import json
import re
import sys
from pathlib import Path
from typing import Any

MANIFEST = ".corrugate-set.json"


def manifest_files(folder: Path) -> dict[str, str]:
    """File name -> SHA-256 of the one set in ``folder``'s manifest."""
    data = json.loads((folder / MANIFEST).read_text(encoding="utf-8"))
    (one,) = data["sets"].values()
    files: dict[str, str] = one["files"]
    return files


def _strip_timings(value: Any) -> Any:
    if isinstance(value, dict):
        return {k: _strip_timings(v) for k, v in value.items() if not k.endswith("_seconds")}
    if isinstance(value, list):
        return [_strip_timings(v) for v in value]
    return value


def without_run_stamps(path: Path) -> bytes:
    """The bytes of ``path`` without what two runs of the same code write differently."""
    raw = path.read_bytes()
    if path.suffix == ".dxf":
        text = raw.decode("utf-8")
        text = re.sub(r"(\$TD(?:CREATE|UPDATE)\r?\n *40\r?\n)[0-9.]+", r"\1X", text)
        text = re.sub(r"\{[0-9A-F-]{36}\}", "{GUID}", text)
        text = re.sub(r"\d+\.\d+\.\d+ @ [0-9T:.+-]+", "VERSION @ TIME", text)
        return text.encode("utf-8")
    if path.name == "design.json":
        data = _strip_timings(json.loads(raw))
        return json.dumps(data, sort_keys=True).encode("utf-8")
    return raw


def compare(before: Path, after: Path) -> list[str]:
    """Print the comparison of every case; return the files that differ (``case/file``)."""
    differ: list[str] = []
    total = same_hash = same_stripped = 0
    for case in sorted(p for p in before.iterdir() if p.is_dir()):
        old, new = manifest_files(case), manifest_files(after / case.name)
        if set(old) != set(new):
            differ.append(f"{case.name}: file lists differ by {sorted(set(old) ^ set(new))}")
        changed = []
        for name in sorted(set(old) & set(new)):
            total += 1
            if old[name] == new[name]:
                same_hash += 1
            elif without_run_stamps(case / name) == without_run_stamps(after / case.name / name):
                same_stripped += 1
                changed.append(name)
            else:
                differ.append(f"{case.name}/{name}")
                changed.append(name)
        print(f"{case.name}: {len(old)} files, hash differs: {changed or 'none'}")
    print(
        f"{total} files: {same_hash} identical SHA-256, {same_stripped} identical without run "
        f"stamps, {len(differ)} differ"
    )
    for line in differ:
        print(f"  differs: {line}")
    return differ


def main(argv: list[str]) -> int:
    if len(argv) != 2:
        print(__doc__, file=sys.stderr)
        return 2
    return 1 if compare(Path(argv[0]), Path(argv[1])) else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
