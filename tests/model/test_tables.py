"""Error tables: reading with units, interpolation, range handling."""

from __future__ import annotations

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from axiscal.conventions import component_names
from axiscal.errors import AxiscalError
from axiscal.model.tables import ErrorTable, read_error_table
from axiscal.units import ARCSEC


def write(tmp_path, text, name="t.csv"):
    path = tmp_path / name
    path.write_text(text)
    return path


def test_reads_units_and_fills_missing_columns(tmp_path):
    path = write(tmp_path, "position_mm,EXX_um,EYX_nm,ECX_arcsec,EAX_mrad\n0,1,100,1,0.001\n10,2,200,2,0.002\n")
    table = read_error_table(path, "X")
    np.testing.assert_allclose(table.position_m, [0.0, 0.01])
    np.testing.assert_allclose(table.component("EXX"), [1e-6, 2e-6])
    np.testing.assert_allclose(table.component("EYX"), [1e-7, 2e-7])
    np.testing.assert_allclose(table.component("ECX"), [ARCSEC, 2 * ARCSEC])
    np.testing.assert_allclose(table.component("EAX"), [1e-6, 2e-6])
    np.testing.assert_array_equal(table.component("EZX"), [0.0, 0.0])


@pytest.mark.parametrize(
    "text, message, line",
    [
        ("position_mm,EXX_furlong\n0,1\n1,2\n", "unknown length unit 'furlong'", 1),
        ("position_mm,EXY_um\n0,1\n1,2\n", "unknown column 'EXY_um' for axis X", 1),
        ("position_mm,EXX_um\n0,1\n0,2\n", "not strictly increasing", 3),
        ("position_mm,EXX_um\n0,1\n1,nan\n", "not a finite number", 3),
        ("pos,EXX_um\n0,1\n1,2\n", "first column must be 'position_mm'", 1),
        ("position_mm,EAX_um\n0,1\n1,2\n", "unknown angle unit 'um'", 1),
        ("position_mm,EXX_um,EXX_nm\n0,1,1\n1,2,2\n", "given twice", 1),
    ],
)
def test_bad_tables_name_file_and_line(tmp_path, text, message, line):
    path = write(tmp_path, text)
    with pytest.raises(AxiscalError) as info:
        read_error_table(path, "X")
    assert message in str(info.value)
    assert info.value.path == str(path) and info.value.line == line


def test_outside_the_table_is_an_error_unless_ends_are_held():
    table = ErrorTable.from_components("Z", np.array([0.0, 0.1]), {"EXZ": np.array([1e-6, 3e-6])})
    with pytest.raises(AxiscalError, match="Z = 150 mm is outside the error table"):
        table.evaluate(np.array([0.05, 0.15]))
    held = ErrorTable.from_components("Z", np.array([0.0, 0.1]), {"EXZ": np.array([1e-6, 3e-6])}, hold_ends=True)
    np.testing.assert_allclose(held.evaluate(np.array([-1.0, 0.05, 0.15]))[0], [1e-6, 2e-6, 3e-6])


def plain_interp(table, q):
    return np.array([np.interp(q, table.position_m, row) for row in table.values])


@settings(max_examples=40, deadline=None)
@given(st.integers(0, 2**31 - 1), st.booleans())
def test_fast_linear_interpolation_matches_numpy_interp(seed, uniform):
    rng = np.random.default_rng(seed)
    rows = int(rng.integers(2, 50))
    position = np.linspace(0, 0.5, rows) if uniform else np.cumsum(rng.uniform(0.001, 0.02, rows))
    table = ErrorTable("Y", position, rng.normal(size=(6, rows)) * 1e-4)
    q = np.concatenate([rng.uniform(position[0], position[-1], 100), position])
    np.testing.assert_allclose(table.evaluate(q), plain_interp(table, q), rtol=1e-12, atol=1e-16)


def test_cubic_interpolation_passes_through_the_rows_and_is_smooth():
    position = np.linspace(0, 0.19, 20)
    values = np.vstack([np.sin(30 * position)] * 6) * 1e-6
    table = ErrorTable("X", position, values, interpolation="cubic")
    np.testing.assert_allclose(table.evaluate(position), values, atol=1e-18)
    q = np.linspace(0, 0.19, 1000)
    assert np.abs(table.evaluate(q)[0] - np.sin(30 * q) * 1e-6).max() < 1e-9
    with pytest.raises(AxiscalError, match="unknown interpolation"):
        ErrorTable("X", position, values, interpolation="quintic")


def test_component_names():
    assert component_names("Z") == ("EXZ", "EYZ", "EZZ", "EAZ", "EBZ", "ECZ")
    assert component_names("A") == ("EXA", "EYA", "EZA", "EAA", "EBA", "ECA")
    with pytest.raises(AxiscalError):
        component_names("U")


@settings(max_examples=40, deadline=None)
@given(
    st.integers(0, 2**31 - 1),
    st.sampled_from(["nm", "um", "mm"]),
    st.sampled_from(["urad", "mrad", "arcsec"]),
)
def test_written_tables_read_back_in_si_whatever_the_units(tmp_path_factory, seed, length_unit, angle_unit):
    from axiscal.units import ANGLE_UNITS, LENGTH_UNITS

    rng = np.random.default_rng(seed)
    rows = int(rng.integers(2, 30))
    position_mm = np.cumsum(rng.uniform(0.5, 20.0, rows))
    values = rng.normal(size=(6, rows)) * np.array([1e-5] * 3 + [1e-4] * 3)[:, None]
    names = component_names("Y")
    header = ["position_mm"] + [f"{n}_{length_unit if k < 3 else angle_unit}" for k, n in enumerate(names)]
    factors = [LENGTH_UNITS[length_unit]] * 3 + [ANGLE_UNITS[angle_unit]] * 3
    lines = [",".join(header)]
    for j in range(rows):
        lines.append(",".join([repr(float(position_mm[j]))] + [repr(float(values[k, j] / factors[k])) for k in range(6)]))
    path = tmp_path_factory.mktemp("t") / "y.csv"
    path.write_text("\n".join(lines) + "\n")
    table = read_error_table(path, "Y")
    np.testing.assert_allclose(table.position_m, position_mm * 1e-3, rtol=1e-15)
    np.testing.assert_allclose(table.values, values, rtol=1e-12, atol=1e-24)
