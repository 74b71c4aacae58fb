"""Start-up: what a process imports before it needs it (issue 13). Speed itself is measured by
benchmarks/pipeline.py, not here; these tests pin the imports that made it slow."""

from __future__ import annotations

import subprocess
import sys
from pathlib import Path

import pytest

import corrugate

ROOT = Path(__file__).resolve().parents[2]


def _run(script: str, *args: str) -> subprocess.CompletedProcess[str]:
    return subprocess.run(
        [sys.executable, "-c", script, *args], capture_output=True, text=True, cwd=ROOT
    )


def _command_without(argv: list[str], modules: tuple[str, ...]) -> subprocess.CompletedProcess[str]:
    """Run ``corrugate ARGV`` in-process in a fresh interpreter (its exit 0) and assert there that
    none of ``modules`` was imported."""
    return _run(
        "import sys\n"
        "from corrugate.cli import main\n"
        "try:\n"
        f"    main({argv!r})\n"
        "except SystemExit as exc:\n"
        "    assert exc.code in (0, None), exc.code\n"
        f"heavy = [m for m in {modules!r} if m in sys.modules]\n"
        "assert not heavy, heavy\n"
    )


def test_import_corrugate_loads_nothing_heavy() -> None:
    done = _run(
        "import sys, corrugate\n"
        "heavy = [m for m in ('numpy', 'pint', 'pydantic', 'matplotlib') if m in sys.modules]\n"
        "assert not heavy, heavy\n"
    )
    assert done.returncode == 0, done.stderr


def test_every_public_name_resolves_to_its_module() -> None:
    import importlib

    for name in corrugate.__all__:
        value = getattr(corrugate, name)
        if name == "__version__":
            continue
        module = importlib.import_module(f"corrugate.{corrugate._WHERE[name]}")
        assert value is getattr(module, name), name
    public = set(corrugate.__all__) - {"__version__"}
    assert public == set(corrugate._WHERE)
    # dir(corrugate) is the public API, without the names the module uses itself
    assert dir(corrugate) == sorted(corrugate.__all__)
    # no public name is a subpackage's too (the import system would bind the subpackage over it)
    packages = {p.name for p in Path(corrugate.__file__).parent.iterdir() if p.is_dir()}
    assert not public & packages, public & packages
    namespace: dict[str, object] = {}
    exec("from corrugate import *", namespace)
    assert set(corrugate.__all__) <= set(namespace)


@pytest.mark.slow
def test_design_files_need_no_mesh_library_pyplot_or_pint(tmp_path: Path) -> None:
    """Every file of a design is written without trimesh, scipy, pyplot, pint or dask, and the
    meshes still read back (here with the test's own parser: the STL triangle count)."""
    done = _run(
        "import sys\n"
        "from pathlib import Path\n"
        "from corrugate import Assembly, Layer, analyze, get_material\n"
        "from corrugate.workflow import write_design_files\n"
        "a = Assembly.identical(Layer(8, 8, 84, get_material('dura-lar')))\n"
        "write_design_files(analyze(a), Path(sys.argv[1]))\n"
        "bad = [m for m in ('trimesh', 'scipy', 'matplotlib.pyplot', 'pint', 'dask')\n"
        "       if m in sys.modules]\n"
        "assert not bad, bad\n",
        str(tmp_path),
    )
    assert done.returncode == 0, done.stderr
    stl = (tmp_path / "assembly.stl").read_bytes()
    count = int.from_bytes(stl[80:84], "little")
    assert count > 0 and len(stl) == 84 + 50 * count
    assert (tmp_path / "assembly.glb").read_bytes()[:4] == b"glTF"


def test_help_loads_neither_numpy_nor_rich_nor_pydantic() -> None:
    """``corrugate --help`` (piped, so click's plain help) needs none of the heavy libraries: they
    cost most of its CPU before (0.64 s against 0.15 s after, benchmarks/pipeline.py)."""
    done = _command_without(["--help"], ("numpy", "rich", "pydantic", "pint"))
    assert done.returncode == 0, done.stderr
    assert "Usage: " in done.stdout and "analyze" in done.stdout


def test_analyze_needs_no_pydantic_pint_or_scipy() -> None:
    """``corrugate analyze`` with plain numbers builds no spec, units or solver machinery."""
    done = _command_without(
        ["analyze", "--W", "8", "--n", "8", "--alpha", "84", "--material", "dura-lar"],
        ("pydantic", "pint", "scipy", "matplotlib"),
    )
    assert done.returncode == 0, done.stderr
    assert "504.5" in done.stdout  # K at eta 0 of the case study, docs/validation/off_axis.md


def test_design_without_out_loads_no_writer_matplotlib_or_ezdxf() -> None:
    """``corrugate design SPEC`` (no ``--out``) prints the answer without importing what only the
    files need: matplotlib, ezdxf, PIL, the stroke font, the package's writers, the sheet planner
    (the machine's profile comes from ``core.cutters``) and the cut plan, nor what no answer
    needs: the FE, pint, scipy and dask (issue 39; its CPU is measured by benchmarks/pipeline.py).
    The answer is there: the case study's optimum, n 9 (the example's header: W 8, n 9, alpha 78,
    2.16 g)."""
    done = _command_without(
        ["design", "examples/blimp_gripper.toml"],
        (
            "matplotlib",
            "ezdxf",
            "PIL",
            "HersheyFonts",
            "corrugate.export.cutfile",
            "corrugate.export.pdf",
            "corrugate.export.plan",
            "corrugate.export.writers",
            "corrugate.fabrication.sheets",
            "corrugate.report",
            "corrugate.fea",
            "pint",
            "scipy",
            "dask",
        ),
    )
    assert done.returncode == 0, done.stderr
    assert "blimp-gripper" in done.stdout and "2.16" in done.stdout


def test_python_m_corrugate_sets_the_collector_thresholds_before_importing() -> None:
    """``python -m corrugate`` applies the command's collector thresholds
    (:data:`corrugate.cli.GC_THRESHOLDS`) before it imports typer, numpy or the package's
    command line (a spy on the import system records the thresholds when typer is looked up)."""
    done = _run(
        "import gc, runpy, sys\n"
        "class Spy:\n"
        "    def find_spec(self, name, path=None, target=None):\n"
        "        if name == 'typer':\n"
        "            print('at typer', gc.get_threshold())\n"
        "        return None\n"
        "sys.meta_path.insert(0, Spy())\n"
        "sys.argv = ['corrugate', '--version']\n"
        "try:\n"
        "    runpy.run_module('corrugate', run_name='__main__', alter_sys=True)\n"
        "except SystemExit:\n"
        "    pass\n"
        "from corrugate.cli import GC_THRESHOLDS\n"
        "print('wanted', GC_THRESHOLDS)\n"
    )
    assert done.returncode == 0, done.stderr
    lines = done.stdout.splitlines()
    at = next(x for x in lines if x.startswith("at typer"))
    wanted = next(x for x in lines if x.startswith("wanted"))
    assert at.removeprefix("at typer") == wanted.removeprefix("wanted")
    assert at != f"at typer {(700, 10, 10)}"  # Python's default is not what it found


def test_model_names_match_the_moduli_table() -> None:
    from corrugate.mechanics.moduli import MODELS
    from corrugate.names import DEFAULT_MODEL, MODEL_NAMES

    assert tuple(MODELS) == MODEL_NAMES and DEFAULT_MODEL in MODELS


def test_the_command_line_freezes_the_collector_at_exit_only() -> None:
    """main() freezes nothing while the process works (here: two commands in one process), and
    at exit moves the tracked objects to the permanent generation (so the interpreter's
    finalization does not collect over them; benchmarks/pipeline.py, issue 24)."""
    done = _run(
        "import atexit, gc, sys\n"
        "atexit.register(lambda: print('frozen at exit', gc.get_freeze_count() > 1000))\n"
        "from corrugate.cli import main\n"
        "for _ in range(2):\n"
        "    try:\n"
        "        main(['--version'])\n"
        "    except SystemExit:\n"
        "        pass\n"
        "print('frozen while running', gc.get_freeze_count())\n"
    )
    assert done.returncode == 0, done.stderr
    lines = done.stdout.splitlines()
    assert sum(x.startswith("corrugate ") for x in lines) == 2  # both commands ran
    assert "frozen while running 0" in lines
    assert lines[-1] == "frozen at exit True"


@pytest.mark.slow
def test_design_out_of_the_case_study_runs_no_collection(tmp_path: Path) -> None:
    """``python -m corrugate design SPEC --out DIR`` of the case study (every file of the set)
    never runs the cyclic collector while its thresholds are :data:`corrugate.cli.GC_THRESHOLDS`
    (at issue 24's 100 000 it ran twice, 0.06 s of CPU; issue 39): counted by
    :data:`gc.callbacks` (those before, while runpy imports at Python's default, are not the
    command's), and the folder holds the set."""
    done = _run(
        "import gc, runpy, sys\n"
        "from corrugate.cli import GC_THRESHOLDS\n"
        "runs = []\n"
        "def count(phase, info):\n"
        "    if phase == 'start' and gc.get_threshold() == GC_THRESHOLDS:\n"
        "        runs.append(info['generation'])\n"
        "gc.callbacks.append(count)\n"
        "sys.argv = ['corrugate', 'design', 'examples/blimp_gripper.toml', '--out', sys.argv[1],"
        " '-q']\n"
        "try:\n"
        "    runpy.run_module('corrugate', run_name='__main__', alter_sys=True)\n"
        "except SystemExit as exc:\n"
        "    assert exc.code in (0, None), exc.code\n"
        "print('collections', runs)\n",
        str(tmp_path / "out"),
    )
    assert done.returncode == 0, done.stderr
    assert done.stdout.splitlines()[-1] == "collections []"
    assert (tmp_path / "out" / "report.html").is_file()
    assert (tmp_path / "out" / "cut-1.dxf").is_file()
