"""What to join the parts with, per library material: a suggestion from common practice for
each sheet, not something this project has tested (ASSEMBLY.md names it in its steps;
docs/fabrication.md)."""

from __future__ import annotations

__all__ = ["ADHESIVES", "DEFAULT_ADHESIVE", "adhesive_for"]

_TAPE = "thin double-sided acrylic tape (transfer tape), or cyanoacrylate (super glue) sparingly"

#: Library material id -> the adhesive suggested for its glue tabs.
ADHESIVES: dict[str, str] = {
    "dura-lar": _TAPE,
    "mylar": _TAPE,
    "petg": _TAPE,
    "polycarbonate": _TAPE,
    "pvc": _TAPE,
    "acetate": _TAPE,
    "polypropylene": (
        "double-sided tape made for low-surface-energy plastics (polypropylene resists most "
        "glues, cyanoacrylate included)"
    ),
    "kapton": "double-sided polyimide or acrylic tape",
    "fr4": "two-part epoxy or cyanoacrylate",
    "cardstock": "PVA (white) glue or a glue stick",
    "aluminium-shim": "two-part epoxy, or cyanoacrylate on lightly sanded tabs",
    "stainless-shim": "two-part epoxy on lightly sanded tabs",
}

#: For a sheet not in the library.
DEFAULT_ADHESIVE = "double-sided tape (try it on an offcut first)"


def adhesive_for(material_id: str) -> str:
    """The adhesive suggested for ``material_id`` (:data:`ADHESIVES`, else the default)."""
    return ADHESIVES.get(material_id, DEFAULT_ADHESIVE)
