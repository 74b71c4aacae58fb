"""Every hostile-input class of issue 22 run against one installed ``corrugate``, one row each.

Run by hand (it takes minutes; on an old checkout some cases run to their time limit):

    python benchmarks/hostile_classes.py --corrugate .venv/bin/corrugate
    python benchmarks/hostile_classes.py --corrugate /path/to/old/.venv/bin/corrugate --skip-folders

Each case runs as its own process group under an address-space limit (``--memory``, default 3 GB, a
guard for this machine, above the 1.5 GB the suite asserts) and a time limit (``--timeout``, default
60 s), in a fresh temporary folder as its working folder. A row gives the exit code (``T`` killed
at the time limit, ``M`` killed by a signal such as the memory limit), the number of stderr lines,
the CPU time (user + system) and the peak resident size of the process (``wait4``), whether a
numpy warning or a traceback reached stderr, and the verdict against the issue's rule: exit 2 with
one stderr line, or an answer (exit 0, 1 or 4) within the time limit, peak below 1.5 GB.

The output-folder cases (``--out /`` and the like) are skipped with ``--skip-folders``: on an old
checkout they may link the whole file system into a staging folder (issue 22).
"""

from __future__ import annotations

import argparse
import os
import resource
import signal
import subprocess
import sys
import tempfile
import time
from collections.abc import Callable
from dataclasses import dataclass
from pathlib import Path

PASS_RSS_MB = 1536.0

_BASE = """
name = "hostile"
model = "refined"
{material}
[layout]
{layout}
[variables]
W = {{ min = "{wmin}", max = "20 mm"{wstep} }}
n = {{ min = 6, max = 60 }}
alpha = {{ min = "{amin}", max = "150 deg"{astep} }}
[constraints]
sheet_max = "300 mm"
{constraints}
{extra}
"""

_DURALAR = '[material]\nname = "dura-lar"\nthickness = "0.125 mm"\n'


def spec(
    *,
    layout: str = 'shape = "square"',
    constraints: str = (
        'side = { min = "40 mm", max = "90 mm" }\n'
        'flexural_rigidity = [{ min = "20 mN*m^2", eta = "0 deg" }]'
    ),
    material: str = _DURALAR,
    extra: str = "",
    wmin: str = "2 mm",
    amin: str = "40 deg",
    grid: bool = True,
) -> str:
    """A spec around the given pieces (gridded W and alpha unless ``grid`` is False)."""
    return _BASE.format(
        material=material,
        layout=layout,
        constraints=constraints,
        extra=extra,
        wmin=wmin,
        amin=amin,
        wstep=', step = "0.5 mm"' if grid else "",
        astep=', step = "1 deg"' if grid else "",
    )


def _holes(count: int) -> str:
    side = int(count**0.5 + 0.999)
    pitch = 50.0 / side
    holes = []
    for i in range(count):
        x = (i % side - (side - 1) / 2) * pitch
        y = (i // side - (side - 1) / 2) * pitch
        holes.append(
            f'{{ shape = "circle", diameter = "2 mm", center = ["{x:.3f} mm", "{y:.3f} mm"] }}'
        )
    return 'shape = "square"\nholes = [' + ", ".join(holes) + "]"


def _polygon(count: int) -> str:
    import math

    pts = ", ".join(
        f"[{40 * math.cos(2 * math.pi * k / count):.6f}, {40 * math.sin(2 * math.pi * k / count):.6f}]"
        for k in range(count)
    )
    return f'shape = "polygon"\nvertices = [{pts}]'


def _bounds(count: int) -> str:
    rows = ", ".join(
        f'{{ min = "1 mN*m^2", eta = "{(k * 0.009) % 90:.4f} deg" }}' for k in range(count)
    )
    return f'side = {{ min = "40 mm", max = "90 mm" }}\nflexural_rigidity = [{rows}]'


def _thicknesses(count: int) -> str:
    values = ", ".join(f'"{0.1 + k * 1e-5:.5f} mm"' for k in range(count))
    return f'[material]\nname = "dura-lar"\nthickness = [{values}]\n'


_MAXIMIZE_36 = (
    'side = { min = "40 mm", max = "90 mm" }\n'
    'mass = { max = "5 g" }\n'
    "bending_stiffness = ["
    + ", ".join(f'{{ min = "1 N*mm", eta = "{k * 2.5:g} deg" }}' for k in range(36))
    + "]"
)

BIGINT = "1" + "0" * 4400

#: The shipped wheel example (its axle hole is made 68.9 mm: a 0.55 mm ligament at the 70 mm disc).
WHEEL = (Path(__file__).parents[1] / "examples" / "wheel_circle.toml").read_text()


@dataclass(frozen=True)
class Case:
    """One hostile input: the class it belongs to, its arguments and an optional spec file."""

    klass: str
    name: str
    args: tuple[str, ...]
    spec: str | None = None
    folder: bool = False


ANALYZE = ("analyze", "--n", "8", "--alpha", "84", "--material", "dura-lar", "-q")


def _analyze_w(w: str) -> tuple[str, ...]:
    return ("analyze", "--W", w, "--n", "8", "--alpha", "84", "--material", "dura-lar", "-q")


def cases() -> list[Case]:
    """Every class of issue 22's fuzz, as runnable cases."""
    design = ("design", "SPEC", "-q")
    out: list[Case] = []
    # 1. the unit parser
    for name, text in [
        ("exponent tower", "1 mm**9**9**9"),
        ("division by zero", "1 mm/0"),
        ("exponent 1/0", "1 mm**(1/0)"),
        ("exponent -0", "1 mm**-0"),
        ("unbalanced (", "1 (mm"),
    ]:
        out.append(Case("unit string", f"analyze --W '{text}' ({name})", _analyze_w(text)))
    out.append(
        Case(
            "unit string",
            "spec W.max = '1 mm**9**9**9'",
            design,
            spec(extra="").replace('max = "20 mm"', 'max = "1 mm**9**9**9"'),
        )
    )
    # huge integers, negative seeds
    out.append(
        Case(
            "huge integer",
            "spec n.max of 4401 digits",
            design,
            spec().replace("max = 60", f"max = {BIGINT}"),
        )
    )
    robust = '[robust]\nprobability = 0.9\nW = "0.1 mm"\nalpha = "2 deg"\nseed = -1\nsamples = 100'
    out.append(Case("negative seed", "[robust] seed = -1", design, spec(extra=robust)))
    out.append(
        Case(
            "negative seed",
            "tolerance --seed -1",
            ("tolerance", "SPEC", "--seed", "-1", "-q"),
            spec(),
        )
    )
    # 4. non-finite and subnormal values
    out.append(
        Case(
            "non-finite",
            "analyze --alpha 5e-324",
            ("analyze", "--W", "8", "--n", "8", "--alpha", "5e-324", "-q"),
        )
    )
    out.append(
        Case("non-finite", "pareto --eta inf", ("pareto", "SPEC", "--eta", "inf", "-q"), spec())
    )
    out.append(
        Case("non-finite", "pareto --eta nan", ("pareto", "SPEC", "--eta", "nan", "-q"), spec())
    )
    out.append(
        Case(
            "non-finite",
            "tolerance --W-tol nan --json",
            ("tolerance", "SPEC", "--W-tol", "nan", "--json"),
            spec(),
        )
    )
    out.append(
        Case(
            "non-finite",
            "tolerance --alpha-tol nan",
            ("tolerance", "SPEC", "--alpha-tol", "nan"),
            spec(),
        )
    )
    out.append(
        Case(
            "non-finite",
            "tolerance --W-tol 1e308",
            ("tolerance", "SPEC", "--W-tol", "1e308"),
            spec(),
        )
    )
    out.append(
        Case("non-finite", "analyze --thickness nan", (*_analyze_w("8"), "--thickness", "nan"))
    )
    out.append(
        Case(
            "non-finite", "spec alpha.min = 5e-324 deg", design, spec(amin="5e-324 deg", grid=False)
        )
    )
    robust1 = '[robust]\nprobability = 0.9\nW = "0.1 mm"\nalpha = "2 deg"\nsamples = 1'
    out.append(Case("non-finite", "[robust] samples = 1", design, spec(extra=robust1)))
    # 2. over-limit counts and perforation density
    pat = (
        "pattern",
        "--W",
        "8",
        "--n",
        "8",
        "--alpha",
        "84",
        "--material",
        "dura-lar",
        "--out",
        "o",
        "-q",
    )
    out.append(
        Case(
            "perforation",
            "--cut 1e-9 --gap 1e-9",
            (*pat, "--fold-style", "perforated", "--cut", "1e-9", "--gap", "1e-9"),
        )
    )
    out.append(
        Case(
            "perforation",
            "--cut 0.001 --gap 0.001",
            (*pat, "--fold-style", "perforated", "--cut", "0.001", "--gap", "0.001"),
        )
    )
    out.append(
        Case(
            "over-limit count",
            "tolerance --samples 20000000",
            ("tolerance", "SPEC", "--samples", "20000000", "-q"),
            spec(),
        )
    )
    out.append(
        Case(
            "over-limit count",
            "pareto --points 1e9",
            ("pareto", "SPEC", "--points", "1000000000", "-q"),
            spec(grid=False),
        )
    )
    out.append(
        Case(
            "over-limit count",
            "pareto --max-points 0",
            ("pareto", "SPEC", "--max-points", "0", "-q"),
            spec(),
        )
    )
    out.append(
        Case(
            "over-limit count",
            "pareto --max-points -1",
            ("pareto", "SPEC", "--max-points", "-1", "-q"),
            spec(),
        )
    )
    # slow specs
    out.append(
        Case(
            "holes",
            "wheel, 68.9 mm axle hole",
            design,
            WHEEL.replace('diameter = "6 mm"', 'diameter = "68.9 mm"'),
        )
    )
    for count in (25, 100, 1000):
        holes = spec(layout=_holes(count)).replace(
            'min = "40 mm", max = "90 mm"', 'min = "70 mm", max = "90 mm"'
        )
        out.append(Case("holes", f"{count} holes of 2 mm", design, holes))
    for count in (2000, 10_000):
        out.append(
            Case(
                "vertices",
                f"polygon of {count} vertices",
                design,
                spec(
                    layout=_polygon(count),
                    constraints='flexural_rigidity = [{ min = "20 mN*m^2", eta = "0 deg" }]',
                ),
            )
        )
    out.append(
        Case("many bounds", "10 000 stiffness bounds", design, spec(constraints=_bounds(10_000)))
    )
    out.append(
        Case(
            "many bounds",
            "36 off-axis bounds, maximize",
            design,
            spec(
                constraints=_MAXIMIZE_36,
                extra='[objective]\nmaximize = "flexural_rigidity"',
                grid=False,
            ),
        )
    )
    out.append(
        Case(
            "many candidates",
            "10 000 thickness candidates",
            design,
            spec(material=_thicknesses(10_000)),
        )
    )
    huge = (
        'side = { min = "1 mm", max = "100000 mm" }\n'
        'flexural_rigidity = [{ min = "1e12 mN*m^2", eta = "0 deg" }]'
    )
    full = (
        spec(constraints=huge, wmin="0.01 mm", amin="0.001 deg", grid=False)
        .replace("max = 60", "max = 5000")
        .replace('max = "20 mm"', 'max = "10000 mm"')
        .replace('sheet_max = "300 mm"', 'sheet_max = "100000 mm"')
    )
    out.append(Case("continuous full range", "full ranges, huge bound", design, full))
    # 5. output folders (after the fix only)
    for target in ("/", ".", "", "..", "/proc", "/etc", "/usr/lib"):
        out.append(
            Case(
                "output folder",
                f"design --out {target!r}",
                ("design", "SPEC", "--out", target, "-q"),
                spec(),
                folder=True,
            )
        )
    return out


@dataclass(frozen=True)
class Row:
    case: Case
    code: str
    lines: int
    cpu_s: float
    rss_mb: float
    warning: bool
    first_line: str

    @property
    def verdict(self) -> str:
        ok_code = (self.code == "2" and self.lines == 1) or self.code in ("0", "1", "4")
        ok = ok_code and self.rss_mb < PASS_RSS_MB and not self.warning
        return "ok" if ok else "FAIL"


def _limit(memory: int) -> Callable[[], None]:
    def apply() -> None:
        resource.setrlimit(resource.RLIMIT_AS, (memory, memory))
        os.setpgrp()

    return apply


def run(case: Case, exe: str, timeout: float, memory: int) -> Row:
    with tempfile.TemporaryDirectory() as tmp:
        args = list(case.args)
        if case.spec is not None:
            path = Path(tmp) / "spec.toml"
            path.write_text(case.spec)
            args = [str(path) if a == "SPEC" else a for a in args]
        err = Path(tmp) / "stderr"
        with err.open("wb") as fh:
            proc = subprocess.Popen(
                [exe, *args],
                cwd=tmp,
                stdout=subprocess.DEVNULL,
                stderr=fh,
                stdin=subprocess.DEVNULL,
                preexec_fn=_limit(memory),
                env={**os.environ, "COLUMNS": "200"},
            )
            start = time.monotonic()
            status = None
            while True:
                pid, st, usage = os.wait4(proc.pid, os.WNOHANG)
                if pid:
                    status = st
                    break
                if time.monotonic() - start > timeout:
                    os.killpg(proc.pid, signal.SIGKILL)
                    pid, st, usage = os.wait4(proc.pid, 0)
                    break
                time.sleep(0.05)
            proc.returncode = 0  # reaped by wait4
        text = err.read_text(errors="replace")
    if status is None:
        code = "T"
    elif os.WIFSIGNALED(status):
        code = f"M{os.WTERMSIG(status)}"
    else:
        code = str(os.WEXITSTATUS(status))
    lines = [ln for ln in text.splitlines() if ln.strip()]
    warning = "Warning" in text or "Traceback" in text
    return Row(
        case,
        code,
        len(lines),
        usage.ru_utime + usage.ru_stime,
        usage.ru_maxrss / 1024,
        warning,
        (lines[0] if lines else "")[:110],
    )


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--corrugate", required=True, help="the corrugate executable to test")
    parser.add_argument("--timeout", type=float, default=60.0)
    parser.add_argument("--memory", type=float, default=3.0, help="address-space limit (GB)")
    parser.add_argument("--skip-folders", action="store_true")
    parser.add_argument("--only", default="", help="run the classes whose name contains this")
    opts = parser.parse_args()
    memory = int(opts.memory * 2**30)
    exe = str(Path(opts.corrugate).absolute())
    print(f"# {opts.corrugate}; time limit {opts.timeout:g} s, address space {opts.memory:g} GB")
    print(
        "| class | case | exit | stderr lines | CPU s | peak MB | warning | verdict | first stderr line |"
    )
    print("|---|---|---|---|---|---|---|---|---|")
    for case in cases():
        if opts.skip_folders and case.folder:
            continue
        if opts.only and opts.only not in case.klass:
            continue
        row = run(case, exe, opts.timeout, memory)
        print(
            f"| {case.klass} | {case.name} | {row.code} | {row.lines} | {row.cpu_s:.2f} | "
            f"{row.rss_mb:.0f} | {'yes' if row.warning else 'no'} | {row.verdict} | "
            f"{row.first_line.replace('|', '/')} |",
            flush=True,
        )
    sys.exit(0)


if __name__ == "__main__":
    main()
