"""Will it hold? The peak stress in the facets of a panel under a load, and its margin.

The stiffness models (docs/theory.md 3) say how far a panel deflects; this module says how hard
its sheet is worked, so that the stress can be set against the material's allowable stress
(:attr:`corrugate.materials.library.Material.yield_strength`). Derivations: docs/theory.md
section 9 ("Strength"); the check against shell FE: docs/validation/strength.md.

Every function is plain arithmetic on floats or NumPy arrays (they broadcast). Units: lengths in
mm, forces in N, moments in N mm, moduli and stresses in MPa (N/mm^2), angles in degrees.
Notation as in docs/theory.md 2: a layer of n creases has n + 1 facets of flat width W and
thickness t, folded to the interior angle alpha; s = sin(alpha/2), c = cos(alpha/2), pitch
p = W s, height h = W c (crease line to crease line, mid-surface), all from the layer's
cross-section, :class:`corrugate.geometry.profile.ZigZag`.

**One layer** (the four closed forms; "width" is the layer's extent along its creases, i.e. the
length of its facets, and the span of a load along the creases is that same length):

* bent along its creases by M (:func:`spanwise_bending_stress`): the layer is a beam whose cross
  section is the zig-zag; sigma = E M (h + t) / (2 EI_S) at the crease lines, with
  EI_S = E (n + 1) W t (h^2 + t^2 s^2) / 12 = D_S x L (:func:`spanwise_rigidity`);
* bent across its creases by M (:func:`chordwise_bending_stress`): every facet carries the same
  plate moment m = M / width, so sigma = 6 M / (width t^2), the same on every facet and along
  it (under a moment that varies along the chord it is largest at the crease nearest the
  largest moment);
* compressed (or pulled) along its creases by P (:func:`spanwise_compression_stress`): every
  facet strains alike, sigma = P / ((n + 1) W t);
* compressed across its creases by P (:func:`chordwise_compression_stress`): the zig-zag is a
  chain of inclined plates whose force line runs at mid-depth, so each crease carries the plate
  moment q h / 2 with q = P / width: sigma = q (3 h / t^2 + s / t) at the creases.

**The assembly** (two layers stacked orthogonally, loaded along a crease direction eta = 0 or 90
deg): the layers act in parallel (same deflection, docs/theory.md 3.3), so a moment or a force
is shared in proportion to their stiffnesses: in bending EI_S of the layer whose creases run
along eta and EI_C of the other (:func:`peak_stress_bending`); in compression K_S and K_C
(:func:`peak_stress_compression`). The moments of the bench tests for a load P over a span Ls:
:func:`bending_moment` (read from each load case's form). The margin: :func:`stress_margin`.

Against the shell FE in 3-point bending (docs/validation/strength.md, three designs, 2/4/8
elements per facet), between 1/8 and 3/8 of the span the peak of the layer bent along its creases
is 0.965-0.993 of the FE's at 8 elements per facet (on a crease line, as modelled); the membrane
stress under platens is exact; the layer loaded across its creases is underestimated (0.65-0.88 of
the FE in bending, 0.73-0.75 in compression) but carries a few per cent of the peak.

What the closed forms leave out (docs/theory.md 9.5): stress concentrations at the load and
support lines (the FE's peak under a rigid line load is well above the beam stress), the
connectors, buckling (:mod:`corrugate.mechanics.buckling`, usually first in compression),
fatigue of the creases and the plastic hinge a crease already is after folding.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Any

import numpy as np
from numpy.typing import ArrayLike

from corrugate.core.errors import InputError
from corrugate.geometry.layer import require_zigzag
from corrugate.geometry.profile import ZigZag
from corrugate.mechanics.moduli import MODELS

__all__ = [
    "LayerSection",
    "PeakStress",
    "assembly_sections",
    "bending_moment",
    "chordwise_bending_stress",
    "chordwise_compression_stress",
    "chordwise_rigidity",
    "chordwise_stiffness",
    "peak_stress_bending",
    "peak_stress_compression",
    "spanwise_bending_stress",
    "spanwise_compression_stress",
    "spanwise_rigidity",
    "spanwise_stiffness",
    "stress_margin",
]


#: The moduli variant the strength formulas use (Xia 2012 with Ye et al.'s spanwise bending).
_REFINED = MODELS["refined"]


def _zigzag(W: ArrayLike, alpha_deg: ArrayLike) -> ZigZag:
    """The layer's cross-section (:class:`corrugate.geometry.profile.ZigZag`) from W (mm) and
    alpha (deg) as float64 arrays: s = sin(alpha/2), c = cos(alpha/2), p = W s, h = W c."""
    return ZigZag.of(np.asarray(W, dtype=np.float64), np.asarray(alpha_deg, dtype=np.float64))


def _out(x: Any) -> Any:
    """A 0-d result as a Python float, an array as it is."""
    a = np.asarray(x, dtype=np.float64)
    return float(a) if a.ndim == 0 else a


# --- one layer: rigidities and stiffnesses -------------------------------------------------


def spanwise_rigidity(
    E: ArrayLike, t: ArrayLike, W: ArrayLike, n: ArrayLike, alpha_deg: ArrayLike
) -> Any:
    """Flexural rigidity EI_S (N mm^2) of a layer bent along its creases: the zig-zag section.

    Each of the n + 1 facets is a strip of width W and thickness t inclined so that it rises by
    h = W c over its width; its centroid is at mid-depth h/2, which is therefore the neutral axis
    of the whole section (every facet is symmetric about it, whatever n). Its second moment about
    that axis is W t (W^2 c^2 + t^2 s^2) / 12 (the rotated rectangle: W^3 t / 12 times c^2 plus
    W t^3 / 12 times s^2), so

        EI_S = E (n + 1) W t (h^2 + t^2 s^2) / 12.

    This is the refined spanwise spring of docs/theory.md 3.2 times the facet length: D_S L =
    (n + 1) Eby t^3 p / 12 with Eby = E (s + W^2 c^2 / (t^2 s)) and p = W s gives the same
    expression. E (not E / (1 - nu^2)): the facets contract freely across their width."""
    z = _zigzag(W, alpha_deg)
    t_ = np.asarray(t, dtype=np.float64)
    return _out(np.asarray(E) * (np.asarray(n) + 1) * z.W * t_ * z.section_depth2(t_) / 12.0)


def chordwise_rigidity(
    E: ArrayLike, nu: ArrayLike, t: ArrayLike, W: ArrayLike, alpha_deg: ArrayLike, width: ArrayLike
) -> Any:
    """Flexural rigidity EI_C (N mm^2) of a layer of facet length ``width`` (mm) bent across its
    creases: the chordwise spring of docs/theory.md 3.2, D_C = 1 / sum_j 12 p / (Ebx L_j t^3)
    with every L_j = width, times the chordwise span (n + 1) p:

        EI_C = D_C (n + 1) p = Ebx width t^3 / 12,

    the equivalent plate of modulus Ebx (refined = Xia 2012; for thin sheets Ebx -> E s /
    (1 - nu^2), the facets as plates in series). Independent of n."""
    m = _REFINED.of_profile(
        np.asarray(E, np.float64),
        np.asarray(nu, np.float64),
        np.asarray(t, np.float64),
        _zigzag(W, alpha_deg),
    )
    t_ = np.asarray(t, dtype=np.float64)
    return _out(m.Ebx * np.asarray(width) * t_**3 / 12.0)


def spanwise_stiffness(
    E: ArrayLike, t: ArrayLike, W: ArrayLike, n: ArrayLike, length: ArrayLike
) -> Any:
    """In-plane spring K_S (N/mm) of a layer compressed along its creases over its facet length
    ``length`` (mm): the n + 1 facets in parallel, K_S = E (n + 1) W t / length (docs/theory.md
    3.2 with Ecy = E / s and p = W s)."""
    return _out(
        np.asarray(E) * (np.asarray(n) + 1) * np.asarray(W) * np.asarray(t) / np.asarray(length)
    )


def chordwise_stiffness(
    E: ArrayLike,
    nu: ArrayLike,
    t: ArrayLike,
    W: ArrayLike,
    n: ArrayLike,
    alpha_deg: ArrayLike,
    width: ArrayLike,
) -> Any:
    """In-plane spring K_C (N/mm) of a layer of facet length ``width`` (mm) compressed across its
    creases: K_C = Ecx t width / ((n + 1) p) (docs/theory.md 3.2, refined = Xia Ecx)."""
    z = _zigzag(W, alpha_deg)
    E_, t_ = (np.asarray(x, np.float64) for x in (E, t))
    m = _REFINED.of_profile(E_, np.asarray(nu, np.float64), t_, z)
    # (n + 1) p evaluated as ((n + 1) W) s
    return _out(m.Ecx * t_ * np.asarray(width) / (z.flat_width(np.asarray(n)) * z.s))


# --- one layer: peak stresses --------------------------------------------------------------


def spanwise_bending_stress(
    E: ArrayLike, t: ArrayLike, W: ArrayLike, n: ArrayLike, alpha_deg: ArrayLike, M: ArrayLike
) -> Any:
    """Peak stress (MPa) of a layer bent along its creases by its share M (N mm) of a moment.

    Beam theory on the zig-zag section (:func:`spanwise_rigidity`): the curvature is M / EI_S and
    the strain along the creases E-independent, eps = z M / EI_S at the height z from the neutral
    axis (mid-depth). The fibres furthest from it are the sheet's outer surfaces at the crease
    lines, z = h/2 + t/2 (the mid-surface of a crease is h/2 away; the shell's surface there is
    (t/2) s higher, at most t/2), so

        sigma = E M (h + t) / (2 EI_S)        (tension on one side, compression on the other).

    Membrane and bending of the facets together: a facet's own bending across its width and its
    in-plane bending are both in this linear strain field. Flat limit (alpha -> 180 deg, h -> 0):
    EI_S -> E b t^3 / 12 with b = (n + 1) W, and sigma -> 6 M / (b t^2), the plate formula."""
    h = _zigzag(W, alpha_deg).height
    EI = spanwise_rigidity(E, t, W, n, alpha_deg)
    return _out(np.asarray(E) * np.asarray(M) * (h + np.asarray(t)) / (2.0 * np.asarray(EI)))


def chordwise_bending_stress(t: ArrayLike, width: ArrayLike, M: ArrayLike) -> Any:
    """Peak stress (MPa) of a layer of facet length ``width`` (mm) bent across its creases by its
    share M (N mm) of a moment: sigma = 6 M / (width t^2).

    The moment vector lies along the creases, hence in the plane of every facet: a pure moment
    passes through the chain of facets unchanged, each facet carrying the plate moment
    m = M / width (N mm per mm) and no membrane force. The plate's surface stress is 6 m / t^2
    (with D = E t^3 / (12 (1 - nu^2)) the curvature is m / D and the surface stress
    E / (1 - nu^2) (t / 2) m / D = 6 m / t^2, whatever E and nu). That is the chordwise spring's
    own model (docs/theory.md 3.2): D_C = facets of bending stiffness D in series, Ebx -> E s /
    (1 - nu^2). The stress is the same along the facet; with a moment that varies along the
    chord it is largest at the crease nearest the largest moment."""
    t_ = np.asarray(t, dtype=np.float64)
    return _out(6.0 * np.asarray(M) / (np.asarray(width) * t_ * t_))


def spanwise_compression_stress(t: ArrayLike, W: ArrayLike, n: ArrayLike, P: ArrayLike) -> Any:
    """Membrane stress (MPa) of a layer loaded along its creases by its share P (N) of a platen
    force: rigid platens give every facet the same strain, so every facet carries the same stress
    over the section of the n + 1 facets, sigma = P / ((n + 1) W t). Compressive for a platen
    load; the end facets buckle long before a thin sheet yields (:mod:`corrugate.mechanics.
    buckling`), so set this against the buckling stress too."""
    return _out(np.asarray(P) / ((np.asarray(n) + 1) * np.asarray(W) * np.asarray(t)))


def chordwise_compression_stress(
    t: ArrayLike, W: ArrayLike, alpha_deg: ArrayLike, width: ArrayLike, P: ArrayLike
) -> Any:
    """Peak stress (MPa) at the creases of a layer of facet length ``width`` (mm) loaded across
    its creases by its share P (N) of a platen force.

    With q = P / width (N/mm), the zig-zag is a chain of facets; by the periodicity of the chain
    (and the platens, which hold the end facets against rotation: the compression fixture of
    docs/fea.md) the force line runs at mid-depth h/2, so at the height z a facet carries the
    plate moment q (z - h/2): zero at mid-facet, q h / 2 at the creases, with the membrane force q s (the
    component of q along the facet, whose direction is (s, c)). Peak:

        sigma = 6 (q h / 2) / t^2 + q s / t = q (3 h / t^2 + s / t).

    This is the model behind Ecx: the strain energy q^2 c^2 W^3 / (24 D) of one facet gives the
    chordwise compliance p / (Ecx t) with Ecx = E t^2 s / ((1 - nu^2) W^2 c^2), the thin-sheet
    limit of docs/theory.md 3.1."""
    z = _zigzag(W, alpha_deg)
    t_ = np.asarray(t, dtype=np.float64)
    q = np.asarray(P) / np.asarray(width)
    return _out(q * (3.0 * z.height / (t_ * t_) + z.s / t_))


# --- the assembly ---------------------------------------------------------------------------


@dataclass(frozen=True, slots=True)
class LayerSection:
    """One layer's sheet and folding for the strength formulas: E (MPa), nu, t (mm), W (mm), n
    creases, alpha_deg (deg)."""

    E: float
    nu: float
    t: float
    W: float
    n: int
    alpha_deg: float

    @classmethod
    def from_layer(cls, layer: Any) -> LayerSection:
        """From a :class:`corrugate.geometry.layer.Layer` folded to the zig-zag (these closed
        forms are its; another profile's layer is refused in one line,
        :func:`corrugate.geometry.layer.require_zigzag`)."""
        require_zigzag(layer, "strength closed forms")
        m = layer.material
        return cls(
            float(m.E),
            float(m.nu),
            float(layer.t),
            float(layer.W),
            int(layer.n),
            float(layer.alpha_deg),
        )

    @property
    def chord_extent(self) -> float:
        """(n + 1) W sin(alpha/2) (mm): the other layer's facet length in a rectangle (evaluated
        as ((n + 1) W) s)."""
        z = ZigZag.of_float(self.W, self.alpha_deg)
        return z.flat_width(self.n) * z.s  # type: ignore[no-any-return]

    def check(self, label: str) -> None:
        """:class:`InputError` unless every field is a positive, normal number, 0 < alpha <
        180 deg and -1 < nu < 0.5 (the ranges of :data:`corrugate.core.limits.LIMITS`)."""
        from corrugate.core.limits import check, check_count

        check("E", self.E, f"{label}.E")
        check("nu", self.nu, f"{label}.nu")
        check("thickness", self.t, f"{label}.t")
        check("W", self.W, f"{label}.W")
        check_count("n", self.n, f"{label}.n")
        check("alpha", self.alpha_deg, f"{label}.alpha")


def assembly_sections(assembly: Any) -> tuple[LayerSection, LayerSection, tuple[float, float]]:
    """The two :class:`LayerSection` of a :class:`corrugate.geometry.layer.Assembly` and its facet
    lengths (L_1, L_2) = (Ly, Lx) (mm), the arguments of :func:`peak_stress_bending` and
    :func:`peak_stress_compression`. Exact for the rectangular layouts (square, rectangle); any
    other outline is taken as its bounding box (its facets are shorter, not modelled here)."""
    a = assembly
    return (
        LayerSection.from_layer(a.layer1),
        LayerSection.from_layer(a.layer2),
        (float(a.Ly), float(a.Lx)),
    )


@dataclass(frozen=True, slots=True)
class PeakStress:
    """The peak facet stress of an assembly under one load: ``sigma`` (MPa, magnitude) in
    ``layer`` (1 or 2) ``where`` (a phrase: "crease lines, outer surfaces", ...); each layer's
    peak (``layer_sigma``, MPa) and its share of the load (``shares``: N mm in bending, N in
    compression; they add up to the load)."""

    sigma: float
    layer: int
    where: str
    layer_sigma: tuple[float, float]
    shares: tuple[float, float]

    def as_dict(self) -> dict[str, Any]:
        return {
            "sigma_MPa": self.sigma,
            "layer": self.layer,
            "where": self.where,
            "layer_sigma_MPa": list(self.layer_sigma),
            "shares": list(self.shares),
        }


def _along(eta_deg: float) -> int:
    """0 if eta runs along layer 1's creases, 1 if along layer 2's; InputError otherwise."""
    from corrugate.geometry.layer import crease_layer

    if not math.isfinite(eta_deg):
        raise InputError(
            "eta", f"{eta_deg!r}", "0 or 90 deg (a crease direction)", reason="is not finite"
        )
    k = crease_layer(eta_deg)
    if k is None:
        raise InputError(
            "eta",
            f"{eta_deg:g} deg",
            "0 or 90 deg (along one layer's creases; off-axis stresses are not modelled)",
        )
    return k


def _lengths(
    layers: tuple[LayerSection, LayerSection], lengths: tuple[float, float] | None
) -> tuple[float, float]:
    """Facet lengths (mm) of layers 1 and 2: given, or those of a rectangle (each layer's facets
    span the other layer's chord extent: L_1 = Ly, L_2 = Lx)."""
    if lengths is not None:
        from corrugate.core.limits import check

        return (check("length", lengths[0], "length1"), check("length", lengths[1], "length2"))
    return (layers[1].chord_extent, layers[0].chord_extent)


def _shares(total: float, a: float, b: float) -> tuple[float, float]:
    """``total`` split in proportion to the stiffnesses a and b (parallel springs: same
    deflection, force proportional to stiffness); the two shares add up to ``total``."""
    first = total * (a / (a + b))
    return first, total - first


def peak_stress_bending(
    layer1: LayerSection,
    layer2: LayerSection,
    M: float,
    eta_deg: float = 0.0,
    lengths: tuple[float, float] | None = None,
) -> PeakStress:
    """Peak facet stress (MPa) of the assembly bent by the moment M (N mm) about the axis across
    eta (the span along eta = 0 or 90 deg, i.e. along one layer's creases).

    The layer whose creases run along eta bends spanwise (EI_S, :func:`spanwise_rigidity`), the
    other chordwise (EI_C over its facet length, :func:`chordwise_rigidity`); both over the same
    span and to the same curvature, they share M as EI_S : EI_C (for the case study the chordwise
    layer takes about 0.2 %). ``lengths``: the facet lengths of layers 1 and 2 (default: a
    rectangle's, L_1 = Ly and L_2 = Lx). Returns the larger of the two layers' peaks."""
    layers = (layer1, layer2)
    for k, lay in enumerate(layers, start=1):
        lay.check(f"layer{k}")
    M = float(M)
    if not math.isfinite(M):
        raise InputError("M", f"{M!r}", "a finite moment in N mm", reason="is not finite")
    a = _along(float(eta_deg))
    b = 1 - a
    L = _lengths(layers, lengths)
    sa, sb = layers[a], layers[b]
    EI_a = spanwise_rigidity(sa.E, sa.t, sa.W, sa.n, sa.alpha_deg)
    EI_b = chordwise_rigidity(sb.E, sb.nu, sb.t, sb.W, sb.alpha_deg, L[b])
    Ma, Mb = _shares(M, EI_a, EI_b)
    sig_a = abs(spanwise_bending_stress(sa.E, sa.t, sa.W, sa.n, sa.alpha_deg, Ma))
    sig_b = abs(chordwise_bending_stress(sb.t, L[b], Mb))
    return _assemble(
        a,
        (sig_a, sig_b),
        (Ma, Mb),
        "crease lines, outer surfaces (bent along the creases)",
        "every facet, outer surfaces (bent across the creases)",
    )


def peak_stress_compression(
    layer1: LayerSection,
    layer2: LayerSection,
    P: float,
    eta_deg: float = 0.0,
    lengths: tuple[float, float] | None = None,
) -> PeakStress:
    """Peak facet stress (MPa) of the assembly between rigid platens pressed along eta = 0 or 90
    deg with the force P (N): the layer along eta carries K_S / (K_S + K_C) of P as membrane
    stress (:func:`spanwise_compression_stress`), the other the rest as crease bending
    (:func:`chordwise_compression_stress`). ``lengths`` as in :func:`peak_stress_bending`."""
    layers = (layer1, layer2)
    for k, lay in enumerate(layers, start=1):
        lay.check(f"layer{k}")
    P = float(P)
    if not math.isfinite(P):
        raise InputError("P", f"{P!r}", "a finite force in N", reason="is not finite")
    a = _along(float(eta_deg))
    b = 1 - a
    L = _lengths(layers, lengths)
    sa, sb = layers[a], layers[b]
    K_a = spanwise_stiffness(sa.E, sa.t, sa.W, sa.n, L[a])
    K_b = chordwise_stiffness(sb.E, sb.nu, sb.t, sb.W, sb.n, sb.alpha_deg, L[b])
    Pa, Pb = _shares(P, K_a, K_b)
    sig_a = abs(spanwise_compression_stress(sa.t, sa.W, sa.n, Pa))
    sig_b = abs(chordwise_compression_stress(sb.t, sb.W, sb.alpha_deg, L[b], Pb))
    return _assemble(
        a,
        (sig_a, sig_b),
        (Pa, Pb),
        "every facet (membrane, along the creases)",
        "crease lines, outer surfaces (across the creases)",
    )


def _assemble(
    a: int,
    sig: tuple[float, float],
    share: tuple[float, float],
    where_a: str,
    where_b: str,
) -> PeakStress:
    """A :class:`PeakStress` from the values of the layer along eta (index ``a``) and the other,
    put back in layer order."""
    by_layer = (sig[0], sig[1]) if a == 0 else (sig[1], sig[0])
    shares = (share[0], share[1]) if a == 0 else (share[1], share[0])
    where = (where_a, where_b) if a == 0 else (where_b, where_a)
    k = 0 if by_layer[0] >= by_layer[1] else 1
    return PeakStress(
        float(by_layer[k]),
        k + 1,
        where[k],
        (float(by_layer[0]), float(by_layer[1])),
        (float(shares[0]), float(shares[1])),
    )


def bending_moment(test: str, P: ArrayLike, span: ArrayLike) -> Any:
    """Peak bending moment (N mm) of a bench test with the load P (N) over the span Ls (mm),
    M = moment x P x Ls with the ``moment`` of the load case's form in the registry of
    behaviours (:mod:`corrugate.mechanics.load_cases`, docs/load_cases.md 6): three-point (P at
    mid-span) M = P Ls / 4, four-point (P/2 at each quarter point) M = P Ls / 8 between the
    loads, cantilever (P at the free end) M = P Ls at the clamp. ``test`` is a bending load
    case's name (the spec's, as every FE fixture is named)."""
    from corrugate.mechanics.behaviours import load_cases

    bending = {b.name: b.form for b in load_cases() if b.form and b.form.kind == "bending"}
    form = bending.get(test.strip().lower())
    if form is None:
        raise InputError("test", test, ", ".join(bending))
    return _out(form.moment * np.asarray(P, dtype=np.float64) * np.asarray(span, dtype=np.float64))


def stress_margin(sigma: ArrayLike, allowable: ArrayLike, safety_factor: ArrayLike = 1.0) -> Any:
    """Margin of safety allowable / (safety_factor x sigma) - 1 (dimensionless): >= 0 holds,
    < 0 fails; +inf for an unloaded part (sigma = 0). ``sigma`` and ``allowable`` in the same
    unit (MPa); sigma is taken by magnitude. :class:`InputError` for an allowable or a safety
    factor that is not positive and finite."""
    sf = np.asarray(safety_factor, dtype=np.float64)
    al = np.asarray(allowable, dtype=np.float64)
    if not (np.all(np.isfinite(sf)) and np.all(sf > 0)):
        raise InputError("safety_factor", f"{safety_factor!r}", "a finite number > 0")
    if not (np.all(np.isfinite(al)) and np.all(al > 0)):
        raise InputError("allowable", f"{allowable!r}", "a finite stress > 0 MPa")
    sig = np.abs(np.asarray(sigma, dtype=np.float64))
    with np.errstate(divide="ignore"):
        return _out(np.where(sig > 0, al / (sf * np.where(sig > 0, sig, 1.0)) - 1.0, np.inf))
