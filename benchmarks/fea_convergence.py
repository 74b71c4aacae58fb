"""Mesh-convergence study of the FE models (docs/fea.md quotes its output).

    python benchmarks/fea_convergence.py unitcell   # reference/unitcell_fe.csv rows, 5-6 meshes
    python benchmarks/fea_convergence.py assembly   # W = 10, n = 7, alpha = 90, Dura-Lar 0.125

Prints Markdown tables. Needs ccx. Takes a few minutes (the finest meshes dominate).
"""

from __future__ import annotations

import csv
import sys
import time
from pathlib import Path

from corrugate import Assembly, Layer, analyze, get_material, moduli
from corrugate.fea.assembly import AssemblyMesh, solve_assembly
from corrugate.fea.unitcell import UnitCell, UnitCellMesh, solve_unit_cell

REFERENCE = Path(__file__).resolve().parents[1] / "docs" / "data" / "unitcell_fe.csv"
KEYS = ("Ecx", "Ecy", "Ebx", "Eby")


def unitcell() -> None:
    lines = [ln for ln in REFERENCE.read_text().splitlines() if not ln.startswith("#")]
    for row in csv.DictReader(lines):
        W, t, a, nu = (float(row[k]) for k in ("W", "t", "alpha_deg", "nu"))
        print(
            f"\n#### W = {W:g} mm, t = {t:g} mm, alpha = {a:g} deg, nu = {nu:g} "
            f"(reference mesh {row['mesh']})\n"
        )
        print(
            "| mesh | nodes | s | "
            + " | ".join(f"{k}/E" for k in KEYS)
            + " | "
            + " | ".join(f"{k} vs ref" for k in KEYS)
            + " |"
        )
        print("|---" * (3 + 2 * len(KEYS)) + "|")
        cell = UnitCell(1.0, nu, t, W, a)
        ref_mesh = tuple(int(v) for v in row["mesh"].split("x"))
        meshes = sorted({(20, 1), (40, 2), (80, 2), (160, 4), (320, 4), ref_mesh})
        for along, through in meshes:
            t0 = time.perf_counter()
            r = solve_unit_cell(cell, UnitCellMesh(along, through))
            dt = time.perf_counter() - t0
            v = r.normalised()
            dev = [f"{v[k] / float(row[k]) - 1:+.3%}" for k in KEYS]
            print(
                f"| {along}x{through} | {r.nodes} | {dt:.1f} | "
                + " | ".join(f"{v[k]:.6e}" for k in KEYS)
                + " | "
                + " | ".join(dev)
                + " |"
            )
        cf = moduli(1.0, nu, t, W, a, "refined").as_dict()
        print(
            "| closed form `refined` | | | "
            + " | ".join(f"{cf[k]:.6e}" for k in KEYS)
            + " | "
            + " | ".join(f"{cf[k] / float(row[k]) - 1:+.3%}" for k in KEYS)
            + " |"
        )


def assembly() -> None:
    layer = Layer(10.0, 7, 90.0, get_material("dura-lar"), 0.125)
    a = Assembly.identical(layer)
    r = analyze(a, "refined", [0.0])
    s1, s2 = r.springs
    print(
        f"\nW = 10 mm, n = 7, alpha = 90 deg, Dura-Lar t = 0.125 mm, L = {a.Lx:.3f} mm, eta = 0\n"
    )
    print(
        "| shell elements per facet | nodes | K N/mm | K layer 1 | K layer 2 | D N mm (3-point) | "
        "D layer 1 | D layer 2 | D4 N mm (pure) | D4 layer 1 | D4 layer 2 | s |"
    )
    print("|---" * 12 + "|")
    for along in (2, 4, 8, 16):
        t0 = time.perf_counter()
        c = solve_assembly(a, "compression", AssemblyMesh(along), 0.0)
        b = solve_assembly(a, "bending", AssemblyMesh(along), 0.0)
        p = solve_assembly(a, "bending4", AssemblyMesh(along), 0.0)
        dt = time.perf_counter() - t0
        kl, dl, pl = c.layer_values, b.layer_values, p.layer_values
        print(
            f"| {along} | {c.nodes} | {c.value():.5g} | {kl[0]:.5g} | {kl[1]:.4g} | "
            f"{b.value():.5g} | {dl[0]:.5g} | {dl[1]:.4g} | {p.value():.5g} | {pl[0]:.5g} | "
            f"{pl[1]:.4g} | {dt:.0f} |"
        )
    D, DS, DC = r.stiffness[0].D, float(s1.D_S), float(s2.D_C)
    print(
        f"| closed form `refined` | | {r.stiffness[0].K:.5g} | {float(s1.K_S):.5g} | "
        f"{float(s2.K_C):.4g} | {D:.5g} | {DS:.5g} | {DC:.4g} | {D:.5g} | {DS:.5g} | {DC:.4g} | |"
    )


if __name__ == "__main__":
    {"unitcell": unitcell, "assembly": assembly}[sys.argv[1] if len(sys.argv) > 1 else "unitcell"]()
