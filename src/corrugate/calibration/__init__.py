"""Calibrating the user's own sheet (docs/calibration.md): the coupons of a kit (``coupons``), the
cantilever elastica (``elastica``), the folded strip with compliant creases (``crease``), a
measurements file (``measurements``), the fit with its bootstrap intervals (``fit``), the
protocol and the kit's files (``protocol``, ``kit``) and the fit written as a user's material
(``entry``)."""
