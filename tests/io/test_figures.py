"""The overlay helpers of io.figures: another campaign's series read once, the same way for every plot."""

from __future__ import annotations

import numpy as np
import pytest

from axiscal.errors import AxiscalError
from axiscal.io.figures import OVERLAY_LABEL, overlay_label, overlay_series


def test_a_series_reads_null_as_nan_and_an_absent_key_as_none():
    values = overlay_series({"deviation_um": [1.5, None, 2]}, "deviation_um", length=3)
    assert np.array_equal(values, [1.5, np.nan, 2.0], equal_nan=True)
    assert overlay_series({"deviation_um": [1.0]}, "position_mm") is None
    assert overlay_series({"deviation_um": None}, "deviation_um") is None


@pytest.mark.parametrize("bad, words", [
    ({"x_um": "1,2"}, "must be numbers"), ({"x_um": [True, 1.0]}, "must be numbers"), ({"x_um": [[1.0]]}, "one-dimensional"),
    ({"x_um": [1.0, 2.0]}, "3 values"), ({"x_um": ["a"]}, "must be numbers"),
])
def test_a_bad_series_is_refused_naming_it(bad, words):
    with pytest.raises(AxiscalError, match=words) as caught:
        overlay_series(bad, "x_um", length=3)
    assert caught.value.message.startswith("overlay x_um")


def test_an_overlay_that_is_not_a_mapping_is_refused():
    with pytest.raises(AxiscalError, match="overlay must be"):
        overlay_series([1, 2], "x_um")


def test_the_legend_label_defaults_to_before():
    assert overlay_label({}) == overlay_label({"label": "  "}) == overlay_label({"label": 5}) == OVERLAY_LABEL == "before"
    assert overlay_label({"label": "as found"}) == "as found"


def _axes():
    from axiscal.io.figures import pyplot

    fig, ax = pyplot().subplots()
    return fig, ax


def test_set_up_axes_labels_titles_grids_and_draws_the_zero_line_and_legend():
    from axiscal.io.figures import LEGEND_FONT_SIZE, pyplot, set_up_axes

    fig, ax = _axes()
    ax.plot([0.0, 1.0], [1.0, -1.0], label="run 1")
    assert set_up_axes(ax, xlabel="position / mm", ylabel="deviation / µm", title="E0: pass", title_size=9, grid=True,
                       legend=True, zero_line=True) is ax
    assert (ax.get_xlabel(), ax.get_ylabel(), ax.get_title()) == ("position / mm", "deviation / µm", "E0: pass")
    assert ax.title.get_fontsize() == 9
    assert all(line.get_visible() for line in ax.get_xgridlines())
    assert [t.get_text() for t in ax.get_legend().get_texts()] == ["run 1"]
    assert ax.get_legend().get_texts()[0].get_fontsize() == LEGEND_FONT_SIZE
    assert any(list(line.get_ydata()) == [0.0, 0.0] for line in ax.get_lines())
    pyplot().close(fig)


def test_set_up_axes_takes_legend_options_over_the_default_size():
    from axiscal.io.figures import pyplot, set_up_axes

    fig, ax = _axes()
    ax.plot([0.0, 1.0], [0.0, 1.0], label="a")
    ax.plot([0.0, 1.0], [1.0, 0.0], label="b")
    set_up_axes(ax, legend=True, legend_options={"fontsize": 7, "ncol": 2})
    assert ax.get_legend().get_texts()[0].get_fontsize() == 7
    assert ax.get_legend()._ncols == 2
    pyplot().close(fig)


def test_set_up_axes_leaves_out_what_is_not_asked_and_a_legend_of_nothing(recwarn):
    from axiscal.io.figures import pyplot, set_up_axes

    fig, ax = _axes()
    ax.plot([0.0, 1.0], [0.0, 1.0])
    set_up_axes(ax, legend=True)
    assert ax.get_legend() is None and ax.get_xlabel() == "" and ax.get_title() == ""
    assert not ax.get_lines()[1:]
    assert not [w for w in recwarn if "legend" in str(w.message).lower()]
    pyplot().close(fig)


def test_every_plot_draws_its_grid_through_set_up_axes():
    import re
    from pathlib import Path

    package = Path(__file__).resolve().parents[2] / "src" / "axiscal"
    own = [f"{p.relative_to(package)}:{n}" for p in sorted(package.rglob("*.py")) if p.name != "figures.py"
           for n, line in enumerate(p.read_text(encoding="utf-8").splitlines(), 1) if re.search(r"\.grid\(", line)]
    assert own == []
