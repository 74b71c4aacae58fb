"""Flat patterns: the parts of a design to cut, their creases, and the folded geometry."""

from corrugate.fabrication.model import Line, Part, Pattern, Role, polygon_area

__all__ = ["Line", "Part", "Pattern", "Role", "polygon_area"]
