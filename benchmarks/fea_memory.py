"""Peak memory and time of ccx for the largest runs of the validation tables, before and after
the memory work of issue 23 item 3 (docs/fea.md 2.9).

    python benchmarks/fea_memory.py one DESIGN TEST ETA ALONG [--aspect R] [--split 0|1]
        # one solve_assembly in this process: prints a JSON line with the value, nodes, the
        # peak RSS of its largest ccx child (wait4 rusage, kB) and the ccx CPU time (user + sys)
    python benchmarks/fea_memory.py compare DESIGN TEST ETA ALONG [ALONG ...] [--aspect R]
        # for each mesh: the one-run solve (split 0, today's direct solve) and the split solve,
        # each in a fresh process, interleaved; prints both and the ratios (value, memory, CPU)
    python benchmarks/fea_memory.py series DESIGN TEST ETA ALONG [ALONG ...] [--aspect R]
        # the split solve only, one fresh process per mesh (the converged series)

DESIGN is one of ``designs()`` (the four of ``fea_offaxis.designs()``, ``W 12, n 13, alpha
115`` of fea_load_cases.py and the two certified off-axis designs of fea_certified.py, ``k15``
and ``k45``). Run the big meshes under the shared lock and a 16 GB address-space cap, e.g.

    flock /work/notes/fe-big.lock prlimit --as=17000000000 \
        python benchmarks/fea_memory.py series k15 compression 15 2 4 8 16

Each solve runs in its own Python process so that the child rusage (``RUSAGE_CHILDREN``, the
largest ccx process it waited for) belongs to that solve alone; gmsh runs inside the Python
process and is not counted. CPU seconds, not wall, compare alternatives on the shared machine.
"""

from __future__ import annotations

import json
import resource
import subprocess
import sys
import time
from pathlib import Path

from corrugate import Assembly, Layer, get_material

HERE = Path(__file__).resolve().parent


def designs() -> dict[str, Assembly]:
    """The designs of the validation tables (docs/validation/off_axis.md, load_cases.md) and the
    two certified off-axis designs (benchmarks/fea_certified.py)."""
    sys.path.insert(0, str(HERE))
    from fea_offaxis import designs as offaxis  # type: ignore[import-not-found]

    dl = get_material("dura-lar")
    out = dict(offaxis())
    out["W 12, n 13, alpha 115"] = Assembly.identical(
        Layer(W=12.0, n=13, alpha_deg=115.0, material=dl)
    )
    out["k15"] = Assembly.identical(Layer(W=5.0, n=12, alpha_deg=104.0, material=dl))
    out["k45"] = Assembly.identical(Layer(W=9.0, n=8, alpha_deg=96.0, material=dl))
    return out


def one(design: str, test: str, eta: float, along: int, aspect: float, split: bool) -> None:
    """One solve in this process; prints a JSON line."""
    from corrugate.fea.assembly import AssemblyMesh, solve_assembly

    a = designs()[design]
    t0 = time.perf_counter()
    r = solve_assembly(
        a,
        test,
        AssemblyMesh(along, aspect),
        eta,
        split=split,
        timeout=7200.0,  # type: ignore[arg-type]
    )
    wall = time.perf_counter() - t0
    ru = resource.getrusage(resource.RUSAGE_CHILDREN)
    print(
        json.dumps(
            {
                "design": design,
                "test": test,
                "eta": eta,
                "along": along,
                "aspect": aspect,
                "split": split,
                "value": r.value(),
                "nodes": r.nodes,
                "ccx_peak_rss_GiB": ru.ru_maxrss / 2**20,  # ru_maxrss is in KiB on Linux
                "ccx_cpu_s": ru.ru_utime + ru.ru_stime,
                "wall_s": wall,
            }
        ),
        flush=True,
    )


def _fresh(design: str, test: str, eta: float, along: int, aspect: float, split: bool) -> dict:
    """:func:`one` in a fresh Python process; its JSON line as a dict (or the error)."""
    cmd = [sys.executable, __file__, "one", design, test, f"{eta:g}", str(along)]
    cmd += ["--aspect", f"{aspect:g}", "--split", str(int(split))]
    proc = subprocess.run(cmd, capture_output=True, text=True, check=False)
    lines = [ln for ln in proc.stdout.splitlines() if ln.startswith("{")]
    if proc.returncode != 0 or not lines:
        tail = (proc.stderr.strip().splitlines() or ["?"])[-1]
        ru = resource.getrusage(resource.RUSAGE_CHILDREN)
        return {"error": tail, "rc": proc.returncode, "peak_GiB_so_far": ru.ru_maxrss / 2**20}
    return dict(json.loads(lines[-1]))


def _row(tag: str, r: dict) -> str:
    if "error" in r:
        return f"  {tag}: FAILED rc {r['rc']}: {r['error']}"
    return (
        f"  {tag}: value {r['value']:.8g}, {r['nodes']} nodes, ccx peak RSS "
        f"{r['ccx_peak_rss_GiB']:.2f} GiB, ccx CPU {r['ccx_cpu_s']:.1f} s, wall {r['wall_s']:.0f} s"
    )


def compare(design: str, test: str, eta: float, alongs: list[int], aspect: float) -> None:
    """One-run (before) against split (after) solve for each mesh, with ratios."""
    for along in alongs:
        print(f"{design}, {test}, eta {eta:g}, {along}/facet, aspect {aspect:g}", flush=True)
        before = _fresh(design, test, eta, along, aspect, False)
        print(_row("one run (before)", before), flush=True)
        after = _fresh(design, test, eta, along, aspect, True)
        print(_row("split (after)   ", after), flush=True)
        if "error" not in before and "error" not in after:
            print(
                f"  after / before: value {after['value'] / before['value'] - 1:+.2e} relative, "
                f"peak RSS {after['ccx_peak_rss_GiB'] / before['ccx_peak_rss_GiB']:.3f}, "
                f"ccx CPU {after['ccx_cpu_s'] / before['ccx_cpu_s']:.3f}",
                flush=True,
            )


def series(design: str, test: str, eta: float, alongs: list[int], aspect: float) -> None:
    """The split solve at each mesh, with the changes between meshes."""
    prev = None
    for along in alongs:
        r = _fresh(design, test, eta, along, aspect, True)
        print(f"{design}, {test}, eta {eta:g}, {along}/facet, aspect {aspect:g}", flush=True)
        print(_row("split", r), flush=True)
        if "error" not in r:
            if prev is not None:
                print(f"  change from the previous mesh: {r['value'] / prev - 1:+.3%}", flush=True)
            prev = r["value"]


def _opts(args: list[str]) -> tuple[list[str], float, bool]:
    aspect, split = 1.0, True
    if "--aspect" in args:
        i = args.index("--aspect")
        aspect = float(args[i + 1])
        args = args[:i] + args[i + 2 :]
    if "--split" in args:
        i = args.index("--split")
        split = args[i + 1] == "1"
        args = args[:i] + args[i + 2 :]
    return args, aspect, split


if __name__ == "__main__":
    argv, aspect_, split_ = _opts(sys.argv[1:])
    if len(argv) >= 5 and argv[0] in ("one", "compare", "series"):
        name, test_, eta_ = argv[1], argv[2], float(argv[3])
        meshes = [int(v) for v in argv[4:]]
        if argv[0] == "one":
            one(name, test_, eta_, meshes[0], aspect_, split_)
        elif argv[0] == "compare":
            compare(name, test_, eta_, meshes, aspect_)
        else:
            series(name, test_, eta_, meshes, aspect_)
    else:
        sys.exit(__doc__)
