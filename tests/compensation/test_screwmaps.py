"""TwinCAT CNC leadscrew error compensation lists: the manual's worked example, a round trip through a
reader written from the manual's syntax, and the control's own interpolation removing the error."""

from __future__ import annotations

import re

import numpy as np
import pytest

from axiscal.compensation import error_curve
from axiscal.compensation.curve import ErrorCurve
from axiscal.compensation.screwmaps import TWINCAT_UNIT, twincat_table
from axiscal.errors import AxiscalError
from axiscal.positioning import read_positioning_run, target_statistics
from axiscal.units import MM, UM


def read_ssfk(text):
    """A compensation value list as the TwinCAT CNC axis compensation manual describes it."""
    values = {}
    for line in text.splitlines():
        line = line.split("#", 1)[0].strip()
        if not line:
            continue
        key, value = line.split(None, 1)
        values[key] = value.strip()
    n = int(values["kw.ssfk.kw_nr_max"])
    assert values["kw.ssfk.unit"] == "1"  # 0.1 um
    interval = int(values["kw.ssfk.interval"])
    start = int(values["kw.ssfk.kw_startpos"])
    if interval:
        setpoints = start + interval * np.arange(n)
    else:
        setpoints = np.array([int(values[f"kw.ssfk.table[{i}].setpoint"]) for i in range(n)])
        assert setpoints[0] == start
    pos = np.array([int(values[f"kw.ssfk.table[{i}].pos"]) for i in range(n)])
    bilateral = values["kw.ssfk.bilateral"] == "1"
    neg = np.array([int(values[f"kw.ssfk.table[{i}].neg"]) for i in range(n)]) if bilateral else pos
    indices = {int(m.group(1)) for k in values if (m := re.match(r"kw\.ssfk\.table\[(\d+)\]", k))}
    assert indices == set(range(n))  # kw_nr_max entries, no more
    return setpoints, pos, neg


def control_correction(setpoints, values, x):
    # the control subtracts the interpolated position error from the setpoint
    return -np.interp(x, setpoints * 0.1 * UM, values * 0.1 * UM)


def test_manual_worked_example():
    # TwinCAT CNC axis compensation, example list: programmed 19866.7 um, reached 19856.5 um (+) and
    # 19874.7 um (-): entered as -102 and 80 (x 0.1 um)
    curve = ErrorCurve(np.array([0.0, 19866.7 * UM]), np.array([0.0, (19856.5 - 19866.7) * UM]),
                       np.array([0.0, (19874.7 - 19866.7) * UM]))
    table = twincat_table(curve)
    assert table.pos.tolist() == [0, -102] and table.neg.tolist() == [0, 80]
    assert table.setpoints.tolist() == [0, 198667]


@pytest.mark.parametrize("interval_mm", [None, 50.0, 7.5])
@pytest.mark.parametrize("bilateral", [True, False])
def test_round_trip_and_residuals(examples, interval_mm, bilateral):
    curve = error_curve(target_statistics(read_positioning_run(examples / "positioning_run.csv").run))
    table = twincat_table(curve, axis="X", interval_m=None if interval_mm is None else interval_mm * MM, bilateral=bilateral)
    setpoints, pos, neg = read_ssfk(table.text())
    np.testing.assert_array_equal(setpoints, table.setpoints)
    np.testing.assert_array_equal(pos, table.pos)
    np.testing.assert_array_equal(neg, table.neg)
    # at the table's points the error left is the rounding to 0.1 um
    x = setpoints * TWINCAT_UNIT
    x = x[x <= curve.positions[-1]]
    for direction, values in (("+", pos), ("-", neg)):
        left = curve.at(x, direction if bilateral else "mean") + control_correction(setpoints, values, x)
        assert np.abs(left).max() <= 0.05 * UM + 1e-12
        np.testing.assert_allclose(table.correction(x, direction), control_correction(setpoints, values, x))
    if interval_mm is None:
        left = curve.at(curve.positions, "+") + control_correction(setpoints, pos, curve.positions)
        assert np.abs(left).max() <= 0.05 * UM + 1e-12 or not bilateral


def test_refusals():
    curve = ErrorCurve(np.array([0.0, 0.1, 0.2]), np.zeros(3), np.zeros(3))
    with pytest.raises(AxiscalError, match="P-COMP-00059"):
        twincat_table(curve, interval_m=1 * MM, max_points=100)
    with pytest.raises(AxiscalError, match="whole number of 0.1 um"):
        twincat_table(curve, interval_m=0.00001 * MM)
    with pytest.raises(AxiscalError, match="positive length"):
        twincat_table(curve, interval_m=0.0)
    with pytest.raises(AxiscalError, match="axis numbers"):
        twincat_table(curve, axis_number=0)


# ---- Mach4 screw map (MachMotion, "Mach 4 Screw Mapping")


def read_mach4(text):
    """The values as MachMotion's page defines them: Start Point, Length, Number of Points (evenly
    spaced, both ends included) and the Error at each point (expected - actual position)."""
    lines = text.splitlines()
    assert lines[0].startswith("Mach4 screw map, axis ")
    fields = {}
    for line in lines[1:4]:
        name, value = re.fullmatch(r"(Start Point|Length|Number of Points)\s+(\S+)(?: (mm|in))?", line).group(1, 2)
        fields[name] = float(value)
    n = int(fields["Number of Points"])
    head = lines[4].split()
    rows = [line.split() for line in lines[5:]]
    assert len(rows) == n and [int(r[0]) for r in rows] == list(range(1, n + 1))
    positions = fields["Start Point"] + fields["Length"] * np.arange(n) / (n - 1)
    np.testing.assert_allclose([float(r[1]) for r in rows], positions, atol=1e-4 + 1e-9)
    up = np.array([float(r[2]) for r in rows])
    down = np.array([float(r[3]) for r in rows]) if "-" in head[-1] else up
    return positions, up, down


@pytest.mark.parametrize("points, bidirectional, unit", [(None, True, "mm"), (33, True, "mm"), (9, False, "in")])
def test_mach4_round_trip_and_the_axis_comes_back(examples, points, bidirectional, unit):
    from axiscal.compensation.screwmaps import mach4_screw_map

    curve = error_curve(target_statistics(read_positioning_run(examples / "positioning_run.csv").run))
    m = mach4_screw_map(curve, points=points, bidirectional=bidirectional, unit=unit)
    positions, up, down = read_mach4(m.text())
    scale = MM if unit == "mm" else 25.4 * MM
    step = 10.0 ** -m.decimals
    assert abs(positions[0] - curve.positions[0] / scale) <= step and abs(positions[-1] - curve.positions[-1] / scale) <= step
    # the error is expected - actual: the map adds it to the command, which cancels the deviation
    for direction, errors in (("+", up), ("-", down)):
        x = positions * scale
        want = curve.at(x, direction if bidirectional else "mean")
        reached = want + np.interp(x, positions * scale, errors * scale)
        assert np.abs(reached).max() <= 0.5 * 10.0 ** -m.decimals * scale + 1e-12
        np.testing.assert_allclose(m.correction(x, direction), errors * scale, atol=1e-15)
    # the example's targets are not evenly spaced: they are resampled, and the note says so
    assert m.resampled and "evenly spaced points" in m.note


def test_mach4_refusals():
    from axiscal.compensation.screwmaps import mach4_screw_map

    curve = ErrorCurve(np.array([0.0, 0.1]), np.zeros(2), np.zeros(2))
    for kwargs, message in [({"points": 1}, "2 to 10\\^5 points"), ({"points": 10**9}, "2 to 10\\^5 points"),
                            ({"unit": "cm"}, "unknown unit"), ({"decimals": 9}, "decimals")]:
        with pytest.raises(AxiscalError, match=message):
            mach4_screw_map(curve, **kwargs)
    rotary = ErrorCurve(np.array([0.0, 1.0]), np.zeros(2), np.zeros(2), period=2 * np.pi)
    with pytest.raises(AxiscalError, match="linear axis"):
        mach4_screw_map(rotary)
    evenly = mach4_screw_map(curve)
    assert not evenly.resampled and evenly.note is None
