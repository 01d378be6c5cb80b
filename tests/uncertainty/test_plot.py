"""The plot of |e| and its interval: against the axis positions, one panel per moving axis."""

from __future__ import annotations

import numpy as np
import pytest

from axiscal.errors import AxiscalError
from axiscal.uncertainty import VolumetricUncertainty, plot_volumetric_uncertainty


def fake(n, rng):
    error = rng.normal(0.0, 5e-6, (n, 3))
    magnitude = np.linalg.norm(error, axis=1)
    spread = np.full((n, 3), 1e-6)
    return VolumetricUncertainty(error, error, spread, error - 2e-6, error + 2e-6, 1000, 0.95,
                                 np.full(n, 1e-6), magnitude - 2e-6, magnitude + 2e-6)


@pytest.mark.parametrize("moving,panels", [("X", 1), ("XY", 2), ("XYZ", 3), ("", 3)])
def test_one_panel_per_moving_axis_labelled_with_its_position(tmp_path, moving, panels):
    rng = np.random.default_rng(0)
    n = 12
    q = {k: (np.linspace(0.0, 0.5, n) if k in moving else np.full(n, 0.1)) for k in "XYZ"}
    path = tmp_path / "p.svg"
    plot_volumetric_uncertainty(q, fake(n, rng), path, title="a map")
    text = path.read_text()
    labels = [k for k in "XYZ" if k in moving] or list("XYZ")
    for k in labels:
        assert f"{k} position / mm" in text
    assert text.count("position / mm") == panels
    assert "point" not in text.replace("points", "")  # never against a point index
    assert "|e| / µm" in text and "95% interval" in text


def test_a_bad_suffix_is_refused_before_drawing(tmp_path):
    with pytest.raises(AxiscalError, match="figure format"):
        plot_volumetric_uncertainty({"X": np.zeros(2)}, fake(2, np.random.default_rng(1)), tmp_path / "p.txt")
