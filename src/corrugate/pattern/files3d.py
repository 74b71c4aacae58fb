"""Writers for the folded geometry: FOLD 1.2 (JSON) per layer, GLB and STL of the assembly."""

from __future__ import annotations

import contextlib
import json
from pathlib import Path

from ..fileio import Staging, staged
from ..geometry import Assembly
from .folded import fold_document, folded_mesh
from .model import Pattern

__all__ = ["write_fold", "write_mesh"]


def write_fold(
    a: Assembly, pattern: Pattern, out_dir: Path, staging: Staging | None = None
) -> list[Path]:
    """Write ``layer1.fold`` and ``layer2.fold`` (FOLD 1.2, mm) into ``out_dir``.

    With ``staging`` the files join that output step; otherwise they are written all or nothing.
    """
    by_name = {p.name: p for p in pattern.parts}
    docs = [
        (index, fold_document(by_name[f"L{index}"], layer))
        for index, layer in ((1, a.layer1), (2, a.layer2))
    ]
    out_dir.mkdir(parents=True, exist_ok=True)
    with contextlib.nullcontext(staging) if staging is not None else staged() as st:
        paths = []
        for index, doc in docs:
            target = out_dir / f"layer{index}.fold"
            st.path(target).write_text(json.dumps(doc, indent=1), encoding="utf-8")
            paths.append(target)
    return paths


def write_mesh(
    a: Assembly, pattern: Pattern, out_dir: Path, staging: Staging | None = None
) -> list[Path]:
    """Write the folded assembly as ``assembly.glb`` and ``assembly.stl`` (mm) with trimesh."""
    import trimesh

    vertices, faces = folded_mesh(a, pattern.parts)
    mesh = trimesh.Trimesh(vertices=vertices, faces=faces, process=False)
    out_dir.mkdir(parents=True, exist_ok=True)
    with contextlib.nullcontext(staging) if staging is not None else staged() as st:
        paths = []
        for name, kind in (("assembly.glb", "glb"), ("assembly.stl", "stl")):
            target = out_dir / name
            mesh.export(str(st.path(target)), file_type=kind)
            paths.append(target)
    return paths
