"""The names of every choice the user makes, and the defaults of the options, importable without
numpy.

Each set of names is a ``Literal`` type defined once here, with the tuple of its values derived
from it (:func:`typing.get_args`), so that the command line declares its options (``corrugate
--help`` loads no numpy), the spec parser and the web app type their fields, and the tables that
implement the names (:data:`corrugate.mechanics.moduli.MODELS`,
:data:`corrugate.fabrication.sheets.CUTTERS`, :func:`corrugate.geometry.layouts.make_layout`,
:data:`corrugate.mechanics.offaxis.SUPPORTS`, ...) all use the same words; ``tests/test_names.py``
checks that each table implements exactly its names. This module imports nothing of corrugate.

Lengths are in mm.
"""

from __future__ import annotations

from typing import Final, Literal, get_args

__all__ = [
    "CUT_FORMATS",
    "DEFAULT_FOLD_STYLE",
    "DEFAULT_HOLE_SHAPE",
    "DEFAULT_LAYOUT",
    "DEFAULT_MACHINE",
    "DEFAULT_MARGIN_MM",
    "DEFAULT_MODEL",
    "DEFAULT_PAPER",
    "DEFAULT_SPACING_MM",
    "DEFAULT_SUPPORT",
    "DEFAULT_TAB_DEPTH_MM",
    "FILE_FORMATS",
    "FOLD_OP_NAMES",
    "FOLD_STYLES",
    "HOLE_SHAPES",
    "JOINTS",
    "LASER",
    "LASER_PREFIX",
    "LAYOUT_SHAPES",
    "LOAD_CASES",
    "MACHINE_NAMES",
    "MODEL_NAMES",
    "PAPER_NAMES",
    "RECTANGULAR_LAYOUTS",
    "STIFFNESS_NAMES",
    "STIFFNESS_ONLY_TESTS",
    "STIFFNESS_SYMBOL",
    "STIFFNESS_SYMBOLS",
    "SUPPORTS",
    "CutFormat",
    "FileFormat",
    "FoldOpName",
    "FoldStyle",
    "HoleShape",
    "JointName",
    "LayoutShape",
    "LoadCaseName",
    "MachineName",
    "ModelName",
    "PaperName",
    "StiffnessName",
    "StiffnessOnlyTest",
    "StiffnessSymbol",
    "Support",
]

# -- the moduli variants (corrugate.mechanics.moduli.MODELS) -----------------------------------

ModelName = Literal["paper", "xia", "refined"]
#: Every moduli variant, in the order tables list them.
MODEL_NAMES: tuple[ModelName, ...] = get_args(ModelName)
#: The variant used unless one is asked for: it agrees with the unit-cell FE (docs/fea.md 1.3).
DEFAULT_MODEL: Final[ModelName] = "refined"

# -- support conditions of a stiffness (corrugate.mechanics.offaxis) --------------------------

Support = Literal["free", "frame"]
#: The support conditions a stiffness can be asked for under: free sides, or a rigid frame.
SUPPORTS: tuple[Support, ...] = get_args(Support)
#: Free sides: a bench test and most mounts (docs/offaxis.md).
DEFAULT_SUPPORT: Final[Support] = "free"

# -- load cases (corrugate.mechanics.load_cases, docs/load_cases.md) --------------------------

LoadCaseName = Literal["three-point", "four-point", "cantilever", "platens"]
#: The tests a deflection is stated in: simply supported with the load at mid-span or at the
#: quarter points, a cantilever loaded at its free end, compression between rigid platens. The
#: command line's ``analyze --test`` choices (declared without numpy); the spec, its reference,
#: the report and the page read the registry itself
#: (:func:`corrugate.mechanics.behaviours.deflection_tests`, which ``tests/test_names.py``
#: checks these are).
LOAD_CASES: tuple[LoadCaseName, ...] = get_args(LoadCaseName)
#: The tests only a stiffness bound names (no deflection, load or strength): the wheel test of a
#: circle's K (docs/load_cases.md 9), registered after the load cases.
StiffnessOnlyTest = Literal["wheel"]
STIFFNESS_ONLY_TESTS: tuple[StiffnessOnlyTest, ...] = get_args(StiffnessOnlyTest)
JointName = Literal["none", "band-edges", "band-flanges"]
#: How the layers are joined (docs/load_cases.md 7): the connector band left out, or bonded
#: along the edges or by its flanges (:data:`corrugate.mechanics.load_cases.JOINTS`).
JOINTS: tuple[JointName, ...] = get_args(JointName)

# -- plan outlines (corrugate.geometry.layouts) and inner cut-outs (corrugate.geometry.holes) --

LayoutShape = Literal["square", "rectangle", "circle", "polygon"]
#: The plan outlines of a panel.
LAYOUT_SHAPES: tuple[LayoutShape, ...] = get_args(LayoutShape)
DEFAULT_LAYOUT: Final[LayoutShape] = "square"
#: The outlines that are rectangles, with straight edges across and along the creases: the ones
#: the FE tests load (``corrugate validate``, a design.json it reads).
RECTANGULAR_LAYOUTS: tuple[LayoutShape, ...] = ("square", "rectangle")

HoleShape = Literal["circle", "polygon"]
#: The shapes of an inner cut-out.
HOLE_SHAPES: tuple[HoleShape, ...] = get_args(HoleShape)
DEFAULT_HOLE_SHAPE: Final[HoleShape] = "circle"

# -- machines (corrugate.fabrication.sheets.CUTTERS, corrugate.export.machines) ---------------

MachineName = Literal["cameo4-12x12", "cameo4-12x24", "maker-12x12", "maker-12x24"]
#: The named machines (cutter and mat); a laser is named by its bed instead, ``laser:WxH`` (mm).
MACHINE_NAMES: tuple[MachineName, ...] = get_args(MachineName)
#: How a laser's name begins, and the form of the whole name (W x H mm, e.g. ``laser:600x400``).
LASER_PREFIX: Final = "laser:"
LASER: Final = "laser:WxH"
#: The default machine: the paper's cutter, a Silhouette Cameo 4 on its 12 x 12 in mat.
DEFAULT_MACHINE: Final[MachineName] = "cameo4-12x12"

#: The cut-ready file formats a machine reads (:class:`corrugate.export.machines.Machine`).
CutFormat = Literal["svg", "dxf"]
CUT_FORMATS: tuple[CutFormat, ...] = get_args(CutFormat)

#: The file sets :func:`corrugate.export.files.write_files` writes: the fold map, the cut files
#: and the PDF.
FileFormat = Literal["svg", "cut", "pdf"]
FILE_FORMATS: tuple[FileFormat, ...] = get_args(FileFormat)

# -- stiffness quantities (the spec's keys and the solver's symbols) --------------------------

StiffnessName = Literal["flexural_rigidity", "bending_stiffness", "inplane_stiffness"]
#: The stiffness kinds a spec may bound or maximise.
STIFFNESS_NAMES: tuple[StiffnessName, ...] = get_args(StiffnessName)
StiffnessSymbol = Literal["EI", "D", "K"]
#: Their symbols: EI(eta) in N mm^2, D(eta) in N mm, K(eta) in N/mm (docs/theory.md).
STIFFNESS_SYMBOLS: tuple[StiffnessSymbol, ...] = get_args(StiffnessSymbol)
#: The symbol of each kind.
STIFFNESS_SYMBOL: Final[dict[StiffnessName, StiffnessSymbol]] = dict(
    zip(STIFFNESS_NAMES, STIFFNESS_SYMBOLS, strict=True)
)

# -- the output options of a pattern ------------------------------------------------------------

FoldStyle = Literal["machine", "solid", "scored", "perforated"]
#: ``--fold-style``: ``machine``, the machine's default fold operations for the sheet
#: (:func:`corrugate.export.operations.default_operations`), or one of the ways of making every
#: fold line (:class:`corrugate.fabrication.linestyle.StyleKind`).
FOLD_STYLES: tuple[FoldStyle, ...] = get_args(FoldStyle)
DEFAULT_FOLD_STYLE: Final[FoldStyle] = "machine"

FoldOpName = Literal["cut-score", "perforate", "score", "pen", "none"]
#: What the machine does with one kind of crease or mark
#: (:class:`corrugate.export.operations.FoldOp`).
FOLD_OP_NAMES: tuple[FoldOpName, ...] = get_args(FoldOpName)

PaperName = Literal["mat", "a4", "letter"]
#: ``mat``: ``pattern.pdf`` only (one mat-size page per sheet); ``a4``, ``letter``: also its 1:1
#: tiles on office paper (:data:`corrugate.export.pdf.PAPERS`).
PAPER_NAMES: tuple[PaperName, ...] = get_args(PaperName)
DEFAULT_PAPER: Final[PaperName] = "mat"

#: Least distance between two parts on a sheet, and from a part to the sheet's edge (mm).
DEFAULT_SPACING_MM: Final = 5.0
DEFAULT_MARGIN_MM: Final = 5.0
#: Depth of the connector band's glue tabs (mm).
DEFAULT_TAB_DEPTH_MM: Final = 4.0
