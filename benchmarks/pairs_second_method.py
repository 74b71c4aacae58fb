"""A second method for the certified optimum of a spec with material choices: the plain per-pair
branch and bound of every sheet pair (no cells, no floors, no pruning of whole pairs), each run to
its end with the incumbent ``MASS * (1 + 1e-9)``; a pair returns a design only if it holds one
lighter than that. The answer is confirmed when exactly the pairs holding designs as light as
``MASS`` return one, none lighter (to the gap), and every pair's search is certified.

Run by hand (minutes: the pair of the optimum is searched down to the gap)::

    python benchmarks/pairs_second_method.py SPEC MASS_G OUT.jsonl

One JSON line per pair (appended as each ends, so a killed run resumes where it stopped): its
index, sheets, the design's mass (null: none lighter than the incumbent), certified, CPU seconds,
boxes. A summary follows.
"""

from __future__ import annotations

import argparse
import json
import time
from pathlib import Path

from corrugate.solver import Problem
from corrugate.solver.bnb import branch_and_bound
from corrugate.solver.quantities import Tables
from corrugate.solver.solve import pairs
from corrugate.spec.schema import load_spec


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("spec", type=Path)
    ap.add_argument("mass", type=float, help="the certified optimum to check (g)")
    ap.add_argument("out", type=Path, help="JSON lines, one per sheet pair (resumed)")
    args = ap.parse_args()
    problem = Problem.from_spec(load_spec(args.spec))
    incumbent = args.mass * (1 + 1e-9)
    tables = Tables(problem)
    done: dict[int, dict[str, object]] = {}
    if args.out.exists():
        for line in args.out.read_text().splitlines():
            row = json.loads(line)
            done[int(row["k"])] = row
    for k, (c1, c2) in enumerate(pairs(problem)):
        if k in done:
            continue
        cpu = time.process_time()
        r = branch_and_bound(problem, c1, c2, incumbent=incumbent, tables=tables)
        row = {
            "k": k,
            "sheets": [c1.label, c2.label],
            "mass": None if r.point is None else r.value,
            "certified": bool(r.certified),
            "cpu": time.process_time() - cpu,
            "boxes": int(r.boxes),
        }
        with args.out.open("a") as f:
            f.write(json.dumps(row) + "\n")
        done[k] = row
        print(json.dumps(row), flush=True)
    found = [r for r in done.values() if r["mass"] is not None]
    cpu_all = sum(float(r["cpu"]) for r in done.values())  # type: ignore[arg-type]
    print(
        f"{len(done)} pairs, {sum(bool(r['certified']) for r in done.values())} certified, "
        f"{cpu_all:.1f} s CPU; designs lighter than {incumbent:.12g} g: "
        + (", ".join(f"{r['sheets']} {r['mass']:.15g} g" for r in found) or "none")
    )


if __name__ == "__main__":
    main()
