"""The memory the machine has available now: what an FE run may still take without swapping.

``corrugate verify`` and the web app's verification read it before an extending CalculiX run,
whose memory is estimated beforehand (docs/fea.md 6: four times the nodes of the run before times
``corrugate.fea.verify.BYTES_PER_NODE``); a run estimated above it is not made, and its row is
"not converged (memory)" rather than a run the kernel kills or CalculiX cannot allocate.
"""

from __future__ import annotations

__all__ = ["available_memory"]


def available_memory() -> int | None:
    """Bytes of memory the machine has available now (``MemAvailable`` of /proc/meminfo: free
    without swapping), None where it cannot be read."""
    try:
        with open("/proc/meminfo", encoding="ascii") as f:
            for text in f:
                if text.startswith("MemAvailable:"):
                    return int(text.split()[1]) * 1024
    except (OSError, ValueError, IndexError):
        return None
    return None
