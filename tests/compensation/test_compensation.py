"""Controller compensation tables: each applied as its control applies it, and each format's rules."""

from __future__ import annotations

import math
import re

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from axiscal.compensation import (
    FORMATS,
    CompensationResult,
    ErrorCurve,
    compensation_table,
    error_curve,
    fanuc_table,
    heidenhain_table,
    linuxcnc_table,
    parse_linuxcnc,
    residuals,
    siemens_table,
)
from axiscal.compensation.readback import parse_fanuc_tape, parse_siemens, read_compensation
from axiscal.errors import AxiscalError
from axiscal.positioning.evaluation import PositioningRun, target_statistics
from axiscal.positioning.reader import read_positioning_run
from axiscal.units import DEG, MM, UM

EPS = 1e-12


@pytest.fixture
def curve(examples) -> ErrorCurve:
    return error_curve(target_statistics(read_positioning_run(examples / "positioning_run.csv").run))


def random_curve(rng, m=17, length=0.8, start=0.0):
    x = np.sort(np.concatenate([[start, start + length], start + rng.uniform(0, length, m - 2)]))
    x = np.unique(np.round(x, 6))
    up = 10e-6 * rng.standard_normal(x.size) + 12e-6 * x
    return ErrorCurve(x, up, up + rng.uniform(2e-6, 6e-6, x.size))


# ---------------------------------------------------------------------------------- LinuxCNC


def linuxcnc_reference(table_rows: np.ndarray, comp_type: int, x: float, forward: bool) -> float:
    """What LinuxCNC's motion module computes, written out from usrmotintf.cc and command.c:
    type 0 trims are nominal - value, type 1 trims the values; the entry list has sentinels at
    -/+ DBL_MAX that copy the first/last trims; the correction is trim + slope * (x - nominal)."""
    nominal = table_rows[:, 0]
    values = table_rows[:, 1] if forward else table_rows[:, 2]
    trims = nominal - values if comp_type == 0 else values
    entries = [(-math.inf, trims[0], 0.0)]
    for k in range(nominal.size):
        slope = (trims[k + 1] - trims[k]) / (nominal[k + 1] - nominal[k]) if k + 1 < nominal.size else 0.0
        entries.append((nominal[k], trims[k], slope))
    for k in range(len(entries) - 1, -1, -1):
        start, trim, slope = entries[k]
        if x >= start:
            return trim + (slope * (x - start) if math.isfinite(start) else 0.0)
    raise AssertionError("unreachable")


@pytest.mark.parametrize("comp_type", [0, 1])
def test_linuxcnc_file_rules_and_residuals(curve, comp_type):
    table = linuxcnc_table(curve, comp_type=comp_type)
    text = table.text()
    rows = parse_linuxcnc(text)  # every line is read: no header, no comments, increasing, <= 256
    assert rows.shape == (curve.positions.size, 3)
    assert all(len(line.split()) == 3 for line in text.splitlines())
    for direction in "+-":
        left = residuals(table, curve, curve.positions, direction)
        assert np.abs(left).max() <= table.resolution / 2 + EPS
    # the control's own arithmetic, also between and beyond the entries
    x = np.linspace(-0.05, 0.85, 97)
    for forward, direction in ((True, "+"), (False, "-")):
        want = [linuxcnc_reference(rows, comp_type, xi / MM, forward) * MM for xi in x]
        assert table.correction(x, direction) == pytest.approx(want, abs=1e-15)


def test_linuxcnc_type_0_holds_positions_reached_and_type_1_corrections(curve):
    t0, t1 = linuxcnc_table(curve, comp_type=0), linuxcnc_table(curve, comp_type=1)
    assert t0.forward == pytest.approx(curve.positions / MM + curve.up / MM, abs=1e-6)
    assert t1.reverse == pytest.approx(-curve.down / MM, abs=1e-6)
    x = np.linspace(0, 0.8, 41)
    assert t0.correction(x, "+") == pytest.approx(t1.correction(x, "+"), abs=2 * t0.resolution)


def test_linuxcnc_limits():
    x = np.linspace(0, 1, 257)
    with pytest.raises(AxiscalError, match="at most 256"):
        linuxcnc_table(ErrorCurve(x, np.zeros(257), np.zeros(257)))
    with pytest.raises(AxiscalError, match="0 or 1"):
        linuxcnc_table(ErrorCurve(x[:3], np.zeros(3), np.zeros(3)), comp_type=2)
    with pytest.raises(AxiscalError, match="stop reading at line 1"):
        parse_linuxcnc("nominal forward reverse\n0 0 0\n")
    with pytest.raises(AxiscalError, match="stop reading at line 2"):
        parse_linuxcnc("0 0 0\n# comment\n1 0 0\n")
    with pytest.raises(AxiscalError, match="strictly increase"):
        parse_linuxcnc("0 0 0\n0 0 0\n")
    with pytest.raises(AxiscalError, match="at most 256"):
        parse_linuxcnc("".join(f"{k} 0 0\n" for k in range(257)))


@settings(max_examples=40, deadline=None)
@given(st.integers(0, 10_000), st.integers(2, 256))
def test_linuxcnc_residuals_within_resolution_for_any_curve(seed, m):
    c = random_curve(np.random.default_rng(seed), m=m)
    for comp_type in (0, 1):
        table = linuxcnc_table(c, comp_type=comp_type)
        parse_linuxcnc(table.text())
        for d in "+-":
            # type 0 writes nominal + e and LinuxCNC subtracts: two roundings
            assert np.abs(residuals(table, c, c.positions, d)).max() <= (1 if comp_type == 0 else 0.5) * table.resolution + EPS


# ---------------------------------------------------------------------------------- FANUC


def tape(text: str) -> tuple[dict[int, int], dict[int, int]]:
    return parse_fanuc_tape(text)


def test_fanuc_point_numbers_follow_the_parameter_manual():
    # FANUC parameter manual, pitch error compensation example 1: stroke -400 .. +800 mm, interval
    # 50 mm, reference point 40 -> farthest - point 40 - 400/50 + 1 = 33, farthest + point 40 + 800/50 = 56
    x = np.linspace(-0.4, 0.8, 25)
    c = ErrorCurve(x, 5e-6 * np.sin(x * 20), 5e-6 * np.sin(x * 20))
    table = fanuc_table(c, interval_m=0.05, reference_point=40)
    params, data = tape(table.text())
    assert params[3620] == 40 and params[3621] == 33 and params[3622] == 56 and params[3624] == 50_000
    assert sorted(data) == list(range(33, 57))


def test_fanuc_rotary_table_sums_to_zero():
    # FANUC parameter manual, example 2: 360 deg per revolution, interval 45 deg, reference point 60:
    # 3621 = 60, 3622 = 60 + 360/45 = 68; points 61..68 sum to zero; point 60 repeats point 68
    deg = math.pi / 180
    x = np.arange(0, 360, 15) * deg
    e = 20e-6 * np.sin(x) + 8e-6 * np.cos(3 * x) + 3e-6
    table = fanuc_table(
        ErrorCurve(x, e, e), interval_m=45 * deg, reference_point=60, rotary=True,
        travel_per_revolution=360 * deg, input_increment_m=0.001 * deg, detection_unit_m=1e-6,
    )
    params, data = tape(table.text())
    assert params[3621] == 60 and params[3622] == 68
    assert sum(data[p] for p in range(61, 69)) == 0
    assert data[60] == data[68]
    nodes = table.nodes
    left = residuals(table, ErrorCurve(x, e, e), nodes[:-1], "mean", offset=table.reference_deviation_m)
    assert np.abs(left).max() <= table.resolution / 2 + EPS
    with pytest.raises(AxiscalError, match="whole sections"):
        fanuc_table(ErrorCurve(x, e, e), interval_m=7 * deg, rotary=True, travel_per_revolution=360 * deg,
                    input_increment_m=0.001 * deg)


@pytest.mark.parametrize("magnification", [1, 2, 5])
def test_fanuc_unidirectional_residuals_within_one_unit(curve, magnification):
    table = fanuc_table(curve, interval_m=0.01, magnification=magnification)
    params, data = tape(table.text())
    assert params[3623] == magnification
    assert max(abs(v) for v in data.values()) <= 127
    left = residuals(table, curve, table.nodes, "mean", offset=table.reference_deviation_m)
    assert np.abs(left).max() <= table.resolution / 2 + EPS
    # at the measured targets the resampling onto the 10 mm grid adds its own (reported) error
    assert np.abs(residuals(table, curve, curve.positions, "mean", offset=table.reference_deviation_m)).max() < 2 * table.resolution


def test_fanuc_bidirectional(curve):
    table = fanuc_table(curve, interval_m=0.02, bidirectional=True)
    params, data = tape(table.text())
    assert params[3626] == params[3622] + 1
    count = params[3622] - params[3621] + 1
    assert sorted(data) == list(range(params[3621], params[3622] + 1)) + list(range(params[3626], params[3626] + count))
    # 3627: the - direction correction at the reference position, relative to the + deviation there
    assert params[3627] == round(-(curve.down[0] - curve.up[0]) / UM)
    for d in "+-":
        left = residuals(table, curve, table.nodes, d, offset=table.reference_deviation_m)
        assert np.abs(left).max() <= table.resolution / 2 + EPS


def test_fanuc_reference_inside_the_travel(curve):
    table = fanuc_table(curve, interval_m=0.05, reference_position_m=0.4)
    params, _ = tape(table.text())
    assert params[3620] - params[3621] + 1 == 8 and params[3622] - params[3620] == 8
    assert table.correction(0.4, "+") == pytest.approx(0.0)


@pytest.mark.parametrize(
    "kwargs,message",
    [
        ({"interval_m": 0.01, "magnification": 0}, "1..100"),
        ({"interval_m": 0.01, "magnification": 101}, "1..100"),
        ({"interval_m": -0.01}, "positive"),
        ({"interval_m": 0.0100005}, "whole number of input increments"),
        ({"interval_m": 0.01, "reference_position_m": 1.0}, "outside the measured travel"),
        ({"interval_m": 0.01, "reference_point": 1020}, "do not fit"),
        ({"interval_m": 0.4, "detection_unit_m": 0.01e-6}, "exceeds"),
    ],
)
def test_fanuc_bad_requests(curve, kwargs, message):
    with pytest.raises(AxiscalError, match=message):
        fanuc_table(curve, **kwargs)


@settings(max_examples=40, deadline=None)
@given(st.integers(0, 10_000), st.sampled_from([0.005, 0.01, 0.025, 0.05]), st.booleans())
def test_fanuc_residuals_within_one_unit_for_any_curve(seed, interval, bidirectional):
    c = random_curve(np.random.default_rng(seed))
    table = fanuc_table(c, interval_m=interval, bidirectional=bidirectional)
    for d in ("+", "-") if bidirectional else ("mean",):
        assert np.abs(residuals(table, c, table.nodes, d, offset=table.reference_deviation_m)).max() <= table.resolution / 2 + EPS


# ---------------------------------------------------------------------------------- SIEMENS


def siemens_parse(text: str) -> tuple[list[float], dict[str, float]]:
    return parse_siemens(text)


def test_siemens_table_rules_and_residuals(curve):
    table = siemens_table(curve, step_m=0.01)
    values, params = siemens_parse(table.text())
    assert params["MIN"] == 0.0 and params["STEP"] == 10.0 and params["IS_MODULO"] == 0
    assert round((params["MAX"] - params["MIN"]) / params["STEP"]) + 1 == len(values) == 81
    assert np.abs(residuals(table, curve, table.nodes, "mean")).max() <= table.resolution / 2 + EPS
    # sign: a positive deviation is entered as a positive value (the axis then moves back)
    assert values[-1] == pytest.approx(round(curve.mean[-1] / MM, 4))
    assert "-0.0000" not in table.text()


def test_siemens_zero_at_reference_and_limits(curve):
    table = siemens_table(curve, step_m=0.05, zero_at_m=0.0)
    assert table.values_mm[0] == 0.0
    assert np.abs(residuals(table, curve, table.nodes, "mean", offset=float(curve.at(0.0, "mean")))).max() <= table.resolution / 2 + EPS
    with pytest.raises(AxiscalError, match="MD38000"):
        siemens_table(curve, step_m=0.0005)
    with pytest.raises(AxiscalError, match="positive"):
        siemens_table(curve, step_m=0.0)
    with pytest.raises(AxiscalError, match="machine axis"):
        siemens_table(curve, step_m=0.01, axis="X 1")


# ---------------------------------------------------------------------------------- HEIDENHAIN


def test_heidenhain_table_rules_and_residuals(curve):
    table = heidenhain_table(curve)
    lines = table.text().splitlines()
    assert lines[0] == "BEGIN X.COM MM" and lines[-1] == "[END]"
    assert lines[1].split() == ["NR", "AXISPOS", "X", "BACKLASH"]
    rows = np.array([[float(c) for c in line.split()] for line in lines[2:-1]])
    assert rows.shape == (17, 4) and np.all(np.diff(rows[:, 1]) > 0) and rows[:, 0].tolist() == list(range(17))
    assert rows[:, 3] == pytest.approx((curve.down - curve.up) / MM, abs=1.01e-4)  # = -B_i
    # + uses one rounded value, - the sum of two: within one resolution step
    assert np.abs(residuals(table, curve, curve.positions, "+")).max() <= table.resolution / 2 + EPS
    assert np.abs(residuals(table, curve, curve.positions, "-")).max() <= table.resolution + EPS
    mean_table = heidenhain_table(curve, backlash=False)
    assert mean_table.text().splitlines()[1].split() == ["NR", "AXISPOS", "X"]
    assert np.abs(residuals(mean_table, curve, curve.positions, "mean")).max() <= table.resolution / 2 + EPS


def test_heidenhain_limits():
    x = np.linspace(0, 1, 257)
    with pytest.raises(AxiscalError, match="at most 256"):
        heidenhain_table(ErrorCurve(x, np.zeros(257), np.zeros(257)))
    with pytest.raises(AxiscalError, match="not an axis"):
        heidenhain_table(ErrorCurve(x[:3], np.zeros(3), np.zeros(3)), axis="1")


def test_error_curve_directions(curve):
    assert curve.at(curve.positions, "mean") == pytest.approx(curve.mean)
    with pytest.raises(AxiscalError, match="unknown direction"):
        curve.at(0.1, "sideways")


# ------------------------------------------------------------ each file read back as its control reads it
# The residual tests above use the table objects; these read the written text alone (nothing of the
# object), rebuild the correction the control applies from it, and apply it to the measured means.


def fanuc_control(text: str, *, reference_position_m: float, unit_m: float, increment_m: float = 1e-6):
    """FANUC pitch error compensation from the parameter tape, as the virtual controller reads it."""
    c = read_compensation(text, "fanuc", reference_position_m=reference_position_m, detection_unit_m=unit_m,
                          increment_m=increment_m)
    return c.correction, c.nodes_m


@pytest.mark.parametrize("bidirectional", [False, True])
@pytest.mark.parametrize("seed", [None, 1, 2])
def test_fanuc_tape_applied_as_the_control_does(curve, bidirectional, seed):
    c = curve if seed is None else random_curve(np.random.default_rng(seed))
    reference = float(c.positions[0]) + 0.2
    table = fanuc_table(c, interval_m=0.025, reference_position_m=reference, bidirectional=bidirectional)
    correction, nodes = fanuc_control(table.text(), reference_position_m=reference, unit_m=1e-6)
    for d in "+-":
        e = c.at(nodes, d if bidirectional else "mean")
        # the table is zero at the reference (3627 relative to it): a deviation there is the reference setting's
        e_ref = float(c.at(reference, "+" if bidirectional else "mean"))
        assert np.abs(e - e_ref + correction(nodes, d)).max() <= 0.5e-6 + EPS
    assert table.correction(nodes, "-") == pytest.approx(correction(nodes, "-"), abs=1e-15)


def siemens_control(text: str, unit: float = MM):
    """SINUMERIK MSEC from the INI text: correction(x) = -(value interpolated over MIN + i STEP)."""
    values, params = siemens_parse(text)
    c = read_compensation(text, "siemens", unit_m=unit)
    assert c.nodes_m[-1] == pytest.approx(params["MAX"] * unit)
    return (lambda x: c.correction(x, "+")), c.nodes_m


@pytest.mark.parametrize("seed", [None, 1, 2])
def test_siemens_file_applied_as_the_control_does(curve, seed):
    c = curve if seed is None else random_curve(np.random.default_rng(seed))
    table = siemens_table(c, step_m=0.005)
    correction, nodes = siemens_control(table.text())
    # a positive value moves the axis negative (K3): what is left is e + correction, within 0.05 um
    assert np.abs(c.at(nodes, "mean") + correction(nodes)).max() <= 0.05e-6 + EPS


def heidenhain_control(text: str, unit: float = MM):
    """HEIDENHAIN .COM from its text: the control subtracts the error column (plus BACKLASH in -)."""
    return read_compensation(text, "heidenhain", unit_m=unit).correction


@pytest.mark.parametrize("backlash", [True, False])
@pytest.mark.parametrize("seed", [None, 1, 2])
def test_heidenhain_file_applied_as_the_control_does(curve, backlash, seed):
    c = curve if seed is None else random_curve(np.random.default_rng(seed))
    correction = heidenhain_control(heidenhain_table(c, backlash=backlash).text())
    for d in "+-":
        e = c.at(c.positions, d if backlash else "mean")
        # + reads one rounded value, - the sum of two: within one step of 0.1 um
        assert np.abs(e + correction(c.positions, d)).max() <= (0.05e-6 if d == "+" or not backlash else 0.1e-6) + EPS


# ------------------------------------------------------------------- the one call behind the command


@pytest.fixture
def run(examples):
    return read_positioning_run(examples / "positioning_run.csv").run


@pytest.mark.parametrize("fmt", FORMATS)
def test_compensation_table_is_the_controller_table_with_its_residual(run, curve, fmt):
    result = compensation_table(run, fmt)
    assert isinstance(result, CompensationResult) and result.format == fmt
    assert result.text == result.table.text() and result.resolution_m == result.table.resolution
    directions = ("+", "-") if fmt in ("linuxcnc", "heidenhain") else ("mean",)
    offset = result.reference_offset_m
    left = max(np.abs(residuals(result.table, curve, curve.positions, d, offset=offset)).max() for d in directions)
    assert result.largest_residual_m == left
    assert "largest error left at the measured targets" in result.note


def test_compensation_table_defaults_are_those_the_command_documents(run, curve):
    fanuc = compensation_table(run, "fanuc").table
    # 17 targets over 800 mm: the mean spacing of 50 mm; the reference at the first target
    assert fanuc.interval_m == pytest.approx(50 * MM) and fanuc.reference_position_m == run.targets[0]
    assert fanuc.magnification == 1 and fanuc.detection_unit_m == UM and fanuc.values_down is None
    assert fanuc.text() == fanuc_table(curve, interval_m=50 * MM, reference_position_m=run.targets[0]).text()
    assert compensation_table(run, "siemens").table.axis == "X1"
    assert compensation_table(run, "heidenhain").table.backlash_mm is not None
    assert compensation_table(run, "linuxcnc").table.comp_type == 1


def test_compensation_table_reference_offset(run, curve):
    fanuc = compensation_table(run, "fanuc", interval_m=25 * MM, reference_position_m=0.2, bidirectional=True)
    assert fanuc.reference_offset_m == pytest.approx(float(curve.at(0.2, "+")))
    assert "-2.000 um is left to the reference position setting" in fanuc.note
    siemens = compensation_table(run, "siemens", reference_position_m=0.1)
    assert siemens.reference_offset_m == pytest.approx(float(curve.at(0.1, "mean")))
    assert siemens.table.values_mm[0] == pytest.approx((curve.at(0.0, "mean") - curve.at(0.1, "mean")) / MM, abs=1e-4)
    assert compensation_table(run, "siemens").reference_offset_m == 0.0
    assert "reference position setting" not in compensation_table(run, "linuxcnc").note


@pytest.mark.parametrize(
    "fmt,option",
    [("linuxcnc", {"bidirectional": True}), ("heidenhain", {"interval_m": 0.01}), ("fanuc", {"backlash": False}),
     ("siemens", {"comp_type": 0}), ("linuxcnc", {"axis": "X"}), ("heidenhain", {"magnification": 2})],
)
def test_compensation_table_refuses_an_option_of_another_format(run, fmt, option):
    name = next(iter(option))
    with pytest.raises(AxiscalError, match=f"^{name} applies to format .*, not {fmt}$"):
        compensation_table(run, fmt, **option)


def test_compensation_table_refuses_an_unknown_format(run):
    with pytest.raises(AxiscalError, match="unknown compensation table format 'okuma'"):
        compensation_table(run, "okuma")


def test_compensation_table_reads_a_run_file(examples, run):
    from_file = compensation_table(examples / "positioning_run.csv", "siemens")
    assert from_file.text == compensation_table(run, "siemens").text
    with pytest.raises(AxiscalError, match="file not found"):
        compensation_table(examples / "nope.csv", "siemens")


# ------------------------------------------------------------------------------------- rotary axes
# A run read from target_deg / deviation_arcsec: each table written in degrees, read back from its text
# as the control reads it and applied to the measured means.


@pytest.fixture
def rotary_run(examples):
    return read_positioning_run(examples / "rotary_run.csv").run


def rotary_curve(run):
    return error_curve(target_statistics(run))


def test_linuxcnc_rotary_comp_file_runs_round_to_360_deg(rotary_run):
    result = compensation_table(rotary_run, "linuxcnc")
    rows = parse_linuxcnc(result.text)
    assert rows[0, 0] == 0.0 and rows[-1, 0] == 360.0 and np.array_equal(rows[0, 1:], rows[-1, 1:])
    curve = rotary_curve(rotary_run)
    for d, forward in (("+", True), ("-", False)):
        trims = np.array([linuxcnc_reference(rows, 1, t, forward) for t in curve.positions / DEG]) * DEG
        assert np.abs(curve.at(curve.positions, d) + trims).max() <= 0.5e-6 * DEG + EPS
    assert "degrees" in result.note and "arcsec" in result.note


def test_fanuc_rotary_tape_from_a_run_keeps_the_rotary_rules(rotary_run):
    result = compensation_table(rotary_run, "fanuc")
    params, data = tape(result.text)
    # FANUC rotary pitch error compensation: 3621 = 3620, the reference point repeats the last point,
    # the values of one revolution sum to zero; interval 30 deg = 30000 input increments of 0.001 deg
    assert params[3621] == params[3620] == 0 and params[3622] == 12 and params[3624] == 30_000
    assert data[0] == data[12] and sum(data[p] for p in range(1, 13)) == 0
    unit = 0.001 * DEG
    correction, nodes = fanuc_control(result.text, reference_position_m=0.0, unit_m=unit, increment_m=unit)
    curve = rotary_curve(rotary_run)
    e = np.interp(nodes, np.append(curve.positions, 2 * np.pi), np.append(curve.mean, curve.mean[0]))
    assert np.abs(e - e[0] + correction(nodes, "+")).max() <= unit / 2 + EPS
    assert result.reference_offset_m == pytest.approx(curve.mean[0])


def test_fanuc_rotary_needs_the_full_circle(tmp_path):
    rows = ["target_deg,run,direction,deviation_arcsec"] + [
        f"{t},{r},{d},{t / 30:.1f}" for r in (1, 2) for d in "+-" for t in range(0, 91, 15)
    ]
    path = tmp_path / "arc.csv"
    path.write_text("\n".join(rows) + "\n")
    with pytest.raises(AxiscalError, match="spans one revolution"):
        compensation_table(path, "fanuc")
    # the tables of a linear kind still take the arc tested, in degrees
    result = compensation_table(path, "siemens")
    assert "IS_MODULO[0,X1]=0" in result.text and result.table.nodes[-1] == pytest.approx(90 * DEG)


def test_siemens_rotary_is_a_modulo_table_from_0_to_360_deg(rotary_run):
    result = compensation_table(rotary_run, "siemens")
    values, params = siemens_parse(result.text)
    assert params["IS_MODULO"] == 1 and params["MIN"] == 0.0 and params["MAX"] == 360.0 and params["STEP"] == 30.0
    assert values[0] == values[-1]
    correction, nodes = siemens_control(result.text, unit=DEG)
    curve = rotary_curve(rotary_run)
    assert np.abs(curve.at(curve.positions, "mean") + correction(curve.positions)).max() <= 0.5e-6 * DEG + EPS
    with pytest.raises(AxiscalError, match="divide"):
        compensation_table(rotary_run, "siemens", interval_rad=7 * DEG)


@pytest.mark.parametrize("backlash", [True, False])
def test_heidenhain_rotary_com_in_degrees(rotary_run, backlash):
    result = compensation_table(rotary_run, "heidenhain", backlash=backlash)
    correction = heidenhain_control(result.text, unit=DEG)
    curve = rotary_curve(rotary_run)
    for d in "+-":
        e = curve.at(curve.positions, d if backlash else "mean")
        assert np.abs(e + correction(curve.positions, d)).max() <= 1e-6 * DEG + EPS
    assert result.text.splitlines()[-2].split()[1] == "+360.000000"


def test_rotary_and_linear_options_do_not_mix(run, rotary_run):
    with pytest.raises(AxiscalError, match="interval_m does not apply: .* rotary axis"):
        compensation_table(rotary_run, "fanuc", interval_m=0.01)
    with pytest.raises(AxiscalError, match="interval_rad does not apply: .* linear axis"):
        compensation_table(run, "fanuc", interval_rad=0.1)


@pytest.mark.parametrize("option", ["interval_m", "detection_unit_m", "reference_position_m"])
@pytest.mark.parametrize("value", [math.nan, math.inf, -math.inf])
def test_non_finite_options_are_refused(run, option, value):
    with pytest.raises(AxiscalError, match=f"{option} must be a finite number"):
        compensation_table(run, "fanuc", **{option: value})


# ------------------------------------------------------------------------------ one-direction tests


@pytest.fixture
def one_way(examples, tmp_path):
    lines = (examples / "positioning_run.csv").read_text().splitlines()
    path = tmp_path / "plus.csv"
    path.write_text("\n".join([lines[0]] + [line for line in lines[1:] if line.split(",")[2] == "+"]) + "\n")
    return read_positioning_run(path).run


@pytest.mark.parametrize(("fmt", "options", "words"), [
    ("linuxcnc", {}, "forward and a reverse column"),
    ("fanuc", {"bidirectional": True}, "a table for each direction"),
    ("heidenhain", {}, "BACKLASH column"),
])
def test_tables_that_need_both_directions_say_so(one_way, fmt, options, words):
    with pytest.raises(AxiscalError, match=f"{words}.*needs a test in both directions.*\\+ direction only"):
        compensation_table(one_way, fmt, **options)


@pytest.mark.parametrize(("fmt", "options"), [("fanuc", {}), ("siemens", {}), ("heidenhain", {"backlash": False})])
def test_one_curve_tables_hold_the_direction_tested(run, one_way, fmt, options):
    result = compensation_table(one_way, fmt, **options)
    assert "from the + direction only" in result.note
    plus = error_curve(target_statistics(run))
    plus = ErrorCurve(plus.positions, plus.up, plus.up)
    left = np.abs(residuals(result.table, plus, plus.positions, "mean", offset=result.reference_offset_m)).max()
    assert left == pytest.approx(result.largest_residual_m)
    # the same table as from a run whose two directions are both the + direction
    twin = PositioningRun(run.targets, run.deviations_up, run.deviations_up)
    assert result.text == compensation_table(twin, fmt, **options).text


@pytest.mark.parametrize("fmt", ["linuxcnc", "fanuc", "siemens", "heidenhain"])
def test_a_correction_no_real_axis_has_is_refused_unless_the_bound_is_raised(fmt):
    """A reading 100 mm off (the wrong offset, unit or scale) must not become a table that moves the axis by 100 mm."""
    targets = np.array([0.0, 0.05, 0.1])
    off = np.full((3, 2), -0.1)  # every reading 100 mm short
    off[1] += 2e-6
    run = PositioningRun(targets, off, off.copy(), source="<run>")
    with pytest.raises(AxiscalError, match=r"mean deviation at 0 mm \(\+\) is -100 mm, beyond the largest correction written"
                                           r" \(1 mm\).*raise max_correction_m"):
        compensation_table(run, fmt)
    assert compensation_table(run, fmt, max_correction_m=0.2).text
    # the bound itself is checked: a positive length of at most 1 m
    for bad in (0.0, -1e-3, math.nan, 1e300):
        with pytest.raises(AxiscalError, match="max_correction_m"):
            compensation_table(run, fmt, max_correction_m=bad)


def test_a_deviation_just_under_the_bound_is_written_and_a_rotary_axis_has_its_own_bound():
    targets = np.array([0.0, 0.05, 0.1])
    near = np.full((3, 2), -0.99e-3)
    assert compensation_table(PositioningRun(targets, near, near.copy()), "heidenhain").text
    angles = np.radians([0.0, 90.0, 180.0, 270.0])
    twist = np.full((4, 2), 2 * DEG)
    rotary = PositioningRun(angles, twist, twist.copy(), rotary=True)
    with pytest.raises(AxiscalError, match=r"\+2 deg, beyond the largest correction written \(1 deg\).*max_correction_rad"):
        compensation_table(rotary, "heidenhain")
    assert compensation_table(rotary, "heidenhain", max_correction_rad=3 * DEG).text
