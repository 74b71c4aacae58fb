"""Run CalculiX (``ccx``) on an input deck and read its printed output.

CalculiX is the finite-element solver of the ``fea`` subpackage (Debian package ``calculix-ccx``,
command ``ccx``; version 2.20 was used to write and test this code). This module only finds the
executable, runs it on a deck in a work folder with a time-out and parses the ``.dat`` file that
``*NODE PRINT`` writes, and the nodal stresses that ``*EL FILE`` / ``S`` writes to the ``.frd``
file (:func:`parse_frd_stresses`); the models are built in :mod:`corrugate.fea.unitcell` and
:mod:`corrugate.fea.assembly`.

The executable is looked up in the environment variable ``CORRUGATE_CCX`` first, then as ``ccx``
on ``PATH``. Errors are :class:`SolverNotFoundError` (no executable) and :class:`SolverError`
(non-zero exit, ``*ERROR`` in the log, time-out, or missing output).
"""

from __future__ import annotations

import ctypes
import os
import re
import shutil
import signal
import subprocess
import sys
import tempfile
from collections.abc import Iterator
from contextlib import contextmanager
from dataclasses import dataclass
from pathlib import Path

import numpy as np
from numpy.typing import NDArray

from corrugate.core.errors import CorrugateError

__all__ = [
    "CCX_ENV",
    "CcxRun",
    "DatBlock",
    "FrdStresses",
    "SolverError",
    "SolverNotFoundError",
    "find_ccx",
    "parse_buckling",
    "parse_dat",
    "parse_frd_stresses",
    "run_ccx",
    "work_dir",
]

#: Environment variable naming the ccx executable (overrides PATH look-up).
CCX_ENV = "CORRUGATE_CCX"

_INSTALL_HINT = (
    "install CalculiX (Debian/Ubuntu: `apt-get install calculix-ccx`, or `make system-deps` as "
    f"root) or set {CCX_ENV} to the ccx executable"
)


class SolverNotFoundError(CorrugateError, RuntimeError):
    """The CalculiX executable ``ccx`` cannot be found."""


class SolverError(CorrugateError, RuntimeError):
    """CalculiX ran but failed: non-zero exit, an ``*ERROR`` message, a time-out or no output."""


def find_ccx() -> str:
    """Absolute path of the ccx executable; :class:`SolverNotFoundError` if there is none."""
    env = os.environ.get(CCX_ENV)
    if env:
        path = shutil.which(env)
        if path is None:
            raise SolverNotFoundError(f"{CCX_ENV} = {env!r} is not an executable; {_INSTALL_HINT}")
        return path
    path = shutil.which("ccx")
    if path is None:
        raise SolverNotFoundError(f"CalculiX (ccx) is not on PATH; {_INSTALL_HINT}")
    return path


@dataclass(frozen=True, slots=True)
class DatBlock:
    """One table of a ccx ``.dat`` file: a quantity for a node set at one (cumulative) time.

    ``quantity`` is the header word (``displacements``, ``forces``, ...); ``rows`` maps a node
    number to its values (for displacements and forces: x, y, z components in mm and N).
    """

    quantity: str
    nset: str
    time: float
    rows: dict[int, tuple[float, ...]]

    def total(self) -> tuple[float, ...]:
        """Component-wise sum over the nodes (for forces: the resultant, N)."""
        sums = [0.0, 0.0, 0.0]
        for values in self.rows.values():
            for i, v in enumerate(values[:3]):
                sums[i] += v
        return tuple(sums)


_HEADER = re.compile(r"^\s*(\w[\w ]*?)\s+\(([^)]*)\)\s+for set\s+(\S+)\s+and time\s+(\S+)")


def parse_dat(text: str) -> list[DatBlock]:
    """The node tables of a ccx ``.dat`` file, in file order (one per ``*NODE PRINT`` and step)."""
    blocks: list[DatBlock] = []
    current: DatBlock | None = None
    for line in text.splitlines():
        m = _HEADER.match(line)
        if m:
            current = DatBlock(m.group(1).strip(), m.group(3).upper(), float(m.group(4)), {})
            blocks.append(current)
            continue
        if current is None:
            continue
        parts = line.split()
        if not parts:
            continue
        try:
            node = int(parts[0])
            values = tuple(float(p) for p in parts[1:])
        except ValueError:
            current = None
            continue
        current.rows[node] = values
    return blocks


_BUCKLING = re.compile(r"B U C K L I N G\s+F A C T O R\s+O U T P U T")


def parse_buckling(text: str) -> list[float]:
    """The buckling factors of a ccx ``.dat`` file (``*BUCKLE`` step), mode 1 first."""
    factors: list[float] = []
    for part in _BUCKLING.split(text)[1:]:
        for line in part.splitlines():
            cells = line.split()
            if len(cells) != 2:
                if factors and cells:
                    break
                continue
            try:
                mode, value = int(cells[0]), float(cells[1])
            except ValueError:
                continue
            if mode == len(factors) + 1:
                factors.append(value)
    return factors


@dataclass(frozen=True, slots=True)
class FrdStresses:
    """The nodal stresses of a ccx ``.frd`` file (``*EL FILE`` with ``S``: stresses extrapolated
    from the integration points to the nodes and averaged over the elements sharing a node).

    Shell elements appear as ccx expands them: 20-node bricks whose nodes lie on the shell's two
    surfaces and its mid-surface (new node numbers; at a crease each facet has its own), so the
    surface stresses are among these nodes. ``ids`` are the node numbers, ``xyz`` their
    coordinates (mm), ``stress`` the components SXX, SYY, SZZ, SXY, SYZ, SZX (MPa, global axes)
    of the last stress block, ``material`` the material number (1-based, in the deck's order of
    ``*MATERIAL``) of the first element that uses each node (0: none)."""

    ids: NDArray[np.int64]
    xyz: NDArray[np.float64]
    stress: NDArray[np.float64]
    material: NDArray[np.int64]

    def principal(self) -> NDArray[np.float64]:
        """Principal stresses (MPa) of every node, ascending: shape (nodes, 3)."""
        s = self.stress
        tensor = np.empty((len(s), 3, 3))
        tensor[:, 0, 0], tensor[:, 1, 1], tensor[:, 2, 2] = s[:, 0], s[:, 1], s[:, 2]
        tensor[:, 0, 1] = tensor[:, 1, 0] = s[:, 3]
        tensor[:, 1, 2] = tensor[:, 2, 1] = s[:, 4]
        tensor[:, 2, 0] = tensor[:, 0, 2] = s[:, 5]
        return np.asarray(np.linalg.eigvalsh(tensor), dtype=np.float64)

    def von_mises(self) -> NDArray[np.float64]:
        """Von Mises equivalent stress (MPa) of every node."""
        xx, yy, zz, xy, yz, zx = self.stress.T
        return np.asarray(
            np.sqrt(
                0.5 * ((xx - yy) ** 2 + (yy - zz) ** 2 + (zz - xx) ** 2)
                + 3.0 * (xy * xy + yz * yz + zx * zx)
            )
        )


def _frd_floats(line: str, count: int) -> list[float]:
    """``count`` 12-character numbers after the node number of a ``-1`` result or node line
    (the fields may touch: "-1.2E-01-3.4E-02")."""
    return [float(line[13 + 12 * k : 25 + 12 * k]) for k in range(count)]


def parse_frd_stresses(text: str) -> FrdStresses:
    """The node coordinates, element materials and last ``STRESS`` block of an ASCII ``.frd``
    file; :class:`SolverError` if it has no stress block."""
    coords: dict[int, tuple[float, ...]] = {}
    material: dict[int, int] = {}
    stresses: dict[int, tuple[float, ...]] = {}
    mode = ""
    current_mat = 0
    found = False
    for line in text.splitlines():
        head = line[:6]
        if head == "    2C":
            mode = "nodes"
            continue
        if head == "    3C":
            mode = "elements"
            continue
        if line.startswith(" -4"):
            if line.split()[1] == "STRESS":
                mode, found = "stress", True
                stresses = {}
            else:
                mode = "other"
            continue
        if line.startswith(" -3"):
            mode = ""
            continue
        if mode == "nodes" and line.startswith(" -1"):
            coords[int(line[3:13])] = tuple(_frd_floats(line, 3))
        elif mode == "elements":
            if line.startswith(" -1"):
                current_mat = int(line.split()[4])
            elif line.startswith(" -2"):
                for node in line.split()[1:]:
                    material.setdefault(int(node), current_mat)
        elif mode == "stress" and line.startswith(" -1"):
            stresses[int(line[3:13])] = tuple(_frd_floats(line, 6))
    if not found:
        raise SolverError("the .frd file holds no STRESS block (no *EL FILE with S?)")
    ids = np.array(sorted(stresses), dtype=np.int64)
    return FrdStresses(
        ids,
        np.array([coords[i] for i in ids], dtype=np.float64).reshape(-1, 3),
        np.array([stresses[i] for i in ids], dtype=np.float64).reshape(-1, 6),
        np.array([material.get(int(i), 0) for i in ids], dtype=np.int64),
    )


@dataclass(frozen=True, slots=True)
class CcxRun:
    """The outcome of one ccx run: the parsed ``.dat`` tables, the buckling factors of a
    ``*BUCKLE`` step (mode 1 first; empty otherwise) and the work folder used."""

    blocks: tuple[DatBlock, ...]
    work_dir: Path
    log: str
    buckling_factors: tuple[float, ...] = ()

    def find(self, quantity: str, nset: str) -> list[DatBlock]:
        """All tables of ``quantity`` (e.g. ``"forces"``) for node set ``nset``, in step order."""
        q, s = quantity.lower(), nset.upper()
        return [b for b in self.blocks if b.quantity.lower() == q and b.nset == s]

    def last(self, quantity: str) -> DatBlock:
        """The table of ``quantity`` (its name's start, e.g. ``"displacements"``) at the latest
        time of the run: the end of a ramp."""
        return max(
            (b for b in self.blocks if b.quantity.startswith(quantity)), key=lambda b: b.time
        )


def _die_with_parent() -> None:
    """In the ccx child (Linux): get SIGKILL when the process that started it dies, so that a
    killed sweep worker leaves no solver running on."""
    try:
        libc = ctypes.CDLL(None)
        libc.prctl(1, signal.SIGKILL, 0, 0, 0)  # PR_SET_PDEATHSIG
    except (OSError, AttributeError):
        pass


@contextmanager
def work_dir(parent: Path | None = None, keep: bool = False) -> Iterator[Path]:
    """A fresh folder for one solver run in ``parent`` (None: the system temporary folder),
    removed afterwards unless ``keep``. Its name records this process's pid
    (``corrugate-ccx-PID-...``, :mod:`corrugate.fea.workdirs`), so that a folder left by a
    process killed during the run is swept later; a folder to keep has no pid in its name
    (``corrugate-ccx-...``) and is never swept."""
    from corrugate.fea.workdirs import PREFIX, owned_prefix

    if parent is not None:
        parent.mkdir(parents=True, exist_ok=True)
    prefix = PREFIX if keep else owned_prefix()
    path = Path(tempfile.mkdtemp(prefix=prefix, dir=parent))
    try:
        yield path
    finally:
        if not keep:
            shutil.rmtree(path, ignore_errors=True)


def run_ccx(
    deck: str,
    folder: Path,
    *,
    job: str = "job",
    timeout: float = 600.0,
    threads: int = 1,
) -> CcxRun:
    """Write ``deck`` to ``folder/job.inp``, run ccx there and parse ``job.dat``.

    ``timeout`` in seconds; ``threads`` sets ``OMP_NUM_THREADS`` (1 by default, so that parallel
    sweeps do not oversubscribe the cores). Raises :class:`SolverNotFoundError` or
    :class:`SolverError`.
    """
    exe = find_ccx()
    folder.mkdir(parents=True, exist_ok=True)
    (folder / f"{job}.inp").write_text(deck)
    env = dict(os.environ, OMP_NUM_THREADS=str(threads), CCX_NPROC_EQUATION_SOLVER=str(threads))
    try:
        proc = subprocess.run(
            [exe, "-i", job],
            cwd=folder,
            env=env,
            capture_output=True,
            text=True,
            timeout=timeout,
            check=False,
            preexec_fn=_die_with_parent if sys.platform == "linux" else None,
        )
    except subprocess.TimeoutExpired:
        raise SolverError(f"ccx timed out after {timeout:g} s in {folder}") from None
    log = proc.stdout + proc.stderr
    (folder / f"{job}.log").write_text(log)
    errors = [ln.strip() for ln in log.splitlines() if "*ERROR" in ln]
    if proc.returncode != 0 or errors:
        first = errors[0] if errors else f"exit code {proc.returncode}"
        raise SolverError(f"ccx failed in {folder}: {first}")
    dat = folder / f"{job}.dat"
    if not dat.exists():
        raise SolverError(f"ccx wrote no {dat.name} in {folder}")
    text = dat.read_text()
    return CcxRun(tuple(parse_dat(text)), folder, log, tuple(parse_buckling(text)))
