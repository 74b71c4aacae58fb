"""The registry of behaviours: the support conditions (and load cases) a stiffness is asked under.

A :class:`Behaviour` is one entry that carries everything the layers above need of it:

* ``name``: the value a spec (``support = "frame"``), the command line and ``analyze`` take;
* ``model``: K (N/mm) or D (N mm) of the two-layer assembly at eta (deg) from the layers' springs
  (:class:`~corrugate.mechanics.springs.LayerSprings`), the value ``analyze`` reports (EI is D x
  span for every behaviour, docs/theory.md 3.3);
* ``bounds``: the same quantity over boxes of designs for the branch and bound, from springs that
  are :class:`~corrugate.solver.interval.Interval` values (plain arithmetic evaluated on
  intervals bounds itself, so it is usually ``model`` again);
* ``fixture``: the name of its finite-element fixture in :mod:`corrugate.fea.fixtures`, which
  ``corrugate verify`` and ``validate`` run (the spec's names: ``platens``, the free support's
  and the platens test's; ``frame``; ``three-point``, ``four-point``, ``cantilever``,
  ``wheel``);
* ``label`` (added to a quantity's readable name: ``in-plane stiffness K in a frame``), ``suffix``
  (added to its kind in quantity keys: ``Kframe@45``), ``units`` (each kind it gives, with its
  internal unit), ``text`` (its meaning in the spec reference), ``curve`` (its legend in the
  report's polar figure) and ``off_axis`` (the model warning off the crease directions);
* ``uses_coupon``: whether ``model`` reads the layout off the crease directions as a coupon
  (:class:`~corrugate.mechanics.offaxis.Coupon`; the free support does);
* ``crease_rule``: whether its K and D along the crease directions (eta 0 or 90 deg) are the
  paper's rule of the layers' springs (docs/theory.md 3.3; free sides and the frame), the terms
  the layer-by-layer search of independent layers sums (:mod:`corrugate.solver.separable`);
* for a load case, how the spec, its reference and the web page offer it: ``choice`` (its words
  in a list of choices, its name when empty: ``between platens``), ``note`` (its remark in the
  spec reference's lists of tests: ``in-plane compression``), ``layouts`` (the plan outlines it
  applies to; empty: every one) and ``stiffness_only`` (only a stiffness bound names it, never a
  deflection or strength bound: the wheel test, docs/load_cases.md 9).

``role`` says which slot of a quantity it fills: a ``support`` condition, or a ``test`` (a load
case: three-point, four-point, cantilever, platens; :mod:`corrugate.mechanics.load_cases`), whose
``form`` (:class:`TestForm`) turns the support's pure-bending D or in-plane K into what that test
measures.

The built-in supports live one per module in :mod:`corrugate.mechanics.supports` and are
registered there, each by one line, then the built-in load cases
(:data:`corrugate.mechanics.load_cases.BUILT_IN`); they are loaded on the first look-up. Adding a
support condition is a module defining its :class:`Behaviour` and one ``register`` line; adding a
load case is its entry in :mod:`corrugate.mechanics.load_cases` and its place in ``BUILT_IN``
(or, outside the package, one :func:`register` call). The spec's test choices
(:func:`deflection_tests`, :func:`load_cases`), its reference, the report's figures and the web
page's test menus read these entries.
"""

from __future__ import annotations

import threading
from collections.abc import Callable, Mapping
from dataclasses import dataclass
from types import MappingProxyType
from typing import Any, Final, Literal, Protocol

from corrugate.core.errors import InputError, UnknownNameError
from corrugate.names import DEFAULT_SUPPORT as _DEFAULT_SUPPORT

__all__ = [
    "DEFAULT_SUPPORT",
    "STIFFNESS_UNITS",
    "Behaviour",
    "DirectionalModel",
    "Role",
    "TestForm",
    "check_support",
    "deflection_tests",
    "either",
    "get_load_case",
    "get_support",
    "listed",
    "load_cases",
    "own_test",
    "register",
    "support_names",
    "supports",
    "unregister",
]

Role = Literal["support", "test"]

#: The support condition of every stiffness unless one is asked for (free sides: a bench test).
DEFAULT_SUPPORT: Final[str] = _DEFAULT_SUPPORT

#: The kinds a support condition gives, with their internal units: EI (N mm^2), D (N mm), K (N/mm).
STIFFNESS_UNITS: Mapping[str, str] = MappingProxyType({"EI": "N*mm^2", "D": "N*mm", "K": "N/mm"})


class DirectionalModel(Protocol):
    """``model(kind, springs, eta_deg, coupon)``: the assembly's ``kind`` (``"K"`` in N/mm or
    ``"D"`` in N mm) at ``eta_deg`` (deg from layer 1's creases) from the two layers' springs
    (arrays or intervals); ``coupon`` is the layout's coupon or None (a square, or a behaviour
    that does not read it)."""

    def __call__(self, kind: str, springs: tuple[Any, Any], eta_deg: float, coupon: Any) -> Any: ...


@dataclass(frozen=True, slots=True)
class TestForm:
    """What a load case measures (docs/load_cases.md, section 3): for a ``bending`` test the
    deflection under the load P over the span Ls,

        delta / P = a Ls^3 / EI + (b Ls + c h) / S

    with EI the pure-bending rigidity, S the transverse shear stiffness (N) and h the depth of
    the corrugation (mm), and ``euler`` the coefficient of the Euler-Bernoulli formula the test's
    apparent EI is read with (EI_app = euler Ls^3 P / delta; ``euler`` = a); for an ``inplane``
    test delta / P = 1 / (f(eta) K), with ``factor`` f the test's own factor at eta (deg; None:
    1, K itself; the wheel test's FE-validated c(eta), :mod:`corrugate.mechanics.wheel`)."""

    kind: Literal["bending", "inplane"]
    a: float = 0.0
    b: float = 0.0
    c: float = 0.0
    moment: float = 0.0  # the largest bending moment is moment x P x Ls (N mm)
    factor: Callable[[float], float] | None = None
    #: The report's sketch of a bending test: where its loads act (fractions of the span from
    #: the root), whether it is a cantilever (clamped at the root, the other end free: its span
    #: is the free length; else the panel rests on rollers at both ends) and its
    #: Euler-Bernoulli deflected shape w(x), x in [0, 1] of the span (any scale).
    loads: tuple[float, ...] = ()
    clamped: bool = False
    shape: Callable[[Any], Any] | None = None

    @property
    def own(self) -> bool:
        """Whether the test measures the support's own K (an in-plane test without a factor:
        platens), the meaning a K bound without a test has."""
        return self.kind == "inplane" and self.factor is None


@dataclass(frozen=True, eq=False)
class Behaviour:
    """One support condition or load case (see the module docstring for each field)."""

    name: str
    model: DirectionalModel
    bounds: DirectionalModel
    fixture: str
    label: str
    suffix: str
    units: Mapping[str, str]
    text: str
    curve: str
    off_axis: Callable[[str, str], str]
    uses_coupon: bool = False
    crease_rule: bool = False
    role: Role = "support"
    form: TestForm | None = None
    choice: str = ""
    note: str = ""
    layouts: tuple[str, ...] = ()
    stiffness_only: bool = False

    def unit(self, kind: str) -> str:
        """Internal unit of ``kind`` under this behaviour."""
        return self.units[kind]

    def in_list(self) -> str:
        """Its words in a list of choices: ``choice``, else its name."""
        return self.choice or self.name


_REGISTRY: dict[Role, dict[str, Behaviour]] = {"support": {}, "test": {}}
_lock = threading.RLock()
_loaded = False
_loading = False


def _entries(role: Role) -> dict[str, Behaviour]:
    """The entries of ``role`` in registration order, the built-ins loaded first (once, under a
    lock: the web app looks supports up from several threads)."""
    global _loaded, _loading
    if not _loaded:
        with _lock:
            if not _loaded and not _loading:  # _loading: the built-ins registering themselves
                _loading = True
                try:
                    import corrugate.mechanics.supports  # noqa: F401  (registers the built-ins)
                finally:
                    _loading = False
                _loaded = True
    return _REGISTRY[role]


def register(behaviour: Behaviour) -> Behaviour:
    """Add ``behaviour`` to the registry (after the built-ins) and return it; its name and its
    key suffix must be new in its role (so every quantity key reads back one way), and a load
    case may not read the coupon (the solver evaluates load cases on the layers' springs)."""
    with _lock:
        entries = _entries(behaviour.role)
        for other in entries.values():
            if other.name == behaviour.name or other.suffix == behaviour.suffix:
                raise InputError(
                    behaviour.role,
                    repr(behaviour.name),
                    f"a name and key suffix not yet registered (taken by {other.name!r})",
                    reason="is already registered",
                )
        if behaviour.role == "test" and behaviour.form is None:
            raise InputError("test", repr(behaviour.name), "a load case with a TestForm")
        if behaviour.role == "test" and behaviour.uses_coupon:
            raise InputError(
                "test", repr(behaviour.name), "a load case whose model needs no coupon"
            )
        entries[behaviour.name] = behaviour
    return behaviour


def unregister(name: str, role: Role = "support") -> None:
    """Remove the entry ``name`` of ``role`` (e.g. one a test registered)."""
    with _lock:
        _entries(role).pop(name)


def supports() -> tuple[Behaviour, ...]:
    """Every support condition, in registration order (the built-ins: free, frame)."""
    return tuple(_entries("support").values())


def support_names() -> tuple[str, ...]:
    """The names of :func:`supports`."""
    return tuple(_entries("support"))


def _get(role: Role, name: str, field: str) -> Behaviour:
    """The entry ``name`` of ``role``, else an error naming ``field`` and the names allowed."""
    entries = _entries(role)
    found = entries.get(name) if isinstance(name, str) else None
    if found is None:
        raise UnknownNameError(field, name, list(entries))
    return found


def get_support(name: str, field: str = "support") -> Behaviour:
    """The support condition ``name``, else an error naming ``field`` and the names allowed."""
    return _get("support", name, field)


def check_support(value: str, field: str = "support") -> str:
    """``value`` if it names a support condition, else an error naming ``field``."""
    return get_support(value, field).name


def load_cases() -> tuple[Behaviour, ...]:
    """Every load case (role ``test``), in registration order (the built-ins: three-point,
    four-point, cantilever, platens)."""
    return tuple(_entries("test").values())


def deflection_tests() -> tuple[Behaviour, ...]:
    """The load cases a deflection or strength bound may name (every one but the stiffness-only
    tests), in registration order (the built-ins: three-point, four-point, cantilever,
    platens)."""
    return tuple(b for b in _entries("test").values() if not b.stiffness_only)


def own_test() -> Behaviour:
    """The load case a K bound without a test is measured in: the first in-plane test whose
    value is the support's own K (:attr:`TestForm.own`; the built-in one: platens)."""
    return next(b for b in _entries("test").values() if b.form is not None and b.form.own)


def get_load_case(name: str) -> Behaviour:
    """The load case ``name``, else an error naming the ones registered."""
    return _get("test", name, "test")


def either(names: tuple[str, ...] | list[str]) -> str:
    """``'a' or 'b'``, ``'a', 'b' or 'c'``: the names quoted, as pydantic words a choice."""
    return listed([repr(n) for n in names])


def listed(items: list[str]) -> str:
    """``a or b``, ``a, b or c``: the items joined as a sentence offers a choice."""
    if len(items) < 2:
        return "".join(items)
    return ", ".join(items[:-1]) + " or " + items[-1]
