"""The whole OADLC assembly as shells in CalculiX: in-plane compression and 3-point bending.

Model (every choice stated; DESIGN.md section 6):

* **Geometry.** Both layers of a rectangular layout (``square`` or ``rectangle``), each as the
  zig-zag mid-surface of its n + 1 facets, L_j equal to the other layer's extent. Layer 1's creases
  run along y, its zig-zag spans x in [0, Lx] between z = 0 and z = h1 (it starts and ends on a
  bottom crease line); layer 2's creases run along x, it spans y in [0, Ly] between z = h1 and
  z = h1 + h2, resting on layer 1. Connectors are not modelled (the fabrication issue has none
  yet).
* **Elements.** 8-node shells with reduced integration (S8R, ``*SHELL SECTION`` of thickness t),
  ``mesh.along`` elements across each facet (even) and elements of about the same size along the
  creases (an even number). Facets share their nodes on the creases; CalculiX turns these nodes
  into knots (rigid links through the thickness), i.e. stiff creases, as in the closed forms.
* **How the layers interact.** In the panel the layers touch along crease lines and are tied by
  connectors at the edges. Here they are **not connected to each other at all**: each layer is
  loaded by the same rigid fixture (same prescribed displacement), and the assembly's force is the
  sum of the two layers' reactions. That is the parallel-spring assumption of the closed forms
  (DESIGN.md 3.3), checked without contact or connector models, which would add stiffness the
  closed forms neglect (the paper saw its experiments slightly stiffer for that reason).
* **Compression along eta** (eta = 0: along y, layer 1's creases; eta = 90: along x). Both loaded
  edges of each layer lie on rigid, frictionless, non-rotating platens: the displacement along the
  load axis is 0 on one edge and -delta on the other, the rotations about the two in-plane axes of
  each platen are held (a plane of symmetry, which makes the end facets of the chordwise layer
  behave as the interior, periodic ones); the other translations are free except for three
  rigid-body constraints per layer. K = (sum of reactions on the moving platen) / delta, N/mm.
* **3-point bending about eta** (span along the load axis, equal to the panel's extent, as in
  ``analyze``: EI = D x span). Line supports at both ends (u_z = 0 on every node of each layer's end
  edge: an end diaphragm, free to rotate and slide), and a rigid line load at mid-span: every node
  of each layer on the mid-span line moves by u_z = -delta, with u along the span held there
  (symmetry). EI = P span^3 / (48 delta) (Euler-Bernoulli 3-point bending), D = EI / span, in
  N mm^2 and N mm. This is the apparent stiffness a bench test would measure: it includes the
  shear deformation of stubby panels, which the closed forms neglect, but not local crushing
  under the rollers (the fixtures act on whole node lines).
* **4-point bending about eta** (``bending4``, a diagnostic the paper did not run): the same
  supports, rigid line loads u_z = -delta at a quarter and three quarters of the span, symmetry at
  mid-span. Between the load lines the moment M = P L / 8 is constant and the shear zero, so the
  deflection of mid-span relative to gauge lines at 3/8 and 5/8 of the span, Delta (means over
  each layer's nodes on those lines; away from the local deformation at the load lines), gives
  the pure bending stiffness of each layer, EI_i = P_i span^3 / (1024 Delta_i), free of shear
  deformation: the quantity the closed forms model. Needs node lines at 1/4 and 3/8 of the span
  (``along`` x (n + 1) divisible by 8).

Only eta = 0 and eta = 90 deg are supported (the two principal directions of the panel).
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from pathlib import Path
from typing import Literal

import numpy as np
from numpy.typing import NDArray

from ..errors import InputError
from ..geometry import Assembly, Layer
from .ccx import SolverError, run_ccx, work_dir

__all__ = [
    "TESTS",
    "AssemblyMesh",
    "AssemblyResult",
    "DeckInfo",
    "LoadTest",
    "assembly_deck",
    "solve_assembly",
]

LoadTest = Literal["compression", "bending", "bending4"]
TESTS: tuple[LoadTest, ...] = ("compression", "bending", "bending4")
FloatArray = NDArray[np.float64]


@dataclass(frozen=True, slots=True)
class AssemblyMesh:
    """Shell mesh: ``along`` S8R elements across each facet (even, >= 2); along the creases the
    element length is about the facet element width, rounded to an even number of elements."""

    along: int = 4

    def __post_init__(self) -> None:
        v = self.along
        if isinstance(v, bool) or not isinstance(v, int) or v < 2 or v % 2:
            raise InputError("mesh.along", v, "an even integer >= 2")

    def refined(self, factor: float = 2.0) -> AssemblyMesh:
        """The mesh with ``along`` scaled by ``factor`` (kept even)."""
        return AssemblyMesh(max(2, 2 * round(self.along * factor / 2)))

    def label(self) -> str:
        return f"{self.along}/facet"


@dataclass(frozen=True, slots=True)
class AssemblyResult:
    """One FE load case of the assembly: K (N/mm) for compression, D (N mm) and EI (N mm^2) for
    bending (the other entries None); ``force`` (N) at the prescribed ``displacement`` (mm), the
    share of the force carried by each layer, and each layer's part of K or D (``layer_values``)."""

    test: LoadTest
    eta_deg: float
    mesh: AssemblyMesh
    span: float
    force: float
    displacement: float
    layer_forces: tuple[float, float]
    K: float | None
    D: float | None
    EI: float | None
    nodes: int
    elements: int
    layer_values: tuple[float, float] = (math.nan, math.nan)

    def value(self) -> float:
        """K (N/mm) for compression, D (N mm) for bending: what ``analyze`` reports."""
        v = self.K if self.test == "compression" else self.D
        assert v is not None
        return v


@dataclass(frozen=True, slots=True)
class _Shell:
    """Nodes (global ids, coordinates) and S8R connectivity of one layer."""

    ids: NDArray[np.int64]
    xyz: FloatArray
    elements: list[list[int]]
    t: float
    E: float
    nu: float


def _layer_shell(
    layer: Layer,
    span: float,
    along: int,
    first_id: int,
    chord_axis: int,
    z0: float,
    multiple: int = 2,
) -> _Shell:
    """S8R mesh of a layer whose chord runs along ``chord_axis`` (0 = x, 1 = y); the number of
    elements along the creases is a multiple of ``multiple``."""
    nf = layer.n + 1
    p, h = layer.pitch, layer.height
    nel_c = along * nf
    nel_s = multiple * max(1, math.ceil(span / (layer.W / along) / multiple))
    ni, nj = 2 * nel_c + 1, 2 * nel_s + 1
    chord = np.linspace(0.0, nf * p, ni)
    crease_c = np.arange(nf + 1) * p
    crease_z = np.where(np.arange(nf + 1) % 2 == 0, 0.0, h) + z0
    z_of = np.interp(chord, crease_c, crease_z)
    spanw = np.linspace(0.0, span, nj)
    ids = np.zeros((ni, nj), dtype=np.int64)
    coords: list[tuple[float, float, float]] = []
    order: list[int] = []
    nid = first_id
    for j in range(nj):
        for i in range(ni):
            if i % 2 and j % 2:
                continue  # S8R has no centre node
            ids[i, j] = nid
            order.append(nid)
            nid += 1
            c, s_ = float(chord[i]), float(spanw[j])
            xy = (c, s_) if chord_axis == 0 else (s_, c)
            coords.append((xy[0], xy[1], float(z_of[i])))
    elements: list[list[int]] = []
    for ej in range(nel_s):
        for ei in range(nel_c):
            i0, j0 = 2 * ei, 2 * ej
            quad = [
                (i0, j0),
                (i0 + 2, j0),
                (i0 + 2, j0 + 2),
                (i0, j0 + 2),
                (i0 + 1, j0),
                (i0 + 2, j0 + 1),
                (i0 + 1, j0 + 2),
                (i0, j0 + 1),
            ]
            elements.append([int(ids[a, b]) for a, b in quad])
    m = layer.material
    return _Shell(
        np.asarray(order, dtype=np.int64), np.asarray(coords), elements, layer.t, m.E, m.nu
    )


def _eta_axis(eta_deg: float) -> int:
    if math.isclose(eta_deg % 180, 0.0, abs_tol=1e-9):
        return 1  # eta = 0: along layer 1's creases, the y axis
    if math.isclose(eta_deg % 180, 90.0, abs_tol=1e-9):
        return 0
    raise InputError("eta", f"{eta_deg} deg", "0 or 90 deg for the FE assembly")


def _fmt_set(name: str, nodes: list[int]) -> list[str]:
    out = [f"*NSET,NSET={name}"]
    for k in range(0, len(nodes), 12):
        out.append(",".join(map(str, nodes[k : k + 12])))
    return out


@dataclass(frozen=True, slots=True)
class DeckInfo:
    """Bookkeeping of an assembly deck: node sets whose reactions make the load (one per layer),
    span along the load axis (mm), prescribed displacement (mm), load axis (0 = x, 1 = y)."""

    sets: tuple[str, str]
    mid_sets: tuple[str, str, str, str] | None  # MID1, MID2, GAUGE1, GAUGE2 (4-point only)
    span: float
    delta: float
    axis: int
    nodes: int
    elements: int


def assembly_deck(
    assembly: Assembly,
    test: LoadTest,
    mesh: AssemblyMesh | None = None,
    eta_deg: float = 0.0,
    delta: float | None = None,
) -> tuple[str, DeckInfo]:
    """CalculiX deck of one load case of the assembly, and its bookkeeping (sets, span, delta)."""
    if test not in TESTS:
        raise InputError("test", test, " or ".join(TESTS))
    if assembly.layout.name not in ("square", "rectangle"):
        raise InputError("layout", assembly.layout.name, "square or rectangle for the FE assembly")
    mesh = mesh or AssemblyMesh()
    axis = _eta_axis(eta_deg)
    other = 1 - axis
    a = assembly
    Lx, Ly = a.Lx, a.Ly
    mult = 8 if test == "bending4" else 2
    shells = [_layer_shell(a.layer1, Ly, mesh.along, 1, 0, 0.0, mult)]
    shells.append(
        _layer_shell(
            a.layer2, Lx, mesh.along, int(shells[0].ids.max()) + 1, 1, a.layer1.height, mult
        )
    )
    L_load = (Lx, Ly)[axis]
    tol = 1e-7 * max(Lx, Ly)
    if delta is None:
        delta = 1e-3 * L_load
    lines = [
        "*HEADING",
        f"corrugate OADLC assembly, {test} at eta = {eta_deg:g} deg (S8R shells)",
        "*NODE",
    ]
    for sh in shells:
        for n, (x, y, z) in zip(sh.ids, sh.xyz, strict=True):
            lines.append(f"{n},{x:.10g},{y:.10g},{z:.10g}")
    e_no = 1
    for k, sh in enumerate(shells, start=1):
        lines.append(f"*ELEMENT,TYPE=S8R,ELSET=L{k}")
        for e in sh.elements:
            lines.append(f"{e_no}," + ",".join(map(str, e)))
            e_no += 1
    for k, sh in enumerate(shells, start=1):
        lines += [
            f"*MATERIAL,NAME=M{k}",
            "*ELASTIC",
            f"{sh.E:.10g},{sh.nu:.10g}",
            f"*SHELL SECTION,ELSET=L{k},MATERIAL=M{k}",
            f"{sh.t:.10g}",
        ]
    bc: list[str] = []
    load_sets: list[str] = []
    mid_sets: list[str] = []
    ua, ub = axis + 1, other + 1
    for k, sh in enumerate(shells, start=1):
        c_load = sh.xyz[:, axis]
        c_other = sh.xyz[:, other]
        lo = [int(n) for n in sh.ids[np.abs(c_load) < tol]]
        hi = [int(n) for n in sh.ids[np.abs(c_load - L_load) < tol]]
        mid = [int(n) for n in sh.ids[np.abs(c_load - L_load / 2) < tol]]
        if not (lo and hi and mid):
            raise SolverError("assembly mesh has no node line at an end or at mid-span")
        lo_other = c_other[np.isin(sh.ids, lo)]
        a_node, b_node = lo[int(np.argmin(lo_other))], lo[int(np.argmax(lo_other))]
        if test == "compression":
            lines += _fmt_set(f"LO{k}", lo) + _fmt_set(f"HI{k}", hi)
            rot_b = 4 + other  # rotation about the platen's in-plane axis
            bc += [
                f"LO{k},{ua},{ua},0",
                f"HI{k},{ua},{ua},{-delta:.12g}",
                f"LO{k},{rot_b},{rot_b},0",
                f"HI{k},{rot_b},{rot_b},0",
                f"LO{k},6,6,0",
                f"HI{k},6,6,0",
                f"{a_node},{ub},{ub},0",
                f"{a_node},3,3,0",
                f"{b_node},3,3,0",
            ]
            load_sets.append(f"HI{k}")
        elif test == "bending4":
            quarter = np.abs(c_load - L_load / 4) < tol
            quarter |= np.abs(c_load - 3 * L_load / 4) < tol
            loads = [int(n) for n in sh.ids[quarter]]
            eighth = np.abs(c_load - 3 * L_load / 8) < tol
            eighth |= np.abs(c_load - 5 * L_load / 8) < tol
            gauges = [int(n) for n in sh.ids[eighth]]
            if not (loads and gauges):
                raise InputError(
                    "mesh.along",
                    mesh.along,
                    "a value with along x (n + 1) divisible by 8 for four-point bending",
                    reason="gives no node lines at 1/4 and 3/8 of the span",
                )
            mid_other = c_other[np.isin(sh.ids, mid)]
            m_node = mid[int(np.argmin(mid_other))]
            lines += _fmt_set(f"SUP{k}", lo + hi) + _fmt_set(f"LOAD{k}", loads)
            lines += _fmt_set(f"MID{k}", mid) + _fmt_set(f"GAUGE{k}", gauges)
            bc += [
                f"SUP{k},3,3,0",
                f"LOAD{k},3,3,{-delta:.12g}",
                f"MID{k},{ua},{ua},0",
                f"{m_node},{ub},{ub},0",
            ]
            load_sets.append(f"LOAD{k}")
            mid_sets += [f"MID{k}", f"GAUGE{k}"]
        else:
            mid_other = c_other[np.isin(sh.ids, mid)]
            m_node = mid[int(np.argmin(mid_other))]
            lines += _fmt_set(f"SUP{k}", lo + hi) + _fmt_set(f"MID{k}", mid)
            bc += [
                f"SUP{k},3,3,0",
                f"MID{k},3,3,{-delta:.12g}",
                f"MID{k},{ua},{ua},0",
                f"{m_node},{ub},{ub},0",
            ]
            load_sets.append(f"MID{k}")
    lines += ["*STEP", "*STATIC", "*BOUNDARY", *bc]
    for name in load_sets:
        lines += [f"*NODE PRINT,NSET={name}", "RF"]
    for name in mid_sets:
        lines += [f"*NODE PRINT,NSET={name}", "U"]
    lines.append("*END STEP")
    n_nodes = sum(len(sh.ids) for sh in shells)
    mids = (mid_sets[0], mid_sets[2], mid_sets[1], mid_sets[3]) if mid_sets else None
    info = DeckInfo((load_sets[0], load_sets[1]), mids, L_load, delta, axis, n_nodes, e_no - 1)
    return "\n".join(lines) + "\n", info


def solve_assembly(
    assembly: Assembly,
    test: LoadTest,
    mesh: AssemblyMesh | None = None,
    eta_deg: float = 0.0,
    *,
    folder: Path | None = None,
    keep: bool = False,
    timeout: float = 600.0,
) -> AssemblyResult:
    """Run one load case of the assembly in CalculiX (see the module docstring for the model)."""
    mesh = mesh or AssemblyMesh()
    deck, info = assembly_deck(assembly, test, mesh, eta_deg)
    with work_dir(folder, keep) as wd:
        run = run_ccx(deck, wd, job=test, timeout=timeout)
    comp = info.axis if test == "compression" else 2
    forces: list[float] = []
    for name in info.sets:
        blocks = run.find("forces", str(name))
        if not blocks:
            raise SolverError(f"ccx printed no reaction forces for {name}")
        forces.append(-blocks[-1].total()[comp])
    delta, span = info.delta, info.span
    P = sum(forces)
    nodes, elements = info.nodes, info.elements
    if test == "compression":
        return AssemblyResult(
            test,
            eta_deg,
            mesh,
            span,
            P,
            delta,
            (forces[0], forces[1]),
            K=P / delta,
            D=None,
            EI=None,
            nodes=nodes,
            elements=elements,
            layer_values=(forces[0] / delta, forces[1] / delta),
        )
    if test == "bending4":
        assert info.mid_sets is not None
        layer_EI: list[float] = []
        for k, f in enumerate(forces):
            mean_uz = []
            for name in (info.mid_sets[k], info.mid_sets[k + 2]):
                blocks = run.find("displacements", name)
                if not blocks:
                    raise SolverError(f"ccx printed no displacements for {name}")
                uz = [v[2] for v in blocks[-1].rows.values()]
                mean_uz.append(sum(uz) / len(uz))
            rel = mean_uz[1] - mean_uz[0]  # mid-span below the gauge lines at 3/8 and 5/8
            layer_EI.append(f * span**3 / (1024 * rel))
        EI4 = sum(layer_EI)
        return AssemblyResult(
            test,
            eta_deg,
            mesh,
            span,
            P,
            delta,
            (forces[0], forces[1]),
            K=None,
            D=EI4 / span,
            EI=EI4,
            nodes=nodes,
            elements=elements,
            layer_values=(layer_EI[0] / span, layer_EI[1] / span),
        )
    EI = P * span**3 / (48 * delta)
    return AssemblyResult(
        test,
        eta_deg,
        mesh,
        span,
        P,
        delta,
        (forces[0], forces[1]),
        K=None,
        D=EI / span,
        EI=EI,
        nodes=nodes,
        elements=elements,
        layer_values=(forces[0] * span**2 / (48 * delta), forces[1] * span**2 / (48 * delta)),
    )
