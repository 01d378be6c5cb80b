"""The CSV reader: errors name file and line; values are finite floats."""

from __future__ import annotations

import numpy as np
import pytest
from hypothesis import given
from hypothesis import strategies as st

from axiscal.errors import AxiscalError
from axiscal.io.tabular import parse_csv, read_csv, write_csv


def test_reads_numbers_skipping_comments_and_blank_lines():
    table = parse_csv(["# made by hand", "position_mm, EXX_um", "", "0, 1.5", "10, -2"])
    assert table.header == ("position_mm", "EXX_um")
    np.testing.assert_array_equal(table.numeric("EXX_um"), [1.5, -2.0])
    assert table.lines == (4, 5)


@pytest.mark.parametrize(
    "lines, message, line",
    [
        (["a,b", "1,x"], "'x' is not a number", 2),
        (["a,b", "1,nan"], "not a finite number", 2),
        (["a,b", "1,2,3"], "3 cells where the header has 2", 2),
        (["a,a", "1,2"], "appears twice", 1),
        (["a,b"], "0 data rows", 1),
    ],
)
def test_errors_name_the_line(lines, message, line):
    with pytest.raises(AxiscalError) as info:
        table = parse_csv(lines, path="f.csv")
        table.numeric("b")
    assert message in str(info.value)
    assert info.value.line == line
    assert str(info.value).startswith(f"f.csv:{line}: ")


def test_missing_column_and_missing_file(tmp_path):
    with pytest.raises(AxiscalError, match="missing column 'c'"):
        parse_csv(["a,b", "1,2"]).numeric("c")
    with pytest.raises(AxiscalError, match="file not found"):
        read_csv(tmp_path / "nope.csv")


@given(st.lists(st.floats(allow_nan=False, allow_infinity=False, width=32), min_size=1, max_size=20))
def test_write_then_read_round_trip(values):
    text = write_csv(None, {"x_mm": values}, fmt="{:.17g}")
    back = parse_csv(text.splitlines()).numeric("x_mm")
    np.testing.assert_array_equal(back, np.asarray(values, dtype=float))
