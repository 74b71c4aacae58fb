"""The built-in support conditions, one module each, registered in the registry of behaviours
(:mod:`corrugate.mechanics.behaviours`) by one line each, in the order every list shows them.

* :mod:`.free`: free sides (the default; a bench test, a part held at two edges);
* :mod:`.frame`: a rigid frame on all four edges (the paper's cos^2 rule).

The load cases (role ``test``: three-point, four-point, cantilever, platens, wheel) are defined in
:mod:`corrugate.mechanics.load_cases` and registered here too, after the supports, in the order
of its :data:`~corrugate.mechanics.load_cases.BUILT_IN`.

A new support condition is a module beside these defining its
:class:`~corrugate.mechanics.behaviours.Behaviour`, and its ``register`` line here; a new built-in
load case is its entry in :mod:`corrugate.mechanics.load_cases` and its place in ``BUILT_IN``.
"""

from corrugate.mechanics import load_cases
from corrugate.mechanics.behaviours import register
from corrugate.mechanics.supports import frame, free

__all__ = ["frame", "free"]

register(free.FREE)
register(frame.FRAME)
for _case in load_cases.BUILT_IN:
    register(_case)
