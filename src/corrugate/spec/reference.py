"""The spec reference (``docs/spec.md``) and a JSON Schema, both generated from the spec model.

:func:`spec_keys` walks the pydantic models of :mod:`corrugate.spec.schema` and lists every key the
parser accepts, by TOML path (``constraints.flexural_rigidity[].eta``). :data:`KEYS` says for each
one its unit and what it means; a key the parser accepts but :data:`KEYS` does not describe is
an error of :func:`reference_markdown` (and of the tests), so the reference cannot fall behind the
parser. :func:`json_schema` is pydantic's schema of :class:`~corrugate.spec.schema.Spec`, widened where
the parser is wider than the types say: every quantity also takes a string with units
(``"48 mm"``), and each key gets its description, so an editor (e.g. Taplo or VS Code's Even Better
TOML, through a ``#:schema`` comment or a schema association) can complete and check spec files.
"""

from __future__ import annotations

import json
import types
import typing
from collections.abc import Iterator, Mapping
from dataclasses import dataclass
from typing import Any

from pydantic import BaseModel

from corrugate.core.limits import MAX_COUNTS
from corrugate.core.parameters import PARAMETERS
from corrugate.mechanics.behaviours import (
    DEFAULT_SUPPORT,
    Behaviour,
    deflection_tests,
    either,
    listed,
    load_cases,
    own_test,
    supports,
)
from corrugate.spec.schema import PLAIN_UNITS, PURE, Spec

__all__ = ["KEYS", "KeyDoc", "json_schema", "plain_number", "reference_markdown", "spec_keys"]


@dataclass(frozen=True, slots=True)
class KeyDoc:
    """What one spec key means: its ``unit`` (internal unit of the value, "" for none; a plain
    number is read in it, a string may carry any compatible unit) and a one-line ``text``."""

    unit: str
    text: str


_STIFF = {
    "flexural_rigidity": ("N*mm^2", "EI(eta), the flexural rigidity of the panel over its span"),
    "bending_stiffness": ("N*mm", "D(eta), the bending stiffness (EI per span)"),
    "inplane_stiffness": ("N/mm", "K(eta), the in-plane compressive stiffness"),
}

#: What a bound's ``duration`` means (docs/load_cases.md section 11).
_DURATION = (
    "How long the load is held, with its unit ('1 week', '168 h'; > 0); default: none, a "
    "short-term load at the material's E. A sustained load reads the material's creep modulus "
    "E_c(t) instead (`corrugate materials`: its creep table, interpolated in log time, refused "
    "beyond its last duration or for a material without creep data; `corrugate docs "
    "load_cases`, section 11)."
)

#: The keys of a spec whose meaning does not depend on the registry of behaviours.
_STATIC: dict[str, KeyDoc] = {
    "name": KeyDoc("", "Name of the design; names the files and the report."),
    "model": KeyDoc("", PARAMETERS["model"].help),
    "layers": KeyDoc(
        "",
        "'identical' (default: both layers the same W, n, alpha, t) or 'independent' (each "
        "layer its own; slower).",
    ),
    "material": KeyDoc("", "The sheet material (a table); or use [[materials]] for a choice."),
    "materials": KeyDoc(
        "", "Candidate materials ([[materials]] tables): the designer picks the lightest."
    ),
    "layout": KeyDoc("", "The plan outline of the panel (a table)."),
    "layout.shape": KeyDoc("", PARAMETERS["layout"].help),
    "layout.vertices": KeyDoc(
        "", "Polygon outline: [[x, y], ...], scaled to the folded extents (polygon only)."
    ),
    "layout.holes": KeyDoc("", "Inner cut-outs, e.g. an axle hole (array of tables)."),
    "layout.holes[].shape": KeyDoc("", "'circle' (default) or 'polygon'."),
    "layout.holes[].diameter": KeyDoc("mm", "Diameter of a circular hole."),
    "layout.holes[].center": KeyDoc(
        "mm", "[x, y] of the hole from the centre of the layout (x across layer 1's creases)."
    ),
    "layout.holes[].vertices": KeyDoc(
        "mm", "Polygonal hole: [[x, y], ...] relative to its center."
    ),
    "variables": KeyDoc("", "Bounds of the design variables (a table)."),
    "variables.W": KeyDoc("mm", "Facet width W: { min, max, step } (step optional: a grid)."),
    "variables.W.min": KeyDoc("mm", "Smallest facet width."),
    "variables.W.max": KeyDoc("mm", "Largest facet width."),
    "variables.W.step": KeyDoc("mm", "Grid step of W (omit for a continuous W)."),
    "variables.n": KeyDoc("", "Number of creases n per layer: { min, max } (integers)."),
    "variables.n.min": KeyDoc("", "Fewest creases (default 1)."),
    "variables.n.max": KeyDoc("", "Most creases (default 200)."),
    "variables.alpha": KeyDoc("deg", "Fold angle alpha: { min, max, step }, 0 < alpha < 180."),
    "variables.alpha.min": KeyDoc("deg", "Smallest fold angle."),
    "variables.alpha.max": KeyDoc("deg", "Largest fold angle."),
    "variables.alpha.step": KeyDoc("deg", "Grid step of alpha (omit for a continuous alpha)."),
    "constraints": KeyDoc("", "What the part must do and fit (a table)."),
    "constraints.sheet_max": KeyDoc(
        "mm", "Longest flat blank the cutter takes: bounds (n + 1) W and every facet length."
    ),
    "constraints.side": KeyDoc("mm", "Folded side L of a square: { min, max }."),
    "constraints.diameter": KeyDoc("mm", "Folded diameter of a circle: { min, max }."),
    "constraints.side_x": KeyDoc("mm", "Folded extent Lx of a rectangle or polygon: { min, max }."),
    "constraints.side_y": KeyDoc("mm", "Folded extent Ly of a rectangle or polygon: { min, max }."),
    "constraints.thickness": KeyDoc("mm", "Folded thickness t_d of the panel: { min, max }."),
    **{
        f"constraints.{k}": KeyDoc(u, f"Lower bounds on {t} (array of tables).")
        for k, (u, t) in _STIFF.items()
    },
    **{f"constraints.{k}[].min": KeyDoc(u, f"Least {t}.") for k, (u, t) in _STIFF.items()},
    **{
        f"constraints.{k}[].eta": KeyDoc("deg", "Direction eta, from layer 1's creases.")
        for k in _STIFF
    },
    **{
        f"constraints.{k}[].duration": KeyDoc("h", _DURATION)
        for k in (*_STIFF, "buckling_load", "deflection")
    },
    "constraints.buckling_load": KeyDoc(
        "N", "Lower bounds on the compressive buckling load (array of tables)."
    ),
    "constraints.buckling_load[].min": KeyDoc("N", "Least buckling load (plate lower bound)."),
    "constraints.buckling_load[].eta": KeyDoc("deg", "Load direction: 0 or 90 deg (required)."),
    "constraints.deflection": KeyDoc(
        "mm", "Load cases: at most max of deflection under load (array of tables)."
    ),
    "constraints.deflection[].load": KeyDoc(
        "N",
        "The load P (> 0); along a layer's creases the panel must also hold it at the safety "
        "factor (its capacity, `corrugate docs load_cases`, section 10).",
    ),
    "constraints.deflection[].max": KeyDoc("mm", "Largest deflection allowed under the load."),
    "constraints.deflection[].eta": KeyDoc("deg", "Direction of the span, from layer 1's creases."),
    "constraints.strength": KeyDoc(
        "N",
        "Loads the panel must hold at the safety factor: its capacity, the least failure load "
        "of every mode (yield, facet buckling in bending and shear, a free outermost facet, "
        "the end facets between platens, crippling under the load lines, the band's walls) / "
        "safety_factor >= load (array of tables; "
        "`corrugate docs load_cases`, sections 6 and 10).",
    ),
    "constraints.strength[].load": KeyDoc("N", "The load P (> 0) to hold."),
    "constraints.strength[].eta": KeyDoc(
        "deg", "Load direction: 0 or 90 deg (along a layer's creases)."
    ),
    "joint": KeyDoc(
        "",
        "How the layers are joined: 'none' (default: the connector band left out, the paper's "
        "assumption and a lower bound), 'band-edges' or 'band-flanges' (the band bonded: its "
        "walls add to bending and in-plane stiffness along the creases; `corrugate docs "
        "load_cases`, section 7).",
    ),
    "trust": KeyDoc(
        "",
        "Where the answer may lie: 'certified' (default: only inside the range of designs each "
        "model the constraints use was validated over against FE, "
        "`corrugate docs validation/ranges`; each range is a constraint, named "
        "validity.MODEL.VARIABLE.END when it binds) "
        "or 'extrapolate' (the ranges dropped: an answer outside one is marked extrapolated, "
        "not certified, and names the ranges it leaves).",
    ),
    "safety_factor": KeyDoc(
        "",
        "Factor on the failure load of every strength bound and load case, 1 to 100, both "
        "included (default 2: "
        "datasheet yield values are typical, not minimum, and polymer films creep under a "
        "sustained load).",
    ),
    "fabrication": KeyDoc(
        "",
        "What making the part asks, as constraints of the solve (a table; `corrugate docs "
        "fabrication`, 'What the solve asks of the making').",
    ),
    "fabrication.machine": KeyDoc(
        "",
        "The cutter every cut part must fit, turned or not (cameo4-12x12, cameo4-12x24, "
        "maker-12x12, maker-12x24, laser:WxH or 'none'); default: `--machine`, else "
        "cameo4-12x12. `design --out` writes its files for it.",
    ),
    "fabrication.min_facet": KeyDoc(
        "mm", "The narrowest facet W anyone is to fold (default 3 mm)."
    ),
    "fabrication.max_t_over_W": KeyDoc(
        "",
        "The thickest sheet for its facet, t / W (default 0.05: where the models were checked "
        "and the thick-sheet warning starts).",
    ),
    "fabrication.max_creases": KeyDoc("", "The most creases n of one layer (default: no limit)."),
    "fabrication.mountain": KeyDoc(
        "",
        "How mountain creases reach the cutter: 'cut-score', 'perforate', 'score', 'pen' or "
        "'none' (default: the machine's, `corrugate docs fabrication`; --mountain overrides).",
    ),
    "fabrication.valley": KeyDoc(
        "", "How valley creases reach the cutter (as mountain; --valley overrides)."
    ),
    "fabrication.marks": KeyDoc(
        "",
        "How the band's angle marks reach the cutter: 'pen', 'score', 'cut-score' or 'none' "
        "(never perforated; --marks overrides).",
    ),
    "constraints.mass": KeyDoc("g", "Mass budget: { max }."),
    "constraints.mass.max": KeyDoc("g", "Heaviest part allowed (layers and connector band)."),
    "objective": KeyDoc("", "What to optimise (a table); default: minimize = 'mass'."),
    "objective.minimize": KeyDoc("", "'mass'."),
    "objective.maximize": KeyDoc(
        "", "A stiffness kind to maximise: " + ", ".join(f"'{k}'" for k in _STIFF) + "."
    ),
    "objective.eta": KeyDoc("deg", "Direction of the stiffness to maximise."),
    "robust": KeyDoc(
        "", "Meet every bound with a probability under manufacturing tolerances (a table)."
    ),
    "robust.probability": KeyDoc("", "Probability of meeting every bound (default 0.9)."),
    "robust.W": KeyDoc("mm", "One-sigma tolerance of W (default 0.1 mm)."),
    "robust.alpha": KeyDoc("deg", "One-sigma tolerance of alpha (default 2 deg)."),
    "robust.t": KeyDoc("", "Relative one-sigma tolerance of the thickness (default 5 %)."),
    "robust.E": KeyDoc("", "Relative one-sigma tolerance of E (default 10 %)."),
    "robust.samples": KeyDoc("", "Monte Carlo samples (default 4000)."),
    "robust.seed": KeyDoc("", "Seed of the random samples (default 0)."),
    "tolerances": KeyDoc(
        "",
        "Worst-case half-widths the certificate covers (a table; docs/tolerances.md), or "
        "'none' for the nominal certificate (the paper's reproduction). Default: the table's "
        "defaults; a spec with [robust] and no [tolerances] is nominal.",
    ),
    "tolerances.alpha": KeyDoc(
        "deg", "Fold angle, each layer (default 3 deg: hand folding, a stated assumption)."
    ),
    "tolerances.W": KeyDoc(
        "mm", "Facet width, each layer (default 0.1 mm: a hobby cutter, a stated assumption)."
    ),
    "tolerances.t": KeyDoc(
        "", "Relative sheet thickness (default 5 %: a datasheet's, a stated assumption)."
    ),
    "tolerances.E": KeyDoc(
        "", "Relative Young's modulus (default 10 %: a datasheet's, a stated assumption)."
    ),
}
for _r in ("side", "diameter", "side_x", "side_y", "thickness"):
    _STATIC[f"constraints.{_r}.min"] = KeyDoc("mm", "Least value.")
    _STATIC[f"constraints.{_r}.max"] = KeyDoc("mm", "Greatest value.")
for _m in ("material", "materials[]"):
    _STATIC |= {
        f"{_m}.name": KeyDoc("", "A library material (corrugate materials) or 'custom'."),
        f"{_m}.thickness": KeyDoc(
            "mm",
            "One thickness, a list of candidates, 'all' (every thickness sold) or nothing "
            "(the material's default).",
        ),
        # the same parameters as the command line's inline material (--E, --nu, --density)
        **{
            f"{_m}.{k}": KeyDoc(PARAMETERS[k].unit, PARAMETERS[k].help)
            for k in ("E", "nu", "density")
        },
        f"{_m}.yield_strength": KeyDoc(
            "MPa",
            "Allowable stress of strength bounds (tensile yield); replaces the library's value.",
        ),
        f"{_m}.crease_stiffness": KeyDoc(
            "N*mm/(rad*mm)",
            "An inline material's crease rotational stiffness per unit crease length, with its "
            "unit (> 0, or 'inf': rigid, the default); the models, the certificate and verify "
            "take the creases as these springs (docs/calibration.md 9).",
        ),
        f"{_m}.springback": KeyDoc(
            "deg",
            "An inline material's springback, the angle a fold opens by after it is released "
            "(-30 to 30 deg; default 0): the part is certified at alpha + springback, the cut "
            "files keep alpha (docs/calibration.md 9).",
        ),
    }


def _support_docs() -> dict[str, KeyDoc]:
    """The ``support`` keys, from the support conditions registered now
    (:mod:`corrugate.mechanics.behaviours`: each one's name and meaning, the default marked)."""
    entries = supports()
    names = either([b.name for b in entries])
    each = [
        f"'{b.name}' ({'default; ' if b.name == DEFAULT_SUPPORT else ''}{b.text})" for b in entries
    ]
    offered = listed(each)
    docs = {
        "support": KeyDoc(
            "", f"Support condition of every stiffness bound unless it says otherwise: {offered}."
        ),
        "objective.support": KeyDoc("", f"{names} for the maximised stiffness."),
    }
    for k in (*_STIFF, "deflection", "strength"):
        docs[f"constraints.{k}[].support"] = KeyDoc(
            "", f"{names} for this bound (default: the spec's support)."
        )
    return docs


def _offered(b: Behaviour) -> str:
    """A load case in the reference's lists of tests: its name quoted, then its note."""
    return repr(b.name) + (f" ({b.note})" if b.note else "")


def _load_case_docs() -> dict[str, KeyDoc]:
    """The ``test`` and ``span`` keys, from the load cases registered now
    (:mod:`corrugate.mechanics.behaviours`: each one's name, its note and its layouts; the
    in-plane test of the support's own K is the default of a K bound, as ``pure`` of EI and D)."""
    cases = load_cases()
    bending = [b for b in cases if b.form is not None and b.form.kind == "bending"]
    inplane = [b for b in cases if b.form is not None and b.form.kind == "inplane"]
    own = own_test()
    others = [b for b in inplane if b is not own]
    # 'a' or, for a circle, 'b': a test of one layout names it after the conjunction
    inplane_text = f"'{own.name}' (the default: K between rigid platens)"
    for i, b in enumerate(others):
        last = i == len(others) - 1
        where = f"for a {b.layouts[0]}, " if len(b.layouts) == 1 else ""
        inplane_text += (" or" if last else ",") + (", " if where and last else " ")
        inplane_text += where + _offered(b)
    docs = {
        "constraints.inplane_stiffness[].test": inplane_text,
        **{
            f"constraints.{k}[].test": f"'{PURE}' (the default: the panel's own pure-bending "
            "rigidity, EI = D x span), "
            + listed([_offered(b) for b in bending])
            + " (what that test reads, shear of the facets included)"
            for k in ("flexural_rigidity", "bending_stiffness")
        },
    }
    out = {
        k: KeyDoc("", f"The test the bound is for (`corrugate docs load_cases`): {text}.")
        for k, text in docs.items()
    }
    loaded = deflection_tests()
    tests = KeyDoc("", listed([_offered(b) for b in loaded]) + ".")
    clamped = ", ".join(f"{b.name}: free length" for b in loaded if b.form and b.form.clamped)
    spacing = (
        f"Support spacing{f' ({clamped})' if clamped else ''}; default the panel's length along eta"
    )
    spanless = [b.name for b in loaded if b.form is not None and b.form.kind == "inplane"]
    out |= {
        "constraints.deflection[].test": tests,
        "constraints.deflection[].span": KeyDoc(
            "mm",
            f"{spacing}; the panel must be at least this long."
            + (f" Not for {' or '.join(spanless)}." if spanless else ""),
        ),
        "constraints.strength[].test": tests,
        "constraints.strength[].span": KeyDoc("mm", f"{spacing}."),
        **{
            f"constraints.{k}[].bearing": KeyDoc(
                "mm",
                "Width of the load and support lines (a roller's contact, a pad, a fingertip; "
                "> 0, at most the span and the panel's length): the crippling of the facets "
                "and of the band's walls under them depends on it; default 10 mm (a fingertip "
                "or small pad; `corrugate docs load_cases`, section 10.5)."
                + (f" Not for {' or '.join(spanless)}." if spanless else ""),
            )
            for k in ("deflection", "strength")
        },
    }
    return out


class _Keys(Mapping[str, KeyDoc]):
    """:data:`_STATIC`, the ``support`` keys and the load cases' ``test`` and ``span`` keys,
    the latter two made from the registry at each look-up (so a support condition or a load
    case registered after import is in the reference)."""

    def _all(self) -> dict[str, KeyDoc]:
        return _STATIC | _support_docs() | _load_case_docs()

    def __getitem__(self, key: str) -> KeyDoc:
        return self._all()[key]

    def __iter__(self) -> Iterator[str]:
        return iter(self._all())

    def __len__(self) -> int:
        return len(self._all())


#: Every key of a spec by TOML path (``[]`` marks the items of an array of tables).
KEYS: Mapping[str, KeyDoc] = _Keys()


def _models(annotation: Any) -> tuple[type[BaseModel] | None, bool]:
    """The pydantic model inside ``annotation`` (through Optional and list) and whether it is a
    list of them."""
    origin = typing.get_origin(annotation)
    if origin in (typing.Union, types.UnionType):
        for arg in typing.get_args(annotation):
            found = _models(arg)
            if found[0] is not None:
                return found
        return None, False
    if origin is list:
        inner, _ = _models(typing.get_args(annotation)[0])
        return inner, True
    if isinstance(annotation, type) and issubclass(annotation, BaseModel):
        return annotation, False
    return None, False


def spec_keys(model: type[BaseModel] = Spec, prefix: str = "") -> list[str]:
    """Every key path the spec parser accepts, depth first in declaration order."""
    out = []
    for name, field in model.model_fields.items():
        path = f"{prefix}{name}"
        out.append(path)
        inner, many = _models(field.annotation)
        if inner is not None:
            out += spec_keys(inner, f"{path}[]." if many else f"{path}.")
    return out


def _check_documented(docs: Mapping[str, KeyDoc]) -> list[str]:
    keys = spec_keys()
    missing = [k for k in keys if k not in docs]
    if missing:
        raise AssertionError(f"spec keys without a description in KEYS: {missing}")
    return keys


def _default(path: str) -> str:
    """The default of ``path`` as TOML-ish text, or '' when the key has none."""
    model: type[BaseModel] = Spec
    parts = path.replace("[]", "").split(".")
    for part in parts[:-1]:
        inner, _ = _models(model.model_fields[part].annotation)
        assert inner is not None
        model = inner
    field = model.model_fields[parts[-1]]
    if field.is_required():
        return "required"
    value = field.get_default()
    if value is None or isinstance(value, BaseModel) or value == []:
        return ""
    return json.dumps(value)


def plain_number(key: str, doc: KeyDoc, table: bool = False) -> str:
    """The *plain* column of the reference: ``yes`` where a plain number is read in the key's
    unit (mm, deg: :data:`~corrugate.spec.schema.PLAIN_UNITS`) or the value is a count or a
    ratio, ``**no**`` where the unit must be written, ``-`` for a table, an array of tables or a
    choice."""
    if table or (not doc.unit and key not in _NUMBERS):
        return "-"
    if not doc.unit or doc.unit in PLAIN_UNITS:
        return "yes"
    return "**no**"


#: Unit-less keys whose value is a number (counts, ratios); the others are names and choices.
_NUMBERS = {
    "variables.n.min",
    "variables.n.max",
    "safety_factor",
    "robust.probability",
    "robust.t",
    "robust.E",
    "robust.samples",
    "robust.seed",
    "tolerances.t",
    "tolerances.E",
    "material.nu",
    "materials[].nu",
}


def _shown(default: str) -> str:
    return "**required**" if default == "required" else f"`{default}`" if default else "-"


def reference_markdown() -> str:
    """``docs/spec.md``: every key with its unit, default and meaning (Markdown)."""
    docs = dict(KEYS)
    keys = _check_documented(docs)
    lines = [
        "# Spec reference",
        "",
        "Generated from the spec model by `corrugate spec --reference` "
        "(`corrugate.spec.reference`); do not edit by hand. A spec is a TOML file; start from "
        "`corrugate init` or an example (`corrugate init --example NAME`). Every quantity is a "
        "string with any unit compatible with the one shown "
        '(`"48 mm"`, `"1.9 in"`, `"80 mN*m^2"`): a number, then unit names joined by `*`, `/`, '
        "`·` or a space, each with an optional whole exponent `^n` or `**n` (-4 <= n <= 4; no "
        "exponent of an exponent, no parenthesised exponent), parentheses at most 4 deep, at "
        "most 64 characters of unit. `[]` marks the items of an array of tables "
        "(`flexural_rigidity = [{ min = ..., eta = ... }]`).",
        "",
        "**Plain numbers** (column *plain*): a length may be a plain number in mm and an angle "
        "one in deg, and counts and ratios (`n`, `nu`, `safety_factor`, the `robust` "
        "tolerances) are plain numbers. Every other quantity (a rigidity, stiffness, load, "
        "modulus, density or mass) must carry its unit: a plain `80` could be 80 N mm^2 or the "
        "80 mN m^2 the web form shows, 1000 times apart, so `flexural_rigidity = [{ min = 80 }]` "
        "is refused with `constraints.flexural_rigidity[0].min = 80 has no unit: write it with "
        'one, e.g. "80 mN*m^2" (or "80 N*mm^2")` (exit 2; HTTP 422 from `POST /api/design`).',
        "",
        "**Directions** (every `eta`, of a spec, `analyze --eta` and the web form): from -360 to "
        "360 deg, both included; beyond that range an angle is refused, not reduced modulo 360 "
        '(`eta = "1e300 deg"` names no direction anyone can check: a typo, not a turn), with one '
        "line naming the key, the value given and the range (exit 2; HTTP 422).",
        "",
        "| key | unit | plain | default | meaning |",
        "|---|---|---|---|---|",
    ]
    tables = {k.rsplit(".", 1)[0] for k in keys if "." in k}
    tables |= {t.removesuffix("[]") for t in tables}
    for k in keys:
        doc = docs[k]
        default = _default(k)
        plain = plain_number(k, doc, k in tables)
        lines.append(f"| `{k}` | {doc.unit or '-'} | {plain} | {_shown(default)} | {doc.text} |")
    lines += [
        "",
        "Exit codes of `corrugate design`: 0 an answer, 1 no design meets the spec (infeasible), "
        "2 bad input (one line naming the key, the value and what is allowed), "
        "4 not certified within the work budget, 130 interrupted (Ctrl-C); with `--verify fe` "
        "also 1 a bound fails in FE, 5 a mesh series is not converged, 6 a bound has no FE twin "
        "(not checked) (docs/fea.md 6).",
        "",
        "Work budget. `design`, `pareto` and `tolerance` take `--budget SECONDS` (default 60; 0.01 to 86400): "
        "CPU seconds of the process (user + system; on an idle machine about wall seconds) for "
        "the whole solve, the explanation included (binding checks, runner-ups, the diagnosis of "
        "an infeasible spec), and at most 10^8 boxes bounded. The branch and bound checks the "
        "budget before each iteration; when it runs out the answer is not certified within the "
        "budget: one stderr line `corrugate: not certified within the budget of 60 s (used ...): "
        "best design found so far ..., proven gap ...` (or: no design found so far and none "
        "proven impossible) and exit code 4; `design --json` prints its object as usual with "
        '`"status": "not-certified"` and `solver.budget` (`cpu_seconds`, `boxes`, '
        "`used_cpu_seconds`, `used_boxes`, `exhausted`, `stopped_by`). A design certified before "
        "the budget ran out keeps exit code 0, with the warning `explanation-partial`. A spec "
        "proven infeasible before the budget ran out keeps exit code 1, and its diagnosis ends "
        "with an entry saying it is partial whenever the budget ran out in it (also inside its "
        "last entry's searches); a value from a search the budget cut short is followed by "
        '"(not certified: the work budget ran out before the search ended)": a design reaching '
        "it was found, not that none goes further; that no design meets the rest, that a frame "
        "does not help or how far a bound reaches alone is said only from searches that ended "
        "(`tests/solver/test_diagnosis.py`). In "
        "Python: `corrugate.design(spec, budget=10)`, `corrugate.workflow.solve_spec(spec, "
        "budget=10)`, `corrugate.solver.solve(problem, budget=10)`.",
        "",
        "Progress. A solve of `design` or `tolerance` that runs over a second shows on stderr "
        "what it is doing (searching; explaining: binding checks, runner-ups, the diagnosis and "
        "the constraint it is on), for how long, the iterations, the proven gap and the best "
        "value found: on a terminal one status line, refreshed in place and removed at the end; "
        "otherwise a line `corrugate: searching: 12 s, ...` at each stage and every 5 s. Nothing "
        "with `--quiet`, nor with `--json` unless stderr is a terminal; stdout carries only the "
        "answer.",
        "",
        f"Counts. A spec has at most {MAX_COUNTS['holes']} `layout.holes`, "
        f"{MAX_COUNTS['vertices']} vertices in `layout.vertices` and in each polygon hole, "
        f"{MAX_COUNTS['bounds']} behavioural bounds (`flexural_rigidity`, `bending_stiffness`, "
        "`inplane_stiffness`, `buckling_load`, `deflection` and `strength` together) and "
        f"{MAX_COUNTS['thicknesses']} candidate sheets (thicknesses over every material); "
        "more is one error line naming the list, its count and the cap (exit code 2).",
        "",
    ]
    return "\n".join(lines)


def _widen(node: Any, docs: Mapping[str, KeyDoc], path: str) -> Any:
    """Let every number also be a string with units and attach descriptions, recursively."""
    if isinstance(node, dict):
        if node.get("type") in ("number", "integer") and node.get("title") != "Seed":
            return {
                "anyOf": [{"type": node["type"]}, {"type": "string"}],
                **{k: v for k, v in node.items() if k != "type"},
            }
        return {k: _widen(v, docs, path) for k, v in node.items()}
    if isinstance(node, list):
        return [_widen(v, docs, path) for v in node]
    return node


def json_schema() -> dict[str, Any]:
    """A JSON Schema (draft 2020-12) of spec files, from :class:`~corrugate.spec.schema.Spec`."""
    docs = dict(KEYS)
    _check_documented(docs)
    schema = Spec.model_json_schema(mode="validation")
    defs = schema.get("$defs", {})

    def describe(props: dict[str, Any], prefix: str) -> None:
        for name, sub in props.items():
            path = f"{prefix}{name}"
            doc = docs.get(path)
            if doc is not None:
                unit = f" [{doc.unit}]" if doc.unit else ""
                sub["description"] = doc.text + unit
            ref = _ref_of(sub)
            if ref is not None:
                many = sub.get("type") == "array" or any(
                    s.get("type") == "array" for s in sub.get("anyOf", [])
                )
                describe(defs[ref].get("properties", {}), f"{path}[]." if many else f"{path}.")

    describe(schema["properties"], "")
    tol = schema["properties"].get("tolerances", {})
    if "$ref" in tol:  # a table, or "none" (the nominal certificate)
        tol["anyOf"] = [{"$ref": tol.pop("$ref")}, {"type": "string", "enum": ["none"]}]
    schema = _widen(schema, docs, "")
    schema["$schema"] = "https://json-schema.org/draft/2020-12/schema"
    schema["title"] = "corrugate design spec"
    return dict(schema)


def _ref_of(node: dict[str, Any]) -> str | None:
    """The $defs name a property refers to, through anyOf and array items."""
    if "$ref" in node:
        return str(node["$ref"]).rsplit("/", 1)[-1]
    for key in ("anyOf", "allOf"):
        for sub in node.get(key, []):
            found = _ref_of(sub)
            if found is not None:
                return found
    if "items" in node and isinstance(node["items"], dict):
        return _ref_of(node["items"])
    return None
