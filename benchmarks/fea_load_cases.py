"""FE values of four load cases along eta, for docs/validation/load_cases.md (FE numbers only).

    python benchmarks/fea_load_cases.py run [PHASE ...] [--minutes M]   # -> load_cases_fe.csv

Writes ``docs/validation/load_cases_fe.csv``, one row per (design, eta_deg, test, shift, along):
``value`` is K (N/mm) for ``compression`` and D (N mm) for ``bending`` (3-point), ``bending4``
(4-point, pure bending) and ``cantilever``, as :meth:`corrugate.fea.assembly.AssemblyResult.value`
reports them; ``nodes`` the model's node count, ``seconds`` the wall-clock time of the case (mesh,
ccx, reading). Fixtures: docs/fea.md 2.1 (at eta 0 and 90 the layout itself on the structured
mesh, at any other eta the coupon of section 2.4 meshed by gmsh). ``shift`` moves both layers'
zig-zags relative to an off-axis coupon by that fraction of each layer's pitch
(:func:`corrugate.fea.shells.oblique_shells`).

Like ``fea_offaxis.py`` the run is resumable: the keys already in the CSV are skipped and each
new row is appended as its case returns. Before running, the rows of
``docs/validation/off_axis_fe.csv`` (compression and 3-point bending, the same fixtures and
meshes, shift 0) are copied in with shift 0 instead of being recomputed.

Designs: the four of ``fea_offaxis.designs()`` and the square of identical layers W 12, n 13,
alpha 115, all Dura-Lar at its library thickness (0.125 mm). Etas 0, 15, ..., 90; for identical
layers eta > 45 deg is the mirror image of 90 - eta and is run only at 2 and 4 elements per facet
(a mirror check), as in ``fea_offaxis.py``. Phases, in the order run (most useful first):

* ``a``: every design but the fifth, 3-point, 4-point and cantilever at eta 0 and 90, 2 / 4 / 8;
* ``b``: the same designs, cantilever off-axis (15 ... 75 deg), shift 0, 2 / 4 / 8;
* ``c``: the fifth design, every test at every eta, 2 / 4 / 8;
* ``d``: shifts 0.25 and 0.5 of the off-axis 3-point and cantilever rows of every design, 2 / 4 / 8
  (all designs at 2, then at 4, then at 8);
* ``f``: the certified design of ``examples/chassis_plate.toml`` (polypropylene, layer 1 n = 6,
  W = 16 mm: outside the sweep the local term was fitted on), every test at eta 0 and 90,
  2 / 4 / 8, and 3-point and cantilever at eta 0 at 12 per facet (its 8-per-facet series still
  moved by 0.4 %);
* ``g``: the 4-point test read at its load points (``bending4-load``: the loading head's travel,
  D = (P / delta) span^2 / 96, what the ``four-point`` load case certifies), every design at eta
  0 and 90, 2 / 4 / 8;
* ``h``: the local term's wider sample (issue 35, docs/load_cases.md 2): the squares of
  identical layers of ``WIDER`` (thin Dura-Lar 0.05 and 0.075 mm, t / W 0.005-0.00625; thick
  polypropylene 0.5 mm, t / W 0.05; polypropylene 0.25 mm), 3-point, 4-point at its load points
  and cantilever at eta 0 (eta 90 is its mirror image), 2 / 4 / 8 / 16 per facet: n 7 or 9, so
  that 16 per facet stays under about 110 000 nodes and the 4-point fixture has node lines at
  every mesh (8 or 10 facets);
* ``i``: 32 per facet for the designs of ``WIDER`` with t / W < 0.01 (thin sheets converge
  slowly: their 4 / 8 / 16 series are not yet asymptotic) whose model has at most
  ``MAX_NODES_32`` nodes;
* ``j``: the off-axis bending factor on more coupons (issue 35, docs/load_cases.md 5): the three
  small squares of ``OFFAXIS_BENDING`` (polypropylene 0.3 mm and Dura-Lar 0.125 and 0.175 mm,
  n 6-7, alpha 40-120), 3-point bending at 15 then 30 deg, shifts 0, 0.25 and 0.5, one whole
  2 / 4 / 8 / 16 series at a time (at most 109 000 nodes, 2.7 GB peak child memory at 16);
  ``python benchmarks/offaxis_bending_factor.py`` judges them;
* ``e``: 16 elements per facet at eta 0 and 90 for 3-point, 4-point and cantilever, for the
  models of at most ``MAX_NODES_16`` nodes. That leaves out the rectangle (169 930 nodes at 16
  per facet) and the fifth design (257 018): ccx's peak memory grew by about 46 kB per node in
  this run (3.3 GB for the rectangle's 72 000-node coupons at 8 per facet), so they would need
  about 8 and 12 GB, and the 280 000-node coupons of off_axis_fe.csv took 484 and 624 s.
  (Measured since: one ccx run per layer, now the default of ``solve_assembly``, halves the peak
  memory, docs/fea.md 2.9; ``MAX_NODES_16`` was not raised, the rectangle and the fifth design
  at 16 per facet were not run.)

Rows that are never written:

* **4-point bending off-axis**: not run (the table asks for it along the creases only; off-axis
  its gauge lines cross the creases obliquely and its series moved by 2.6 % and 6 % per doubling,
  docs/fea.md 2.5).
* **4-point bending where the structured mesh has no node lines at 1/4 and 3/8 of the span**:
  the layer whose chord runs along the span has 2 x along x (n + 1) node intervals along it
  (corner and mid-side nodes), which must be divisible by 8, else
  :func:`corrugate.fea.assembly.assembly_deck` refuses the case (InputError) and the run prints
  ``skip``: for n = 8 (9 facets), n = 10 (11) and n = 6 (7) along = 2 is skipped (4, 8 and 16
  qualify); n = 17 (18 facets) and n = 13 (14) qualify at every along.

**The committed CSV** (runs of 2026-12-01 and 2026-12-02 on 2 cores shared with other jobs):
phases ``a``, ``b``, ``c``, ``f`` and ``g`` are complete; ``d`` (shifts) at 2 and 4 per facet
and at 8 per facet for 15, 30 and 45 deg (every design) and 60 and 75 deg (the differing layers
and the rectangle; the identical squares mirror 15 and 30 deg there); of ``e`` only the case
study's 4-point bending at eta 0 (90 850 nodes, 201 s, 4.2 GB peak). Peak ccx memory: 4.1-4.7 GB
at 8 per facet, 11.3 GB for the chassis plate at 12 (218 130 nodes, 316-401 s). ``run``
resumes from there.

Phases ``h`` and ``i`` ran on 2026-12-06 on 2 cores shared with other jobs (load average 3-9):
16 per facet took 15-263 s a case (44 000-116 000 nodes, peak child memory 1-2.7 GB), 32 per
facet 161-620 s (170 000-235 000 nodes, 4.2-5.8 GB). Not run: the thin design at alpha 110 at 32
per facet (330 000 nodes > ``MAX_NODES_32``).

Phase ``k`` (the refit's coupon, polypropylene 0.5 mm W 10, n 6, alpha 40 at 35 deg, three
shifts) ran on 2026-12-07 under ``ulimit -v 4000000`` (load average 6-12): 16 per facet took
294-329 s a case (81 184-81 406 nodes, peak child memory 1.95 GB).

``--minutes M`` starts no new case after M minutes. Needs ccx and gmsh (the ``fea`` extra).
"""

from __future__ import annotations

import csv
import resource
import sys
import time
from collections.abc import Iterator
from pathlib import Path
from typing import Any

from corrugate import Assembly, Layer, get_material, make_layout
from fea_offaxis import CSV as OFFAXIS_CSV  # type: ignore[import-not-found]
from fea_offaxis import ETAS
from fea_offaxis import designs as offaxis_designs
from resumable_csv import appender, done_keys  # type: ignore[import-not-found]
from stored_names import FIXTURE_OF  # type: ignore[import-not-found]

OUT = Path(__file__).resolve().parents[1] / "docs" / "validation"
CSV = OUT / "load_cases_fe.csv"
FIELDS = ("design", "eta_deg", "test", "shift", "along", "nodes", "value", "seconds")
KEY = ("design", "eta_deg", "test", "shift", "along")
FIFTH = "W 12, n 13, alpha 115"
CHASSIS = (
    "chassis plate 79.2 x 121.2, polypropylene 0.25: layer 1 W 16, n 6, alpha 90; "
    "layer 2 W 5, n 27, alpha 120"
)
#: The designs of phase ``h`` (issue 35: the local term refitted on thin, thick and polypropylene
#: sheets): squares of identical layers, eta 0 only (eta 90 is its mirror image).
WIDER = {
    "thin Dura-Lar 0.05: W 10, n 7, alpha 50": ("dura-lar", 0.05, 10.0, 7, 50.0),
    "thick polypropylene 0.5: W 10, n 7, alpha 50": ("polypropylene", 0.5, 10.0, 7, 50.0),
    "thick polypropylene 0.5: W 10, n 7, alpha 120": ("polypropylene", 0.5, 10.0, 7, 120.0),
    "thin Dura-Lar 0.05: W 10, n 7, alpha 110": ("dura-lar", 0.05, 10.0, 7, 110.0),
    "Dura-Lar 0.075: W 12, n 7, alpha 70": ("dura-lar", 0.075, 12.0, 7, 70.0),
    "polypropylene 0.25: W 10, n 9, alpha 90": ("polypropylene", 0.25, 10.0, 9, 90.0),
}
#: The designs of phase ``j`` (issue 35 item 3: the off-axis bending factor 0.3 / sqrt(n) on more
#: than one coupon): small squares of identical layers (n 6-7, so that 16 per facet stays under
#: about 110 000 nodes and 4 GB) that differ in n, alpha, W and sheet, polypropylene among them.
OFFAXIS_BENDING = {
    "polypropylene 0.3: W 8, n 6, alpha 120": ("polypropylene", 0.3, 8.0, 6, 120.0),
    "Dura-Lar 0.125: W 6, n 7, alpha 60": ("dura-lar", 0.125, 6.0, 7, 60.0),
    "Dura-Lar 0.175: W 10, n 6, alpha 40": ("dura-lar", 0.175, 10.0, 6, 40.0),
}
#: The coupon of phase ``k`` (issue 35 item 3, the refit of docs/load_cases.md 5): the thickest
#: sheet the springs cover (t / W 0.05) with the fewest facets, at 35 deg, where a layer of n 6
#: holds about two facets from support to support ((n + 1)(1 - tan 35) = 2.1), so that counting
#: one fewer matters most while the strip bound still exceeds the plate bound.
OFFAXIS_COUNT = {
    "polypropylene 0.5: W 10, n 6, alpha 40": ("polypropylene", 0.5, 10.0, 6, 40.0),
}
PHASES = ("a", "b", "c", "d", "e", "f", "g", "h", "i", "j", "k")
#: The 4-point test read at its load points (the loading head's travel), from the same run as
#: ``bending4``'s gauge value: D = (P / delta) span^2 / 96.
LOAD_POINTS = "bending4-load"
MAX_NODES_16 = 150_000
#: Phase ``i`` runs 32 per facet only on models of at most this many nodes (about 5 GB peak).
MAX_NODES_32 = 250_000
Job = tuple[str, float, str, float, int]


def designs() -> dict[str, Assembly]:
    """The four designs of ``fea_offaxis.designs()`` and the square of identical layers W 12,
    n 13, alpha 115 (Dura-Lar, library thickness)."""
    out = offaxis_designs()
    out[FIFTH] = Assembly.identical(
        Layer(W=12.0, n=13, alpha_deg=115.0, material=get_material("dura-lar"))
    )
    pp = get_material("polypropylene")
    out[CHASSIS] = Assembly(
        Layer(W=16.0, n=6, alpha_deg=90.0, material=pp, t=0.25),
        Layer(W=5.0, n=27, alpha_deg=120.0, material=pp, t=0.25),
        layout=make_layout("rectangle"),
    )
    for name, (material, t, W, n, alpha) in (WIDER | OFFAXIS_BENDING | OFFAXIS_COUNT).items():
        out[name] = Assembly.identical(
            Layer(W=W, n=n, alpha_deg=alpha, material=get_material(material), t=t)
        )
    return out


def _mirror(a: Assembly, eta: float, along: int) -> bool:
    """Identical layers: eta > 45 deg mirrors 90 - eta; run only at 2 and 4 per facet."""
    return eta > 45 and a.layer1 == a.layer2 and along > 4


def jobs(phases: tuple[str, ...], ds: dict[str, Assembly]) -> Iterator[Job]:
    """(design, eta, test, shift, along) in the order of the phases (module docstring)."""
    first4 = [n for n in ds if n not in (FIFTH, CHASSIS, *WIDER, *OFFAXIS_BENDING)]
    ends = (0.0, 90.0)
    off = tuple(e for e in ETAS if e not in ends)
    for phase in phases:
        if phase == "a":
            for along in (2, 4, 8):
                for name in first4:
                    for eta in ends:
                        for test in ("bending", "bending4", "cantilever"):
                            yield name, eta, test, 0.0, along
        elif phase == "b":
            for along in (2, 4, 8):
                for name in first4:
                    for eta in off:
                        yield name, eta, "cantilever", 0.0, along
        elif phase == "c":
            for along in (2, 4, 8):
                for eta in ETAS:
                    for test in ("compression", "bending", "bending4", "cantilever"):
                        if test != "bending4" or eta in ends:
                            yield FIFTH, eta, test, 0.0, along
        elif phase == "d":  # 15 and 75 deg first: there the model is nearest the FE
            for along in (2, 4, 8):
                for eta in sorted(off, key=lambda e: (min(e, 90 - e) != 15, e)):
                    for name in [*first4, FIFTH]:
                        for test in ("bending", "cantilever"):
                            for shift in (0.5, 0.25):
                                yield name, eta, test, shift, along
        elif phase == "e":
            for name in [*first4, FIFTH]:
                for eta in ends:
                    for test in ("bending", "bending4", "cantilever"):
                        yield name, eta, test, 0.0, 16
        elif phase == "f":
            for along in (2, 4, 8):
                for eta in ends:
                    for test in ("compression", "bending", "bending4", "cantilever"):
                        yield CHASSIS, eta, test, 0.0, along
            for test in ("bending", "cantilever"):
                yield CHASSIS, 0.0, test, 0.0, 12
        elif phase == "g":
            for along in (2, 4, 8):
                for name in [n for n in ds if n not in WIDER and n not in OFFAXIS_BENDING]:
                    for eta in ends:
                        yield name, eta, LOAD_POINTS, 0.0, along
        elif phase == "h":
            for name in WIDER:
                for along in (2, 4, 8, 16):
                    for test in ("bending", LOAD_POINTS, "cantilever"):
                        yield name, 0.0, test, 0.0, along
        elif phase == "i":  # the thin sheets converge slowly: 32 per facet
            for name in [n for n in WIDER if WIDER[n][1] / WIDER[n][2] < 0.01]:
                for test in ("bending", LOAD_POINTS, "cantilever"):
                    yield name, 0.0, test, 0.0, 32
        elif phase == "j":  # 3-point off the creases, every shift, one whole series at a time
            for eta in (15.0, 30.0):
                for name in OFFAXIS_BENDING:
                    for shift in (0.0, 0.25, 0.5):
                        for along in (2, 4, 8, 16):
                            yield name, eta, "bending", shift, along
        elif phase == "k":  # the refit's coupon at 35 deg, every shift, one series at a time
            for name in OFFAXIS_COUNT:
                for shift in (0.0, 0.25, 0.5):
                    for along in (2, 4, 8, 16):
                        yield name, 35.0, "bending", shift, along


def load_point_D(r: Any) -> float:
    """The 4-point run's D read at its load points: (P / delta) span^2 / 96 (N mm), P the total
    reaction of the load lines (N) at their prescribed travel delta (mm)."""
    return float(r.force / r.displacement * r.span**2 / 96.0)


def _key(name: str, eta: float, test: str, shift: float, along: int) -> tuple[str, ...]:
    return (name, f"{eta:g}", test, f"{shift:g}", str(along))


def reuse_offaxis() -> int:
    """Copy the rows of off_axis_fe.csv (shift 0) that the new CSV lacks; their number."""
    done = done_keys(CSV, KEY)
    n = 0
    with OFFAXIS_CSV.open() as f, appender(CSV, FIELDS) as write:
        for r in csv.DictReader(f):
            key = (r["design"], r["eta_deg"], r["test"], "0", r["along"])
            if key in done:
                continue
            write((*key, r["nodes"], r["value"], r["seconds"]))
            n += 1
    return n


def run(phases: tuple[str, ...] = PHASES, minutes: float = float("inf")) -> None:
    """Run the cases of ``phases`` not yet in the CSV, one ccx at a time; no new case starts
    after ``minutes``."""
    from corrugate.core.errors import InputError
    from corrugate.fea.assembly import AssemblyMesh, assembly_deck, solve_assembly
    from corrugate.fea.ccx import SolverError

    print(f"reused {reuse_offaxis()} rows of {OFFAXIS_CSV.name}", flush=True)
    ds = designs()
    done = done_keys(CSV, KEY)
    start = time.perf_counter()
    with appender(CSV, FIELDS) as write:
        for name, eta, test, shift, along in jobs(phases, ds):
            key = _key(name, eta, test, shift, along)
            a = ds[name]
            if key in done or _mirror(a, eta, along):
                continue
            if time.perf_counter() - start > 60 * minutes:
                print(f"stopped: {minutes:g} minutes", flush=True)
                return
            mesh = AssemblyMesh(along)
            try:
                cap = {16: 0 if name in WIDER else MAX_NODES_16, 32: MAX_NODES_32}.get(along, 0)
                if cap:
                    nodes = assembly_deck(a, FIXTURE_OF[test], mesh, eta)[1].nodes
                    if nodes > cap:
                        print("skip", *key, f"{nodes} nodes > {cap}", flush=True)
                        continue
                t0 = time.perf_counter()
                r = solve_assembly(a, FIXTURE_OF[test], mesh, eta, shift=shift)
            except InputError as exc:
                print("skip", *key, exc, flush=True)
                continue
            except SolverError as exc:
                print("failed", *key, exc, flush=True)
                continue
            s = time.perf_counter() - t0
            done.add(key)
            value = r.value() if test != LOAD_POINTS else load_point_D(r)
            write((*key, r.nodes, f"{value:.8g}", f"{s:.1f}"))
            peak = resource.getrusage(resource.RUSAGE_CHILDREN).ru_maxrss / 1024
            print(*key, r.nodes, f"{value:.5g}", f"{s:.0f} s", f"peak child {peak:.0f} MB")
            sys.stdout.flush()


if __name__ == "__main__":
    if sys.argv[1:2] == ["run"]:
        args = sys.argv[2:]
        minutes = float("inf")
        if "--minutes" in args:
            i = args.index("--minutes")
            minutes = float(args[i + 1])
            args = args[:i] + args[i + 2 :]
        bad = [p for p in args if p not in PHASES]
        if bad:
            sys.exit(f"unknown phase {bad[0]!r}: allowed {', '.join(PHASES)}")
        run(tuple(args) or PHASES, minutes)
    else:
        sys.exit(__doc__)
