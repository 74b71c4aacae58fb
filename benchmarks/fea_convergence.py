"""Mesh-convergence study of the FE models (docs/fea.md quotes its output).

    python benchmarks/fea_convergence.py unitcell   # docs/data/unitcell_fe.csv rows, 5-6 meshes
    python benchmarks/fea_convergence.py assembly   # W = 10, n = 7, alpha = 90, Dura-Lar 0.125
    python benchmarks/fea_convergence.py pure 8 16  # case study, pure bending (4-point), per facet
    python benchmarks/fea_convergence.py order M1 M2 M3 V1 V2 V3    # order p from three meshes

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
        c = solve_assembly(a, "platens", AssemblyMesh(along), 0.0)
        b = solve_assembly(a, "three-point", AssemblyMesh(along), 0.0)
        p = solve_assembly(a, "four-point", AssemblyMesh(along), 0.0)
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


def richardson(meshes: list[int], values: list[float]) -> tuple[float, float]:
    """Extrapolation to zero element size of the last three values on meshes of ``meshes``
    elements per facet (h = 1 / mesh): the order p and the limit, from
    (v2 - v1) / (v3 - v2) = (h1^p - h2^p) / (h2^p - h3^p), solved by bisection on p in [0.05, 4]."""
    (m1, m2, m3), (v1, v2, v3) = meshes[-3:], values[-3:]
    h1, h2, h3 = 1 / m1, 1 / m2, 1 / m3
    target = (v2 - v1) / (v3 - v2)

    def f(p: float) -> float:
        return (h1**p - h2**p) / (h2**p - h3**p) - target

    lo, hi = 0.05, 4.0
    for _ in range(200):
        mid = 0.5 * (lo + hi)
        lo, hi = (mid, hi) if f(lo) * f(mid) > 0 else (lo, mid)
    p = 0.5 * (lo + hi)
    return p, v3 + (v3 - v2) * h3**p / (h2**p - h3**p)


def pure(alongs: list[int]) -> None:
    """Pure bending (4-point) D4 of the case study (W 8, n 8, alpha 84, Dura-Lar 0.125 mm, square,
    eta = 0) at each mesh (elements per facet: multiples of 8, so that the gauge lines are node
    lines), with the first-order (p = 1) extrapolation of each step and, from three meshes, the
    observed order and its extrapolation."""
    layer = Layer(8.0, 8, 84.0, get_material("dura-lar"), 0.125)
    a = Assembly.identical(layer)
    D = analyze(a, "refined", [0.0]).stiffness[0].D
    print("\ncase study W 8, n 8, alpha 84, Dura-Lar 0.125 mm, square, eta = 0, `bending4`\n")
    print("| elements per facet | nodes | D4 FE N mm | refined / FE | extrapolated (p = 1) | s |")
    print("|---" * 6 + "|")
    values: list[float] = []
    for along in alongs:
        t0 = time.perf_counter()
        r = solve_assembly(a, "four-point", AssemblyMesh(along), 0.0, timeout=3600.0)
        dt = time.perf_counter() - t0
        v = r.value()
        ext = ""
        if values:
            ratio = along / alongs[len(values) - 1]
            limit = v + (v - values[-1]) / (ratio - 1)
            ext = f"{limit:.5g} (refined / it {D / limit:.4f})"
        values.append(v)
        print(f"| {along} | {r.nodes} | {v:.5g} | {D / v:.4f} | {ext} | {dt:.0f} |", flush=True)
    print(f"| closed form `refined` | | {D:.5g} | | | |")
    if len(values) >= 3:
        p, limit = richardson(alongs, values)
        print(
            f"\nobserved order p = {p:.2f}; extrapolated D4 = {limit:.5g}, refined / it {D / limit:.4f}"
        )


if __name__ == "__main__":
    mode = sys.argv[1] if len(sys.argv) > 1 else "unitcell"
    if mode == "pure":
        pure([int(v) for v in sys.argv[2:]] or [8, 16])
    elif mode == "order":  # three meshes, three values: observed order and extrapolation
        m, v = sys.argv[2:5], sys.argv[5:8]
        p, limit = richardson([int(x) for x in m], [float(x) for x in v])
        print(f"observed order p = {p:.2f}; extrapolated {limit:.5g}")
    else:
        {"unitcell": unitcell, "assembly": assembly}[mode]()
