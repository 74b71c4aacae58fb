"""Unit-cell mesh convergence over the range the tool is used in (docs/fea.md, section 1.3).

    python benchmarks/unitcell_range.py run > cells.csv     # the mesh series, CSV (about 10 min)
    python benchmarks/unitcell_range.py deep > deep.csv     # alpha = 40 deg: finer meshes (7 min)
    python benchmarks/unitcell_range.py table cells.csv deep.csv   # the Markdown tables

Dura-Lar (E = 2700 MPa, nu = 0.43); the paper's range W = 8-14 mm, t = 0.125 mm, alpha =
40-115 deg, plus t/W = 0.0067 (W = 18.75 mm) and t/W = 0.02 (W = 8 mm, t = 0.16 mm). The moduli
scale with E and depend on t and W only through t/W. "converged" is the first-order (p = 1)
Richardson extrapolation of the last doubling of the series, 2 E(finest) - E(previous); each
series is printed so that the extrapolation can be judged. Needs ccx.
"""

from __future__ import annotations

import csv
import sys
import time
from collections import defaultdict

from corrugate import moduli
from corrugate.fea.unitcell import UnitCell, UnitCellMesh, solve_unit_cell

E, NU = 2700.0, 0.43
ALPHAS = (40.0, 65.0, 90.0, 115.0)
CELLS = ((8.0, 0.125), (14.0, 0.125), (18.75, 0.125), (8.0, 0.16))
MESHES = ((40, 2), (80, 2), (160, 2), (320, 4))
DEEP = (((18.75, 0.125, 40.0), (8.0, 0.125, 40.0)), ((160, 4), (320, 8), (640, 4), (1280, 4)))
HEADER = "W,t,alpha,mesh,nodes,s,Ecx,Ecy,Ebx,Eby"


def _run(cells: list[tuple[float, float, float]], meshes: tuple[tuple[int, int], ...]) -> None:
    print(HEADER, flush=True)
    for W, t, a in cells:
        for along, through in meshes:
            t0 = time.perf_counter()
            r = solve_unit_cell(
                UnitCell(E, NU, t, W, a), UnitCellMesh(along, through), timeout=1800
            )
            s = time.perf_counter() - t0
            m = r.as_dict()
            print(
                f"{W},{t},{a},{along}x{through},{r.nodes},{s:.1f},"
                + ",".join(f"{m[k]:.8g}" for k in ("Ecx", "Ecy", "Ebx", "Eby")),
                flush=True,
            )


def _dev(runs: dict[str, dict[str, float]], conv: dict[str, float], m: str, k: str) -> str:
    return f"{runs[m][k] / conv[k] - 1:+.2%}" if m in runs else "-"


def table(paths: list[str]) -> None:
    series: dict[tuple[float, float, float], dict[str, dict[str, float]]] = defaultdict(dict)
    for path in paths:
        with open(path) as fh:
            for row in csv.DictReader(fh):
                key = (float(row["W"]), float(row["t"]), float(row["alpha"]))
                series[key][row["mesh"]] = {k: float(row[k]) for k in ("s", "Ecx", "Ebx")}
    print(
        "| W mm | t mm | t/W | alpha | Ecx/E by mesh (s per run) | Ecx/E extrapolated | "
        "Ecx 40x2 | Ecx 160x2 | Ecx 320x4 | Ebx 40x2, 160x2, 320x4 | refined/extr. Ecx, Ebx |"
    )
    print("|---" * 11 + "|")
    for (W, t, a), runs in sorted(series.items(), key=lambda kv: (kv[0][2], kv[0][1] / kv[0][0])):
        order = sorted(runs, key=lambda m: tuple(int(v) for v in m.split("x")))
        # last doubling of `along`: the finest mesh and the one with half its elements
        fine = order[-1]
        half = max(
            (m for m in order if int(m.split("x")[0]) * 2 == int(fine.split("x")[0])),
            key=lambda m: int(m.split("x")[1]),
        )
        conv = {k: 2 * runs[fine][k] - runs[half][k] for k in ("Ecx", "Ebx")}
        cf = moduli(E, NU, t, W, a, "refined").as_dict()
        text = ", ".join(f"{m} {runs[m]['Ecx'] / E:.5g} ({runs[m]['s']:.0f})" for m in order)

        print(
            f"| {W:g} | {t:g} | {t / W:.4f} | {a:g} | {text} | "
            f"{conv['Ecx'] / E:.5g} ({half}, {fine}) | {_dev(runs, conv, '40x2', 'Ecx')} | {_dev(runs, conv, '160x2', 'Ecx')} | "
            f"{_dev(runs, conv, '320x4', 'Ecx')} | {_dev(runs, conv, '40x2', 'Ebx')}, {_dev(runs, conv, '160x2', 'Ebx')}, "
            f"{_dev(runs, conv, '320x4', 'Ebx')} | {cf['Ecx'] / conv['Ecx']:.4f}, {cf['Ebx'] / conv['Ebx']:.4f} |"
        )


if __name__ == "__main__":
    mode = sys.argv[1] if len(sys.argv) > 1 else "run"
    if mode == "run":
        _run([(W, t, a) for a in ALPHAS for W, t in CELLS], MESHES)
    elif mode == "deep":
        _run(list(DEEP[0]), DEEP[1])
    else:
        table(sys.argv[2:])
