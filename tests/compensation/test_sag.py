"""SINUMERIK sag compensation tables ($AN_CEC): read back with a reader of the K3 syntax, applied as the
control interpolates them to a sagging cross-rail, and the refusals."""

from __future__ import annotations

import re

import numpy as np
import pytest

from axiscal.compensation.sag import sinumerik_sag_table
from axiscal.errors import AxiscalError
from axiscal.units import MM, UM


def read_cec(text):
    """%_N_NC_CEC_INI as the function manual K3 describes it."""
    lines = text.splitlines()
    assert lines[0] == "%_N_NC_CEC_INI" and lines[-1] == "M17"
    values, params = {}, {}
    for line in lines[2:-1]:
        m = re.fullmatch(r"\$AN_CEC\[(\d+),(\d+)\]=(\S+)", line)
        if m:
            values[(int(m.group(1)), int(m.group(2)))] = float(m.group(3))
            continue
        m = re.fullmatch(r"\$AN_CEC_(\w+)\[(\d+)\]=(\S+)", line)
        params[m.group(1)] = m.group(3)
    tables = {t for t, _ in values}
    assert len(tables) == 1
    (t,) = tables
    n = len(values)
    v = np.array([values[(t, i)] for i in range(n)])
    step, start, end = float(params["STEP"]), float(params["MIN"]), float(params["MAX"])
    assert abs(start + step * (n - 1) - end) < 1e-6  # equidistant, MIN..MAX
    return np.linspace(start, end, n) * MM, v * MM, params


def sag(y):
    # a cross-rail sagging along Y, seen on X: 30 um at mid-span and a 5 urad tilt
    return -30 * UM * np.sin(np.pi * y / 0.8) + 5e-6 * y


def test_round_trip_and_the_rail_comes_back_straight():
    y = np.linspace(0.0, 0.8, 33)
    table = sinumerik_sag_table(y, sag(y), input_axis="AX2", output_axis="AX1", step_m=25 * MM)
    nodes, values, params = read_cec(table.text())
    assert params["INPUT_AXIS"] == "(AX2)" and params["OUTPUT_AXIS"] == "(AX1)" and params["DIRECTION"] == "0"
    np.testing.assert_allclose(nodes, table.nodes, atol=1e-12)
    np.testing.assert_allclose(values, table.values_mm * MM, atol=1e-12)
    assert not table.resampled and table.note is None
    # the control removes the interpolated value: at the points only the 0.1 um rounding is left
    left = sag(nodes) - np.interp(nodes, nodes, values)
    assert np.abs(left).max() <= 0.05 * UM + 1e-12
    np.testing.assert_allclose(table.correction(nodes), -values)


def test_resampling_is_said_and_reference_removes_the_line():
    y = np.array([0.0, 0.13, 0.31, 0.52, 0.8])
    table = sinumerik_sag_table(y, sag(y), input_axis="Y1", output_axis="Z1", step_m=100 * MM, reference="end-points")
    assert table.resampled and "resampled onto 9 points 100 mm apart" in table.note
    assert table.values_mm[0] == 0 and table.values_mm[-1] == pytest.approx(0.0, abs=1e-4)


def test_refusals():
    y = np.linspace(0.0, 0.8, 9)
    e = sag(y)
    with pytest.raises(AxiscalError, match="MD18342"):
        sinumerik_sag_table(y, e, input_axis="AX2", output_axis="AX1", step_m=1 * MM, max_points=200)
    with pytest.raises(AxiscalError, match="must differ"):
        sinumerik_sag_table(y, e, input_axis="AX1", output_axis="ax1", step_m=0.1)
    with pytest.raises(AxiscalError, match="strictly increasing"):
        sinumerik_sag_table(y[::-1], e, input_axis="AX2", output_axis="AX1", step_m=0.1)
    with pytest.raises(AxiscalError, match="positive length"):
        sinumerik_sag_table(y, e, input_axis="AX2", output_axis="AX1", step_m=-1.0)
    with pytest.raises(AxiscalError, match="DIRECTION"):
        sinumerik_sag_table(y, e, input_axis="AX2", output_axis="AX1", step_m=0.1, direction=2)


# ---- HEIDENHAIN dependent-axis .COM (Z = F(Y))


def read_com(text):
    """A .COM table as the TNC 407 / MANUALplus 620 technical manuals describe it:
    ``BEGIN NAME.COM MM``, a header ``NR AXISPOS <axis>... [BACKLASH]``, numbered rows, ``[END]``."""
    lines = text.splitlines()
    begin = re.fullmatch(r"BEGIN (\w+)\.COM (MM|INCH)", lines[0])
    assert begin and lines[-1] == "[END]"
    header = lines[1].split()
    assert header[:2] == ["NR", "AXISPOS"]
    rows = [line.split() for line in lines[2:-1]]
    assert [int(r[0]) for r in rows] == list(range(len(rows)))
    columns = {name: np.array([float(r[k]) for r in rows]) * MM for k, name in enumerate(header) if k}
    assert np.all(np.diff(columns["AXISPOS"]) > 0) and len(rows) <= 256
    return begin.group(1), columns


def test_heidenhain_dependent_axis_round_trip_and_the_rail_comes_back_straight():
    from axiscal.compensation.sag import heidenhain_sag_table

    y = np.linspace(-0.09, 0.41, 41)  # the manual's example: Y from -90 mm, over 500 mm
    table = heidenhain_sag_table(y, sag(y + 0.09), base_axis="y", compensation_axis="z")
    name, columns = read_com(table.text())
    assert name == "YZ" and set(columns) == {"AXISPOS", "Z"}
    np.testing.assert_allclose(columns["AXISPOS"], y, atol=1e-12)
    np.testing.assert_allclose(columns["Z"], table.error_mm * MM, atol=1e-12)
    # the control subtracts the interpolated error of Z at the commanded Y
    left = sag(y + 0.09) + table.correction(y, "+")
    assert np.abs(left).max() <= 0.05 * UM + 1e-12
    assert not table.resampled
    assert "enter YZ.COM in column Y of the .CMA table (Z = F(Y))" in table.note


def test_heidenhain_dependent_axis_resampling_limit_and_refusals():
    from axiscal.compensation.sag import heidenhain_sag_table

    y = np.linspace(0.0, 0.8, 801)
    with pytest.raises(AxiscalError, match="at most 256.*at least 3.137 mm"):
        heidenhain_sag_table(y, sag(y), base_axis="Y", compensation_axis="Z")
    table = heidenhain_sag_table(y, sag(y), base_axis="Y", compensation_axis="Z", step_m=5 * MM, name="sag_z")
    name, columns = read_com(table.text())
    assert name == "sag_z" and columns["AXISPOS"].size == 161 and table.resampled
    assert "resampled onto 161 rows" in table.note
    np.testing.assert_allclose(columns["Z"], sag(columns["AXISPOS"]), atol=0.05 * UM + 1e-12)
    for kwargs, message in [
        ({"base_axis": "Y", "compensation_axis": "y"}, "must differ"),
        ({"base_axis": "Y1", "compensation_axis": "Z"}, "not an axis key"),
        ({"base_axis": "Y", "compensation_axis": "Z", "step_m": 0.0}, "positive length"),
        ({"base_axis": "Y", "compensation_axis": "Z", "step_m": 1e-12}, "10\\^6 points"),
        ({"base_axis": "Y", "compensation_axis": "Z", "name": "../x"}, "plain file name"),
        ({"base_axis": "Y", "compensation_axis": "Z", "reference": "best"}, "unknown reference"),
    ]:
        with pytest.raises(AxiscalError, match=message):
            heidenhain_sag_table(y[::100], sag(y[::100]), **kwargs)
    with pytest.raises(AxiscalError, match="finite"):
        heidenhain_sag_table(np.array([0.0, np.nan]), np.zeros(2), base_axis="Y", compensation_axis="Z")


def test_sag_table_file_refuses_options_of_the_other_controller(examples):
    from axiscal.compensation.sag import sag_table_file

    run = examples / "squareness_y.csv"
    with pytest.raises(AxiscalError, match="needs the step"):
        sag_table_file(run, controller="siemens", base_axis="AX2", compensation_axis="AX1")
    with pytest.raises(AxiscalError, match="SINUMERIK settings"):
        sag_table_file(run, controller="heidenhain", base_axis="Y", compensation_axis="X", direction=1)
    with pytest.raises(AxiscalError, match="HEIDENHAIN setting"):
        sag_table_file(run, controller="siemens", base_axis="AX2", compensation_axis="AX1", step_m=0.01, name="x")
    with pytest.raises(AxiscalError, match="unknown controller"):
        sag_table_file(run, controller="fanuc", base_axis="Y", compensation_axis="X")
