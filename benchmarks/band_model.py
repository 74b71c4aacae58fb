"""The connector band as two wall beams: a candidate joint model against the band FE of the sweep.

    python benchmarks/band_model.py

For the ten designs of the parameter sweep (docs/validation/sweep_paper.md) with the band bonded
along its edges (docs/validation/connectors/) or on its glue flanges (docs/validation/flanges/),
3-point bending at eta = 0, CalculiX 8 elements per facet (one mesh, not refined): the layers'
three-point model (corrugate.mechanics.load_cases) plus the two band walls along the span as
independent Timoshenko beams (height t_d, the sheet of layer 1, shear area 5/6 of the section),
printed as D = EI / L (N mm) with model/FE: the model of joint = 'band-edges' / 'band-flanges'
(docs/load_cases.md, section 7), written out here independently of the solver's code.
"""

from __future__ import annotations

import csv
import re
from pathlib import Path

from corrugate import Assembly, Layer, analyze, get_material
from corrugate.mechanics.load_cases import THREE_POINT, apparent, load_stiffness, shear_and_depth

ROOT = Path(__file__).resolve().parents[1]


def rows(path: Path) -> dict[str, float]:
    """{case: FE three-point D (N mm) at eta = 0} of a sweep CSV."""
    out = {}
    with path.open() as f:
        for r in csv.DictReader(f):
            if r["quantity"] == "D_Nmm@0" and r["FE"]:
                out[r["case"]] = float(r["FE"])
    return out


def main() -> None:
    dl = get_material("dura-lar")
    E, nu, t = dl.E, dl.nu, 0.125
    G = E / (2 * (1 + nu))
    edges = rows(ROOT / "docs/validation/connectors/sweep_paper.csv")
    flanges = rows(ROOT / "docs/validation/flanges/sweep_paper.csv")
    form = THREE_POINT.form
    assert form is not None
    for case, fe_edges in edges.items():
        m = re.match(r"W=(\S+) n=(\d+) alpha=(\S+)", case)
        assert m is not None
        a = Assembly.identical(
            Layer(W=float(m[1]), n=int(m[2]), alpha_deg=float(m[3]), material=dl)
        )
        r = analyze(a, eta_deg=[0])
        st = r.stiffness[0]
        L = st.span
        V, h = shear_and_depth(r.springs, 1.0, 0.0)
        D3 = apparent(form, "D", load_stiffness(form, st.D, float(V), float(h), L), L)
        td = a.thickness
        EI_w = 2 * E * t * td**3 / 12  # two walls, bent in their own plane
        GA_w = 2 * (5 / 6) * G * t * td
        D_w = L**2 / 48 / (L**3 / (48 * EI_w) + L / (4 * GA_w))
        model = D3 + D_w
        fl = flanges.get(case, float("nan"))
        print(
            f"{case:22s} layers {D3:7.0f} walls {D_w:7.0f} model {model:7.0f}  "
            f"edges FE {fe_edges:7.0f} ({model / fe_edges:.2f})  flanges FE {fl:7.0f} "
            f"({model / fl:.2f})"
        )


if __name__ == "__main__":
    main()
