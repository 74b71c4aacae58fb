"""The design report: one self-contained HTML file with the figures embedded."""

from corrugate.report.figures import design_space_figure, mass_by_n_figure, polar_figure
from corrugate.report.html import report_html

__all__ = ["design_space_figure", "mass_by_n_figure", "polar_figure", "report_html"]
