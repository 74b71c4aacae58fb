"""Geometry of a design: the cross-section of a corrugation (:mod:`.profile`: the zig-zag and the
registry of profiles), one folded layer and the two-layer assembly (:mod:`.layer`), the outline
it fills (:mod:`.layouts`, with :mod:`.holes` and :mod:`.planar`), and the fabrication allowances
and connector geometry the mechanics needs (:mod:`.fabrication_options`, :mod:`.connectors`).
docs/theory.md section 2.
"""
