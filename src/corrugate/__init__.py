"""corrugate: design orthogonally assembled double-layered corrugated (OADLC) panels.

Quick use::

    import corrugate
    result = corrugate.design("examples/blimp_gripper.toml")  # a path, a dict or TOML text
    corrugate.write_files(result, "out/gripper")

    from corrugate import Assembly, Layer, analyze, get_material
    layer = Layer(W=8, n=8, alpha_deg=84, material=get_material("dura-lar"))
    result = analyze(Assembly.identical(layer), model="refined", eta_deg=[0, 90])
    print(result.to_dict())

Internal units: mm, N, MPa, g (DESIGN.md section 8).
"""

import sys
from importlib import import_module
from types import ModuleType
from typing import TYPE_CHECKING, Any

if TYPE_CHECKING:
    from .analysis import (
        Analysis,
        DirectionalStiffness,
        Evaluation,
        LayerArrays,
        analyze,
        evaluate,
    )
    from .checks import ModelWarning, design_warnings
    from .errors import CorrugateError, InputError, UnknownNameError
    from .geometry import Assembly, Layer
    from .layouts import Circle, Polygon, Rectangle, Square, make_layout
    from .mass import MassBreakdown, assembly_mass
    from .materials import Material, get_material, inline_material, library
    from .moduli import DEFAULT_MODEL, MODELS, Moduli, get_model, moduli

#: Where each public name lives; imported on first use (PEP 562), so ``import corrugate`` (and
#: every ``corrugate.x`` submodule import, the command line's start-up included) costs nothing
#: until a name is used.
_WHERE: dict[str, str] = {
    **dict.fromkeys(
        ("Analysis", "DirectionalStiffness", "Evaluation", "LayerArrays", "analyze", "evaluate"),
        "analysis",
    ),
    **dict.fromkeys(("ModelWarning", "design_warnings"), "checks"),
    **dict.fromkeys(("CorrugateError", "InputError", "UnknownNameError"), "errors"),
    **dict.fromkeys(("Assembly", "Layer"), "geometry"),
    **dict.fromkeys(("Circle", "Polygon", "Rectangle", "Square", "make_layout"), "layouts"),
    **dict.fromkeys(("MassBreakdown", "assembly_mass"), "mass"),
    **dict.fromkeys(("Material", "get_material", "inline_material", "library"), "materials"),
    **dict.fromkeys(("DEFAULT_MODEL", "MODELS", "Moduli", "get_model", "moduli"), "moduli"),
    **dict.fromkeys(("DesignResult", "write_files"), "api"),
}

#: Public names that are subpackages themselves (``corrugate.design(spec)`` is callable).
_SUBPACKAGES = ("design",)


def __getattr__(name: str) -> Any:
    if name in _SUBPACKAGES:
        return import_module(f".{name}", __name__)
    where = _WHERE.get(name)
    if where is None:
        raise AttributeError(f"module 'corrugate' has no attribute {name!r}")
    value = getattr(import_module(f".{where}", __name__), name)
    globals()[name] = value
    return value


def __dir__() -> list[str]:
    return sorted({*globals(), *_WHERE})


class _Package(ModuleType):
    """The package module: the import system binds each loaded submodule on it
    (``corrugate.moduli`` the module), which would hide the public function of the same name;
    such a binding is dropped, so the name still resolves through :func:`__getattr__`, as it did
    when this file imported every name eagerly."""

    def __setattr__(self, name: str, value: Any) -> None:
        if (
            name in _WHERE
            and isinstance(value, ModuleType)
            and value.__name__ == f"{__name__}.{name}"
        ):
            return
        super().__setattr__(name, value)


sys.modules[__name__].__class__ = _Package


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
