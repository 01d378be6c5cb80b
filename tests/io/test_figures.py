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
