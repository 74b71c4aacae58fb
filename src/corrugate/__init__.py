"""corrugate: design orthogonally assembled double-layered corrugated (OADLC) panels.

Quick use::

    from corrugate import Assembly, Layer, analyze, get_material
    layer = Layer(W=8, n=8, alpha_deg=84, material=get_material("dura-lar"))
    result = analyze(Assembly.identical(layer), model="refined", eta_deg=[0, 90])
    print(result.to_dict())

Internal units: mm, N, MPa, g (DESIGN.md section 8).
"""

from .analysis import Analysis, DirectionalStiffness, Evaluation, LayerArrays, analyze, evaluate
from .checks import ModelWarning, design_warnings
from .errors import CorrugateError, InputError, UnknownNameError
from .geometry import Assembly, Layer
from .layouts import Circle, Polygon, Rectangle, Square, make_layout
from .mass import MassBreakdown, assembly_mass
from .materials import Material, get_material, inline_material, library
from .moduli import DEFAULT_MODEL, MODELS, Moduli, get_model, moduli

__version__ = "0.1.0"

__all__ = [
    "DEFAULT_MODEL",
    "MODELS",
    "Analysis",
    "Assembly",
    "Circle",
    "CorrugateError",
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
    "design_warnings",
    "evaluate",
    "get_material",
    "get_model",
    "inline_material",
    "library",
    "make_layout",
    "moduli",
]
