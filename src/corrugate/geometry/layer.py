"""Layers and assemblies: the design parameters and the folded geometry they imply.

A :class:`Layer` is one folded sheet: facet width W (mm), n creases (n + 1 facets), interior fold
angle alpha (deg), material and thickness t (mm), folded to a registered profile
(:class:`~corrugate.geometry.profile.ProfileKind`, the zig-zag unless another is named). An :class:`Assembly` is two layers stacked
orthogonally on a :mod:`layout <corrugate.geometry.layouts>`; the two layers may differ in every parameter.
"""

from __future__ import annotations

import math
import numbers
from dataclasses import dataclass, field
from typing import Any

import numpy as np
from numpy.typing import NDArray

from corrugate.core.errors import InputError
from corrugate.geometry.layouts import Layout, Square, facet_lengths
from corrugate.geometry.profile import ZIGZAG, ProfileKind, ZigZag
from corrugate.materials.library import Material

__all__ = ["Assembly", "FacetGeometry", "Layer", "crease_layer", "require_zigzag"]

#: Relative tolerance to which Lx and Ly must agree for a square or circular layout.
EQUAL_SIDES_RTOL = 1e-6


LIMITS_W = "0.01 <= W <= 10000 mm"
#: The default of :attr:`Layer.t`, "not given": this very object (a NaN of its own), so that a NaN
#: a user gives is refused as not finite instead of taken for "the material's default".
_DEFAULT_T = float("nan")


def crease_layer(eta_deg: float) -> int | None:
    """Index (0 or 1) of the layer whose creases run along the direction ``eta_deg`` (deg from
    layer 1's creases): 0 for eta = 0 mod 180 deg, 1 for eta = 90 mod 180 deg (to 1e-9 deg),
    None for every direction in between."""
    r = math.remainder(eta_deg, 180.0)  # in [-90, 90]
    if math.isclose(r, 0.0, abs_tol=1e-9):
        return 0
    if math.isclose(abs(r), 90.0, abs_tol=1e-9):
        return 1
    return None


class FacetGeometry:
    """Plan geometry of a zig-zag with facet width ``W`` (mm) and interior angle ``alpha_deg``:
    its :class:`~corrugate.geometry.profile.ZigZag` profile and, from it, s, c, the pitch p = W s
    and the height h = W c (docs/theory.md section 2). A mixin for the dataclasses that carry W and
    alpha_deg (a layer, a finite-element unit cell)."""

    __slots__ = ()
    W: float
    alpha_deg: float

    @property
    def profile(self) -> ZigZag:
        """The cross-section (:mod:`corrugate.geometry.profile`), in Python floats."""
        return ZigZag.of_float(self.W, self.alpha_deg)

    @property
    def s(self) -> float:
        """sin(alpha/2)."""
        return self.profile.s  # type: ignore[no-any-return]

    @property
    def c(self) -> float:
        """cos(alpha/2)."""
        return self.profile.c  # type: ignore[no-any-return]

    @property
    def pitch(self) -> float:
        """Plan width of one facet, p = W sin(alpha/2) (mm)."""
        return self.profile.pitch  # type: ignore[no-any-return]

    @property
    def height(self) -> float:
        """Corrugation height, h = W cos(alpha/2) (mm), crease line to crease line."""
        return self.profile.height  # type: ignore[no-any-return]


@dataclass(frozen=True, slots=True)
class Layer(FacetGeometry):
    """One corrugated layer.

    ``W``: flat facet width (mm, > 0); ``n``: number of creases (integer >= 1); ``alpha_deg``:
    interior angle between adjacent facets (0 < alpha < 180 deg, 180 = flat); ``t``: sheet
    thickness (mm, > 0; defaults to the material's default thickness); ``profile_kind``: the
    profile it is folded to (:class:`~corrugate.geometry.profile.ProfileKind`: a registered
    designable profile's name and fixed parameters; the zig-zag by default).
    """

    W: float
    n: int
    alpha_deg: float
    material: Material
    t: float = field(default=_DEFAULT_T)
    profile_kind: ProfileKind = ZIGZAG

    @property
    def profile(self) -> Any:
        """The cross-section (:mod:`corrugate.geometry.profile`) of the layer's profile kind, in
        Python floats."""
        return self.profile_kind.of_float(self.W, self.alpha_deg)

    def __post_init__(self) -> None:
        from corrugate.core.limits import check, check_count

        if not isinstance(self.W, numbers.Real):
            raise InputError("W", repr(self.W)[:60], LIMITS_W, reason="is not a number")
        check("W", self.W)
        check_count("n", self.n)
        object.__setattr__(self, "n", int(self.n))
        if not isinstance(self.alpha_deg, numbers.Real):
            raise InputError("alpha", repr(self.alpha_deg)[:60], "0 < alpha < 180 deg")
        check("alpha", self.alpha_deg)
        t = self.t
        if t is _DEFAULT_T:
            if self.material.default_thickness is None:
                raise InputError(
                    "thickness", None, "t > 0 mm", reason=f"is not given for {self.material.id}"
                )
            t = self.material.default_thickness
            object.__setattr__(self, "t", t)
        if not isinstance(t, numbers.Real):
            raise InputError("thickness", repr(t)[:60], "t > 0 mm", reason="is not a number")
        check("thickness", t)

    @property
    def chord_extent(self) -> float:
        """Folded length across the creases, (n + 1) p (mm)."""
        return self.profile.extent(self.n)  # type: ignore[no-any-return]

    @property
    def flat_width(self) -> float:
        """Flat blank width across the creases, (n + 1) developed ((n + 1) W for the zig-zag; mm)."""
        return self.profile.flat_width(self.n)  # type: ignore[no-any-return]

    @property
    def fold_angle_deg(self) -> float:
        """Dihedral fold angle used by origami tools, 180 deg - alpha."""
        return 180.0 - self.alpha_deg


def require_zigzag(layer: Layer, what: str) -> None:
    """An :class:`InputError` in one line (``profile = flat-crest has no fold pattern yet``)
    when ``layer`` is folded to another profile than the zig-zag: the flat pattern and the FE
    meshes are the zig-zag's (``what``: what the caller would make)."""
    if layer.profile_kind != ZIGZAG:
        raise InputError("profile", layer.profile_kind.name, "zig-zag", reason=f"has no {what} yet")


@dataclass(frozen=True, slots=True)
class Assembly:
    """Two layers assembled orthogonally on a layout.

    Layer 1's creases run along y and it spans Lx = (n1 + 1) p1 across them; layer 2's creases run
    along x and it spans Ly = (n2 + 1) p2. Square and circle layouts need Lx = Ly. The layout's
    holes must fit inside the outline (:func:`corrugate.geometry.holes.check_holes`).
    """

    layer1: Layer
    layer2: Layer
    layout: Layout = field(default_factory=Square)

    def __post_init__(self) -> None:
        Lx, Ly = self.Lx, self.Ly
        if self.layout.equal_sides and abs(Lx - Ly) > EQUAL_SIDES_RTOL * max(Lx, Ly):
            raise InputError(
                "layout",
                self.layout.name,
                "layers of equal folded extent (n + 1) W sin(alpha/2), or layout 'rectangle'",
                reason=f"needs Lx = Ly but layer 1 spans {Lx:.4g} mm and layer 2 {Ly:.4g} mm",
            )
        if self.layout.holes:
            from corrugate.geometry.holes import check_holes  # a layout with holes only

            check_holes(self.layout.holes, self.layout.plan_outline(Lx, Ly), Lx, Ly)

    @classmethod
    def identical(cls, layer: Layer, layout: Layout | None = None) -> Assembly:
        """Two identical layers (the paper's case)."""
        return cls(layer, layer, layout if layout is not None else Square())

    @property
    def layers(self) -> tuple[Layer, Layer]:
        return (self.layer1, self.layer2)

    @property
    def Lx(self) -> float:
        """Extent along x, across layer 1's creases (mm)."""
        return self.layer1.chord_extent

    @property
    def Ly(self) -> float:
        """Extent along y, across layer 2's creases (mm)."""
        return self.layer2.chord_extent

    @property
    def thickness(self) -> float:
        """Folded thickness t_d = W1 cos(alpha1/2) + W2 cos(alpha2/2) (mm), docs/theory.md section 2."""
        return self.layer1.height + self.layer2.height

    def facet_lengths(self, index: int) -> NDArray[np.float64]:
        """L_j (mm) of layer ``index`` (1 or 2), in order along its chordwise direction."""
        if index == 1:
            return facet_lengths(self.layout, self.layer1.n, self.Ly, "x")
        if index == 2:
            return facet_lengths(self.layout, self.layer2.n, self.Lx, "y")
        raise InputError("layer", index, "1 or 2")
