"""Writers for the folded geometry: FOLD 1.2 (JSON) per layer, GLB and STL of the assembly."""

from __future__ import annotations

import json
from pathlib import Path

from ..fileio import atomic_path, atomic_write
from ..geometry import Assembly
from .folded import fold_document, folded_mesh
from .model import Pattern

__all__ = ["write_fold", "write_mesh"]


def write_fold(a: Assembly, pattern: Pattern, out_dir: Path) -> list[Path]:
    """Write ``layer1.fold`` and ``layer2.fold`` (FOLD 1.2, mm) into ``out_dir``."""
    paths = []
    by_name = {p.name: p for p in pattern.parts}
    for index, layer in ((1, a.layer1), (2, a.layer2)):
        doc = fold_document(by_name[f"L{index}"], layer)
        paths.append(atomic_write(out_dir / f"layer{index}.fold", json.dumps(doc, indent=1)))
    return paths


def write_mesh(a: Assembly, pattern: Pattern, out_dir: Path) -> list[Path]:
    """Write the folded assembly as ``assembly.glb`` and ``assembly.stl`` (mm) with trimesh."""
    import trimesh

    vertices, faces = folded_mesh(a, pattern.parts)
    mesh = trimesh.Trimesh(vertices=vertices, faces=faces, process=False)
    paths = []
    for name, kind in (("assembly.glb", "glb"), ("assembly.stl", "stl")):
        with atomic_path(out_dir / name) as tmp:
            mesh.export(str(tmp), file_type=kind)
        paths.append(out_dir / name)
    return paths
