"""Peak facet stress in 3-point bending at eta = 0: shell FE against corrugate.mechanics.strength
(docs/theory.md 9, docs/validation/strength.md).

    python benchmarks/fea_stress.py [--meshes 2 4 8] [--test platens]

For each design (Dura-Lar 0.125 mm, square, identical layers) and mesh (elements per facet) it
runs the 3-point fixture of corrugate.fea.assembly with ccx writing nodal stresses, and reports:

* the FE peak stress (largest |principal stress| over the shells' nodes, surfaces included) in
  the Saint-Venant window, 1/8 to 3/8 and 5/8 to 7/8 of the span (away from the supports and the
  load line), for layer 1 (bent along its creases) and layer 2 (bent across them);
* the model's peak at the largest moment in that window, M(3L/8) = 3 P L / 16 with P the FE's
  reaction, and the window's "stress per moment" ratio max_nodes sigma_FE / M(y) against the
  model's sigma / M (the moment at each node's own position, M(y) = P y / 2 up to mid-span);
* the absolute FE peak (anywhere, the load line included) against the model at M = P L / 4;
* the von Mises peak in the window, and where the window peak sits (y / L, height z / t_layer).

``--test platens``: the platen fixture instead (eta = 0), the FE peaks in the middle half of
the span against the membrane stress of layer 1 and the crease bending of layer 2.

Prints Markdown tables. Needs ccx; runs one ccx job at a time. About 2 minutes per design at
8 elements per facet.
"""

from __future__ import annotations

import argparse
import time

import numpy as np

from corrugate import Assembly, Layer, get_material
from corrugate.fea.assembly import AssemblyMesh, solve_assembly
from corrugate.mechanics.strength import (
    LayerSection,
    chordwise_bending_stress,
    chordwise_compression_stress,
    peak_stress_bending,
    peak_stress_compression,
    spanwise_bending_stress,
    spanwise_compression_stress,
)

DESIGNS = {
    "W 8, n 8, alpha 84 (case study)": (8.0, 8, 84.0),
    "W 10, n 10, alpha 40": (10.0, 10, 40.0),
    "W 12, n 13, alpha 115": (12.0, 13, 115.0),
}


def run(name: str, W: float, n: int, alpha: float, along: int) -> dict[str, float]:
    layer = Layer(W=W, n=n, alpha_deg=alpha, material=get_material("dura-lar"))
    a = Assembly.identical(layer)
    t0 = time.perf_counter()
    r = solve_assembly(a, "three-point", AssemblyMesh(along), 0.0, stresses=True)
    seconds = time.perf_counter() - t0
    f = r.stresses
    assert f is not None
    L, P = r.span, r.force
    y = f.xyz[:, 1]
    pr = f.principal()
    amax = np.max(np.abs(pr), axis=1)  # largest |principal| at each node
    vm = f.von_mises()
    M_of_y = P * np.minimum(y, L - y) / 2.0  # 3-point: M(y) = P y / 2 up to mid-span
    window = ((y >= L / 8) & (y <= 3 * L / 8)) | ((y >= 5 * L / 8) & (y <= 7 * L / 8))
    narrow = ((y >= L / 4) & (y <= 3 * L / 8)) | ((y >= 5 * L / 8) & (y <= 3 * L / 4))
    sec = LayerSection.from_layer(layer)
    ps = peak_stress_bending(sec, sec, 1.0, 0.0)
    unit = ps.layer_sigma  # MPa per N mm of the assembly's moment, layers 1 and 2
    M_win = 3 * P * L / 16
    out: dict[str, float] = {
        "along": along,
        "nodes": r.nodes,
        "seconds": seconds,
        "P": P,
        "L": L,
        "model_win_1": unit[0] * M_win,
        "model_win_2": unit[1] * M_win,
        "model_mid_1": unit[0] * P * L / 4,
        "share_1": ps.shares[0],
        "share_2": ps.shares[1],
        "P1": r.layer_forces[0],
        "P2": r.layer_forces[1],
    }
    # the single layers' own stresses per moment (their whole share), for the FE's own split
    own = (
        spanwise_bending_stress(sec.E, sec.t, sec.W, sec.n, sec.alpha_deg, 1.0),
        chordwise_bending_stress(sec.t, a.Lx, 1.0),
    )
    for k in (1, 2):
        part = f.material == k
        w = window & part
        i = int(np.argmax(np.where(w, amax, -1.0)))
        out[f"fe_win_{k}"] = float(amax[i])
        out[f"vm_win_{k}"] = float(np.max(vm[w]))
        out[f"y_win_{k}"] = float(y[i] / L)
        z0 = 0.0 if k == 1 else layer.height
        out[f"z_win_{k}"] = float((f.xyz[i, 2] - z0) / layer.height)
        # stress per unit moment: the largest sigma / M(y) over the window's nodes
        out[f"k_win_{k}"] = float(np.max(amax[w] / M_of_y[w]))
        wn = narrow & part
        out[f"k_narrow_{k}"] = float(np.max(amax[wn] / M_of_y[wn]))
        out[f"unit_{k}"] = unit[k - 1]
        # the model's stress at M(3L/8) of the layer's own FE force (the FE's split of P)
        out[f"own_win_{k}"] = own[k - 1] * 3 * r.layer_forces[k - 1] * L / 16
        out[f"fe_abs_{k}"] = float(np.max(amax[part]))
        j = int(np.argmax(np.where(part, amax, -1.0)))
        out[f"y_abs_{k}"] = float(y[j] / L)
    return out


def run_compression(name: str, W: float, n: int, alpha: float, along: int) -> dict[str, float]:
    """Platen compression at eta = 0: layer 1 along its creases (membrane), layer 2 across them
    (crease bending); FE peaks in the middle half of the span, away from the platens."""
    layer = Layer(W=W, n=n, alpha_deg=alpha, material=get_material("dura-lar"))
    a = Assembly.identical(layer)
    t0 = time.perf_counter()
    r = solve_assembly(a, "platens", AssemblyMesh(along), 0.0, stresses=True)
    seconds = time.perf_counter() - t0
    f = r.stresses
    assert f is not None
    L, P = r.span, r.force
    y = f.xyz[:, 1]
    amax = np.max(np.abs(f.principal()), axis=1)
    mid = (y >= L / 4) & (y <= 3 * L / 4)
    sec = LayerSection.from_layer(layer)
    ps = peak_stress_compression(sec, sec, P, 0.0)
    own = (
        spanwise_compression_stress(sec.t, sec.W, sec.n, r.layer_forces[0]),
        chordwise_compression_stress(sec.t, sec.W, sec.alpha_deg, a.Lx, r.layer_forces[1]),
    )
    out: dict[str, float] = {"along": along, "nodes": r.nodes, "seconds": seconds, "P": P}
    for k in (1, 2):
        part = f.material == k
        w = mid & part
        i = int(np.argmax(np.where(w, amax, -1.0)))
        out[f"fe_{k}"] = float(amax[i])
        z0 = 0.0 if k == 1 else layer.height
        out[f"z_{k}"] = float((f.xyz[i, 2] - z0) / layer.height)
        out[f"fe_mean_syy_{k}"] = float(np.mean(np.abs(f.stress[w, 1])))
        out[f"model_{k}"] = ps.layer_sigma[k - 1]
        out[f"own_{k}"] = abs(float(own[k - 1]))
        out[f"share_fe_{k}"] = r.layer_forces[k - 1] / P
        out[f"share_model_{k}"] = ps.shares[k - 1] / P
        out[f"fe_abs_{k}"] = float(np.max(amax[part]))
    return out


def main_compression(args: argparse.Namespace) -> None:
    rows: list[tuple[str, dict[str, float]]] = []
    for d in args.designs:
        name = list(DESIGNS)[d]
        W, n, alpha = DESIGNS[name]
        for along in args.meshes:
            rows.append((name, run_compression(name, W, n, alpha, along)))
            o = rows[-1][1]
            print(
                f"# {name} {along}/facet: {o['nodes']:.0f} nodes, {o['seconds']:.0f} s, "
                f"P = {o['P']:.4g} N",
                flush=True,
            )
    print()
    print("Platen compression at eta = 0, middle half of the span (1/4-3/4):")
    print()
    print(
        "| design | elements/facet | P (N) | layer | FE peak (MPa) | at z/h | FE mean abs SYY | "
        "model (MPa) | model/FE | FE share | model share | model/FE, FE's share | "
        "FE peak anywhere |"
    )
    print("|---" * 13 + "|")
    for name, o in rows:
        for k in (1, 2):
            print(
                f"| {name} | {o['along']:.0f} | {o['P']:.4g} | {k} | {o[f'fe_{k}']:.4g} | "
                f"{o[f'z_{k}']:.2f} | {o[f'fe_mean_syy_{k}']:.4g} | {o[f'model_{k}']:.4g} | "
                f"{o[f'model_{k}'] / o[f'fe_{k}']:.3f} | {o[f'share_fe_{k}']:.4f} | "
                f"{o[f'share_model_{k}']:.4f} | {o[f'own_{k}'] / o[f'fe_{k}']:.3f} | "
                f"{o[f'fe_abs_{k}']:.4g} |"
            )


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--meshes", type=int, nargs="+", default=[2, 4, 8])
    ap.add_argument("--designs", type=int, nargs="+", default=list(range(len(DESIGNS))))
    ap.add_argument("--test", choices=("three-point", "platens"), default="three-point")
    args = ap.parse_args()
    if args.test == "platens":
        main_compression(args)
        return
    rows: list[tuple[str, dict[str, float]]] = []
    for d in args.designs:
        name = list(DESIGNS)[d]
        W, n, alpha = DESIGNS[name]
        for along in args.meshes:
            rows.append((name, run(name, W, n, alpha, along)))
            o = rows[-1][1]
            print(
                f"# {name} {along}/facet: {o['nodes']:.0f} nodes, {o['seconds']:.0f} s, "
                f"P = {o['P']:.4g} N, L = {o['L']:.4g} mm",
                flush=True,
            )
    print()
    print("Layer 1 (bent along its creases), window 1/8-3/8 of the span:")
    print()
    print(
        "| design | elements/facet | P (N) | FE peak (MPa) | at y/L, z/h | von Mises (MPa) | "
        "model at M(3L/8) (MPa) | model/FE | model/FE, sigma/M(y) | same, 1/4-3/8 | "
        "FE share P1/P | model share | model/FE, FE's P1 |"
    )
    print("|---" * 13 + "|")
    for name, o in rows:
        print(
            f"| {name} | {o['along']:.0f} | {o['P']:.4g} | {o['fe_win_1']:.4g} | "
            f"{o['y_win_1']:.3f}, {o['z_win_1']:.2f} | {o['vm_win_1']:.4g} | "
            f"{o['model_win_1']:.4g} | {o['model_win_1'] / o['fe_win_1']:.3f} | "
            f"{o['unit_1'] / o['k_win_1']:.3f} | {o['unit_1'] / o['k_narrow_1']:.3f} | "
            f"{o['P1'] / o['P']:.4f} | "
            f"{o['share_1']:.4f} | {o['own_win_1'] / o['fe_win_1']:.3f} |"
        )
    print()
    print("Layer 2 (bent across its creases), same window:")
    print()
    print(
        "| design | elements/facet | FE peak (MPa) | at y/L, z/h | model at M(3L/8) (MPa) | "
        "model/FE | model/FE, sigma/M(y) | FE share P2/P | model share | model/FE, FE's P2 |"
    )
    print("|---" * 10 + "|")
    for name, o in rows:
        print(
            f"| {name} | {o['along']:.0f} | {o['fe_win_2']:.4g} | "
            f"{o['y_win_2']:.3f}, {o['z_win_2']:.2f} | {o['model_win_2']:.4g} | "
            f"{o['model_win_2'] / o['fe_win_2']:.3f} | {o['unit_2'] / o['k_win_2']:.3f} | "
            f"{o['P2'] / o['P']:.4f} | {o['share_2']:.4f} | "
            f"{o['own_win_2'] / o['fe_win_2']:.3f} |"
        )
    print()
    print("Absolute peak (anywhere, load line included), layer 1 against the model at P L / 4:")
    print()
    print("| design | elements/facet | FE peak (MPa) | at y/L | model (MPa) | model/FE |")
    print("|---" * 6 + "|")
    for name, o in rows:
        print(
            f"| {name} | {o['along']:.0f} | {o['fe_abs_1']:.4g} | {o['y_abs_1']:.3f} | "
            f"{o['model_mid_1']:.4g} | {o['model_mid_1'] / o['fe_abs_1']:.3f} |"
        )


if __name__ == "__main__":
    main()
