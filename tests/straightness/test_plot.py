"""Plots of the straightness room, written through io.figures."""

from __future__ import annotations

import numpy as np
import pytest

from axiscal.errors import AxiscalError
from axiscal.straightness.plot import plot_separation, plot_straightness
from axiscal.straightness.reference import reference_line
from axiscal.straightness.separation import reversal
from axiscal.units import MM, UM


def test_plots_are_written(tmp_path):
    x = np.linspace(0, 300, 31) * MM
    y = np.sin(x / (100 * MM)) * UM
    line = reference_line(x, y, reference="minimum-zone")
    assert plot_straightness(tmp_path / "zone.png", x, y, line).read_bytes()[:4] == b"\x89PNG"
    result = reversal(x, y, -y)
    assert plot_separation(tmp_path / "sep.svg", result).read_text().lstrip().startswith("<?xml")


def test_an_unknown_format_is_refused(tmp_path):
    x = np.linspace(0, 1, 5)
    with pytest.raises(AxiscalError, match="figure format"):
        plot_straightness(tmp_path / "zone.txt", x, x, reference_line(x, x))


def test_an_overlay_is_drawn_behind_with_its_legend(tmp_path):
    x = np.linspace(0, 300, 31) * MM
    y = np.sin(x / (100 * MM)) * UM
    line = reference_line(x, y)
    overlay = {"position_mm": list(x / MM), "deviation_um": [None] + list(2 * y[1:] / UM), "residual_um": list(y / UM)}
    text = plot_straightness(tmp_path / "zone.svg", x, y, line, overlay=overlay).read_text()
    assert "before: profile" in text and "before: about its line" in text  # a null is a gap, not an error
    text = plot_straightness(tmp_path / "as-found.svg", x, y, line, overlay={**overlay, "label": "as found"}).read_text()
    assert "as found: profile" in text
    assert "before" not in plot_straightness(tmp_path / "none.svg", x, y, line, overlay={"label": "x"}).read_text()
    result = reversal(x, y, -y)
    separated = {"position_mm": list(x / MM), "profile_um": list(2 * y / UM), "motion_um": [None] * x.size}
    text = plot_separation(tmp_path / "sep.svg", result, overlay=separated).read_text()
    assert "before: profile R" in text and "before: motion S" in text


@pytest.mark.parametrize("reference", ["least-squares", "minimum-zone"])
def test_the_separation_legend_gives_the_straightness_the_table_gives(tmp_path, reference):
    # R and S drawn about R's line keep S's tilt; the legend states each one's straightness about its own line
    x = np.linspace(0, 300, 31) * MM
    profile = np.sin(x / (60 * MM)) * UM
    motion = (2.0 * np.cos(x / (90 * MM)) + 4.0 * x / (300 * MM)) * UM          # bowed and tilted
    result = reversal(x, profile + motion, -profile + motion)
    expected = reference_line(result.position_m, result.motion_m, reference=reference).straightness_m / UM
    text = plot_separation(tmp_path / "sep.svg", result, reference=reference).read_text()
    assert f"motion S (straightness {expected:.3f} µm)" in text
    assert f"about each curve's own {reference} line" in text
    assert "P-V" not in text
