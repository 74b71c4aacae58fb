"""The FE twin of every behavioural constraint of a design: what ``corrugate verify`` runs.

A design's ``design.json`` lists its constraints (``constraints[]``: name, quantity key, sense,
bound, the model's value, unit). Each behavioural one (a stiffness K, D or EI, a load case's
P / delta or deflection, a buckling load) is checked in the FE fixture of the test it states
(:mod:`corrugate.fea.assembly`, the runs ``corrugate validate`` makes; the same function, the
same arguments, so the same numbers):

The twin is the fixture the quantity's behaviour names (:attr:`corrugate.mechanics.behaviours.
Behaviour.fixture`: the load case's, else the support condition's), looked up in
:mod:`corrugate.fea.fixtures`:

=========================================  =========================================================
constraint                                 FE twin
=========================================  =========================================================
K, free sides (no test, or ``platens``)    ``platens``: K between platens
K in a frame (a support with a fixture    the support's fixture: ``frame``, K_frame(eta) of two
of its own, not the free coupon's)         runs (:func:`corrugate.fea.frame.solve_frame`); no
                                           twin for its bending or a deflection
D, EI, no test (pure bending)              ``four-point``: the pure-bending gauge between load lines
D, EI, P / delta, ``three-point``          ``three-point``: P / delta under the load
D, EI, P / delta, ``four-point``           ``four-point``: P / delta at the load points
D, EI, P / delta, ``cantilever``           ``cantilever``: P / delta at the tip
Pb (buckling, eta 0 or 90)                 ``platens`` as a linear buckling run: the first
                                           buckling load
Pmax (a load capacity, eta 0 or 90)        its test's fixture as a linear buckling run: the
                                           first buckling load over the safety factor
circle: K, ``test = "wheel"``              ``wheel`` (:mod:`corrugate.fea.outline`): the
                                           model's test (docs/load_cases.md 9)
circle: K, free sides (no test, platens)   ``wheel``: not the model's test, the row says so
circle: D, EI                              none (the row says why)
polygon at eta 0 or 90                     the rows above on the polygon cut from its box
=========================================  =========================================================

A bending test's D and EI are read as the test's own formula reads P / delta over the panel's
length (:func:`corrugate.mechanics.load_cases.apparent`), a deflection bound as load / (P /
delta). Each twin runs on a mesh series (elements per facet, default 2 / 4 / 8), refined
until it is shown asymptotic against its bound or ``max_mesh`` is reached
(:func:`corrugate.fea.extrapolate.judge`); each row's verdict is one of :data:`VERDICTS`
(holds, fails, not converged, not checked; docs/fea.md 6). A span shorter than the panel along a
crease direction runs with the supports (the clamp) inside the panel, the ends overhanging
(:func:`corrugate.fea.assembly.assembly_deck`). What has no FE twin yet says so in its row and
is not checked: a span longer than the panel or off the crease directions, D or EI in a frame, EI or a bending test's P / delta off the crease directions (the
coupon has its own span), load capacities off the crease directions, and the band joint off
the crease directions or in a frame.

Off the crease directions the coupon (:func:`corrugate.fea.shells.oblique_shells`) holds a
whole number of facets, and which ones depends on where it is cut: its FE value depends on the
position (docs/load_cases.md 5: 7-8 % in 3-point bending at 15 deg). The twin therefore runs at
several coupon positions, ``shifts`` (fractions of each layer's pitch, default 0, 1/4, 1/2, 3/4:
the distinct positions up to turning a layer over are 0 <= shift < 1, sampled evenly), and the
value that counts is the worst one (the least stiff for a minimum bound, the largest deflection
for a maximum); the row names that shift and every shift's value (docs/fea.md 6).
"""

from __future__ import annotations

import math
from collections.abc import Callable, Generator, Hashable, Mapping, Sequence
from concurrent.futures import Executor
from dataclasses import dataclass, field, replace
from pathlib import Path
from typing import TYPE_CHECKING, Any, TypeVar

from corrugate.core.errors import CorrugateError, InputError
from corrugate.core.text import foreign_digits
from corrugate.fea.assembly import (
    AssemblyMesh,
    AssemblyResult,
    Bond,
    principal_axis,
    solve_assembly,
)
from corrugate.fea.calibrated import certified_part
from corrugate.fea.extrapolate import Judgement, judge
from corrugate.fea.fixtures import Fixture, fixture_names, fixtures, get_fixture
from corrugate.fea.frame import FrameStiffness, solve_frame
from corrugate.fea.outline import OutlineResult, solve_outline
from corrugate.fea.shells import check_shift, specimen
from corrugate.fea.steps import STATIC, LinearBuckling, Step
from corrugate.fea.tasks import Request, Tasks, worker_failure
from corrugate.geometry.layer import Assembly
from corrugate.mechanics.behaviours import (
    DEFAULT_SUPPORT,
    Behaviour,
    get_load_case,
    get_support,
    own_test,
)
from corrugate.solver.quantity import Quantity

if TYPE_CHECKING:
    from corrugate.solver.solve import ConstraintReport

__all__ = [
    "BEHAVIOURAL_KINDS",
    "BYTES_PER_NODE",
    "DEFAULT_MAX_MESH",
    "DEFAULT_MESHES",
    "DEFAULT_SHIFTS",
    "EXIT_CODES",
    "VERDICTS",
    "Checked",
    "Row",
    "Twin",
    "Verification",
    "behavioural",
    "check_layout",
    "joint_options",
    "parse_max_mesh",
    "parse_meshes",
    "parse_shifts",
    "safety_factor",
    "twin_of",
    "verify_design",
]

#: The mesh series unless asked for another (elements per facet).
DEFAULT_MESHES: tuple[int, ...] = (2, 4, 8)
#: The finest mesh a series is extended to (elements per facet) while it is not shown asymptotic
#: (:func:`corrugate.fea.extrapolate.judge`; docs/fea.md 2.9: with one ccx run per layer a
#: 16-per-facet run of the off-axis coupons fits in 7.5 GiB).
DEFAULT_MAX_MESH = 16
#: What a run on that mesh costs, said on stderr before it (docs/fea.md 2.9: the largest coupon of
#: the validation tables, 518 s of ccx CPU and 7.47 GiB per layer's run; section 6: 3.1 GiB for
#: the K(45) case-study coupon).
FINE_COST = "a 16-per-facet run may take minutes and up to ~8 GB of memory"
#: Bytes of CalculiX memory per node of a run, for the estimate of an extending run (its nodes:
#: four times the run's before, twice as many elements across and along each facet): the peak
#: RSS of ccx over the nodes of the outline meshes of docs/fea.md 2.8 and 2.9 (0.98 GB at
#: 22 800 nodes, 4.3 GB at 90 072, 12.4 GB at 280 000: 43-48 kB a node), rounded up.
BYTES_PER_NODE = 48_000
#: The coupon positions off the crease directions (fractions of each layer's pitch).
DEFAULT_SHIFTS: tuple[float, ...] = (0.0, 0.25, 0.5, 0.75)
#: The screen of coupon positions: the finest mesh runs at every position whose value on the
#: mesh before is within this fraction of the worst there (docs/fea.md 6: at K(45) of a case
#: study design the four positions' values at 4 per facet were within 0.22 %, and the worst
#: extrapolated position was not the worst at 4 per facet, 0.65 % apart).
SCREEN_WITHIN = 0.05
#: A row's verdict, and what ``corrugate verify`` exits with when it is the worst of a design's
#: (this order, the first the worst; docs/fea.md 6): ``fails`` 1, the FE shows the bound missed;
#: ``not converged`` 5, its series was not shown asymptotic up to the finest mesh allowed (or a
#: run failed); ``not checked`` 6, the constraint has no FE twin; ``holds`` 0.
VERDICTS: tuple[str, ...] = ("fails", "not converged", "not checked", "holds")
EXIT_CODES: dict[str, int] = {"fails": 1, "not converged": 5, "not checked": 6, "holds": 0}
#: A design's verdict in words (:attr:`Verification.statement`; ``{code}`` its exit code).
STATEMENTS: dict[str, str] = {
    "holds": "every constraint holds in FE",
    "fails": "not every constraint holds in FE (exit {code})",
    "not converged": (
        "no constraint fails, but not every FE series converged: not shown to hold (exit {code})"
    ),
    "not checked": (
        "every constraint with an FE twin holds; the others are not checked by FE (only the "
        "model's certificate covers them; exit {code})"
    ),
}
#: The quantity kinds a behavioural constraint bounds.
BEHAVIOURAL_KINDS = ("K", "D", "EI", "k", "Pb", "Pmax")

#: Called with one line before each CalculiX run.
Progress = Callable[[str], None]
_T = TypeVar("_T")


@dataclass(frozen=True, slots=True)
class Twin:
    """The FE fixture of one constraint: the fixture ``test`` (a name of
    :mod:`corrugate.fea.fixtures`) run as ``step`` at ``eta`` (deg), and how its result
    is read (``read``: ``K``, ``D``, ``EI``, ``k`` (P / delta, N/mm), ``pure-D``, ``pure-EI``
    (the 4-point gauge), ``Pb``), with the test's ``a`` coefficient for a bending test's
    apparent stiffness; ``load`` (N) turns P / delta into a deflection (mm); ``note`` is what the
    row should add; ``span`` (mm): a bending test over supports (a cantilever's free length) that
    far apart, inside a longer panel (None: the panel's length, supported at its ends); ``scale`` multiplies a load
    capacity's FE load (``Pmax``: 1 / the safety factor); ``part``: the key of the part it meshes
    (:attr:`corrugate.fea.calibrated.CertifiedPart.key`; "" the design as cut)."""

    test: str
    eta: float
    read: str
    a: float = 0.0
    load: float | None = None
    note: str = ""
    span: float | None = None
    step: Step = STATIC
    scale: float = 1.0
    part: str = ""

    @property
    def fixture(self) -> Fixture:
        return get_fixture(self.test)

    @property
    def shifted(self) -> bool:
        """Whether the twin runs on the gmsh coupon cut along eta (off the crease directions),
        whose FE value depends on where it is cut (module docstring); the frame and an outline
        fixture (the wheel) hold the whole part, which has no cut to shift."""
        return self.fixture.kind == "coupon" and principal_axis(self.eta) is None

    @property
    def label(self) -> str:
        """What a progress line and the row call the fixture run."""
        return self.step.describe(self.fixture.label, self.fixture.loading)

    def value(
        self, r: AssemblyResult | OutlineResult | None, frame: FrameStiffness | None
    ) -> float:
        """The constraint's quantity (in its unit) from the fixture's result."""
        if self.fixture.kind == "frame":
            assert frame is not None
            return frame.K(self.eta)
        assert r is not None
        if isinstance(r, OutlineResult):  # the wheel's K or the plate's P / delta
            return r.value if self.load is None else self.load / r.value
        if self.read == "Pb":
            return r.value()
        if self.read == "Pmax":  # the first buckling load at the safety factor
            return r.value() * self.scale
        if self.read == "K":
            assert r.K is not None
            return r.K
        if self.read == "pure-D":
            assert r.D is not None
            return r.D
        if self.read == "pure-EI":
            assert r.EI is not None
            return r.EI
        k = r.force / r.displacement  # P / delta of the test (compression: K)
        if self.read == "D":
            return self.a * r.span**2 * k
        if self.read == "EI":
            return self.a * r.span**3 * k
        return k if self.load is None else self.load / k


@dataclass(frozen=True, slots=True)
class Row:
    """One constraint and its FE twin: ``name``, quantity key, ``sense`` (min or max), ``unit``,
    the spec's ``bound``, the ``model`` value of the certificate, ``fe_series`` (elements per
    facet -> FE value, None where the run failed), the estimate ``fe`` (None without a twin or
    without a value), the observed ``order``, ``how`` the estimate was found, whether the
    constraint ``holds`` in FE (False without a twin) and a ``note`` (why there is no twin,
    failed runs); off the crease directions ``shift`` is the coupon position whose value counts
    (the worst) and ``by_shift`` each position's estimate (empty along the creases); ``test``
    names the FE fixture; ``extended`` says to which mesh the series was run on past the
    requested ones and why (:func:`corrugate.fea.extrapolate.judge`), "" when it was not;
    ``verdict`` one of :data:`VERDICTS` (given "": ``holds`` when ``holds``, else ``fails`` with
    an FE series and ``not checked`` without; given, it sets ``holds``)."""

    name: str
    quantity: str
    sense: str
    unit: str
    bound: float
    model: float
    fe_series: dict[int, float | None] = field(default_factory=dict)
    fe: float | None = None
    order: float | None = None
    how: str = ""
    holds: bool = False
    note: str = ""
    shift: float | None = None
    by_shift: dict[float, float | None] = field(default_factory=dict)
    test: str = ""
    extended: str = ""
    verdict: str = ""

    def __post_init__(self) -> None:
        if not self.verdict:
            v = "holds" if self.holds else ("fails" if self.fe_series else "not checked")
            object.__setattr__(self, "verdict", v)
        elif self.verdict not in VERDICTS:
            raise ValueError(f"verdict must be one of {VERDICTS}, not {self.verdict!r}")
        object.__setattr__(self, "holds", self.verdict == "holds")

    @property
    def has_twin(self) -> bool:
        return bool(self.fe_series)

    def as_json(self) -> dict[str, Any]:
        """The row as ``verify --json`` and verify.json write it (no NaN: null where unknown)."""
        return {
            "name": self.name,
            "quantity": self.quantity,
            "sense": self.sense,
            "unit": self.unit,
            "bound": _finite(self.bound),
            "model": _finite(self.model),
            "fe_series": {str(k): _finite(v) for k, v in self.fe_series.items()},
            "fe": _finite(self.fe),
            "order": _finite(self.order),
            "estimate": self.how or None,
            "holds": self.holds,
            "verdict": self.verdict,
            "note": self.note or None,
            "test": self.test or None,
            "shift": self.shift,
            "fe_by_shift": {f"{k:g}": _finite(v) for k, v in self.by_shift.items()},
            "extended": self.extended or None,
        }


def _finite(v: float | None) -> float | None:
    return v if v is not None and math.isfinite(v) else None


@dataclass(frozen=True, slots=True)
class Verification:
    """Every row of a design, the mesh series they ran on and the coupon positions (``shifts``)
    of the rows off the crease directions; ``holds`` when every row does; ``verdict`` the worst
    row's (:data:`VERDICTS`; ``holds`` without a row) and ``exit_code`` its code."""

    rows: tuple[Row, ...]
    meshes: tuple[int, ...]
    shifts: tuple[float, ...] = (0.0,)

    @property
    def holds(self) -> bool:
        return all(r.holds for r in self.rows)

    @property
    def verdict(self) -> str:
        found = {r.verdict for r in self.rows}
        return next((v for v in VERDICTS if v in found), "holds")

    @property
    def exit_code(self) -> int:
        return EXIT_CODES[self.verdict]

    @property
    def no_failure(self) -> bool:
        """Whether every row the FE could check holds (the rows without a twin aside)."""
        return self.verdict in ("holds", "not checked")

    @property
    def statement(self) -> str:
        """The design's verdict in words, with its exit code unless it holds (docs/fea.md 6):
        what ``corrugate verify`` prints under its table and the web page under its own."""
        if not self.rows:
            return "no behavioural constraint: nothing for the FE to check"
        return STATEMENTS[self.verdict].format(code=self.exit_code)

    def as_json(self) -> dict[str, Any]:
        return {
            "holds": self.holds,
            "verdict": self.verdict,
            "exit_code": self.exit_code,
            "statement": self.statement,
            "meshes": list(self.meshes),
            "shifts": list(self.shifts),
            "constraints": [r.as_json() for r in self.rows],
        }


def joint_options(joint: str) -> tuple[bool, Bond]:
    """``connectors`` and ``bond`` of the FE for the design's joint (docs/load_cases.md 7)."""
    if joint in ("none", ""):
        return False, "edges"
    if joint == "band-edges":
        return True, "edges"
    if joint == "band-flanges":
        return True, "flanges"
    raise InputError("joint", repr(joint), "none, band-edges or band-flanges", reason="is unknown")


def twin_of(
    q: Quantity, assembly: Assembly, joint: str = "none", load: float | None = None
) -> Twin | str:
    """The FE twin of the constraint on ``q`` (module docstring), or why it has none yet (one
    phrase). ``load`` (N): a deflection bound's load (its value is then a deflection, mm)."""
    if q.duration is not None:  # the decks carry the sheet's short-term E
        return (
            f"no FE twin yet (a load held {q.duration:g} h: the FE runs at the short-term E, "
            "the model at the creep modulus, `corrugate docs load_cases` section 11)"
        )
    connectors, _ = joint_options(joint)
    eta = q.eta if q.eta is not None else 0.0
    principal = principal_axis(eta) is not None
    note = ""
    shape = assembly.layout.name
    if shape == "circle":
        return _circle_twin(q, eta, connectors, load)
    if shape == "polygon":
        why = _polygon_refusal(q, principal, connectors)
        if why:
            return why
        note = POLYGON_NOTE
    if q.kind == "Pmax":
        return _capacity_twin(q, assembly, eta, principal, note)
    if q.kind == "Pb":
        if not principal:
            return "no FE twin yet (buckling off the crease directions)"
        # compression between platens (the own in-plane test's fixture) as a buckling run
        return Twin(own_test().fixture, eta, "Pb", step=LinearBuckling())
    support = get_support(q.support or DEFAULT_SUPPORT)
    if support.fixture not in fixture_names():
        return f"no FE twin yet (support {q.support})"
    held = _held(q)
    if connectors and (not principal or held is not None):
        return f"no FE twin yet (the band joint off the crease directions or{support.label})"
    test = q.test
    span: float | None = None  # a bending test over a span shorter than the panel
    if q.span is not None:
        length = specimen(assembly, eta)[1]
        if abs(q.span - length) > 1e-9 * max(1.0, length):
            takes = test is not None and get_fixture(get_load_case(test).fixture).takes_span
            if not (takes and principal and q.span < length and held is None):
                return f"no FE twin yet (span {q.span:.6g} mm: {_span_why(length)})"
            span = q.span
    if held is not None:  # only its own K, in its own fixture (the frame's two runs)
        if get_fixture(held.fixture).measures == "K" and (
            q.kind == "K" or (q.kind == "k" and test == own_test().name)
        ):
            if load is not None:
                return f"no FE twin yet (a deflection{held.label})"
            return Twin(held.fixture, eta, "K")
        return f"no FE twin yet (bending{held.label})"
    if test is None:
        if q.kind == "K":  # the support's own fixture: the free coupon between platens
            return Twin(support.fixture, eta, "K", note=note)
        if q.kind == "EI" and not principal:
            return "no FE twin yet (EI off the crease directions: the coupon has its own span)"
        # pure bending: the gauge between the load lines of the four-point fixture
        pure = get_load_case("four-point").fixture
        return Twin(pure, eta, "pure-" + q.kind, note=note)
    case = get_load_case(test)  # its own fixture, when it is a coupon's (module docstring)
    fx = get_fixture(case.fixture) if case.fixture in fixture_names("coupon") else None
    if fx is not None and fx.measures == "K":  # an in-plane test: K, or P / delta
        return Twin(fx.name, eta, "K" if q.kind == "K" else "k", load=load, note=note)
    if not principal and q.kind != "D":
        return (
            f"no FE twin yet ({q.kind} of a bending test off the crease directions: "
            "the coupon has its own span)"
        )
    form = case.form
    assert form is not None
    if fx is None or fx.measures != "D":
        return f"no FE twin yet (test {test})"
    return Twin(fx.name, eta, q.kind, a=form.a, load=load, note=note, span=span)


def _span_why(length: float) -> str:
    """Why a span has no FE twin: what the fixtures take."""
    takes = ", ".join(f.label for f in fixtures("coupon") if f.takes_span)
    return f"the FE takes a span up to the panel's length, {length:.6g} mm, in {takes} along a crease direction"


def _capacity_twin(
    q: Quantity, assembly: Assembly, eta: float, principal: bool, note: str
) -> Twin | str:
    """A load capacity's twin (``Pmax``: the load case's load held at the safety factor): its
    load case's fixture run as a linear buckling analysis, the first buckling load (a dead
    load) over the safety factor (:attr:`Twin.scale`, set from the constraint by
    :func:`verify_design`), or why it has none."""
    if not principal:
        return "no FE twin yet (a load capacity off the crease directions)"
    if q.support not in (None, DEFAULT_SUPPORT):
        return f"no FE twin yet (a load capacity, support {q.support})"
    fixture = (get_load_case(q.test) if q.test else own_test()).fixture
    if fixture not in fixture_names("coupon"):
        return f"no FE twin yet (a load capacity in test {q.test})"
    fx = get_fixture(fixture)
    span: float | None = None
    if q.span is not None:
        length = specimen(assembly, eta)[1]
        if abs(q.span - length) > 1e-9 * max(1.0, length):
            if not (fx.takes_span and q.span < length):
                return f"no FE twin yet (span {q.span:.6g} mm: {_span_why(length)})"
            span = q.span
    what = CAPACITY_NOTE
    return Twin(
        fx.name,
        eta,
        "Pmax",
        note="; ".join(x for x in (what, note) if x),
        span=span,
        step=LinearBuckling(),
    )


#: What a load capacity's FE twin is; verify_design adds the safety factor.
CAPACITY_NOTE = "FE: the first buckling load (a dead load) over the safety factor"


def safety_factor(c: Mapping[str, Any]) -> float | None:
    """The safety factor of a load capacity's constraint in design.json: its ``safety_factor``
    (written since issue 35), else, in a design.json written before, its least
    ``failure_loads_N`` (the model's first failure, N) over its ``value`` (the capacity at the
    safety factor, N); None when neither can be read. The second reading is the factor only
    for a nominal certificate: under tolerances (docs/tolerances.md) the capacity is the worst
    part's, below the nominal first failure over the factor (the chassis plate: 56.92 / 15.258 =
    3.73 for a factor of 2)."""
    sf = c.get("safety_factor")
    if isinstance(sf, int | float) and not isinstance(sf, bool) and math.isfinite(sf) and sf > 0:
        return float(sf)
    loads = c.get("failure_loads_N")
    value = c.get("value")
    if not isinstance(loads, Mapping) or isinstance(value, bool):
        return None
    if not isinstance(value, int | float) or value <= 0:
        return None
    found = [float(v) for v in loads.values() if isinstance(v, int | float)]
    return min(found) / float(value) if found else None


#: What a polygon's FE twin is (docs/fea.md 2.8), added to its rows.
POLYGON_NOTE = (
    "the polygon cut from its box: platens and supports act where the outline lies on the box's "
    "edges; the model sums its strips between their own ends on the outline"
)
#: What the wheel fixture measures against the model's statement (docs/fea.md 2.8).
WHEEL_NOTE = (
    "not the model's test: the model's K of a disc sums its strips' springs between platens "
    "(no bench test); FE: the wheel's radial K, a no-slip ground patch of +-15 deg at eta "
    "against a rigid axle in the hub"
)


#: What the wheel fixture is for a bound in the wheel test (docs/load_cases.md 9).
WHEEL_TEST_NOTE = (
    "the model's test: the wheel's radial K between a no-slip ground patch of +-15 deg at eta and "
    "a rigid axle in the hub, modelled as c(eta) x the strips' K (`corrugate docs load_cases`, "
    "section 9)"
)


def _circle_twin(q: Quantity, eta: float, connectors: bool, load: float | None) -> Twin | str:
    """A circle's twin: its in-plane K in the wheel fixture (:mod:`corrugate.fea.outline`), or
    why a constraint has none; a bound in the wheel test (``test = "wheel"``) is that fixture's
    own statement, any other K is not."""
    if connectors:
        return "no FE twin yet (the band joint on a circle)"
    held = _held(q)
    if held is not None:
        return f"no FE twin yet (a circle{held.label})"
    if q.test == "wheel":
        if q.kind not in ("K", "k"):
            return f"no FE twin yet ({q.kind} in the wheel test)"
        return Twin("wheel", eta, "K" if q.kind == "K" else "k", load=load, note=WHEEL_TEST_NOTE)
    if q.kind == "K" or (q.kind == "k" and q.test == own_test().name):
        if q.support not in (None, DEFAULT_SUPPORT):
            return f"no FE twin yet (support {q.support})"
        return Twin("wheel", eta, "K", load=load, note=WHEEL_NOTE)
    if q.kind in ("D", "EI"):
        return (
            "no FE twin: the model's D of a disc sums its strips' pure-bending springs (EI = D x "
            "diameter), which no bench test of a disc measures (`corrugate docs fea`, 2.8)"
        )
    return f"no FE twin yet ({q.kind} of a circle)"


def _polygon_refusal(q: Quantity, principal: bool, connectors: bool) -> str:
    """Why a polygon's constraint has no FE twin ("" when it has the rectangle's)."""
    if not principal:
        return "no FE twin yet (a polygon off the crease directions: no coupon of its own)"
    if connectors:
        return "no FE twin yet (the band joint on a polygon)"
    held = _held(q)
    if held is not None:
        return f"no FE twin yet (a polygon{held.label})"
    return ""


def _held(q: Quantity) -> Behaviour | None:
    """The support condition of ``q`` when it holds the panel in a fixture of its own instead
    of the free coupon the tests run on (its fixture is not the own in-plane test's,
    :func:`~corrugate.mechanics.behaviours.own_test`: the frame's), else None (free sides)."""
    support = get_support(q.support or DEFAULT_SUPPORT)
    return None if support.fixture == own_test().fixture else support


@dataclass(frozen=True, slots=True)
class Checked:
    """One behavioural constraint as its FE twin checks it: ``name``, ``quantity`` (as its key
    reads back, the way design.json states it, so that a run and ``corrugate verify`` of its
    folder check the same twin), ``sense`` (min or max), ``unit``, the ``bound`` and the model's
    ``value`` in that unit, and a deflection bound's ``load`` (N; None otherwise)."""

    name: str
    quantity: Quantity
    sense: str
    unit: str
    bound: float
    value: float
    load: float | None

    @classmethod
    def of(cls, c: ConstraintReport | Mapping[str, Any]) -> Checked | None:
        """``c`` (a solution's :class:`~corrugate.solver.solve.ConstraintReport`, or an entry
        of design.json's ``constraints``) as checked, None when it is not behavioural; an entry
        that cannot be read is an error naming it."""
        q = _behavioural(c.get("quantity") if isinstance(c, Mapping) else c.quantity.key)
        if q is None:
            return None
        if not isinstance(c, Mapping):
            deflection = q.kind == "k" and c.unit == "mm"
            if c.sense not in ("min", "max"):
                raise InputError(f"constraints[{c.name}].sense", repr(c.sense), "min or max")
            if deflection and c.load is None:
                raise InputError(f"constraints[{c.name}].load_N", "None", "a number")
            load = c.load if deflection else None
            return cls(c.name, q, c.sense, c.unit, float(c.bound), float(c.value), load)
        name = str(c.get("name", q.key))
        sense = str(c.get("sense", "min"))
        if sense not in ("min", "max"):
            raise InputError(f"constraints[{name}].sense", repr(sense), "min or max")
        unit = str(c.get("unit", ""))
        bound, value = _number(c, "bound"), _number(c, "value")
        deflection = q.kind == "k" and c.get("unit") == "mm"  # a deflection bound, under load_N
        return cls(name, q, sense, unit, bound, value, _number(c, "load_N") if deflection else None)


def behavioural(
    constraints: Sequence[Mapping[str, Any]],
) -> list[tuple[Mapping[str, Any], Quantity]]:
    """The behavioural constraints of a design.json's ``constraints`` with their quantities."""
    found = ((c, _behavioural(c.get("quantity"))) for c in constraints)
    return [(c, q) for c, q in found if q is not None]


def _behavioural(key: object) -> Quantity | None:
    """The quantity of a constraint's key when it is behavioural (a direction and a kind of
    :data:`BEHAVIOURAL_KINDS`), else None."""
    if not isinstance(key, str) or "@" not in key:
        return None
    q = Quantity.parse(key)
    return q if q.kind in BEHAVIOURAL_KINDS else None


def _number(c: Mapping[str, Any], name: str) -> float:
    v = c.get(name)
    if isinstance(v, bool) or not isinstance(v, int | float):
        raise InputError(
            f"constraints[{c.get('name', '?')}].{name}", repr(v), "a number", reason="is not one"
        )
    return float(v)


#: One coupon position of a row: its estimate (None: no value), shift, series, the judgement of
#: its series (None: screened out before the finest mesh) and its failed runs.
_Found = tuple[float | None, float, dict[int, float | None], Judgement | None, list[str]]


#: A run's result as a plan reads it: the fixture's result, or the run's error.
_Outcome = AssemblyResult | OutlineResult | FrameStiffness | CorrugateError
_Key = tuple[str, str, float, int, float, float | None, str]


def _key(twin: Twin, along: int, shift: float) -> _Key:
    """What makes two runs one: the fixture, the step, eta (none for the frame's two runs), the
    mesh, the coupon position, the span and the part meshed (a calibrated sheet's worst end)."""
    whole = twin.fixture.kind == "frame"
    eta = 0.0 if whole else twin.eta
    return (twin.fixture.name, twin.step.name, eta, along, shift, twin.span, twin.part)


@dataclass(frozen=True, slots=True)
class _Run:
    """One CalculiX run of :func:`verify_design`, a task shipped to a worker whole (pickled):
    ``twin``'s fixture on ``along`` elements per facet at coupon position ``shift``, with the
    design's band options, the work folder's parent, whether to keep it and the time-out (s);
    ``why`` is said on its progress line."""

    assembly: Assembly
    twin: Twin
    along: int
    shift: float
    connectors: bool
    bond: Bond
    folder: Path | None
    keep: bool
    timeout: float
    why: str = ""

    @property
    def key(self) -> _Key:
        return _key(self.twin, self.along, self.shift)

    def line(self) -> str:
        """The run in words, as its progress line says it."""
        twin, eta, span = self.twin, self.twin.eta, self.twin.span
        where = "" if twin.fixture.kind == "frame" else f" along eta = {eta:g} deg"
        at = f", coupon shifted {self.shift:g} pitch" if self.shift else ""
        at += f", span {span:g} mm" if span is not None else ""
        why = f" ({self.why})" if self.why else ""
        return f"assembly, {twin.label}{where}{at}, mesh {AssemblyMesh(self.along).label()}{why}"


def _solve(run: _Run) -> AssemblyResult | OutlineResult | FrameStiffness:
    """Run ``run`` in CalculiX (raises the run's :class:`CorrugateError`)."""
    a, twin, fixture = run.assembly, run.twin, run.twin.fixture
    mesh = AssemblyMesh(run.along)
    folder, keep, timeout = run.folder, run.keep, run.timeout
    if fixture.kind == "outline":
        return solve_outline(
            a, fixture.name, mesh, twin.eta, folder=folder, keep=keep, timeout=timeout
        )
    if fixture.kind == "frame":  # K_frame(eta) of two runs, at 0 and 90 deg
        return solve_frame(a, mesh, fixture=fixture, folder=folder, keep=keep, timeout=timeout)
    return solve_assembly(
        a,
        fixture,
        mesh,
        twin.eta,
        step=twin.step,
        connectors=run.connectors,
        bond=run.bond,
        shift=run.shift,
        span=twin.span,
        folder=folder,
        keep=keep,
        timeout=timeout,
    )


def _solve_caught(run: _Run) -> _Outcome:
    """:func:`_solve`, its error returned as its result (a task of :class:`Tasks`)."""
    try:
        return _solve(run)
    except CorrugateError as exc:
        return exc


def _lost(run: _Run, exc: Exception) -> _Outcome:
    """The result of a run lost with its worker (killed, out of memory): its error."""
    return CorrugateError(worker_failure(exc))


def verify_design(
    assembly: Assembly,
    constraints: Sequence[ConstraintReport | Mapping[str, Any]],
    joint: str = "none",
    meshes: Sequence[int] = DEFAULT_MESHES,
    *,
    shifts: Sequence[float] = DEFAULT_SHIFTS,
    screen: bool = True,
    progress: Progress = lambda line: None,
    folder: Path | None = None,
    keep: bool = False,
    timeout: float = 900.0,
    max_mesh: int = DEFAULT_MAX_MESH,
    memory_bytes: int | None = None,
    executor: Executor | None = None,
    jobs: int | None = None,
) -> Verification:
    """Run the FE twin of every behavioural constraint (module docstring; ``constraints``: a
    solution's reports or design.json's entries, :class:`Checked`) on the mesh series
    ``meshes`` (elements per facet) and compare its estimate with the bound; off the crease
    directions at every coupon position of ``shifts`` (fractions of each layer's pitch), each
    position's series extrapolated on its own and the worst estimate counting; with ``screen``
    (the default) every position runs on the meshes but the finest, and the finest mesh only at
    the positions within :data:`SCREEN_WITHIN` of the worst on the mesh before (docs/fea.md 6:
    the measured cost and ranking); ``by_shift`` holds the others' values at that mesh. A run that fails
    (a solver error, a mesh the fixture refuses) leaves None in the series and its message in
    the row's note; runs shared by constraints (the same test, eta, shift and mesh) run once.

    Each position that ran the finest requested mesh is judged by
    :func:`corrugate.fea.extrapolate.judge` (a series counts only when shown asymptotic against
    the bound); while one is open, the open position with the worst estimate has its series
    extended by doubling its finest mesh, up to ``max_mesh`` elements per facet, and is judged
    again (positions screened out stay out); a position that fails ends the row. The row fails
    when a position fails, holds when every judged position holds and no run failed, and is
    "not converged" otherwise; a constraint without a twin is "not checked". The row's
    ``extended`` says what was run on and why. With ``memory_bytes`` (the memory a run may
    take, e.g. the web app's cap) an extending run whose estimate (:data:`BYTES_PER_NODE` times
    four times the nodes of the run before) is larger is not made: the row is "not converged
    (memory)".

    With ``executor`` (e.g. a dask cluster, :func:`corrugate.fea.tasks.dask_executor`) or
    ``jobs`` (a local pool of that many processes) the runs are tasks submitted in rounds
    (:class:`corrugate.fea.tasks.Tasks`): every row's runs on the requested meshes at once, then
    each open row's next extending run, and so on; ``progress`` is called as each finishes. The
    rows are the same as in process (ccx is deterministic; docs/fea.md 4); a run whose worker
    died is a failed run of its row ("worker failed: ...")."""
    connectors, bond = joint_options(joint)
    if not shifts:
        raise InputError("shifts", "none", "at least one coupon position, e.g. 0")
    for sh in shifts:
        check_shift(sh)
    tasks: Tasks[_Run, _Outcome] = Tasks(
        _solve_caught, _Run.line, _lost, progress, executor=executor, jobs=jobs
    )
    runs = tasks.results

    def request(twin: Twin, shift: float, along: int, why: str = "") -> Request[_Run]:
        """The run of ``twin`` at ``shift`` on ``along`` elements per facet, as a plan asks."""
        part = parts[twin.part]
        r = _Run(part, twin, along, shift, connectors, bond, folder, keep, timeout, why)
        return r.key, r

    def series_at(
        twin: Twin, shift: float, which: tuple[int, ...]
    ) -> tuple[dict[int, float | None], list[str]]:
        """The values of ``twin``'s runs at ``shift`` on the meshes ``which`` (run before)."""
        series: dict[int, float | None] = {}
        failures: list[str] = []
        for along in which:
            r = runs[_key(twin, along, shift)]
            if isinstance(r, CorrugateError):
                series[along] = None
                failures.append(f"{along}/facet not run: {_short(r)}")
            elif isinstance(r, FrameStiffness):
                series[along] = twin.value(None, r)
            else:
                series[along] = twin.value(r, None)
        return series, failures

    planned: list[tuple[Row, Twin | str]] = []  # every entry read before any run: bad input first
    parts: dict[str, Assembly] = {"": assembly}
    for entry in constraints:
        c = Checked.of(entry)
        if c is None:
            continue
        base = Row(c.name, c.quantity.key, c.sense, c.unit, c.bound, c.value)
        twin = twin_of(c.quantity, assembly, joint, c.load)
        if c.quantity.kind == "Pmax" and isinstance(twin, Twin):
            sf = safety_factor(entry if isinstance(entry, Mapping) else entry.as_dict())
            twin = (
                replace(
                    twin,
                    scale=1.0 / sf,
                    note=twin.note.replace(CAPACITY_NOTE, f"{CAPACITY_NOTE} {sf:g}"),
                )
                if sf
                else "no FE twin yet (no failure_loads_N to read the safety factor from)"
            )
        if isinstance(twin, Twin):  # a calibrated sheet: the part certified, at its worst end
            q = c.quantity
            part = certified_part(assembly, q.kind, q.eta, q.support or DEFAULT_SUPPORT)
            if part.calibrated:
                parts[part.key] = part.assembly
                note = "; ".join(n for n in (part.words(), twin.note) if n)
                twin = replace(twin, part=part.key, note=note)
        planned.append((base, twin))

    def plan(base: Row, twin: Twin) -> Generator[list[Request[_Run]], None, Row]:
        """The row of ``twin``: its runs asked for in rounds (:class:`~corrugate.fea.tasks.
        Tasks`), each round's judged before the next is asked for."""
        sense = base.sense
        positions = tuple(shifts) if twin.shifted else (0.0,)
        sign = 1.0 if sense == "min" else -1.0
        screened = screen and len(positions) > 1 and len(meshes) > 1

        def judged(
            series: dict[int, float | None], bound: float = base.bound, sense: str = sense
        ) -> Judgement:
            return judge({k: v for k, v in series.items() if v is not None}, bound, sense)

        # (estimate or None, shift, series, judgement or None, failures) per position
        found: list[_Found] = []
        if screened:  # every position on the coarser meshes, the finest near the worst only
            coarse, last = tuple(meshes[:-1]), meshes[-2]
            yield [request(twin, sh, along) for sh in positions for along in coarse]
            pre = {sh: series_at(twin, sh, coarse) for sh in positions}
            at_last = {sh: pre[sh][0].get(last) for sh in positions}
            ranked = {sh: v for sh, v in at_last.items() if v is not None}
            if ranked:
                low = min(sign * v for v in ranked.values())
                picks = [
                    sh for sh, v in ranked.items() if sign * v <= low + SCREEN_WITHIN * abs(low)
                ]
            else:
                picks = list(positions)
            yield [request(twin, sh, meshes[-1]) for sh in positions if sh in picks]
            for sh in positions:
                series, failures = pre[sh]
                if sh in picks:
                    fine, fine_failures = series_at(twin, sh, (meshes[-1],))
                    series, failures = {**series, **fine}, failures + fine_failures
                    j = judged(series)
                    found.append((j.value, sh, series, j, failures))
                else:
                    found.append((at_last[sh], sh, series, None, failures))
        else:
            yield [request(twin, sh, along) for sh in positions for along in meshes]
            for sh in positions:
                series, failures = series_at(twin, sh, tuple(meshes))
                j = judged(series)
                found.append((j.value, sh, series, j, failures))

        # Refine every position that ran the finest requested mesh while its series is open
        # (not shown asymptotic against the bound), the worst first, up to max_mesh; a position
        # shown to fail ends the row, a run that fails leaves it open (docs/fea.md 6).
        extended: list[str] = []
        refused = ""  # an extension the memory does not allow
        unsettled = False  # an extension's run failed (or was refused): its series stays open
        while not unsettled:
            if any(_outcome(f) == "fails" for f in found):
                break
            pending = [
                i
                for i, f in enumerate(found)
                if _outcome(f) == "open" and f[0] is not None and 2 * max(f[2]) <= max_mesh
            ]
            if not pending:
                break
            i = min(pending, key=lambda k: sign * (found[k][0] or 0.0))
            _, sh, series, before, failures = found[i]
            assert before is not None
            finer = 2 * max(series)
            need = _memory_estimate(runs, twin, max(series), sh)
            if memory_bytes is not None and need is not None and need > memory_bytes:
                refused = (
                    f"not extended to {finer} per facet: its run would take about "
                    f"{need / 1e9:.1f} GB (4 x the nodes of the run at {max(series)} per facet x "
                    f"{BYTES_PER_NODE // 1000} kB), more than the {memory_bytes / 1e9:.1f} GB "
                    "allowed"
                )
                unsettled = True
                break
            why = f"extending {base.name}'s series: {before.why}"
            if finer >= DEFAULT_MAX_MESH:
                why += f"; {FINE_COST}"
            yield [request(twin, sh, finer, why)]
            more, more_failures = series_at(twin, sh, (finer,))
            series = {**series, **more}
            after = judged(series)
            found[i] = (after.value, sh, series, after, failures + more_failures)
            unsettled = bool(more_failures)
            extended.append(
                f"extended to {finer} per facet"
                f"{f' at shift {sh:g}' if twin.shifted else ''} ({before.why})"
            )
        outcomes = {_outcome(f) for f in found} - {""}
        known = [f for f in found if f[0] is not None]
        complete = len(known) == len(found)
        if twin.shifted:  # a run that failed at any position could hide the worst one
            complete = complete and not any(f[4] for f in found)
        if "fails" in outcomes:
            verdict = "fails"
            counted = [f for f in found if _outcome(f) == "fails"]
        elif outcomes == {"holds"} and complete and not unsettled:
            verdict = "holds"
            counted = list(found)
        else:
            verdict = "not converged"
            counted = [f for f in found if _outcome(f) == "open"] or list(found)
        _, shift, series, judgement, failures = counted[_worst(counted, sign)]
        if twin.shifted:
            failures = [f"shift {f[1]:g}: {x}" for f in found for x in f[4]]
        notes = [n for n in (twin.note, *failures) if n]
        notes += extended
        if refused:
            notes.append(refused)
        elif unsettled:
            notes.append("the run extending the series failed")
        if verdict == "not converged":
            if judgement is not None and judgement.verdict == "open":
                at = f" at shift {shift:g}" if twin.shifted else ""
                at += " (memory)" if refused else ""
                notes.append(
                    f"not converged{at} at {max(series)} per facet (the finest allowed is "
                    f"{max_mesh}, --max-mesh): {judgement.why}"
                )
            elif not complete:
                notes.append("not converged: a run failed or gave no FE value")
            else:
                notes.append("not converged")
        if twin.shifted:
            each = ", ".join(f"{f[1]:g}: {_fmt_value(f[0])}" for f in found)
            if screened:
                coarse_each = ", ".join(
                    f"{f[1]:g}: {_fmt_value(f[2].get(meshes[-2]))}" for f in found
                )
                ran = ", ".join(f"{f[1]:g}: {_fmt_value(f[0])}" for f in found if f[3] is not None)
                notes.insert(
                    0,
                    f"worst of {len(positions)} coupon positions at shift {shift:g} pitch "
                    f"(at mesh {meshes[-2]}, by shift {coarse_each}; run on to mesh "
                    f"{meshes[-1]} within {100 * SCREEN_WITHIN:g} % of the worst there, "
                    f"estimates {ran})",
                )
            else:
                notes.insert(
                    0,
                    f"worst of {len(positions)} coupon positions at shift {shift:g} pitch "
                    f"(by shift {each})",
                )
            if not complete:
                notes.append("a coupon position has a failed run or no FE value: not proven")
        return replace(
            base,
            fe_series=series,
            fe=None if judgement is None else judgement.value,
            order=None if judgement is None else judgement.order,
            how="" if judgement is None else judgement.how,
            note="; ".join(notes),
            shift=shift if twin.shifted else None,
            test=twin.label
            + ("" if twin.fixture.kind == "frame" else f" along eta = {twin.eta:g} deg"),
            by_shift={f[1]: f[0] for f in found} if twin.shifted else {},
            extended="; ".join(extended),
            verdict=verdict,
        )

    plans = [plan(base, twin) for base, twin in planned if isinstance(twin, Twin)]
    checked = iter(tasks.drive(plans))
    rows = [
        replace(base, note=twin, verdict="not checked") if isinstance(twin, str) else next(checked)
        for base, twin in planned
    ]
    return Verification(tuple(rows), tuple(meshes), tuple(shifts))


def _memory_estimate(
    runs: Mapping[Hashable, object], twin: Twin, along: int, shift: float
) -> float | None:
    """The bytes a run of ``twin`` twice as fine as its run at ``along`` per facet would take:
    four times that run's nodes times :data:`BYTES_PER_NODE` (None when it has no node count,
    e.g. it failed)."""
    nodes = getattr(runs.get(_key(twin, along, shift)), "nodes", None)
    if not isinstance(nodes, int) or nodes <= 0:
        return None
    return 4.0 * nodes * BYTES_PER_NODE


def _outcome(f: _Found) -> str:
    """The judgement of one coupon position's series ("" when it was screened out)."""
    return "" if f[3] is None else f[3].verdict


def _worst(found: Sequence[tuple[float | None, float, Any, Any, Any]], sign: float) -> int:
    """The index in ``found`` (estimate, shift, series, extrapolation or None, failures: one
    entry per coupon position) of the worst position among those that ran the finest mesh (an
    extrapolation); when none of them has a value, the first (the row is unproven)."""
    full = [i for i, f in enumerate(found) if f[3] is not None]
    valued = [i for i in full if found[i][0] is not None]
    return min(valued, key=lambda i: sign * (found[i][0] or 0.0)) if valued else full[0]


def _fmt_value(v: float | None) -> str:
    return "-" if v is None else f"{v:.5g}"


def _short(exc: CorrugateError) -> str:
    """A failed run's message, short for a table row."""
    if isinstance(exc, InputError) and exc.field == "mesh.along" and "four-point" in str(exc):
        return "the 4-point fixture needs elements per facet x (n + 1) divisible by 4"
    return str(exc)


def _comma_values(
    text: str, convert: Callable[[str], _T], name: str, allowed: str
) -> tuple[_T, ...]:
    """The values of option ``name`` given as ``text``, separated by commas, each read by
    ``convert``; one line naming the option and what it allows when one cannot be read."""
    if foreign_digits(text):  # int("８") and float("０.５") read them: refused, 0-9 only
        raise InputError(name, repr(text), allowed, reason="has digits other than 0-9")
    try:
        return tuple(convert(v) for v in text.split(","))
    except ValueError:
        raise InputError(name, repr(text), allowed, reason="cannot be read") from None


def parse_meshes(text: str) -> tuple[int, ...]:
    """``--mesh 2,4,8``: even element counts >= 2, increasing, without repeats."""
    values = _comma_values(text, int, "mesh", "even integers separated by commas, e.g. 2,4,8")
    for v in values:
        AssemblyMesh(v)  # even, >= 2, within the limits
    if not values or list(values) != sorted(set(values)):
        raise InputError("mesh", repr(text), "increasing element counts, e.g. 2,4,8")
    return values


def parse_max_mesh(n: int, name: str = "--max-mesh") -> int:
    """``--max-mesh N``: the finest mesh a series may be extended to (elements per facet); 0 is
    the default cap (:data:`corrugate.fea.verify.DEFAULT_MAX_MESH`), at most ``LIMITS["mesh"]``'s
    top (64: a number of 400 digits is refused by its name, not run)."""
    from corrugate.core.limits import LIMITS, integer_shown

    top = int(LIMITS["mesh"].hi)
    if not 0 <= n <= top:
        raise InputError(
            name, integer_shown(n), f"0 (the default, 16) or elements per facet 1 to {top}"
        )
    return n or DEFAULT_MAX_MESH


def parse_shifts(text: str) -> tuple[float, ...]:
    """``--shifts 0,0.25,0.5,0.75``: coupon positions, fractions of each layer's pitch in [0, 1),
    increasing, without repeats."""
    values = _comma_values(
        text, float, "shifts", "fractions of the pitch separated by commas, e.g. 0,0.25,0.5,0.75"
    )
    for v in values:
        try:
            check_shift(v)
        except InputError as exc:
            raise InputError("shifts", repr(text), exc.allowed) from None
    if not values or list(values) != sorted(set(values)):
        raise InputError("shifts", repr(text), "increasing fractions, e.g. 0,0.25,0.5,0.75")
    return values


def check_layout(name: str) -> None:
    """Refuse a layout the FE has no fixtures for, naming what is missing. Every layout has
    them now (a circle: the wheel fixture; a polygon: the rectangle's fixtures cut to it;
    docs/fea.md 2.8), so only an unknown name is refused."""
    from corrugate.names import LAYOUT_SHAPES

    if name not in LAYOUT_SHAPES:
        raise InputError("layout", name, " or ".join(LAYOUT_SHAPES), reason="has no FE fixtures")
