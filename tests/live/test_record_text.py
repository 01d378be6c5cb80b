"""The compiled writer of the record's lines against Python's ``%`` formatting: same text, or one unit in the last digit."""

from __future__ import annotations

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from axiscal.live.record_text import FIXED, GENERAL, INTEGER, format_rows, python_format
from axiscal.live.recorder import Recorder, read_record

KINDS = np.array([FIXED, GENERAL, GENERAL, INTEGER, GENERAL], dtype=np.int64)
DIGITS = np.array([9, 15, 9, 0, 6], dtype=np.int64)


def assert_cells_agree(fast: str, reference: str, kinds=KINDS, digits=DIGITS) -> None:
    """Line by line and cell by cell: the same text, or values one unit apart in the last digit written."""
    fast_lines, reference_lines = fast.split("\n"), reference.split("\n")
    assert len(fast_lines) == len(reference_lines)
    for line, expected in zip(fast_lines, reference_lines):
        cells, wanted = line.split(","), expected.split(",")
        assert len(cells) == len(wanted)
        for cell, want, kind, places in zip(cells, wanted, kinds, digits):
            if cell == want:
                continue
            got, value = float(cell), float(want)
            unit = abs(value) * 10.0 ** (1 - int(places)) if kind == GENERAL else 10.0 ** -int(places)
            assert abs(got - value) <= 1.01 * unit, (cell, want)


def test_typical_and_special_values_are_written_as_python_writes_them():
    rng = np.random.default_rng(0)
    n = 5000
    table = np.column_stack(
        [
            np.arange(n) / 1e4,
            rng.normal(size=n) * 10.0 ** rng.integers(-30, 30, n),
            rng.normal(size=n) * 10.0 ** rng.integers(-8, 12, n),
            rng.integers(0, 300, n).astype(float),
            rng.normal(size=n) * 10.0 ** rng.integers(-300, 300, n),
        ]
    )
    special = [np.nan, np.inf, -np.inf, 0.0, -0.0, 1e-4, 9.9999e-5, 123456789.0, 1e16, 9.9999999996, 5e-324, 1e308, -1e-12]
    table[: len(special), 1] = special
    table[: len(special), 2] = special
    table[: len(special), 4] = special
    table[: len(special), 0] = [np.nan, np.inf, -np.inf, 0.0, -0.0, 1e-4, 9.9999e-5, 0.5, 0.0, 9.9999999996, 5e-324, 0.0, -1e-12]
    fast = format_rows(table, KINDS, DIGITS).decode("ascii")
    reference = "".join(python_format(KINDS, DIGITS) % tuple(row) for row in table.tolist())
    assert_cells_agree(fast, reference)
    lines = fast.splitlines()
    assert lines[0].split(",")[1:3] == ["nan", "nan"] and lines[1].split(",")[1] == "inf" and lines[2].split(",")[1] == "-inf"
    assert lines[4].split(",")[:3] == ["-0.000000000", "-0", "-0"] and lines[12].split(",")[0] == "-0.000000000"
    assert lines[7].split(",")[2] == "123456789" and lines[8].split(",")[2] == "1e+16" and lines[5].split(",")[2] == "0.0001"


@settings(max_examples=300, deadline=None)
@given(st.lists(st.floats(allow_nan=True, allow_infinity=True), min_size=1, max_size=30))
def test_any_double_is_written_to_its_digits(values):
    table = np.column_stack([np.zeros(len(values)), values, values, np.zeros(len(values)), values])
    fast = format_rows(table, KINDS, DIGITS).decode("ascii")
    reference = "".join(python_format(KINDS, DIGITS) % tuple(row) for row in table.tolist())
    assert_cells_agree(fast, reference)


@pytest.mark.parametrize("too_large", [2.0**53 / 1e9, 1e300])
def test_a_time_stamp_too_large_for_the_compiled_writer_is_left_to_python(too_large):
    assert format_rows(np.array([[too_large, 1.0, 1.0, 0.0, 1.0]]), KINDS, DIGITS) is None


def test_the_record_reads_back_what_python_wrote_and_falls_back_for_huge_time_stamps(tmp_path):
    rng = np.random.default_rng(1)
    t = np.array([0.0, 1e-4, 2e-4, 1e7])  # the last one too large for the compiled writer
    values = rng.normal(size=(4, 2)) * 100
    fault = np.array([0, 1, 0, 256])
    results = {"e_um": rng.normal(size=4), "x_mm": np.array([np.nan, 1.5, -0.0, 1e-7])}
    with Recorder(tmp_path / "run.csv", ("a_mm", "b_um"), ("e_um", "x_mm")) as recorder:
        recorder.append(t[:3], values[:3], fault[:3], {name: column[:3] for name, column in results.items()})
        recorder.append(t[3:], values[3:], fault[3:], {name: column[3:] for name, column in results.items()})
    lines = (tmp_path / "run.csv").read_text().splitlines()
    assert lines[0] == "t_s,a_mm,b_um,fault,e_um,x_mm"
    fmt = "%.9f,%.15g,%.15g,%d,%.9g,%.9g"
    kinds = np.array([FIXED, GENERAL, GENERAL, INTEGER, GENERAL, GENERAL])
    digits = np.array([9, 15, 15, 0, 9, 9])
    reference = "\n".join(fmt % (t[i], *values[i], fault[i], results["e_um"][i], results["x_mm"][i]) for i in range(4))
    assert_cells_agree("\n".join(lines[1:]), reference, kinds, digits)
    assert lines[4] == reference.splitlines()[3]  # written by Python itself
    record = read_record(tmp_path / "run.csv")
    np.testing.assert_allclose(record.columns["a_mm"], values[:, 0], rtol=1e-14)
    np.testing.assert_array_equal(record.columns["fault"], fault)
