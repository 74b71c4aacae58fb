"""The names the stored tables of ``docs/validation/`` (``load_cases_fe.csv``, ``off_axis_fe.csv``,
``off_axis_fe_held_platens.csv``) give their tests in the ``test`` column, and the FE fixture
(``corrugate.fea.fixtures``) each names: the one mapping, documented in docs/fea.md section 2.
The benchmarks that append rows to those tables keep writing the stored names."""

from __future__ import annotations

FIXTURE_OF: dict[str, str] = {
    "compression": "platens",
    "bending": "three-point",
    "bending4": "four-point",  # its pure-bending gauge
    "bending4-load": "four-point",  # the same run read at its load points
    "cantilever": "cantilever",
}
