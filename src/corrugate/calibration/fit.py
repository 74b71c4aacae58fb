"""The fit of a measurements file: E per direction, the crease stiffness, the springback.

**E** (MPa) of each direction is the least-squares fit of the elastica
(:mod:`corrugate.calibration.elastica`) to every sag of that direction's flat set-ups: the one E
that minimises the sum of squared differences (mm^2) between the sags read and the sags the
elastica gives. **The interval** is a parametric bootstrap of that fit (docs/calibration.md
section 5): the readings are drawn again around the fitted sags with the scatter found (the
residuals' standard deviation, itself drawn from its chi-square law so that a few repeats widen
the interval as Student's t does, never less than the ruler's reading error: a reading of +-r mm
uniform has r / sqrt(3)), the fit is repeated, and the 5th and 95th percentiles of the refitted
E are the 90 % interval. A bootstrap, not the linearised standard error, because the sag is not
linear in E (the elastica stiffens as it sags) and the interval is not symmetric; a parametric
one, not resampling the readings themselves, because three to five repeats that often read the
same millimetre would give an interval of zero width.

**The crease** stiffness per unit length k (N mm/(rad mm)) follows from the compliance of the
zig-zag strip (:mod:`corrugate.calibration.crease`): the least-squares line through the origin of
extension against coin weight, less the facets' share at the fitted E of the ``along`` direction
(the strip is cut along x), its interval bootstrapped with that E's. **The springback** is the
angle the strip's unloaded length gives (:func:`~corrugate.calibration.crease.angle_from_length`)
less the angle it was folded to (deg).
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from dataclasses import dataclass
from functools import lru_cache

import numpy as np
from numpy.typing import NDArray

from corrugate.calibration.coupons import GRAVITY
from corrugate.calibration.crease import angle_from_length, compliance
from corrugate.calibration.elastica import Anticlastic, drop_ratios, rigidity
from corrugate.calibration.measurements import CreaseTest, FlatTest, Measurements
from corrugate.core.errors import InputError
from corrugate.materials.library import Material

__all__ = [
    "BOOTSTRAP",
    "CreaseFit",
    "Fit",
    "ModulusFit",
    "fit_crease",
    "fit_measurements",
    "fit_modulus",
    "sag_model",
]

#: Bootstrap resamples.
BOOTSTRAP = 1000
#: The interval's coverage.
LEVEL = 0.90
#: The moduli searched: the library's E times 1/SPAN to SPAN.
SPAN = 20.0
#: The kit strip's facets bend up to this fraction more than the closed form's plate (their free
#: edges curl): the FE of the strip with crease strips at k = 1e6, 16 elements per facet, gives
#: 1.57 % at nu 0.43 (alpha 84 and 100 deg) and 0.95 % at nu 0.3 (docs/calibration.md section 7).
#: The fit takes the rigid strip's compliance times (1 + phi), phi uniform in [0, FACET_SOFTENING]
#: in the bootstrap (a model uncertainty, not fitted on the readings), its middle for the estimate.
FACET_SOFTENING = 0.016
#: A fit whose residuals' RMS exceeds this many reading errors (plus 10 % of the sag) is refused:
#: no single E explains the sags.
MISFIT = 4.0


@lru_cache(maxsize=256)
def _table(
    q: float, P: float, L: float, EI_ref: float, law: Anticlastic
) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
    """(log E/E_ref, log sag) of a strip (weight q N/mm, tip load P N, free length L mm, moment
    law ``law``) over E_ref / SPAN .. E_ref * SPAN, where EI_ref is the plate rigidity at E_ref
    (N mm^2)."""
    s = np.geomspace(1.0 / SPAN, SPAN, 81)  # load factors: E = E_ref / s
    a, b = q * L**3 / EI_ref, P * L**2 / EI_ref
    keep = s * max(a, b) <= 1.0e4
    w = L * drop_ratios(s[keep], a, b, law)
    logE = -np.log(s[keep])
    return logE[::-1].copy(), np.log(w[::-1])


def sag_model(
    test: FlatTest, E: NDArray[np.float64] | float, material_density: float, t: float, nu: float
) -> NDArray[np.float64]:
    """The elastica's sag (mm) of ``test``'s set-up at modulus ``E`` (MPa; an array), for a sheet
    of density (g/mm^3) and thickness ``t`` (mm), the strip's anticlastic moment law included
    (:class:`~corrugate.calibration.elastica.Anticlastic`); nan outside the tabulated moduli."""
    from scipy.interpolate import CubicSpline

    E_ref = 1000.0
    q = material_density * test.width * t * GRAVITY
    EI_ref = rigidity(E_ref, nu, test.width, t)
    law = Anticlastic.for_strip(test.width, t, test.overhang, nu)
    logE, logw = _table(q, test.tip_g * GRAVITY, test.overhang, EI_ref, law)
    x = np.log(np.asarray(E, dtype=np.float64) / E_ref)
    out = np.exp(CubicSpline(logE, logw)(x))
    return np.where((x >= logE[0]) & (x <= logE[-1]), out, np.nan)


@dataclass(frozen=True, slots=True)
class ModulusFit:
    """E (MPa) of one ``direction`` with its 90 % interval (``lo``, ``hi``), the bootstrap's E
    samples, the number of readings, the fitted sags and residuals (mm, reading order), the scatter
    found (mm, at least the ruler's) and the tests fitted."""

    direction: str
    E: float
    lo: float
    hi: float
    samples: tuple[float, ...]
    n: int
    predicted: tuple[float, ...]
    residuals: tuple[float, ...]
    sigma: float
    tests: tuple[FlatTest, ...]


@dataclass(frozen=True, slots=True)
class CreaseFit:
    """The crease stiffness k (N mm/(rad mm); inf: stiffer than the readings tell) and its 90 %
    interval, the angle the strip took (deg) with its interval, the springback (deg, the angle
    less the angle folded to), the E used (MPa), and the fitted compliance (mm/N) with the loads
    (N) and mean extensions (mm)."""

    k: float
    k_lo: float
    k_hi: float
    angle: float
    angle_lo: float
    angle_hi: float
    springback: float
    E: float
    C: float
    loads: tuple[float, ...]
    extensions: tuple[float, ...]
    n: int


@dataclass(frozen=True, slots=True)
class Fit:
    """The fit of a measurements file: the moduli by direction and the crease (None: not
    measured)."""

    measurements: Measurements
    moduli: tuple[ModulusFit, ...]
    crease: CreaseFit | None

    def modulus(self, direction: str) -> ModulusFit | None:
        return next((m for m in self.moduli if m.direction == direction), None)


def _sigma(residuals: NDArray[np.float64], ruler: float, params: int = 1) -> float:
    """The scatter (mm): the residuals' standard deviation, at least the ruler's r / sqrt(3)."""
    n = residuals.size
    s2 = float(residuals @ residuals) / max(n - params, 1)
    return math.sqrt(max(s2, ruler**2 / 3.0))


def _sigmas(
    residuals: NDArray[np.float64],
    ruler: float,
    rng: np.random.Generator,
    samples: int,
    params: int = 1,
) -> NDArray[np.float64]:
    """One scatter (mm) per resample: the residuals' variance s^2 on nu = n - params degrees of
    freedom is itself uncertain, so each resample draws sigma^2 = nu s^2 / chi^2_nu (what makes
    the interval of a few repeats as wide as Student's t, not the normal's), never below the
    ruler's (r / sqrt(3))^2."""
    nu = max(residuals.size - params, 1)
    s2 = float(residuals @ residuals) / nu
    draws = nu * s2 / rng.chisquare(nu, samples)
    return np.sqrt(np.maximum(draws, ruler**2 / 3.0))


def _best(
    Y: NDArray[np.float64], M: NDArray[np.float64], logE: NDArray[np.float64]
) -> NDArray[np.float64]:
    """The log E minimising sum_i (Y[b, i] - M[i, g])^2 for each row b of Y, on the grid logE with
    a parabola through the best point and its neighbours. Rows of M that are equal (the repeats
    of one set-up) are summed first, and the products are taken element by element (no BLAS
    call: its threads only contend on a busy machine)."""
    groups: dict[bytes, list[int]] = {}
    for i, row in enumerate(M):
        groups.setdefault(row.tobytes(), []).append(i)
    sse = np.zeros((Y.shape[0], logE.size))
    for rows_i in groups.values():
        m = M[rows_i[0]][None, :]
        s1 = Y[:, rows_i].sum(axis=1)[:, None]
        sse += len(rows_i) * m * m - 2.0 * s1 * m
    g = np.clip(np.argmin(sse, axis=1), 1, logE.size - 2)
    rows = np.arange(Y.shape[0])
    y0, y1, y2 = sse[rows, g - 1], sse[rows, g], sse[rows, g + 1]
    denom = y0 - 2 * y1 + y2
    shift = np.where(denom > 0, 0.5 * (y0 - y2) / np.where(denom > 0, denom, 1.0), 0.0)
    best: NDArray[np.float64] = logE[g] + np.clip(shift, -1.0, 1.0) * (logE[1] - logE[0])
    return best


def _rows(
    tests: Sequence[FlatTest], logE: NDArray[np.float64], material: Material, t: float
) -> NDArray[np.float64]:
    """The model's sags (mm) on the grid ``logE``, one row per reading."""
    return np.vstack(
        [
            np.repeat(
                sag_model(test, np.exp(logE), material.density, t, material.nu)[None, :],
                len(test.sags),
                axis=0,
            )
            for test in tests
        ]
    )


def fit_modulus(
    tests: Sequence[FlatTest],
    material: Material,
    t: float,
    ruler: float,
    rng: np.random.Generator,
    samples: int = BOOTSTRAP,
) -> ModulusFit:
    """The least-squares E (MPa) of ``tests`` (one direction) of a sheet of ``material``'s
    density and nu, ``t`` mm thick, and its bootstrap interval (module docstring); the search
    spans the material's E / 20 .. E * 20.
    :class:`InputError` naming the tests' field when no E in that range explains the sags."""
    E_guide = material.E
    y = np.array([s for test in tests for s in test.sags])
    grid = np.linspace(math.log(E_guide / SPAN) + 0.05, math.log(E_guide * SPAN) - 0.05, 1201)
    M = _rows(tests, grid, material, t)
    usable = ~np.isnan(M).any(axis=0)
    if usable.sum() < 3:
        raise InputError(
            tests[0].field, "...", "a strip that does not hang down at the library's E"
        )
    grid, M = grid[usable], M[:, usable]
    logE = float(_best(y[None, :], M, grid)[0])
    where = tests[0].field.split("[")[0] + f" ({tests[0].direction})"
    if logE <= grid[1] + 1e-9 or logE >= grid[-2] - 1e-9:
        raise InputError(
            where,
            "sags " + ", ".join(f"{s:g}" for t_ in tests for s in t_.sags) + " mm",
            f"sags that one E between {math.exp(grid[0]):.4g} and {math.exp(grid[-1]):.4g} MPa "
            "explains (check the overhang, tip mass and thickness)",
            reason="fit no modulus",
        )
    E = math.exp(logE)
    pred = np.array(
        [
            float(sag_model(test, E, material.density, t, material.nu))
            for test in tests
            for _ in test.sags
        ]
    )
    res = y - pred
    rms = float(np.sqrt(np.mean(res**2)))
    limit = MISFIT * ruler + 0.1 * float(np.mean(y))
    if rms > limit:
        raise InputError(
            where,
            f"residual RMS {rms:.1f} mm at the best E = {E:.4g} MPa",
            f"at most {limit:.1f} mm ({MISFIT:g} ruler readings + 10 % of the mean sag): "
            "no single E explains these sags (check the overhang, tip mass and readings)",
            reason="fit no modulus",
        )
    sigma = _sigma(res, ruler)
    # the bootstrap: on a fine grid +-0.4 in log E around E (spacing 0.002), on +-1.5 when a
    # resample's best E reaches the narrow grid's end
    Y = pred[None, :] + _sigmas(res, ruler, rng, samples)[:, None] * rng.standard_normal(
        (samples, y.size)
    )
    for half, points in ((0.4, 401), (1.5, 1501)):
        fine = np.linspace(max(logE - half, grid[0]), min(logE + half, grid[-1]), points)
        best = _best(Y, _rows(tests, fine, material, t), fine)
        if half >= 1.5 or (best.min() > fine[1] and best.max() < fine[-2]):
            break
    Es = np.exp(best)
    lo, hi = np.quantile(Es, [(1 - LEVEL) / 2, (1 + LEVEL) / 2])
    return ModulusFit(
        direction=tests[0].direction,
        E=E,
        lo=float(lo),
        hi=float(hi),
        samples=tuple(float(e) for e in Es),
        n=int(y.size),
        predicted=tuple(float(p) for p in pred),
        residuals=tuple(float(r) for r in res),
        sigma=sigma,
        tests=tuple(tests),
    )


def fit_crease(
    test: CreaseTest,
    material: Material,
    E_samples: Sequence[float],
    E: float,
    t: float,
    ruler: float,
    rng: np.random.Generator,
) -> CreaseFit:
    """The crease stiffness, angle and springback of ``test`` (module docstring) at modulus ``E``
    (MPa; nu the ``material``'s), the interval drawn with ``E_samples`` (the bootstrap's E, or E alone)."""
    lengths = np.array(test.lengths)
    angle = angle_from_length(float(lengths.mean()), test.facet, test.creases)
    if math.isnan(angle):
        raise InputError(
            "crease.length", f"{lengths.mean():g} mm", "a length below creases x facet"
        )
    F = np.array(
        [m * GRAVITY for m, e in zip(test.masses, test.extensions, strict=True) for _ in e]
    )
    d = np.array([x for e in test.extensions for x in e])
    C = float(F @ d / (F @ F))
    n = len(E_samples)
    sig_d = _sigmas(d - C * F, ruler, rng, n)[:, None]
    sig_l = _sigmas(lengths - lengths.mean(), ruler, rng, n)

    def hinge(
        Cs: NDArray[np.float64],
        Es: NDArray[np.float64],
        alphas: NDArray[np.float64],
        phis: NDArray[np.float64],
    ) -> NDArray[np.float64]:
        """The crease compliance per unit length 1/k (rad/N) of compliances Cs, the rigid
        strip's taken times (1 + phis) (:data:`FACET_SOFTENING`)."""
        e = test.facet * np.cos(np.radians(alphas) / 2) / 2
        rigid = np.array(
            [
                compliance(
                    math.inf,
                    float(Ei),
                    t,
                    test.width,
                    test.facet,
                    float(a),
                    test.creases,
                    material.nu,
                )
                for Ei, a in zip(Es, alphas, strict=True)
            ]
        )
        inv: NDArray[np.float64] = (Cs - rigid * (1.0 + phis)) * test.width / (test.creases * e**2)
        return inv

    Es = np.asarray(E_samples, dtype=np.float64)
    Ls = lengths.mean() + sig_l / math.sqrt(lengths.size) * rng.standard_normal(n)
    Ls = np.clip(Ls, 1e-6, test.creases * test.facet * (1 - 1e-9))
    alphas = np.degrees(2 * np.arcsin(Ls / (test.creases * test.facet)))
    Ds = (C * F)[None, :] + sig_d * rng.standard_normal((n, d.size))
    Cs = (Ds * F[None, :]).sum(axis=1) / float(F @ F)
    inv = hinge(Cs, Es, alphas, rng.uniform(0.0, FACET_SOFTENING, n))
    mid = np.array([FACET_SOFTENING / 2])
    inv0 = float(hinge(np.array([C]), np.array([E]), np.array([angle]), mid)[0])
    lo_inv, hi_inv = np.quantile(inv, [(1 - LEVEL) / 2, (1 + LEVEL) / 2])
    a_lo, a_hi = np.quantile(alphas, [(1 - LEVEL) / 2, (1 + LEVEL) / 2])
    means = tuple(float(np.mean(e)) for e in test.extensions)
    return CreaseFit(
        k=math.inf if inv0 <= 0 else 1.0 / inv0,
        k_lo=math.inf if hi_inv <= 0 else 1.0 / hi_inv,
        k_hi=math.inf if lo_inv <= 0 else 1.0 / lo_inv,
        angle=angle,
        angle_lo=float(a_lo),
        angle_hi=float(a_hi),
        springback=angle - test.folded_to,
        E=E,
        C=C,
        loads=tuple(m * GRAVITY for m in test.masses),
        extensions=means,
        n=int(d.size + lengths.size),
    )


def fit_measurements(m: Measurements, seed: int = 0, samples: int = BOOTSTRAP) -> Fit:
    """Every fit a measurements file allows (module docstring), the bootstrap seeded with
    ``seed`` (the same file gives the same intervals)."""
    rng = np.random.default_rng(seed)
    moduli = []
    for direction in ("along", "across"):
        tests = [f for f in m.flat if f.direction == direction]
        if tests:
            moduli.append(fit_modulus(tests, m.material, m.t, m.ruler, rng, samples))
    crease = None
    if m.crease is not None:
        along = next((f for f in moduli if f.direction == "along"), moduli[0] if moduli else None)
        E = m.material.E if along is None else along.E
        Es = [E] * samples if along is None else list(along.samples)
        crease = fit_crease(m.crease, m.material, Es, E, m.t, m.ruler, rng)
    return Fit(m, tuple(moduli), crease)
