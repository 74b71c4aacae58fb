"""corrugate: design orthogonally assembled double-layered corrugated (OADLC) panels.

Quick use::

    import corrugate
    result = corrugate.design("examples/blimp_gripper.toml")  # a path, a dict or TOML text
    corrugate.write_files(result, "out/gripper")

    from corrugate import Assembly, Layer, analyze, get_material
    layer = Layer(W=8, n=8, alpha_deg=84, material=get_material("dura-lar"))
    result = analyze(Assembly.identical(layer), model="refined", eta_deg=[0, 90])
    print(result.to_dict())

Internal units: mm, N, MPa, g (docs/theory.md section 8).
"""

from importlib import import_module as _import_module
from typing import TYPE_CHECKING as _TYPE_CHECKING
from typing import Any as _Any

if _TYPE_CHECKING:
    from corrugate.analysis.evaluate import (
        Analysis,
        DirectionalStiffness,
        Evaluation,
        LayerArrays,
        analyze,
        evaluate,
    )
    from corrugate.analysis.warnings import ModelWarning, design_warnings
    from corrugate.core.errors import CorrugateError, InputError, UnknownNameError
    from corrugate.geometry.layer import Assembly, Layer
    from corrugate.geometry.layouts import Circle, Polygon, Rectangle, Square, make_layout
    from corrugate.materials.library import Material, get_material, inline_material, library
    from corrugate.mechanics.mass import MassBreakdown, assembly_mass
    from corrugate.mechanics.moduli import DEFAULT_MODEL, MODELS, Moduli, get_model, moduli
    from corrugate.workflow import DesignResult, design, write_files

#: Where each public name lives; imported on first use (PEP 562), so ``import corrugate`` (and
#: every ``corrugate.x`` submodule import, the command line's start-up included) costs nothing
#: until a name is used. No public name is also a subpackage's name, so the import system's
#: binding of a loaded subpackage never hides one.
_WHERE: dict[str, str] = {
    **dict.fromkeys(
        ("Analysis", "DirectionalStiffness", "Evaluation", "LayerArrays", "analyze", "evaluate"),
        "analysis.evaluate",
    ),
    **dict.fromkeys(("ModelWarning", "design_warnings"), "analysis.warnings"),
    **dict.fromkeys(("CorrugateError", "InputError", "UnknownNameError"), "core.errors"),
    **dict.fromkeys(("Assembly", "Layer"), "geometry.layer"),
    **dict.fromkeys(
        ("Circle", "Polygon", "Rectangle", "Square", "make_layout"), "geometry.layouts"
    ),
    **dict.fromkeys(("MassBreakdown", "assembly_mass"), "mechanics.mass"),
    **dict.fromkeys(
        ("Material", "get_material", "inline_material", "library"), "materials.library"
    ),
    **dict.fromkeys(
        ("DEFAULT_MODEL", "MODELS", "Moduli", "get_model", "moduli"), "mechanics.moduli"
    ),
    **dict.fromkeys(("DesignResult", "design", "write_files"), "workflow"),
}


def __getattr__(name: str) -> _Any:
    # corrugate.core.lazy.lazy_names, written out: the top package imports no module of its own,
    # so that importing one leaf module (corrugate.names) loads nothing else (tests/test_names.py)
    where = _WHERE.get(name)
    if where is None:
        raise AttributeError(f"module 'corrugate' has no attribute {name!r}")
    value = getattr(_import_module(f".{where}", __name__), name)
    globals()[name] = value
    return value


def __dir__() -> list[str]:
    """The public API (:data:`__all__`): ``dir(corrugate)`` lists what a user may call."""
    return sorted(__all__)


__version__ = "0.1.0"

__all__ = [
    "DEFAULT_MODEL",
    "MODELS",
    "Analysis",
    "Assembly",
    "Circle",
    "CorrugateError",
    "DesignResult",
    "DirectionalStiffness",
    "Evaluation",
    "InputError",
    "Layer",
    "LayerArrays",
    "MassBreakdown",
    "Material",
    "ModelWarning",
    "Moduli",
    "Polygon",
    "Rectangle",
    "Square",
    "UnknownNameError",
    "__version__",
    "analyze",
    "assembly_mass",
    "design",
    "design_warnings",
    "evaluate",
    "get_material",
    "get_model",
    "inline_material",
    "library",
    "make_layout",
    "moduli",
    "write_files",
]
