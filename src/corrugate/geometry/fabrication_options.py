"""Fabrication options: the sizes of the connector band and its glue tabs (mm)."""

from __future__ import annotations

from dataclasses import dataclass

from corrugate.core.errors import InputError
from corrugate.core.limits import LIMITS, abnormal_reason, is_normal
from corrugate.names import DEFAULT_TAB_DEPTH_MM

__all__ = ["DEFAULT_FABRICATION", "FabricationOptions"]


@dataclass(frozen=True, slots=True)
class FabricationOptions:
    """Connector sizes (mm).

    ``tab_depth``: depth g of the glue tabs on the band's two long edges; ``tab_length``: their
    nominal length along the band (each straight run is divided into equal tabs no longer than
    this); ``overlap``: length of the tab that joins one band segment to the next;
    ``segment_max``: longest band segment along a smooth outline (a circle's band is cut in equal
    arcs no longer than this, so that it fits the cutter's mat).
    """

    tab_depth: float = DEFAULT_TAB_DEPTH_MM
    tab_length: float = 12.0
    overlap: float = 8.0
    segment_max: float = 200.0

    def __post_init__(self) -> None:
        for name in ("tab_depth", "tab_length", "overlap", "segment_max"):
            value = getattr(self, name)
            if not (is_normal(value) and 0 < value <= LIMITS["length"].hi):
                allowed = f"0 < {name} <= {LIMITS['length'].hi:g} mm"
                raise InputError(
                    name, f"{value} mm", allowed, reason=abnormal_reason(value) or "is out of range"
                )
        if self.tab_length <= self.tab_depth:
            raise InputError(
                "tab_length",
                f"{self.tab_length} mm",
                f"tab_length > tab_depth = {self.tab_depth} mm",
            )


DEFAULT_FABRICATION = FabricationOptions()
