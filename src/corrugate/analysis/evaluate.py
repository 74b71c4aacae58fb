"""Analyse a design: moduli, springs, K(eta), D(eta), EI(eta), mass and warnings.

Two entry points share one implementation:

* :func:`evaluate`, vectorised over NumPy arrays of layer parameters (a sweep over a million designs
  is one call; the optimiser uses it);
* :func:`analyze`, for one :class:`~corrugate.geometry.layer.Assembly`, returning an :class:`Analysis`
  with everything ``corrugate analyze`` prints.
"""

from __future__ import annotations

from collections.abc import Callable, Sequence
from dataclasses import dataclass
from typing import Any, Literal

import numpy as np
from numpy.typing import ArrayLike, NDArray

from corrugate.analysis.warnings import ModelWarning, design_warnings
from corrugate.core.errors import InputError
from corrugate.geometry.fabrication_options import DEFAULT_FABRICATION, FabricationOptions
from corrugate.geometry.layer import Assembly, Layer, crease_layer
from corrugate.geometry.layouts import (
    Circle,
    Layout,
    Rectangle,
    inverse_length_sum,
    layer_inverse_sums,
    length_sum,
)
from corrugate.geometry.profile import ZIGZAG, ProfileKind
from corrugate.mechanics.behaviours import check_support, get_support
from corrugate.mechanics.buckling import BucklingEstimate, buckling_bounds
from corrugate.mechanics.creases import flexibility, is_rigid
from corrugate.mechanics.load_cases import band_walls
from corrugate.mechanics.mass import MassBreakdown, assembly_mass, connector_mass, layer_mass
from corrugate.mechanics.moduli import DEFAULT_MODEL, Moduli, ModuliModel, get_model
from corrugate.mechanics.offaxis import Coupon, assembly_directional
from corrugate.mechanics.profiles import profile_moduli
from corrugate.mechanics.springs import LayerSprings, layer_springs
from corrugate.names import DEFAULT_SUPPORT

__all__ = [
    "Analysis",
    "DirectionalStiffness",
    "Evaluation",
    "LayerArrays",
    "LazyEvaluation",
    "analyze",
    "coupon_of",
    "evaluate",
    "facet_buckling_load",
    "identical_layers",
]

FloatArray = NDArray[np.float64]


@dataclass(frozen=True, slots=True)
class LayerArrays:
    """Parameters of one layer as arrays that broadcast together (internal units).

    E (MPa), nu, t (mm), W (mm), n (creases), alpha_deg (deg), density (g/mm^3), the
    profile they are folded to (:class:`~corrugate.geometry.profile.ProfileKind`, the zig-zag
    unless told) and the creases' flexibility 1 / k (rad/N; 0.0, the default: rigid creases,
    :mod:`corrugate.mechanics.creases`).
    """

    E: ArrayLike
    nu: ArrayLike
    t: ArrayLike
    W: ArrayLike
    n: ArrayLike
    alpha_deg: ArrayLike
    density: ArrayLike
    profile_kind: ProfileKind = ZIGZAG
    crease_flex: ArrayLike = 0.0

    @classmethod
    def of(cls, layer: Layer) -> LayerArrays:
        m = layer.material
        return cls(
            m.E,
            m.nu,
            layer.t,
            layer.W,
            layer.n,
            layer.alpha_deg,
            m.density,
            layer.profile_kind,
            flexibility(m.crease_stiffness),
        )

    def profile(self) -> Any:
        """The layers' cross-section (:class:`corrugate.geometry.profile.Profile` of their
        profile kind; :class:`~corrugate.geometry.profile.ZigZag` by default) over the arrays:
        pitch, height, developed width, extent (n + 1) pitch, flat width (n + 1) developed (mm)."""
        return self.profile_kind.of(
            np.asarray(self.W, dtype=np.float64), np.asarray(self.alpha_deg, dtype=np.float64)
        )


def coupon_of(layout: Layout, Lx: Any, Ly: Any, pq: Callable[[], tuple[Any, Any]]) -> Coupon | None:
    """How ``layout`` is read off the crease directions under the free support
    (:class:`corrugate.mechanics.offaxis.Coupon`): None for a square; a rectangle's coupon from Lx / Ly
    alone; a circle or polygon from its box and the layers' geometry factors ``pq()`` (called
    only for them: p sum_j 1/L_j of each layer without holes), capped by its own springs.
    Arrays and intervals alike."""
    if isinstance(layout, Rectangle):
        if layout.equal_sides:
            return None
        return Coupon(Lx / Ly, Lx / Ly, Ly / Lx)
    pq1, pq2 = pq()
    return Coupon(Lx / Ly, pq1, pq2, capped=True)


def directional(
    kind: Literal["K", "D"],
    springs: tuple[LayerSprings, LayerSprings],
    eta_deg: ArrayLike,
    support: str,
    coupon: Coupon | None = None,
) -> FloatArray:
    """K or D of the assembly (:func:`corrugate.mechanics.offaxis.assembly_directional`; ``coupon``:
    :func:`coupon_of`) broadcast over the springs' arrays and ``eta_deg`` (deg): one
    evaluation per distinct eta."""
    eta = np.asarray(eta_deg, dtype=np.float64)
    if eta.ndim == 0:  # one direction: no masks, no copies
        return np.asarray(assembly_directional(kind, springs, float(eta), support, coupon))
    values = {
        float(e): assembly_directional(kind, springs, float(e), support, coupon)
        for e in sorted(set(eta.ravel().tolist()))  # (np.unique would import numpy.ma: 0.1 s)
    }
    shape = np.broadcast_shapes(np.shape(springs[0].K_S), np.shape(springs[1].K_S), eta.shape)
    out = np.zeros(shape)
    for e, v in values.items():
        out = np.where(eta == e, v, out)
    return np.asarray(out, dtype=np.float64)


@dataclass(frozen=True, slots=True)
class Evaluation:
    """Vectorised results (arrays broadcast over the inputs): lengths in mm, K in N/mm,
    D in N mm, EI in N mm^2, mass in g. Each array keeps the smallest shape that carries it
    (e.g. the moduli do not depend on n, the thickness not on n); all broadcast together."""

    Lx: FloatArray
    Ly: FloatArray
    thickness: FloatArray
    mass: FloatArray
    mass_connectors: FloatArray
    K: FloatArray
    D: FloatArray
    EI: FloatArray
    moduli: tuple[Moduli, Moduli]
    springs: tuple[LayerSprings, LayerSprings]


def _same_field(a: ArrayLike, b: ArrayLike) -> bool:
    if a is b:
        return True
    x, y = np.asarray(a), np.asarray(b)
    return x.shape == y.shape and bool(np.array_equal(x, y))


def identical_layers(layer1: LayerArrays, layer2: LayerArrays, layout: Layout) -> bool:
    """Whether layer 2's springs, extent and mass are layer 1's, so :func:`evaluate` computes one
    layer only: the same parameters (the same objects, or equal arrays of the same shape) on an
    outline that is symmetric under x <-> y (rectangle, square, circle) and has no holes (holes
    need not be symmetric). Then Lx = Ly and q = sum_j 1/L_j is the same for both layers
    (docs/theory.md 3.2), so every per-layer quantity is bit for bit the same."""
    if layout.holes or not isinstance(layout, Rectangle | Circle):
        return False
    if layer1 is layer2:
        return True
    return layer1.profile_kind == layer2.profile_kind and all(
        _same_field(getattr(layer1, f), getattr(layer2, f))
        for f in ("alpha_deg", "W", "n", "t", "E", "nu", "density", "crease_flex")
    )


@dataclass(frozen=True, slots=True)
class _LayerPart:
    """One layer's share of :func:`evaluate`, from its cross-section ``z``
    (:class:`corrugate.geometry.profile.Profile`; the zig-zag's s = sin(alpha/2), c =
    cos(alpha/2)): pitch p and height h (mm), chord extent (n + 1) p (mm) and moduli (MPa)."""

    z: Any
    p: FloatArray
    h: FloatArray
    extent: FloatArray
    moduli: Moduli


def _layer_part(layer: LayerArrays, model: ModuliModel) -> _LayerPart:
    """Trigonometry once per layer (the profile's sin and cos of alpha/2), then the geometry and
    the moduli (:func:`corrugate.mechanics.profiles.profile_moduli`: the zig-zag's closed forms,
    another profile's Xia general theory)."""
    z = layer.profile()
    # scalars as Python floats: the nu polynomials of the moduli cost nothing then
    flex = layer.crease_flex
    flex = flex if is_rigid(flex) else _num(flex)
    m = profile_moduli(z, _num(layer.E), _num(layer.nu), _num(layer.t), model.name, flex)
    # n as float64: (n + 1) is exact, and float * float avoids a cast loop
    return _LayerPart(z, z.pitch, z.height, z.extent(np.asarray(layer.n, np.float64)), m)


def _on_creases(eta_deg: ArrayLike) -> Any:
    """Whether each eta (deg) runs along a layer's creases (0 or 90 deg, modulo 180)."""
    e = np.mod(np.asarray(eta_deg, dtype=np.float64), 90.0)
    return np.minimum(e, 90.0 - e) < 1e-12


def _num(x: ArrayLike) -> Any:
    """A 0-d input as a Python float, an array as a float64 array."""
    a = np.asarray(x, dtype=np.float64)
    return float(a) if a.ndim == 0 else a


def evaluate(
    layer1: LayerArrays,
    layer2: LayerArrays,
    layout: Layout,
    model: str = DEFAULT_MODEL,
    eta_deg: ArrayLike = 0.0,
    fabrication: FabricationOptions = DEFAULT_FABRICATION,
    support: str = DEFAULT_SUPPORT,
    joint: str = "none",
) -> Evaluation:
    """Stiffness, size and mass of assemblies given as arrays of layer parameters.

    ``joint`` (:data:`corrugate.mechanics.load_cases.JOINTS`): with the connector band bonded
    (``band-edges``, ``band-flanges``) its two walls along eta add their bending D_w and axial
    K_w along the crease directions (:func:`corrugate.mechanics.load_cases.band_walls`,
    docs/load_cases.md section 7); off them, and with ``none``, the band is left out.

    K (N/mm), D (N mm) and EI (N mm^2) are those of ``support``, a registered support condition
    (:mod:`corrugate.mechanics.behaviours`: ``free`` sides, the default, or a rigid ``frame``,
    :mod:`corrugate.mechanics.offaxis`); the built-in two agree at eta = 0 and 90 deg.
    Springs from docs/theory.md 3.2, moduli from the variant ``model`` (3.1), the assembly from 3.3.

    ``mass`` (g) counts both layers and the connector band (cut from layer 1's sheet), as the cut
    files do; ``mass_connectors`` is the band's share.

    sin and cos of alpha/2 are computed once per layer, and when the two layers are the same
    (:func:`identical_layers`) layer 2 is not evaluated again: its results are layer 1's. Inputs
    that broadcast (e.g. ``n`` of shape (k, 1, 1), ``W`` (1, m, 1), ``alpha_deg`` (1, 1, j))
    keep each step on the smallest shape that carries it (trigonometry on alpha's axis only).

    No validation is done (see :class:`~corrugate.geometry.layer.Layer` for the allowed ranges), and the
    equal-sides requirement of square and circle layouts is left to the caller.
    """
    b = _base(layer1, layer2, layout, model, eta_deg, fabrication, support)
    D = directional("D", b.springs, eta_deg, support, b.coupon)
    K = directional("K", b.springs, eta_deg, support, b.coupon)
    if joint != "none":
        D_w, _, K_w = band_walls(layer1.E, layer1.nu, layer1.t, b.thickness, b.span)
        on = _on_creases(eta_deg)
        D = np.asarray(D + np.where(on, D_w, 0.0))
        K = np.asarray(K + np.where(on, K_w, 0.0))
    return Evaluation(
        Lx=b.Lx,
        Ly=b.Ly,
        thickness=b.thickness,
        mass=b.mass + b.mass_connectors,
        mass_connectors=b.mass_connectors,
        K=K,
        D=D,
        EI=np.asarray(D * b.span),
        moduli=b.moduli,
        springs=b.springs,
    )


@dataclass(frozen=True, slots=True)
class _Base:
    """What :func:`evaluate` computes before the directional stiffness: the extents Lx, Ly (mm),
    the folded thickness (mm), the layers' mass and the connector band's (g), the moduli (MPa),
    the springs, the layout's coupon (None when no direction reads it) and the span (mm) along
    each eta."""

    Lx: FloatArray
    Ly: FloatArray
    thickness: FloatArray
    mass: FloatArray
    mass_connectors: FloatArray
    moduli: tuple[Moduli, Moduli]
    springs: tuple[LayerSprings, LayerSprings]
    coupon: Coupon | None
    span: FloatArray


def _base(
    layer1: LayerArrays,
    layer2: LayerArrays,
    layout: Layout,
    model: str,
    eta_deg: ArrayLike,
    fabrication: FabricationOptions,
    support: str,
) -> _Base:
    """The part of :func:`evaluate` that does not depend on which stiffness is read
    (:class:`_Base`)."""
    variant = get_model(model)
    same = identical_layers(layer1, layer2, layout)
    g1 = _layer_part(layer1, variant)
    g2 = g1 if same else _layer_part(layer2, variant)
    Lx, Ly = g1.extent, g2.extent
    q1, qs1 = layer_inverse_sums(layout, layer1.n, g1.p, Ly, "x")
    s1 = layer_springs(
        g1.moduli,
        layer1.t,
        g1.p,
        q1,
        layer1.E,
        layer1.nu,
        g1.z.plan_ratio,
        qs1,
        web2=g1.z.web2,
        height=g1.h,
        n=layer1.n,
    )
    if same:
        s2 = s1
    else:
        q2, qs2 = layer_inverse_sums(layout, layer2.n, g2.p, Lx, "y")
        s2 = layer_springs(
            g2.moduli,
            layer2.t,
            g2.p,
            q2,
            layer2.E,
            layer2.nu,
            g2.z.plan_ratio,
            qs2,
            web2=g2.z.web2,
            height=g2.h,
            n=layer2.n,
        )
    coupon = None
    if get_support(support).uses_coupon and any(
        crease_layer(float(e)) is None
        for e in set(np.asarray(eta_deg, dtype=float).ravel().tolist())
    ):
        coupon = coupon_of(
            layout,
            Lx,
            Ly,
            lambda: (
                g1.p * inverse_length_sum(layout, layer1.n, Ly, "x"),
                g2.p * inverse_length_sum(layout, layer2.n, Lx, "y"),
            ),
        )
    mass = layer_mass(
        layer1.density, layer1.t, g1.z.developed, length_sum(layout, layer1.n, Ly), layout, g1.p
    )
    if same:  # x + x == 2 x exactly
        thickness = np.asarray(2.0 * g1.h)
        mass = np.asarray(2.0 * mass)
    else:
        thickness = np.asarray(g1.h + g2.h)
        mass = mass + layer_mass(
            layer2.density, layer2.t, g2.z.developed, length_sum(layout, layer2.n, Lx), layout, g2.p
        )
    m_conn = connector_mass(layer1.density, layer1.t, layout, Lx, Ly, thickness, fabrication)
    span = np.asarray(layout.span(Lx, Ly, np.asarray(eta_deg, dtype=float)))
    return _Base(Lx, Ly, thickness, mass, m_conn, (g1.moduli, g2.moduli), (s1, s2), coupon, span)


class LazyEvaluation:
    """:func:`evaluate` of the same arguments (``eta_deg`` a scalar or a 1-D array) computing
    each stiffness only when it is read: :meth:`column` ``(kind, j)`` is
    ``getattr(evaluate(...), kind)[:, j]`` (K in N/mm, D in N mm, EI in N mm^2 at the j-th
    direction), bit for bit, without the directions and kinds nobody reads (the solver's
    evaluations at points ask for the quantities of the problem's constraints and objective:
    an off-axis D, two free-panel coupons, is the dearest and is seldom bounded). The other
    fields (Lx, Ly, thickness in mm, mass and mass_connectors in g, moduli, springs) are
    ``evaluate``'s. Each column is computed once and kept."""

    def __init__(
        self,
        layer1: LayerArrays,
        layer2: LayerArrays,
        layout: Layout,
        model: str = DEFAULT_MODEL,
        eta_deg: ArrayLike = 0.0,
        fabrication: FabricationOptions = DEFAULT_FABRICATION,
        support: str = DEFAULT_SUPPORT,
        joint: str = "none",
    ) -> None:
        eta = np.asarray(eta_deg, dtype=np.float64)
        if eta.ndim > 1:
            raise ValueError("eta_deg must be a scalar or a 1-D array")
        self._eta, self._support, self._joint, self._layer1 = eta, support, joint, layer1
        b = _base(layer1, layer2, layout, model, eta, fabrication, support)
        self._b = b
        self.Lx, self.Ly, self.thickness = b.Lx, b.Ly, b.thickness
        self.mass = b.mass + b.mass_connectors
        self.mass_connectors = b.mass_connectors
        self.moduli, self.springs = b.moduli, b.springs
        self._columns: dict[tuple[str, int], FloatArray] = {}
        self._walls: tuple[Any, Any] | None = None

    def column(self, kind: str, j: int) -> FloatArray:
        """``getattr(evaluate(...), kind)[:, j]``: the stiffness ``kind`` ("K", "D" or "EI")
        at the j-th direction (K N/mm, D N mm, EI = D x span N mm^2) over the points
        (computed once)."""
        key = (kind, j)
        v = self._columns.get(key)
        if v is None:
            if kind == "EI":
                v = np.asarray(self.column("D", j) * self._span(j))
            elif kind == "K":
                v = self._directional("K", j)
            elif kind == "D":
                v = self._directional("D", j)
            else:
                raise ValueError(f"kind {kind!r}: K, D or EI")
            self._columns[key] = v
        return v

    @property
    def K(self) -> FloatArray:
        """K (N/mm) at every direction, points by directions (:func:`evaluate`'s)."""
        return self._all("K")

    @property
    def D(self) -> FloatArray:
        """D (N mm) at every direction, points by directions (:func:`evaluate`'s)."""
        return self._all("D")

    @property
    def EI(self) -> FloatArray:
        """EI (N mm^2) at every direction, points by directions (:func:`evaluate`'s)."""
        return self._all("EI")

    def _all(self, kind: str) -> FloatArray:
        m = self._eta.size if self._eta.ndim else 1
        return np.stack([self.column(kind, j) for j in range(m)], axis=1)

    def _directional(self, kind: Literal["K", "D"], j: int) -> FloatArray:
        """K or D at the j-th direction as :func:`evaluate` computes it: one
        :func:`directional` value, broadcast as its mask loop broadcasts it, plus the band's
        walls on the creases."""
        b, eta = self._b, self._eta
        if eta.ndim == 0:
            out = directional(kind, b.springs, eta, self._support, b.coupon)
        else:
            v = assembly_directional(kind, b.springs, float(eta[j]), self._support, b.coupon)
            shape = np.broadcast_shapes(
                np.shape(b.springs[0].K_S), np.shape(b.springs[1].K_S), eta.shape
            )
            # evaluate's np.where(eta == e, v, out) puts v in column j as it broadcasts
            out = np.broadcast_to(np.asarray(v, dtype=np.float64), shape)
        if self._joint != "none":
            D_w, K_w = self._band()
            out = np.asarray(out + (D_w if kind == "D" else K_w))
        return np.array(out[:, j] if eta.ndim else out[:, 0], dtype=np.float64)  # a copy

    def _span(self, j: int) -> FloatArray:
        span = self._b.span
        return np.asarray(span[:, j] if self._eta.ndim else span[:, 0])

    def _band(self) -> tuple[Any, Any]:
        """The band's walls' D_w (N mm) and K_w (N/mm) on the creases, 0 off them, over the
        points and directions (as :func:`evaluate` adds them)."""
        if self._walls is None:
            l1, b = self._layer1, self._b
            D_w, _, K_w = band_walls(l1.E, l1.nu, l1.t, b.thickness, b.span)
            on = _on_creases(self._eta)
            self._walls = (np.where(on, D_w, 0.0), np.where(on, K_w, 0.0))
        return self._walls


@dataclass(frozen=True, slots=True)
class DirectionalStiffness:
    """Stiffness of the assembly in the direction eta (deg, from layer 1's creases)."""

    eta_deg: float
    K: float  # N/mm
    D: float  # N mm
    EI: float  # N mm^2
    span: float  # mm, the length EI = D x span is taken over

    def as_dict(self) -> dict[str, float]:
        return {
            "eta_deg": self.eta_deg,
            "K_N_per_mm": self.K,
            "D_Nmm": self.D,
            "EI_Nmm2": self.EI,
            "span_mm": self.span,
        }


@dataclass(frozen=True, slots=True)
class Analysis:
    """Everything known about one design under one model."""

    assembly: Assembly
    model: str
    support: str
    moduli: tuple[Moduli, Moduli]
    springs: tuple[LayerSprings, LayerSprings]
    stiffness: tuple[DirectionalStiffness, ...]
    mass: MassBreakdown
    warnings: tuple[ModelWarning, ...]
    joint: str = "none"

    def __repr__(self) -> str:
        """Five lines at most (:func:`corrugate.analysis.display.analysis_repr`)."""
        from corrugate.analysis.display import analysis_repr

        return analysis_repr(self)

    def _repr_html_(self) -> str:
        from corrugate.analysis.display import analysis_html

        return analysis_html(self)

    @property
    def buckling(self) -> tuple[BucklingEstimate, ...]:
        """Bounds (N) on the in-plane compressive load along 0 and 90 deg at which the end
        facets buckle (:mod:`corrugate.mechanics.buckling`); empty for layouts other than a square or a
        rectangle."""
        found = (buckling_bounds(self.assembly, self.springs, e) for e in (0.0, 90.0))
        return tuple(b for b in found if b is not None)

    @property
    def L(self) -> float | None:
        """Side of a square (or diameter of a circle) layout (mm); None for other layouts."""
        a = self.assembly
        return a.Lx if a.layout.equal_sides else None

    def to_dict(self) -> dict[str, object]:
        """The JSON object of ``corrugate analyze --json`` (keys carry units)."""
        a = self.assembly
        layers = []
        for i, (layer, m, sp) in enumerate(zip(a.layers, self.moduli, self.springs, strict=True)):
            layers.append(
                {
                    "index": i + 1,
                    "W_mm": layer.W,
                    "n": layer.n,
                    "alpha_deg": layer.alpha_deg,
                    "material": layer.material.id,
                    "t_mm": layer.t,
                    "pitch_mm": layer.pitch,
                    "height_mm": layer.height,
                    "flat_size_mm": [layer.flat_width, float(np.max(a.facet_lengths(i + 1)))],
                    "moduli_MPa": m.as_dict(),
                    "springs": {
                        "K_C_N_per_mm": float(sp.K_C),
                        "K_S_N_per_mm": float(sp.K_S),
                        "D_C_Nmm": float(sp.D_C),
                        "D_S_Nmm": float(sp.D_S),
                    },
                }
            )
        return {
            "model": self.model,
            "model_source": get_model(self.model).source,
            "support": self.support,
            "joint": self.joint,
            "layout": a.layout.describe(),
            "layers": layers,
            "L_mm": self.L,
            "extent_x_mm": a.Lx,
            "extent_y_mm": a.Ly,
            "thickness_mm": a.thickness,
            "mass_g": self.mass.total,
            "mass_breakdown_g": self.mass.as_dict(),
            "stiffness": [s.as_dict() for s in self.stiffness],
            "buckling": [b.as_dict() for b in self.buckling],
            "warnings": [w.as_dict() for w in self.warnings],
        }


def analyze(
    assembly: Assembly,
    model: str = DEFAULT_MODEL,
    eta_deg: Sequence[float] = (0.0, 90.0),
    fabrication: FabricationOptions = DEFAULT_FABRICATION,
    support: str = DEFAULT_SUPPORT,
    joint: str = "none",
) -> Analysis:
    """Analyse ``assembly`` with moduli variant ``model`` at the directions ``eta_deg`` (deg),
    its sides ``free`` (default), held in a rigid ``frame`` (:mod:`corrugate.mechanics.offaxis`)
    or under any other registered support condition (:mod:`corrugate.mechanics.behaviours`),
    its layers joined by ``joint`` (``none``: the band left out; ``band-edges``,
    ``band-flanges``: its walls added along the creases, :func:`evaluate`).

    Returns moduli (MPa) and springs of each layer, K (N/mm), D (N mm) and EI (N mm^2) at each eta,
    the mass (g; layers and connector band) and the model's warnings. Example::

        >>> from corrugate import Assembly, Layer, analyze, get_material
        >>> layer = Layer(W=8, n=8, alpha_deg=84, material=get_material("dura-lar"))
        >>> r = analyze(Assembly.identical(layer), model="paper", eta_deg=[0])
        >>> round(r.stiffness[0].EI / 1000, 2)  # mN m^2, the paper's Table 1, case 1
        87.84
    """
    from corrugate.core.errors import ResultError
    from corrugate.core.limits import require_finite

    # A design at the edge of LIMITS (alpha 1e-200 deg) may overflow: the overflow is caught here
    # and the non-finite results by require_finite, so no numpy warning reaches the user.
    with np.errstate(all="ignore"):
        try:
            result = _analysis(assembly, model, eta_deg, fabrication, support, joint)
        except (OverflowError, ZeroDivisionError):
            raise ResultError(
                "result overflows: the inputs are outside the range the models can evaluate"
            ) from None
        require_finite(result.to_dict(), "result")  # NaN or infinity is never printed
    return result


def _analysis(
    assembly: Assembly,
    model: str,
    eta_deg: Sequence[float],
    fabrication: FabricationOptions,
    support: str,
    joint: str = "none",
) -> Analysis:
    """The body of :func:`analyze` (its results may still be non-finite)."""
    from corrugate.mechanics.load_cases import JOINTS

    if joint not in JOINTS:
        from corrugate.core.errors import UnknownNameError

        raise UnknownNameError("joint", joint, list(JOINTS))
    if joint != "none" and assembly.layout.name not in ("square", "rectangle"):
        from corrugate.core.errors import InputError

        raise InputError(
            "joint",
            repr(joint),
            "'none' for a layout other than a square or rectangle",
            reason="has no model for a curved band",
        )
    variant = get_model(model)
    model = variant.name
    for i, layer in enumerate(assembly.layers):
        variant.check_nu(layer.material.nu, "nu" if i == 0 else "nu2")
    support = check_support(support)
    etas = np.asarray(list(eta_deg), dtype=np.float64)
    a = assembly
    ev = evaluate(
        LayerArrays.of(a.layer1),
        LayerArrays.of(a.layer2),
        a.layout,
        model,
        etas,
        fabrication,
        support,
        joint,
    )
    span = a.layout.span(np.asarray(a.Lx), np.asarray(a.Ly), etas)
    stiffness = tuple(
        DirectionalStiffness(float(e), float(k), float(d), float(ei), float(sp))
        for e, k, d, ei, sp in zip(etas, ev.K, ev.D, ev.EI, span, strict=True)
    )
    result = Analysis(
        assembly=a,
        model=model,
        support=support,
        moduli=ev.moduli,
        springs=ev.springs,
        stiffness=stiffness,
        mass=assembly_mass(a, fabrication),
        warnings=tuple(design_warnings(a, model, [float(e) for e in etas], support)),
        joint=joint,
    )
    return result


def facet_buckling_load(
    assembly: Assembly, eta_deg: float = 0.0, model: str = "refined"
) -> BucklingEstimate:
    """The plate-theory bounds (N) on the compression load at which the end facets of
    ``assembly`` buckle along ``eta_deg`` (:func:`corrugate.mechanics.buckling.buckling_bounds` with the
    springs of ``model``); an :class:`InputError` where the bounds do not apply (a layout other
    than a square or rectangle, eta other than 0 or 90 deg)."""
    b = buckling_bounds(assembly, analyze(assembly, model, [eta_deg]).springs, eta_deg)
    if b is None:
        if assembly.layout.name not in ("square", "rectangle"):
            raise InputError("layout", assembly.layout.name, "square or rectangle")
        raise InputError("eta", f"{eta_deg:g} deg", "0 or 90 deg (along a layer's creases)")
    return b
