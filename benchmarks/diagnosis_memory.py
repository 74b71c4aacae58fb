"""CPU time and peak memory of infeasible specs' diagnoses, before and after bounding them
(issue 39 item 2, issue 35 item 2; docs/tolerances.md section 5).

    python benchmarks/diagnosis_memory.py BEFORE_TREE AFTER_TREE [SPEC ...]
    python benchmarks/diagnosis_memory.py one TREE SPEC     # one run

Each spec is solved and explained (``corrugate design SPEC``) in a fresh process per tree, the
trees' ``src`` first on the path, the runs of the two trees interleaved, under an address-space
cap of 6 GB (``RLIMIT_AS``: a run that needs more stops with "needs more memory than is
available", exit 2, instead of taking the machine down). Printed per spec and tree: the CPU
seconds (user + system of the child, ``wait4``), its peak resident memory (``ru_maxrss``), the
exit code and the last line of the answer (of stderr when it printed none). Without SPEC arguments: examples/chassis_plate.toml
with the default tolerances and benchmarks/specs/independent_k45_infeasible.toml nominal
(``tolerances = "none"``) and with the default tolerances, each written to a temporary folder
with its tolerances stated, so either tree reads them alike.
"""

from __future__ import annotations

import os
import re
import resource
import subprocess
import sys
import tempfile
from pathlib import Path

HERE = Path(__file__).resolve().parent
CAP_BYTES = 6_000_000_000


def _with(text: str, tolerances: str) -> str:
    """The spec ``text`` with its tolerances stated: ``"none"`` or ``"defaults"`` (an empty
    ``[tolerances]`` table: its keys take the defaults)."""
    text = re.sub(r'(?m)^tolerances = "none".*\n', "", text)
    text = re.sub(r"(?m)^\[tolerances\].*\n", "", text)
    if tolerances == "none":
        return re.sub(r"(?m)^(name = .*\n)", r'\1tolerances = "none"\n', text, count=1)
    return text + "\n[tolerances]\n"


def default_specs(folder: Path) -> list[Path]:
    """The specs of the module docstring, written to ``folder``."""
    chassis = (HERE.parent / "examples" / "chassis_plate.toml").read_text()
    k45 = (HERE / "specs" / "independent_k45_infeasible.toml").read_text()
    out = []
    for name, text, tol in (
        ("chassis_plate_defaults", chassis, "defaults"),
        ("independent_k45_none", k45, "none"),
        ("independent_k45_defaults", k45, "defaults"),
    ):
        path = folder / f"{name}.toml"
        path.write_text(_with(text, tol))
        out.append(path)
    return out


def _cap() -> None:
    resource.setrlimit(resource.RLIMIT_AS, (CAP_BYTES, CAP_BYTES))


def run(tree: Path, spec: Path) -> tuple[float, float, int, str]:
    """CPU seconds, peak RSS (MB), exit code and the answer's last line of ``corrugate design
    SPEC`` with ``tree``'s sources."""
    env = {**os.environ, "PYTHONPATH": str(tree / "src")}
    proc = subprocess.Popen(
        [sys.executable, "-m", "corrugate", "design", str(spec)],
        cwd=tree,
        env=env,
        stdout=subprocess.PIPE,
        stderr=subprocess.PIPE,
        text=True,
        preexec_fn=_cap,
    )
    out, err = proc.communicate()
    usage = resource.getrusage(resource.RUSAGE_CHILDREN)
    lines = [ln for ln in out.splitlines() if ln.strip()] or [
        ln for ln in err.splitlines() if ln.strip()
    ]
    return usage.ru_utime + usage.ru_stime, usage.ru_maxrss / 1024, proc.returncode, lines[-1]


def main(argv: list[str]) -> None:
    if argv[0] == "one":  # one run, in this process's own child
        c, m, rc, last = run(Path(argv[1]), Path(argv[2]))
        print(f"{c:.1f} s CPU, {m:.0f} MB peak, exit {rc}: {last[:160]}")
        return
    before, after = Path(argv[0]).resolve(), Path(argv[1]).resolve()
    with tempfile.TemporaryDirectory() as tmp:
        specs = [Path(s).resolve() for s in argv[2:]] or default_specs(Path(tmp))
        for spec in specs:
            for label, tree in (("before", before), ("after", after)):
                # a fresh interpreter measures each run alone: RUSAGE_CHILDREN is cumulative
                res = subprocess.run(
                    [sys.executable, __file__, "one", str(tree), str(spec)],
                    capture_output=True,
                    text=True,
                    check=False,
                )
                print(f"{spec.stem:28s} {label:6s} {res.stdout.strip() or res.stderr[-300:]}")
                sys.stdout.flush()


if __name__ == "__main__":
    main(sys.argv[1:])
