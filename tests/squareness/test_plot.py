"""Plots of the squareness room, written through io.figures."""

from __future__ import annotations

import numpy as np

from axiscal.instruments.optics import pentaprism_sensitivity
from axiscal.squareness.evaluation import squareness
from axiscal.squareness.plot import plot_pentaprism, plot_squareness
from axiscal.units import ARCMIN, MM, UM


def test_plots_are_written(tmp_path):
    x = np.linspace(0, 100, 11) * MM
    runs = ((x, 1e-4 * x + 0.1 * UM), (x, -2e-4 * x))
    result = squareness(*runs[0], *runs[1])
    assert plot_squareness(tmp_path / "sq.png", result, runs).read_bytes()[:4] == b"\x89PNG"
    table = pentaprism_sensitivity(np.linspace(-5, 5, 3) * ARCMIN, np.linspace(-2, 2, 3) * MM)
    assert plot_pentaprism(tmp_path / "fig5.png", table).stat().st_size > 1000


def test_an_overlay_draws_the_other_runs_and_lines(tmp_path):
    x = np.linspace(0, 100, 11) * MM
    runs = ((x, 1e-4 * x + 0.1 * UM), (x, -2e-4 * x))
    result = squareness(*runs[0], *runs[1])
    other = {which: {"position_mm": list(x / MM), "deviation_um": list(3e-4 * x / UM), "line_um": list(3e-4 * x / UM)}
             for which in ("first", "second")}
    text = plot_squareness(tmp_path / "sq.svg", result, runs, overlay=other).read_text()
    assert text.count("before: measured") == 2 and text.count("before: line") == 2
    del other["second"]["line_um"]
    text = plot_squareness(tmp_path / "one.svg", result, runs, overlay=other).read_text()
    assert text.count("before: measured") == 2 and text.count("before: line") == 1
