"""One design's performance: :mod:`.evaluate` (vectorised evaluation and :func:`analyze`),
:mod:`.warnings` (where a model is used outside its evidence), :mod:`.sweep` (chunked grids of
designs) and :mod:`.display` (short text and HTML views for the REPL and notebooks)."""
