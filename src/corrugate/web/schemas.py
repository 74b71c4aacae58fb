"""Request and response bodies of the JSON API (pydantic), with the CLI's field names.

Values are numbers in the field's default unit or strings that may carry units, exactly as the CLI
takes them; the conversion and every range check are :mod:`corrugate.spec.inputs`', so a bad value gets
the same message on both. Only the sizes of things (string lengths, list lengths) are checked here.
"""

from __future__ import annotations

from typing import Annotated, Any, Literal

from pydantic import BaseModel, ConfigDict, Field, StrictFloat, StrictInt, StringConstraints

from corrugate.core.parameters import PARAMETERS
from corrugate.export.writers import WRITERS
from corrugate.mechanics.behaviours import load_cases
from corrugate.names import DEFAULT_HOLE_SHAPE, DEFAULT_MACHINE, HOLE_SHAPES

__all__ = [
    "OUTPUT_OPTIONS",
    "AnalyzeBody",
    "DesignAnswer",
    "DesignBody",
    "ErrorBody",
    "FieldError",
    "FormatInfo",
    "HoleBody",
    "LoadCaseInfo",
    "ModelInfo",
    "ModelsBody",
    "OutputBody",
    "PatternBody",
    "ResultBody",
    "ResultFile",
    "format_list",
    "load_case_list",
]

MAX_ETAS = 181
MAX_VERTICES = 256

Text = Annotated[str, StringConstraints(max_length=64)]
Number = Annotated[StrictInt | StrictFloat, Field(allow_inf_nan=False)]
#: A number in the field's default unit, or a string such as "0.3 in" or "2.7 GPa".
Value = Number | Text
Pair = tuple[
    Annotated[float, Field(allow_inf_nan=False)], Annotated[float, Field(allow_inf_nan=False)]
]


MAX_HOLES = 16


def parameter(name: str) -> Any:
    """The pydantic field of the parameter ``name`` (:data:`~corrugate.core.parameters.PARAMETERS`):
    its default (required when the command line requires it) and its help text as the
    description."""
    p = PARAMETERS[name]
    if p.required:
        return Field(description=p.help)
    return Field(p.default, description=p.help)


class HoleBody(BaseModel):
    """An inner cut-out of the layout (:mod:`corrugate.geometry.holes`): lengths in mm (or with units) from
    the centre of the layout's bounding box, x across layer 1's creases."""

    model_config = ConfigDict(extra="forbid")

    shape: Text = Field(DEFAULT_HOLE_SHAPE, description=" | ".join(HOLE_SHAPES) + ".")
    diameter: Value | None = Field(None, description="Circle: diameter (mm or '6 mm').")
    center: Annotated[list[Value], Field(min_length=2, max_length=2)] | None = Field(
        None, description="Centre [x, y] (mm) from the layout's centre; default [0, 0]."
    )
    vertices: (
        Annotated[
            list[Annotated[list[Value], Field(min_length=2, max_length=2)]],
            Field(max_length=MAX_VERTICES),
        ]
        | None
    ) = Field(None, description="Polygon: [[x, y], ...] (mm) relative to the centre.")


class AnalyzeBody(BaseModel):
    """The options of ``corrugate analyze``, as JSON (``--json`` is implied)."""

    model_config = ConfigDict(
        extra="forbid",
        json_schema_extra={
            "examples": [
                {
                    "W": 8,
                    "n": 8,
                    "alpha": "84 deg",
                    "material": "dura-lar",
                    "model": "paper",
                    "eta": [0, 90],
                }
            ]
        },
    )

    W: Value = parameter("W")
    n: Value = parameter("n")
    alpha: Value = parameter("alpha")
    material: Text | None = parameter("material")
    thickness: Value | None = parameter("thickness")
    E: Value | None = parameter("E")
    nu: Value | None = parameter("nu")
    density: Value | None = parameter("density")
    W2: Value | None = parameter("W2")
    n2: Value | None = parameter("n2")
    alpha2: Value | None = parameter("alpha2")
    material2: Text | None = parameter("material2")
    thickness2: Value | None = parameter("thickness2")
    layout: Text = parameter("layout")
    vertices: (
        Annotated[str, StringConstraints(max_length=8 * MAX_VERTICES)]
        | Annotated[list[Pair], Field(max_length=MAX_VERTICES)]
        | None
    ) = parameter("vertices")
    holes: Annotated[list[HoleBody], Field(max_length=MAX_HOLES)] | None = parameter("holes")
    model: Text = parameter("model")
    eta: Annotated[list[Value], Field(max_length=MAX_ETAS)] | None = Field(
        None, description="Directions (deg from layer 1's creases). Default [0, 90]."
    )
    support: Text = parameter("support")
    test: Text | None = parameter("test")
    load: Value | None = parameter("load")
    span: Value | None = parameter("span")
    joint: Text = parameter("joint")


#: The keys of a request that state a load case (``corrugate analyze --test --load --span``)
#: and how its layers are joined (``--joint``).
LOAD_CASE_KEYS = ("test", "load", "span", "joint")

#: The keys of a design request that are output options, not spec keys.
OUTPUT_OPTIONS = ("cutter", "fold_style", "cut", "gap", "paper")

_SPEC_KEY = "A key of the spec, as in the TOML file (see corrugate.spec.schema and examples/)."

#: The paper's case study (``examples/blimp_gripper.toml``, the project's model) as a design request.
BLIMP_GRIPPER: dict[str, Any] = {
    "name": "blimp-gripper",
    "model": "refined",
    "material": {"name": "dura-lar", "thickness": "0.125 mm"},
    "layout": {"shape": "square"},
    "variables": {
        "W": {"min": "1 mm", "max": "30 mm", "step": "1 mm"},
        "n": {"min": 1, "max": 200},
        "alpha": {"min": "1 deg", "max": "120 deg", "step": "1 deg"},
    },
    "constraints": {
        "sheet_max": "250 mm",
        "side": {"min": "48 mm", "max": "60 mm"},
        "thickness": {"min": "10 mm", "max": "12.5 mm"},
        "flexural_rigidity": [{"min": "80 mN*m^2", "eta": "0 deg"}],
    },
    "objective": {"minimize": "mass"},
    "cutter": DEFAULT_MACHINE,
}


class OutputBody(BaseModel):
    """The output options of ``corrugate design`` and ``corrugate pattern`` (the keys of
    :data:`OUTPUT_OPTIONS`)."""

    cutter: Text = parameter("cutter")
    fold_style: Text = parameter("fold_style")
    cut: Value | None = parameter("cut")
    gap: Value | None = parameter("gap")
    paper: Text = parameter("paper")


class PatternBody(AnalyzeBody, OutputBody):
    """A design as ``corrugate analyze`` takes it plus the output options: every file
    ``corrugate pattern --out`` writes (cut files, fold map, PDF, FOLD, GLB/STL, steps,
    design.json)."""


class DesignBody(OutputBody):
    """A design spec as JSON, with the keys of the TOML file, plus the output options of
    ``corrugate design`` (``cutter``, ``fold_style``, ``cut``, ``gap``, ``paper``).

    The spec keys are validated by :func:`corrugate.spec.schema.parse_spec` (the CLI's own rules), so a
    bad value gets 422 naming its TOML path (``constraints.side.min``); only the output options
    are typed here.
    """

    model_config = ConfigDict(extra="allow", json_schema_extra={"examples": [BLIMP_GRIPPER]})

    name: Any = Field(None, description="Name of the design. " + _SPEC_KEY)
    model: Any = Field(None, description="Moduli variant: paper | xia | refined. " + _SPEC_KEY)
    layers: Any = Field(None, description="identical | independent. " + _SPEC_KEY)
    material: Any = Field(None, description="{name, thickness} or inline {E, nu, density, ...}.")
    materials: Any = Field(None, description="Candidate materials (a list). " + _SPEC_KEY)
    layout: Any = Field(None, description="{shape, vertices, holes}. " + _SPEC_KEY)
    variables: Any = Field(None, description="Bounds and steps of W, n and alpha. " + _SPEC_KEY)
    constraints: Any = Field(
        None,
        description="Size, stiffness, load-case (deflection) and mass bounds. " + _SPEC_KEY,
    )
    objective: Any = Field(None, description="{minimize = 'mass'} or {maximize, eta}.")
    robust: Any = Field(None, description="Tolerances for a robust design. " + _SPEC_KEY)
    tolerances: Any = Field(
        None,
        description="Worst-case tolerances the certificate covers ({alpha, W, t, E}) or 'none'. "
        + _SPEC_KEY,
    )


class SpecFileBody(BaseModel):
    """A spec file's text, as ``corrugate design FILE.toml`` reads it (the page's "Load a spec")."""

    model_config = ConfigDict(extra="forbid")

    toml: Annotated[str, StringConstraints(max_length=200_000)] = Field(
        description="The TOML text of a spec file (the keys of examples/blimp_gripper.toml)."
    )
    name: Annotated[str, StringConstraints(max_length=200)] = Field(
        "the file", description="The file's name, which errors name."
    )


class FieldError(BaseModel):
    """One problem with one field."""

    field: str = Field(description="The field, as named in the request (e.g. 'alpha2', 'body').")
    message: str
    value: str | None = None
    allowed: str | None = None


class ErrorBody(BaseModel):
    """Every error answer: a message, the (first) field at fault, and all the problems found."""

    detail: str
    field: str | None = None
    errors: list[FieldError] = []


class ResultFile(BaseModel):
    """A file the app made, downloadable at ``url`` while the result is kept."""

    name: str
    url: str
    media_type: str
    bytes: int


class ResultBody(BaseModel):
    """A stored result: its opaque id and its files."""

    id: str
    files: list[ResultFile]


class ModelInfo(BaseModel):
    """A moduli variant."""

    name: str
    source: str


class ModelsBody(BaseModel):
    """The moduli variants and the default."""

    default: str
    models: list[ModelInfo]


class DesignAnswer(BaseModel):
    """The design (``corrugate design --json``) and, when one exists, its files."""

    design: dict[str, Any] = Field(description="The object `corrugate design --json` prints.")
    result: ResultBody | None = Field(
        description="The files of the design when they are already made (they are made on "
        "demand: POST `files_url`); null until then, and when the spec is infeasible."
    )
    design_id: str | None = Field(
        default=None,
        description="The design's id (a keyed hash of the request and its design; null when "
        "the spec is infeasible).",
    )
    files_url: str | None = Field(
        default=None,
        description="POST here to make (once per design) and list every file `corrugate design "
        "--out` writes: `{id, files}` as `result`; null when the spec is infeasible.",
    )


class FormatInfo(BaseModel):
    """One kind of file a design's output folder holds (an entry of the writers registry)."""

    name: str = Field(description="The entry's name, e.g. 'cut-dxf'.")
    pattern: str = Field(
        description="Its file names: '{sheet}' is the sheet number from 1, '{layer}' the layer "
        "(1 or 2), '{paper}' a4 or letter; e.g. 'cut-{sheet}.dxf'."
    )
    media_type: str = Field(description="The media type its downloads are served with.")
    extra: str | None = Field(
        description="The package extra writing it needs ('fab'), or null for none."
    )
    description: str = Field(description="What the file is.")
    order: int = Field(description="Its place in the page's list of downloads (ascending).")


def format_list() -> list[FormatInfo]:
    """Every entry of the registry, in the order the files are written."""
    return [
        FormatInfo(
            name=w.name,
            pattern=w.pattern,
            media_type=w.media_type,
            extra=w.extra,
            description=w.description,
            order=w.order,
        )
        for w in WRITERS
    ]


class LoadCaseInfo(BaseModel):
    """One load case a requirement may name (an entry of the registry of behaviours with role
    ``test``, :mod:`corrugate.mechanics.behaviours`; docs/load_cases.md)."""

    name: str = Field(description="The spec's value of `test`, e.g. 'three-point'.")
    label: str = Field(description="Its words in a list of choices, e.g. 'between platens'.")
    kind: Literal["bending", "inplane"] = Field(
        description="'bending' (EI and D bounds may name it; it takes a span) or 'inplane' (K "
        "bounds may name it; no span)."
    )
    own: bool = Field(
        description="Whether it measures the support's own K: the test of a K bound that "
        "names none."
    )
    deflection: bool = Field(
        description="Whether a deflection or strength bound may name it (false: a stiffness "
        "bound only)."
    )
    layouts: list[str] = Field(description="The layouts it applies to (empty: every one).")
    text: str = Field(description="What the test is.")


def load_case_list() -> list[LoadCaseInfo]:
    """Every registered load case, in the order the spec's lists show them."""
    return [
        LoadCaseInfo(
            name=b.name,
            label=b.in_list(),
            kind=b.form.kind,
            own=b.form.own,
            deflection=not b.stiffness_only,
            layouts=list(b.layouts),
            text=b.text,
        )
        for b in load_cases()
        if b.form is not None
    ]


class VerifyBody(BaseModel):
    """An FE verification of a stored design (``corrugate verify DIR`` on its folder)."""

    model_config = ConfigDict(extra="forbid")

    result: Text = Field(description="The id of a design's result (`result.id` of its answer).")
    mesh: Annotated[str, StringConstraints(max_length=32)] = Field(
        "2,4,8",
        description="Mesh series: shell elements across each facet, even and increasing "
        "(as `corrugate verify --mesh`).",
    )


class JobLinks(BaseModel):
    """Where to follow a job."""

    status: str = Field(description="GET: the job's state (this object).")
    events: str = Field(description="GET: its progress as server-sent events.")


class JobBody(BaseModel):
    """A background job (``/api/jobs``): its state, the limits it runs under, its last progress
    event and, when finished, its result (a design: the answer of ``POST /api/design``; a
    verification: ``corrugate verify --json`` with the design's label) or its error."""

    id: str
    kind: str = Field(description="design | verify")
    status: str = Field(description="queued | running | done | failed | cancelled")
    limits: dict[str, Any] = Field(
        description="budget_s: solver CPU seconds (design); time_limit_s: wall seconds after "
        "which the job is stopped; memory_bytes: the worker's address-space cap."
    )
    created: float = Field(description="Unix time the job was made.")
    elapsed_s: float
    events: int = Field(description="Progress events so far.")
    progress: dict[str, Any] | None = Field(description="The last progress event.")
    result: Any = None
    error: dict[str, Any] | None = Field(
        None, description="{status: HTTP status it would have had, body: ErrorBody}"
    )
    links: JobLinks


class FeaInfo(BaseModel):
    """Whether this server can run FE verifications (CalculiX installed)."""

    available: bool
    ccx: str | None = Field(description="The ccx executable, or null.")
    message: str
    max_mesh: int = Field(
        description="Finest mesh (elements per facet) a web verification runs: a series not "
        "shown asymptotic is refined up to it, as corrugate verify --max-mesh."
    )
    time_limit_s: float = Field(description="Wall seconds after which a verification is stopped.")
