"""Request and response bodies of the JSON API (pydantic), with the CLI's field names.

Values are numbers in the field's default unit or strings that may carry units, exactly as the CLI
takes them; the conversion and every range check are :mod:`corrugate.inputs`', so a bad value gets
the same message on both. Only the sizes of things (string lengths, list lengths) are checked here.
"""

from __future__ import annotations

from typing import Annotated

from pydantic import BaseModel, ConfigDict, Field, StrictFloat, StrictInt, StringConstraints

from ..moduli import DEFAULT_MODEL

__all__ = [
    "AnalyzeBody",
    "ErrorBody",
    "FieldError",
    "ModelInfo",
    "ModelsBody",
    "ResultBody",
    "ResultFile",
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

    W: Value = Field(description="Facet width (mm, or with units: '0.3 in').")
    n: Value = Field(description="Number of creases (n + 1 facets).")
    alpha: Value = Field(description="Interior fold angle (deg, 180 = flat; or '1.4 rad').")
    material: Text | None = Field(None, description="Library material id (GET /api/materials).")
    thickness: Value | None = Field(None, description="Sheet thickness (mm); default: material's.")
    E: Value | None = Field(None, description="Inline material: Young's modulus (MPa or '2.7GPa').")
    nu: Value | None = Field(None, description="Inline material: Poisson's ratio.")
    density: Value | None = Field(None, description="Inline material: density (g/cm^3).")
    W2: Value | None = Field(None, description="Layer 2 facet width (default: layer 1's).")
    n2: Value | None = Field(None, description="Layer 2 creases (default: layer 1's).")
    alpha2: Value | None = Field(None, description="Layer 2 fold angle (default: layer 1's).")
    material2: Text | None = Field(None, description="Layer 2 library material.")
    thickness2: Value | None = Field(None, description="Layer 2 thickness (default: layer 1's).")
    layout: Text = Field("square", description="square | rectangle | circle | polygon.")
    vertices: (
        Annotated[str, StringConstraints(max_length=8 * MAX_VERTICES)]
        | Annotated[list[Pair], Field(max_length=MAX_VERTICES)]
        | None
    ) = Field(None, description="Polygon outline: '0,0 1,0 0.5,1' or [[0,0],[1,0],[0.5,1]].")
    model: Text = Field(DEFAULT_MODEL, description="Moduli variant: paper | xia | refined.")
    eta: Annotated[list[Value], Field(max_length=MAX_ETAS)] | None = Field(
        None, description="Directions (deg from layer 1's creases). Default [0, 90]."
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
