"""The explained answers before and after a change that must not change them (issue 39 item 2).

Run by hand (a few minutes; films-13-k45 alone takes its whole 60 s budget per tree)::

    python benchmarks/explain_same.py --base main [--work DIR] [--rows NAME,NAME]

For every shipped example (examples/*.toml) and every spec of ``benchmarks/edges.py --write``
except the continuous ones (films-5-cont, films-13-cont: they run out of budget), it runs
``corrugate design SPEC --json`` with the BEFORE tree (``git archive REF`` unpacked in a temporary
folder, its ``src`` first on PYTHONPATH) and with this tree, one process each under a 4 GB
address-space cap, and compares the JSON answers minus the timings (``solver.solve_seconds``,
``solver.total_seconds``) and the budget's use (``solver.budget.used_cpu_seconds`` and
``used_boxes``, printed beside: a cheaper explanation uses fewer boxes). Printed: per spec
``same`` or ``DIFFER`` (with the keys that differ) and the count of each.

films-13-k45 exhausts its 60 s budget in the diagnosis, so its answer depends on the CPU time a
run gets: the BEFORE tree itself gave "K up to 2073 N/mm" and "K up to 2086 N/mm" in two runs of
the same tree; it is compared all the same and a difference there says nothing.
"""

from __future__ import annotations

import argparse
import json
import os
import resource
import subprocess
import sys
import tempfile
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent))

from edges import ROOT, _base_tree, write_specs

CAP = 4 << 30


def _cap() -> None:
    resource.setrlimit(resource.RLIMIT_AS, (CAP, CAP))


def _answer(src: Path, spec: Path) -> tuple[int, dict[str, object] | None]:
    env = dict(os.environ, PYTHONPATH=str(src))
    p = subprocess.run(
        [sys.executable, "-m", "corrugate", "design", str(spec), "--json"],
        env=env,
        capture_output=True,
        text=True,
        preexec_fn=_cap,
        check=False,
    )
    try:
        return p.returncode, json.loads(p.stdout)
    except json.JSONDecodeError:
        return p.returncode, None


def _used(answer: dict[str, object] | None) -> object:
    solver = (answer or {}).get("solver", {})
    assert isinstance(solver, dict)
    return solver.get("budget", {}).get("used_boxes")


def _clean(answer: dict[str, object] | None) -> dict[str, object] | None:
    if answer is None:
        return None
    out = json.loads(json.dumps(answer))
    solver = out.get("solver", {})
    for key in ("solve_seconds", "total_seconds"):
        solver.pop(key, None)
    for key in ("used_cpu_seconds", "used_boxes"):
        solver.get("budget", {}).pop(key, None)
    return out


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--base", default="main", help="git ref of the BEFORE tree")
    ap.add_argument("--work", default="", help="folder for the specs (default: a temporary one)")
    ap.add_argument("--rows", default="", help="comma-separated spec names (default: all)")
    args = ap.parse_args()
    with tempfile.TemporaryDirectory() as tmp:
        work = Path(args.work or tmp)
        (work / "specs").mkdir(parents=True, exist_ok=True)
        specs = {f"examples/{p.stem}": p for p in sorted((ROOT / "examples").glob("*.toml"))}
        for name, path in write_specs(work / "specs").items():
            if not name.endswith("-cont"):
                specs[name] = path
        if args.rows:
            wanted = set(args.rows.split(","))
            specs = {k: v for k, v in specs.items() if k in wanted or Path(k).name in wanted}
        base = _base_tree(args.base, Path(tempfile.mkdtemp(dir=tmp)))
        same = differ = 0
        for name, spec in specs.items():
            rc_b, before = _answer(base / "src", spec)
            rc_a, after = _answer(ROOT / "src", spec)
            used = f"used_boxes {_used(before)} -> {_used(after)}"
            if rc_b == rc_a and before is not None and _clean(before) == _clean(after):
                same += 1
                print(f"same   {name} (exit {rc_a}; {used})", flush=True)
                continue
            differ += 1
            print(f"DIFFER {name} (exit {rc_b} -> {rc_a}; {used})", flush=True)
            b, a = _clean(before) or {}, _clean(after) or {}
            for key in sorted(set(b) | set(a)):
                if b.get(key) != a.get(key):
                    print(f"   {key}: {str(b.get(key))[:200]} | {str(a.get(key))[:200]}")
        print(f"{same} same, {differ} differ")


if __name__ == "__main__":
    main()
