"""The built-in support conditions, one module each, registered in the registry of behaviours
(:mod:`corrugate.mechanics.behaviours`) by one line each, in the order every list shows them.

* :mod:`.free`: free sides (the default; a bench test, a part held at two edges);
* :mod:`.frame`: a rigid frame on all four edges (the paper's cos^2 rule).

The load cases (role ``test``: three-point, four-point, cantilever, platens, wheel) are defined in
:mod:`corrugate.mechanics.load_cases` and registered here too, after the supports.

A new support condition (or load case) is a module beside these defining its
:class:`~corrugate.mechanics.behaviours.Behaviour`, and its ``register`` line here.
"""

from corrugate.mechanics import load_cases
from corrugate.mechanics.behaviours import register
from corrugate.mechanics.supports import frame, free

__all__ = ["frame", "free"]

register(free.FREE)
register(frame.FRAME)
register(load_cases.THREE_POINT)
register(load_cases.FOUR_POINT)
register(load_cases.CANTILEVER)
register(load_cases.PLATENS)
register(load_cases.WHEEL)
