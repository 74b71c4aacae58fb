"""The solver at the edges (issue 39 items 1 and 2): material choices, continuous variables on
independent layers and infeasible specs, certified and explained, before and after.

Run by hand (a few minutes: the before tree's slow rows dominate)::

    python benchmarks/edges.py --base main [--repeats 1] [--rows NAME,NAME] [--cap-mb 6000]
                               [--no-base] [--inproc-repeats 3]
    python benchmarks/edges.py --write DIR   # write the specs only

The specs (written to a temporary folder, default tolerances on: no ``tolerances`` key):

- ``films-5``, ``films-13``, ``films-25``, ``films-32``: examples/rectangle_independent.toml with
  ``[[materials]]`` of library films at every thickness sold (dura-lar 5; + mylar 8 = 13; +
  kapton 6 + polycarbonate 6 = 25; + acetate 7 = 32, the cap of candidate sheets), W on 1 mm and
  alpha on 5 deg as the example has them;
- ``films-5-cont``, ``films-13-cont``: the same with continuous W and alpha (no ``step``);
- ``k45``: benchmarks/specs/independent_k45_infeasible.toml (one sheet, K(45) >= 100 N/mm in
  plane, no design meets it); ``films-13-k45``: that bound on the 13-sheet spec;
- ``wheel-ligament``: examples/wheel_circle.toml with a 56 mm axle hole in its 70-80 mm disc
  (thin ligaments), infeasible;
- ``case-study``: examples/blimp_gripper.toml.

Each row is run in fresh processes, the BEFORE tree (``--base REF``: ``git archive REF`` unpacked
in a temporary folder, its ``src`` first on PYTHONPATH) interleaved with this tree, same
interpreter and libraries, compiled bytecode: the certified solve (``solve(problem,
explain=False)``) and the explained answer (``corrugate design SPEC --json``). Printed: CPU
seconds (user + system of the child, ``os.wait4``), peak RSS (``ru_maxrss``), the answer (status,
certified, mass to 12 digits) of both trees, whether the answers are the same, and the targets of
issue 39 (every row explained within 10 s CPU and 500 MB, the infeasible ones within 10 s and 300
MB; the explanation within 2x the certified search on the case study and the 13-sheet row).
Each child runs under an address-space cap (``--cap-mb``, RLIMIT_AS): a run that needs more ends
with "needs more memory" (exit 2) and is printed as such.
"""

from __future__ import annotations

import argparse
import compileall
import json
import os
import re
import resource
import statistics
import subprocess
import sys
import sysconfig
import tempfile
from dataclasses import dataclass
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
EXAMPLES = ROOT / "examples"

FILMS = {
    "dura-lar": 5,
    "mylar": 8,
    "kapton": 6,
    "polycarbonate": 6,
    "acetate": 7,
}
SETS = {5: ("dura-lar",), 13: ("dura-lar", "mylar")}
SETS[25] = (*SETS[13], "kapton", "polycarbonate")
SETS[32] = (*SETS[25], "acetate")
INFEASIBLE = {"k45", "films-13-k45", "wheel-ligament"}

INPROC_CODE = (
    "import sys, time, json, statistics; from corrugate.spec.schema import load_spec; "
    "from corrugate.solver import Problem, solve; "
    "p = Problem.from_spec(load_spec(sys.argv[1])); solve(p); r = {'solve': [], 'explained': []}\n"
    "for _ in range(int(sys.argv[2])):\n"
    "    for k, e in (('solve', False), ('explained', True)):\n"
    "        c = time.process_time(); solve(p, explain=e); r[k].append(time.process_time() - c)\n"
    "print(json.dumps({k: statistics.median(v) for k, v in r.items()}))"
)
SOLVE_CODE = (
    "import sys, json; from corrugate.spec.schema import load_spec; "
    "from corrugate.solver import Problem, solve; "
    "s = solve(Problem.from_spec(load_spec(sys.argv[1])), explain=False); "
    "a = s.assembly; "
    "print(json.dumps({'status': str(s.status), 'certified': bool(s.certified), "
    "'mass_g': None if a is None else s.mass, 'design': None if a is None else repr(a)}))"
)


def _materials_block(names: tuple[str, ...]) -> str:
    """``[[materials]]`` tables of every thickness the library sells of each of ``names``."""
    import tomllib

    lib = tomllib.loads((ROOT / "src" / "corrugate" / "data" / "materials.toml").read_text())
    out = []
    for name in names:
        ts = lib[name]["thicknesses"]
        assert len(ts) == FILMS[name], (name, ts)
        out.append(f'[[materials]]\nname = "{name}"\nthickness = {json.dumps(ts)}\n')
    return "\n".join(out)


def _replace_material(text: str, block: str) -> str:
    """``text`` with its ``[material]`` table replaced by ``block``."""
    new, k = re.subn(r"(?m)^\[material\]\n(?:[^\[\n].*\n)*", block + "\n", text, count=1)
    assert k == 1
    return new


def _continuous(text: str) -> str:
    """W and alpha without their ``step``: continuous variables."""
    new, k = re.subn(r', step = "[^"]*"', "", text)
    assert k == 2, k
    return new


def write_specs(folder: Path) -> dict[str, Path]:
    """The module docstring's specs, written to ``folder``, by row name."""
    rect = (EXAMPLES / "rectangle_independent.toml").read_text()
    k45 = (ROOT / "benchmarks" / "specs" / "independent_k45_infeasible.toml").read_text()
    k45 = re.sub(r'(?m)^tolerances = "none".*\n', "", k45)
    texts: dict[str, str] = {}
    for n, names in SETS.items():
        texts[f"films-{n}"] = _replace_material(rect, _materials_block(names))
    for n in (5, 13):
        texts[f"films-{n}-cont"] = _continuous(texts[f"films-{n}"])
    texts["k45"] = k45
    texts["films-13-k45"] = _replace_material(k45, _materials_block(SETS[13]))
    wheel = (EXAMPLES / "wheel_circle.toml").read_text()
    wheel = re.sub(r'(?m)^tolerances = "none".*\n', "", wheel)
    wheel, k = re.subn(r'diameter = "6 mm"', 'diameter = "56 mm"', wheel)
    assert k == 1
    texts["wheel-ligament"] = wheel
    texts["case-study"] = (EXAMPLES / "blimp_gripper.toml").read_text()
    out = {}
    for name, text in texts.items():
        path = folder / f"{name}.toml"
        path.write_text(text)
        out[name] = path
    return out


@dataclass(frozen=True)
class Run:
    """One child process: CPU seconds, peak RSS (MB), exit code, its answer (JSON) or error."""

    cpu: float
    rss: float
    rc: int
    answer: dict[str, object] | None
    error: str


def _run(argv: list[str], env: dict[str, str], cap_mb: int) -> Run:
    """Run ``argv`` to its end under an address-space cap of ``cap_mb``, reaped by ``os.wait4``
    (its own rusage), its output read by threads."""
    import threading

    def cap() -> None:
        b = cap_mb * 1024 * 1024
        resource.setrlimit(resource.RLIMIT_AS, (b, b))

    proc = subprocess.Popen(
        argv, env=env, stdout=subprocess.PIPE, stderr=subprocess.PIPE, preexec_fn=cap
    )
    bufs: dict[str, bytes] = {}

    def read(name: str, stream: object) -> None:
        bufs[name] = stream.read()  # type: ignore[attr-defined]

    ts = [
        threading.Thread(target=read, args=("out", proc.stdout)),
        threading.Thread(target=read, args=("err", proc.stderr)),
    ]
    for t in ts:
        t.start()
    _, status, usage = os.wait4(proc.pid, 0)
    for t in ts:
        t.join()
    proc.returncode = os.waitstatus_to_exitcode(status)
    out, err = bufs.get("out", b""), bufs.get("err", b"")
    answer = None
    text = out.decode(errors="replace").strip()
    for cand in (text, text.splitlines()[-1] if text else ""):
        try:
            got = json.loads(cand)
        except json.JSONDecodeError:
            continue
        if isinstance(got, dict):
            answer = got
            break
    lines = [ln for ln in err.decode(errors="replace").splitlines() if ln.strip()]
    return Run(
        usage.ru_utime + usage.ru_stime,
        usage.ru_maxrss / 1024,
        proc.returncode,
        answer,
        lines[-1] if lines else "",
    )


def _answer(run: Run) -> str:
    """The answer's status, certificate and mass, in one short string."""
    a = run.answer
    if a is None:
        return f"exit {run.rc}: {run.error[:90]}"
    mass = a.get("mass_g")
    m = "-" if mass is None else f"{float(mass):.12f} g"  # type: ignore[arg-type]
    return f"{a.get('status')} cert={a.get('certified')} {m}"


def _key(run: Run) -> tuple[object, ...]:
    """What must be the same before and after: status, certified, mass, the design."""
    a = run.answer or {}
    design = a.get("design")
    if isinstance(design, dict):
        design = json.dumps(design, sort_keys=True)
    return (a.get("status"), a.get("certified"), a.get("mass_g"), design, run.rc)


def _base_tree(ref: str, folder: Path) -> Path:
    """``git archive ref`` of this repository unpacked in ``folder``."""
    archive = subprocess.run(
        ["git", "-C", str(ROOT), "archive", ref], check=True, capture_output=True
    ).stdout
    subprocess.run(["tar", "-x", "-C", str(folder)], input=archive, check=True)
    return folder


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--base", default="main", help="git ref of the BEFORE tree")
    ap.add_argument("--repeats", type=int, default=1)
    ap.add_argument("--rows", default="", help="comma-separated row names (default: all)")
    ap.add_argument("--cap-mb", type=int, default=6000)
    ap.add_argument("--write", default="", help="write the specs to this folder and stop")
    ap.add_argument("--no-base", action="store_true", help="this tree only")
    ap.add_argument(
        "--inproc-repeats", type=int, default=3, help="in-process runs of the 13-sheet row"
    )
    args = ap.parse_args()
    if args.write:
        Path(args.write).mkdir(parents=True, exist_ok=True)
        for name, path in write_specs(Path(args.write)).items():
            print(name, path)
        return
    with tempfile.TemporaryDirectory() as tmp:
        specs = write_specs(Path(tmp))
        if args.rows:
            specs = {k: v for k, v in specs.items() if k in args.rows.split(",")}
        trees = {"after": ROOT / "src"}
        if not args.no_base:
            base = Path(tmp) / "base"
            base.mkdir()
            trees = {"before": _base_tree(args.base, base) / "src", **trees}
        for src in (*trees.values(), Path(sysconfig.get_paths()["purelib"])):
            compileall.compile_dir(str(src), quiet=1, workers=1)
        env0 = {k: v for k, v in os.environ.items() if k != "PYTHONDONTWRITEBYTECODE"}
        envs = {t: {**env0, "PYTHONPATH": str(src)} for t, src in trees.items()}
        py = sys.executable
        kinds = {
            "solve": lambda spec: [py, "-c", SOLVE_CODE, str(spec)],
            "explained": lambda spec: [py, "-m", "corrugate", "design", str(spec), "--json"],
        }
        print(
            f"== benchmarks/edges.py: before = {args.base} ({trees.get('before', '-')}), after = "
            f"{ROOT}; fresh processes, CPU = user + sys of the child (os.wait4), peak RSS, cap "
            f"{args.cap_mb} MB, median of {args.repeats}",
            flush=True,
        )
        ok_all = True
        for row, spec in specs.items():
            runs: dict[tuple[str, str], list[Run]] = {}
            for r in range(args.repeats):
                for kind, argv in kinds.items():
                    order = list(trees)[:: 1 if r % 2 == 0 else -1]
                    for tree in order:
                        runs.setdefault((kind, tree), []).append(
                            _run(argv(spec), envs[tree], args.cap_mb)
                        )
            med = {k: statistics.median(x.cpu for x in v) for k, v in runs.items()}
            rss = {k: max(x.rss for x in v) for k, v in runs.items()}
            infeasible = row in INFEASIBLE
            cpu_t, mem_t = 10.0, 300.0 if infeasible else 500.0
            print(f"\n-- {row} ({'infeasible' if infeasible else 'feasible'})")
            for kind in kinds:
                for tree in trees:
                    last = runs[(kind, tree)][-1]
                    print(
                        f"   {kind:9s} {tree:6s} CPU {med[(kind, tree)]:7.2f} s  peak "
                        f"{rss[(kind, tree)]:7.0f} MB  {_answer(last)}"
                    )
                if "before" in trees:
                    same = _key(runs[(kind, "before")][-1]) == _key(runs[(kind, "after")][-1])
                    ok_all &= same
                    print(f"   {kind:9s} same answer before/after: {same}")
            c, m = med[("explained", "after")], rss[("explained", "after")]
            ans = runs[("explained", "after")][-1].answer or {}
            done = ans.get("certified") is True or (
                infeasible and ans.get("status") == "infeasible"
            )
            met = c <= cpu_t and m <= mem_t and bool(done)
            print(
                f"   target (explained within {cpu_t:g} s and {mem_t:g} MB, "
                f"{'diagnosed' if infeasible else 'certified'}): {'met' if met else 'NOT met'}"
            )
            if row in ("case-study", "films-13"):
                ratio = {t: med[("explained", t)] / max(med[("solve", t)], 1e-9) for t in trees}
                print(
                    "   explained / certified search, whole processes (imports included): "
                    + ", ".join(f"{t} {v:.2f}x" for t, v in ratio.items())
                )
                reps = "21" if row == "case-study" else str(args.inproc_repeats)
                inproc = {}
                for t in trees:  # imports done, warm, explain=False and True interleaved
                    got = _run([py, "-c", INPROC_CODE, str(spec), reps], envs[t], args.cap_mb)
                    inproc[t] = got.answer or {}
                    print(
                        f"   in one process (imports done, median of {reps}) {t:6s}: certified "
                        f"search {float(inproc[t].get('solve', 'nan')):.4f} s, solve(explain=True) "
                        f"{float(inproc[t].get('explained', 'nan')):.4f} s CPU"
                    )
                a = inproc["after"]
                r2 = float(a.get("explained", "nan")) / float(a.get("solve", "nan"))
                print(
                    f"   explained within 2x the certified search (in one process, after): "
                    f"{r2:.2f}x, {'met' if r2 <= 2 else 'NOT met'}"
                )
            sys.stdout.flush()
        if "before" in trees:
            print(f"\nevery answer the same before and after: {ok_all}")


if __name__ == "__main__":
    main()
