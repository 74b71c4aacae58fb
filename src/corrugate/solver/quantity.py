"""A quantity of a design that a constraint bounds or the objective optimises: a value.

A :class:`Quantity` is a ``kind`` with, for what depends on a direction, ``eta`` (deg from layer
1's creases), and for a stiffness the ``support`` condition it is taken under and room for a
``test`` (a load case; None today), both names in the registry of behaviours
(:mod:`corrugate.mechanics.behaviours`). The kinds (docs/theory.md sections 3-5):

* ``Lx``, ``Ly``: folded extents (mm), Lx = (n1 + 1) W1 sin(alpha1/2), Ly likewise for layer 2;
* ``thickness``: folded thickness t_d = W1 cos(alpha1/2) + W2 cos(alpha2/2) (mm);
* ``flat``: longest flat blank, max over layers of (n + 1) W (mm);
* ``facet``: longest facet, max over layers and facets of L_j (mm);
* ``mass``: g;
* ``EI`` (N mm^2), ``D`` (N mm), ``K`` (N/mm): stiffness at eta under a support condition
  (``free`` sides by default, a rigid ``frame``, :mod:`corrugate.mechanics.offaxis`);
* ``Pb``: lower bound (N) of the compressive load at which the end facets buckle along eta
  (0 or 90 deg; :mod:`corrugate.mechanics.buckling`);
* ``length``: the panel's length along eta (mm; the span of its stiffness, which must hold a
  load case's span);
* ``k``: P / delta (N/mm) of a load case (``test``: three-point, four-point, cantilever, platens;
  :mod:`corrugate.mechanics.load_cases`) over ``span`` (mm; None: the panel's length along eta).
  A load case also gives EI, D (bending tests) or K (platens) as its own formula reads them;
* ``Pmax``: the largest load (N) of a load case at which every layer's peak facet stress times
  the problem's safety factor stays at or below its material's yield strength (along the
  creases; :func:`corrugate.mechanics.load_cases.stress_per_load`).

Its :attr:`~Quantity.key` is the text the answer shows (``constraints[].quantity`` of ``corrugate
design --json`` and design.json): the kind, the support's key suffix (none for ``free``,
``frame`` for a frame) and the load case's, then ``@`` and eta, and a load case's span after
``/L=``, the hours of a sustained load after ``/t=`` and a load capacity's bearing width (mm)
after ``/b=``, e.g. ``EI@0``, ``Kframe@45``, ``Pb@90``, ``EI3pt@0``, ``k3pt@0/L=120``,
``Pmax3pt@0/b=5mm``;
:meth:`Quantity.parse` reads one back.
"""

from __future__ import annotations

from dataclasses import dataclass, field, replace

from corrugate.core.errors import InputError
from corrugate.mechanics.behaviours import (
    DEFAULT_SUPPORT,
    Behaviour,
    get_load_case,
    get_support,
    load_cases,
    supports,
)
from corrugate.names import STIFFNESS_SYMBOL, STIFFNESS_SYMBOLS

__all__ = [
    "CREASES",
    "FACET",
    "FLAT",
    "LX",
    "LY",
    "MASS",
    "PART_LONG",
    "PART_SHORT",
    "SPEC_KINDS",
    "STIFFNESS",
    "THICKNESS",
    "T_OVER_W",
    "W_MIN",
    "Quantity",
    "declare_kind",
]

#: Quantity kind of each stiffness a spec may bound (docs/theory.md 3.3).
SPEC_KINDS: dict[str, str] = {name: symbol for name, symbol in STIFFNESS_SYMBOL.items()}
#: The stiffness kinds, each taken under a support condition.
STIFFNESS: tuple[str, ...] = STIFFNESS_SYMBOLS

#: Readable name and internal unit of each kind (a behaviour's own ``units`` come first; a load
#: case may give a kind of its own, then named by its kind).
_KINDS: dict[str, tuple[str, str]] = {
    "Lx": ("folded extent Lx", "mm"),
    "Ly": ("folded extent Ly", "mm"),
    "thickness": ("folded thickness t_d", "mm"),
    "flat": ("flat blank (n + 1) W", "mm"),
    "facet": ("longest facet L_j", "mm"),
    "part_short": ("largest cut part's shorter side", "mm"),
    "part_long": ("largest cut part's longer side", "mm"),
    "W_min": ("narrowest facet W", "mm"),
    "t_over_W": ("sheet thickness over facet width t/W", ""),
    "creases": ("most creases n in a layer", ""),
    "mass": ("mass", "g"),
    "EI": ("flexural rigidity EI", "N*mm^2"),
    "D": ("bending stiffness D", "N*mm"),
    "K": ("in-plane stiffness K", "N/mm"),
    "Pb": ("buckling load Pb", "N"),
    "length": ("panel length L", "mm"),
    "k": ("load over deflection P/delta", "N/mm"),
    "Pmax": ("load capacity Pmax", "N"),
}

#: Words a kind's description ends with, after its direction, test and span (the label ends with
#: the symbol the direction is written on: ``load capacity Pmax(0 deg) as a cantilever over
#: 150 mm at the safety factor``, never ``... safety factor(0 deg)``).
_AFTER: dict[str, str] = {"Pb": " (a lower bound)", "Pmax": " at the safety factor"}


def declare_kind(kind: str, label: str, unit: str) -> None:
    """Name a new kind (its readable ``label`` and internal ``unit``), for a kind registered
    with the solver's evaluators (:func:`corrugate.solver.evaluator.register`)."""
    _KINDS[kind] = (label, unit)


@dataclass(frozen=True, slots=True)
class Quantity:
    """One quantity of a design (see the module docstring). ``eta`` is kept as its key shows it
    (12 significant digits), so two quantities are equal exactly when their keys are."""

    kind: str
    eta: float | None = None
    support: str | None = None
    test: str | None = None
    span: float | None = None
    duration: float | None = None  # hours of sustained load; None: short-term
    bearing: float | None = None  # mm, a load case's load and support lines; None: the default
    # the hash, once (the solver looks quantities up in dicts and sets in every iteration)
    _hash: int = field(default=0, init=False, repr=False, compare=False)

    def __post_init__(self) -> None:
        if self.eta is not None:
            object.__setattr__(self, "eta", float(f"{self.eta:.12g}"))
        if self.span is not None:
            object.__setattr__(self, "span", float(f"{self.span:.12g}"))
        if self.duration is not None:
            object.__setattr__(self, "duration", float(f"{self.duration:.12g}"))
        if self.bearing is not None:
            object.__setattr__(self, "bearing", float(f"{self.bearing:.12g}"))
        object.__setattr__(
            self,
            "_hash",
            hash(
                (
                    self.kind,
                    self.eta,
                    self.support,
                    self.test,
                    self.span,
                    self.duration,
                    self.bearing,
                )
            ),
        )

    def __hash__(self) -> int:
        return self._hash

    @classmethod
    def stiffness(cls, kind: str, eta_deg: float, support: str = DEFAULT_SUPPORT) -> Quantity:
        """A stiffness (``kind``: a spec name such as ``flexural_rigidity``, or EI, D, K) at
        ``eta_deg`` (deg) under ``support``."""
        k = SPEC_KINDS.get(kind, kind)
        if k not in STIFFNESS:
            raise InputError("kind", repr(kind), "one of " + ", ".join([*SPEC_KINDS, *STIFFNESS]))
        return cls(k, eta_deg, get_support(support).name)

    @classmethod
    def load_case(
        cls,
        kind: str,
        eta_deg: float,
        test: str,
        support: str = DEFAULT_SUPPORT,
        span: float | None = None,
    ) -> Quantity:
        """``kind`` (EI, D, K or k) of the load case ``test`` at ``eta_deg`` (deg) under
        ``support``, over ``span`` (mm; None: the panel's length along eta)."""
        t = get_load_case(test)
        if kind not in t.units:
            raise InputError("kind", repr(kind), "one of " + ", ".join(t.units))
        return cls(kind, eta_deg, get_support(support).name, t.name, span)

    @classmethod
    def parse(cls, key: str) -> Quantity:
        """The quantity whose :attr:`key` is ``key`` (e.g. ``Kframe@45``), over the behaviours
        registered now."""
        key, on, bearing_text = key.partition("/b=")
        if on:
            try:
                bearing = float(bearing_text.removesuffix("mm"))
            except ValueError:
                raise InputError(
                    "quantity", repr(key), "a quantity key such as Pmax3pt@0/b=10mm"
                ) from None
            return replace(cls.parse(key), bearing=bearing)
        key, held, hours_text = key.partition("/t=")
        duration = None
        if held:
            try:
                duration = float(hours_text.removesuffix("h"))
            except ValueError:
                raise InputError(
                    "quantity", repr(key), "a quantity key such as k3pt@0/L=120/t=168h"
                ) from None
            if not hours_text.endswith("h"):
                raise InputError("quantity", repr(key), "a quantity key such as EI@0/t=168h")
            base = cls.parse(key)
            if base.eta is None:
                raise InputError("quantity", repr(key), "a directional quantity such as EI@0")
            return replace(base, duration=duration)
        key, slash, span_text = key.partition("/L=")
        span = None
        if slash:
            try:
                span = float(span_text)
            except ValueError:
                raise InputError(
                    "quantity", repr(key), "a quantity key such as k3pt@0/L=120"
                ) from None
        head, at, eta = key.partition("@")
        if not at:
            if head not in _KINDS or head in STIFFNESS or head in ("Pb", "length", "k", "Pmax"):
                raise InputError("quantity", repr(key), "a quantity key such as mass or EI@0")
            return cls(head)
        if head in ("Pb", "length"):
            return cls(head, float(eta))
        for s in supports():
            for t in (None, *load_cases()):
                kinds = STIFFNESS if t is None else tuple(t.units)
                for kind in kinds:
                    if head == kind + s.suffix + ("" if t is None else t.suffix):
                        return cls(kind, float(eta), s.name, None if t is None else t.name, span)
        raise InputError("quantity", repr(key), "a quantity key such as mass or EI@0")

    @property
    def behaviour(self) -> Behaviour | None:
        """The entry that gives this quantity's value: its load case if it has one, else its
        support condition (None for a quantity that has neither)."""
        if self.test is not None:
            return get_load_case(self.test)
        return None if self.support is None else get_support(self.support)

    @property
    def key(self) -> str:
        """The text of the answer (module docstring), e.g. ``EI@0``, ``Kframe@45``, ``mass``."""
        if self.eta is None:
            return self.kind
        head = self.kind
        if self.support is not None:
            head += get_support(self.support).suffix
        if self.test is not None:
            head += get_load_case(self.test).suffix
        tail = "" if self.span is None else f"/L={self.span:.12g}"
        if self.duration is not None:
            tail += f"/t={self.duration:.12g}h"
        if self.bearing is not None:
            tail += f"/b={self.bearing:.12g}mm"
        return f"{head}@{self.eta:.12g}{tail}"

    @property
    def unit(self) -> str:
        """Internal unit (``mm``, ``g``, ``N*mm^2``, ``N*mm``, ``N/mm``, ``N``)."""
        b = self.behaviour
        if b is not None and self.kind in b.units:
            return b.unit(self.kind)
        return _KINDS[self.kind][1]

    @property
    def description(self) -> str:
        """A readable name, e.g. ``flexural rigidity EI(0 deg)``, ``in-plane stiffness K(45 deg)
        in a frame``, ``load over deflection P/delta(90 deg) as a cantilever over 150 mm``,
        ``load capacity Pmax(0 deg) in three-point bending at the safety factor``, ``mass``:
        the direction on the symbol the label ends with, then the support, the test, the span,
        the duration and the kind's closing words (:data:`_AFTER`)."""
        text = _KINDS[self.kind][0] if self.kind in _KINDS else self.kind
        if self.eta is not None:  # the direction on the symbol: EI(0 deg) in a frame over ...
            text += f"({self.eta:.12g} deg)"
        if self.support is not None:
            text += get_support(self.support).label
        if self.test is not None:
            text += get_load_case(self.test).label
        if self.span is not None:
            text += f" over {self.span:.12g} mm"
        if self.duration is not None:
            text += f" held {self.duration:.12g} h"
        return text + _AFTER.get(self.kind, "")

    @property
    def directional(self) -> bool:
        """Whether it depends on a direction (a stiffness or a buckling load: the quantities the
        solver bounds in interval arithmetic)."""
        return self.eta is not None

    def __str__(self) -> str:
        return self.key


#: The size and mass quantities.
LX = Quantity("Lx")
LY = Quantity("Ly")
THICKNESS = Quantity("thickness")
FLAT = Quantity("flat")
FACET = Quantity("facet")
MASS = Quantity("mass")
#: What a cutter and a pair of hands need (docs/fabrication.md, "What the solve asks of the
#: making"): the cut parts' sides (every part fits the machine's area, turned or not, iff the
#: largest shorter side fits its shorter side and the largest longer side its longer one), the
#: narrowest facet, the thickest sheet for its facet and the most creases of a layer.
PART_SHORT = Quantity("part_short")
PART_LONG = Quantity("part_long")
W_MIN = Quantity("W_min")
T_OVER_W = Quantity("t_over_W")
CREASES = Quantity("creases")
