"""The as-left positioning plot with the as-found curves: named, one colour per direction, readable, legend clear."""

from __future__ import annotations

import numpy as np
import pytest

import axiscal.positioning.plot as plot_module
from axiscal.positioning import evaluate_positioning_file


@pytest.fixture
def drawn(monkeypatch):
    figures = []

    def keep(fig, path, **_):
        figures.append(fig)
        return path

    monkeypatch.setattr(plot_module, "save_figure", keep)
    return figures


def _as_found(evaluation, scale: float) -> dict:
    per = evaluation.to_dict()["targets"]
    return {"target_mm": per["target_mm"], "mean_up_um": [scale * (1 + v) for v in per["mean_up_um"]],
            "mean_down_um": [scale * (1 - v) for v in per["mean_down_um"]], "label": "as found", "current_label": "as left"}


def test_as_found_forty_times_larger_goes_to_an_inset_and_as_left_stays_readable(examples, tmp_path, drawn):
    evaluation = evaluate_positioning_file(examples / "positioning_run.csv")
    evaluation.plot(tmp_path / "p.png", overlay=_as_found(evaluation, 40 * 13.0), figures_table=False)
    (fig,) = drawn
    ax = fig.axes[0]
    labels = [line.get_label() for line in ax.get_lines() if not line.get_label().startswith("_")]
    assert "as left: mean x̄↑ (+)" in labels and "as found: mean x̄↑ (inset)" in labels
    # each direction its own colour
    colours = {line.get_label(): line.get_color() for line in ax.get_lines()}
    assert colours["as found: mean x̄↑ (inset)"] != colours["as found: mean x̄↓ (inset)"]
    # the main plot's y range is the as-left data's, the as-found curves drawn in the inset at their scale
    low, high = ax.get_ylim()
    singles = np.concatenate([d.ravel() for d in (evaluation.run.deviations_up, evaluation.run.deviations_down)]) * 1e6
    assert low <= singles.min() and high >= singles.max() and high - low < 3 * np.ptp(singles)
    (inset,) = [child for child in ax.child_axes]
    assert max(np.nanmax(line.get_ydata()) for line in inset.get_lines()) > 40 * 13.0 * 0.9
    # the legend sits at the top, the footnote at the bottom
    assert ax.get_legend()._loc == 2  # upper left


def test_a_comparable_overlay_is_drawn_on_the_plot_itself(examples, tmp_path, drawn):
    evaluation = evaluate_positioning_file(examples / "positioning_run.csv")
    evaluation.plot(tmp_path / "p.png", overlay=_as_found(evaluation, 1.0), figures_table=False)
    (fig,) = drawn
    labels = [line.get_label() for line in fig.axes[0].get_lines()]
    assert "as found: mean x̄↑" in labels and "as found: mean x̄↓" in labels and not fig.axes[0].child_axes
