"""Chunked sweeps over a grid of designs: bounded memory, in process or on a dask cluster.

:func:`sweep` evaluates every design of a grid W x n x alpha of identical layers (one sheet, one
layout) with :func:`corrugate.analysis.evaluate.evaluate`, one block of about ``chunk`` designs at a time,
and returns reductions over the grid (the best design under bounds, the range of each quantity,
how many designs meet the bounds) and, on request, every design's values. Memory is that of a few
blocks (plus the per-design arrays when ``keep=True``), whatever the size of the grid, so 10^8
designs fit in well under a gigabyte.

Each block is the sub-grid ``W[i:j] x n[k:l] x alpha[u:v]`` passed to ``evaluate`` as broadcasting
arrays of shapes (j - i, 1, 1), (1, l - k, 1) and (1, 1, v - u): the trigonometry runs once per
alpha value, the moduli once per (W, alpha) pair, and only what depends on n runs once per design
(the spring sums of docs/theory.md 3.2, the assembly of 3.3 and the mass of section 4). A block is small
enough to stay in the processor's cache.

Quantities (``fields``; units mm, g, N/mm, N mm, N mm^2):

* ``Lx``: folded side (n + 1) W sin(alpha/2) (both layers, square and circle: L);
* ``thickness``: folded thickness t_d = 2 W cos(alpha/2);
* ``flat``: flat blank (n + 1) W;
* ``mass``: both layers and the connector band (:mod:`corrugate.mechanics.mass`);
* ``K``, ``D``, ``EI``: in-plane stiffness, bending stiffness and flexural rigidity at ``eta_deg``
  under ``support`` (:mod:`corrugate.mechanics.offaxis`).

With ``scheduler`` (a ``distributed.Client`` or a scheduler address such as
``tcp://host:8786``) the grid is cut into tasks of whole W rows, each task runs the same chunked
loop on a worker, and the partial results are combined exactly as in process: the results are
identical (ties in the objective go to the lowest flat index in both cases). Needs the ``dist``
extra (``pip install corrugate[dist]``).
"""

from __future__ import annotations

import itertools
import math
from collections.abc import Iterator, Mapping, Sequence
from dataclasses import dataclass, field
from typing import Any

import numpy as np
from numpy.typing import ArrayLike, NDArray

from corrugate.analysis.evaluate import LayerArrays, evaluate
from corrugate.core.errors import InputError
from corrugate.geometry.fabrication_options import DEFAULT_FABRICATION, FabricationOptions
from corrugate.geometry.layouts import Layout, Square
from corrugate.materials.library import Material
from corrugate.mechanics.behaviours import check_support
from corrugate.mechanics.moduli import DEFAULT_MODEL, get_model
from corrugate.names import DEFAULT_SUPPORT

__all__ = ["FIELDS", "SweepResult", "sweep"]

FloatArray = NDArray[np.float64]
#: Quantities a sweep can report and bound (see the module docstring).
FIELDS = ("Lx", "thickness", "flat", "mass", "K", "D", "EI")
#: Designs per block: 16000 keeps each working array (125 KiB) in cache and below glibc's mmap
#: threshold (128 KiB), so blocks reuse heap memory instead of faulting in fresh pages (dask
#: workers, which trim the heap at 64 KiB, slow down 3x with larger blocks).
DEFAULT_CHUNK = 16_000

Bounds = Mapping[str, tuple[float | None, float | None]]


@dataclass(frozen=True)
class _Setup:
    """Everything a worker needs to evaluate blocks (picklable)."""

    W: FloatArray
    n: NDArray[np.int64]
    alpha: FloatArray
    E: float
    nu: float
    t: float
    density: float
    layout: Layout
    model: str
    eta: float
    support: str
    fabrication: FabricationOptions
    fields: tuple[str, ...]
    bounds: tuple[tuple[str, float | None, float | None], ...]
    objective: str
    chunk: int

    @property
    def shape(self) -> tuple[int, int, int]:
        return (len(self.W), len(self.n), len(self.alpha))


@dataclass
class _Partial:
    """Reductions over part of the grid; :meth:`merge` combines two exactly."""

    count: int = 0
    feasible: int = 0
    best_value: float = math.inf
    best_flat: int = -1  # flat (C order) index of the best design, -1 if none
    minimum: dict[str, float] = field(default_factory=dict)
    maximum: dict[str, float] = field(default_factory=dict)
    blocks: list[tuple[tuple[slice, slice, slice], dict[str, FloatArray]]] = field(
        default_factory=list
    )

    def offer(self, value: float, index: int) -> None:
        """Keep (value, index) if it is a design and beats the best so far (lowest value, then
        lowest index: the same answer whatever the order of the blocks)."""
        if index >= 0 and (
            self.best_flat < 0 or (value, index) < (self.best_value, self.best_flat)
        ):
            self.best_value, self.best_flat = value, index

    def merge(self, other: _Partial) -> _Partial:
        self.count += other.count
        self.feasible += other.feasible
        self.offer(other.best_value, other.best_flat)
        for k, v in other.minimum.items():
            self.minimum[k] = min(self.minimum.get(k, math.inf), v)
        for k, v in other.maximum.items():
            self.maximum[k] = max(self.maximum.get(k, -math.inf), v)
        self.blocks.extend(other.blocks)
        return self


@dataclass(frozen=True)
class SweepResult:
    """Outcome of :func:`sweep` over the grid W x n x alpha (shape ``shape``).

    ``count`` designs evaluated, ``feasible`` of them within every bound; ``best`` the feasible
    design with the lowest ``objective`` (its W mm, n, alpha deg and every field; ties go to the
    lowest index), ``best_index`` its (i_W, i_n, i_alpha); ``minimum`` / ``maximum`` of each
    field over the feasible designs (NaN if none); ``values`` every design's fields as arrays of
    shape ``shape`` when the sweep was asked to ``keep`` them, else None."""

    shape: tuple[int, int, int]
    count: int
    feasible: int
    objective: str
    best_index: tuple[int, int, int] | None
    best: dict[str, float] | None
    minimum: dict[str, float]
    maximum: dict[str, float]
    values: dict[str, FloatArray] | None


def _blocks(setup: _Setup, w_range: tuple[int, int]) -> Iterator[tuple[slice, slice, slice]]:
    """Sub-grids of about ``chunk`` designs covering W[w_range] x n x alpha."""
    _, nn, na = setup.shape
    ka = max(1, min(na, setup.chunk))
    kn = max(1, min(nn, setup.chunk // ka))
    kW = max(1, setup.chunk // (ka * kn))
    for i in range(w_range[0], w_range[1], kW):
        for j in range(0, nn, kn):
            for k in range(0, na, ka):
                yield (
                    slice(i, min(i + kW, w_range[1])),
                    slice(j, min(j + kn, nn)),
                    slice(k, min(k + ka, na)),
                )


def _fields(setup: _Setup, W: FloatArray, n: NDArray[np.int64], a: FloatArray) -> dict[str, Any]:
    """The quantities of one block (arrays that broadcast to its shape)."""
    layer = LayerArrays(setup.E, setup.nu, setup.t, W, n, a, setup.density)
    ev = evaluate(
        layer, layer, setup.layout, setup.model, setup.eta, setup.fabrication, setup.support
    )
    return {
        "Lx": ev.Lx,
        "thickness": ev.thickness,
        "flat": layer.profile().flat_width(n.astype(np.float64)),
        "mass": ev.mass,
        "K": ev.K,
        "D": ev.D,
        "EI": ev.EI,
    }


def _run(setup: _Setup, w_range: tuple[int, int], keep: bool) -> _Partial:
    """Evaluate and reduce the designs with W index in ``w_range``, block by block."""
    out = _Partial()
    _, nn, na = setup.shape
    for bw, bn, ba in _blocks(setup, w_range):
        W = setup.W[bw, None, None]
        n = setup.n[None, bn, None]
        a = setup.alpha[None, None, ba]
        shape = (W.shape[0], n.shape[1], a.shape[2])
        vals = _fields(setup, W, n, a)
        ok: NDArray[np.bool_] | None = None
        for name, lo, hi in setup.bounds:
            v = vals[name]
            if lo is not None:
                ok = v >= lo if ok is None else ok & (v >= lo)
            if hi is not None:
                ok = v <= hi if ok is None else ok & (v <= hi)
        size = shape[0] * shape[1] * shape[2]
        out.count += size
        obj = np.broadcast_to(vals[setup.objective], shape)
        if ok is None:
            n_ok = size
            masked = obj
        else:
            ok = np.broadcast_to(ok, shape)
            n_ok = int(np.count_nonzero(ok))
            masked = np.where(ok, obj, np.inf)
        out.feasible += n_ok
        if n_ok:
            flat = int(np.argmin(masked))  # first (lowest index) of the minima in the block
            value = float(masked.reshape(-1)[flat])
            i, j, k = np.unravel_index(flat, shape)
            index = ((bw.start + i) * nn + bn.start + j) * na + ba.start + k
            out.offer(value, int(index))
            for name in setup.fields:
                v = np.broadcast_to(vals[name], shape)
                if ok is None:
                    lo, hi = float(v.min()), float(v.max())
                else:
                    lo = float(np.min(v, where=ok, initial=math.inf))
                    hi = float(np.max(v, where=ok, initial=-math.inf))
                out.minimum[name] = min(out.minimum.get(name, math.inf), lo)
                out.maximum[name] = max(out.maximum.get(name, -math.inf), hi)
        if keep:
            out.blocks.append(
                (
                    (bw, bn, ba),
                    {k: np.array(np.broadcast_to(vals[k], shape)) for k in setup.fields},
                )
            )
    return out


def _client(scheduler: Any) -> tuple[Any, bool]:
    """A ``distributed.Client`` for ``scheduler`` (a Client, or an address); whether we own it."""
    if hasattr(scheduler, "submit") and hasattr(scheduler, "gather"):
        return scheduler, False
    try:
        from distributed import Client
    except ImportError as exc:  # pragma: no cover - depends on the extra
        raise InputError(
            "scheduler",
            scheduler,
            "an installed dask.distributed (pip install corrugate[dist])",
            reason="needs the dist extra",
        ) from exc
    return Client(scheduler), True  # type: ignore[no-untyped-call]


def sweep(
    W: ArrayLike,
    n: ArrayLike,
    alpha_deg: ArrayLike,
    material: Material,
    t: float,
    *,
    layout: Layout | None = None,
    model: str = DEFAULT_MODEL,
    eta_deg: float = 0.0,
    support: str = DEFAULT_SUPPORT,
    fabrication: FabricationOptions = DEFAULT_FABRICATION,
    bounds: Bounds | None = None,
    objective: str = "mass",
    fields: Sequence[str] = FIELDS,
    keep: bool = False,
    chunk: int = DEFAULT_CHUNK,
    scheduler: Any = None,
    tasks: int | None = None,
) -> SweepResult:
    """Evaluate every design of the grid ``W`` (mm) x ``n`` (creases) x ``alpha_deg`` (deg) of
    identical layers of ``material`` at thickness ``t`` (mm), block by block.

    ``bounds`` maps a field (:data:`FIELDS`) to (lower, upper) bounds (either None); a design is
    feasible when it meets all of them. The result holds the feasible design that minimises
    ``objective`` (a field; negate nothing: to maximise a stiffness, bound the mass and read
    ``maximum``), the minimum and maximum of each of ``fields`` over the feasible designs, and,
    with ``keep=True``, every design's ``fields`` as arrays of shape (len(W), len(n), len(alpha))
    (8 bytes per design and field: the only memory that grows with the grid).

    ``chunk``: designs per block (memory and cache use). ``scheduler``: a ``distributed.Client``
    or a scheduler address; the grid is then split into ``tasks`` tasks (default: about 4 per
    worker thread) of whole W rows, and the result equals the in-process one.

    Example, the case study of docs/theory.md 3.5 by exhaustive search::

        >>> import numpy as np
        >>> from corrugate import get_material
        >>> r = sweep(np.arange(1.0, 31), np.arange(1, 201), np.arange(1.0, 121),
        ...           get_material("dura-lar"), 0.125, model="paper",
        ...           bounds={"Lx": (48, 60), "thickness": (10, 12.5), "flat": (None, 250),
        ...                   "EI": (80e3, None)})
        >>> r.best["W"], r.best["n"], r.best["alpha"]
        (8.0, 8.0, 84.0)
    """
    get_model(model)
    support = check_support(support)
    lay = layout if layout is not None else Square()
    if not lay.equal_sides and lay.name != "rectangle":
        raise InputError(
            "layout", lay.name, "a square, rectangle or circle", reason="is not symmetric"
        )
    bounds = dict(bounds or {})
    for name in (*fields, *bounds, objective):
        if name not in FIELDS:
            raise InputError("fields", name, f"one of {', '.join(FIELDS)}", reason="is unknown")
    if chunk < 1:
        raise InputError("chunk", chunk, "a positive number of designs")
    Ws = np.asarray(W, dtype=np.float64).reshape(-1)
    ns = np.asarray(n, dtype=np.int64).reshape(-1)
    As = np.asarray(alpha_deg, dtype=np.float64).reshape(-1)
    setup = _Setup(
        Ws,
        ns,
        As,
        float(material.E),
        float(material.nu),
        float(t),
        float(material.density),
        lay,
        model,
        float(eta_deg),
        support,
        fabrication,
        tuple(dict.fromkeys((*fields, objective))),
        tuple((k, lo, hi) for k, (lo, hi) in bounds.items()),
        objective,
        int(chunk),
    )
    nW = len(Ws)
    if scheduler is None:
        total = _run(setup, (0, nW), keep)
    else:
        client, owned = _client(scheduler)
        try:
            if tasks is None:
                threads = sum(client.nthreads().values()) or 1
                tasks = 4 * threads
            edges = np.linspace(0, nW, min(max(int(tasks), 1), max(nW, 1)) + 1).astype(int)
            ranges = [(int(a), int(b)) for a, b in itertools.pairwise(edges) if b > a]
            remote = client.scatter(setup, broadcast=True)
            futures = [client.submit(_run, remote, r, keep, pure=False) for r in ranges]
            total = _Partial()
            for part in client.gather(futures):
                total.merge(part)
        finally:
            if owned:
                client.close()
    return _result(setup, total, keep)


def _result(setup: _Setup, total: _Partial, keep: bool) -> SweepResult:
    shape = setup.shape
    best_index: tuple[int, int, int] | None = None
    best: dict[str, float] | None = None
    if total.best_flat >= 0:
        i, j, k = (int(x) for x in np.unravel_index(total.best_flat, shape))
        best_index = (i, j, k)
        W = setup.W[i : i + 1]
        n = setup.n[j : j + 1]
        a = setup.alpha[k : k + 1]
        vals = _fields(setup, W, n, a)
        best = {"W": float(W[0]), "n": float(n[0]), "alpha": float(a[0])}
        best.update({name: float(np.asarray(v).reshape(-1)[0]) for name, v in vals.items()})
    nan = math.nan
    values: dict[str, FloatArray] | None = None
    if keep:
        values = {k: np.empty(shape) for k in setup.fields}
        for sl, block in total.blocks:
            for name, v in block.items():
                values[name][sl] = v
    return SweepResult(
        shape=shape,
        count=total.count,
        feasible=total.feasible,
        objective=setup.objective,
        best_index=best_index,
        best=best,
        minimum={k: total.minimum.get(k, nan) for k in setup.fields},
        maximum={k: total.maximum.get(k, nan) for k in setup.fields},
        values=values,
    )
