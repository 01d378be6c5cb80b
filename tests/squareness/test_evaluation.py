"""Squareness from two straightness runs (paper 002) and the prism's deviation (papers 002, 004)."""

from __future__ import annotations

import math

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from axiscal.errors import AxiscalError
from axiscal.squareness.evaluation import (
    included_angle_from_iso,
    iso_from_included_angle,
    iso_term,
    prism_deviation_from_wedge,
    prism_reversal,
    psd_angular_resolution,
    squareness,
    squareness_from_files,
    squareness_from_slopes,
)
from axiscal.units import ARCMIN, ARCSEC, MM, UM

K_FIRST = -0.00044783  # paper 002, section 4: slope of the first axis' fitted line
K_SECOND_COMMON = 3001.62173825  # slope of the second axis' fitted line, in the same XY frame


def _angle_between_common_lines(k, k_prime):
    """Plain reference: angle from +X (direction (1, k)) to +Y (direction (1, k') turned to point up)."""
    first = np.array([1.0, k])
    second = np.array([1.0, k_prime]) * math.copysign(1.0, k_prime)
    return math.acos(first @ second / np.linalg.norm(first) / np.linalg.norm(second))


def test_paper_002_worked_case():
    # paper 002, section 4: k = -0.00044783, k' = 3001.62173825, prism error 2.7" -> 20.9"
    result = squareness_from_slopes(K_FIRST, 1.0 / K_SECOND_COMMON, plane="XY", prism_deviation_rad=2.7 * ARCSEC)
    value = result.squareness_rad / ARCSEC
    # exact arithmetic gives 20.954"; the paper prints 20.9" (cut to one decimal, docs/squareness.md)
    assert math.floor(value * 10) / 10 == 20.9
    expected = (_angle_between_common_lines(K_FIRST, K_SECOND_COMMON) - math.pi / 2) / ARCSEC - 2.7
    assert value == pytest.approx(expected, abs=1e-6)
    assert value == pytest.approx(20.9538, abs=1e-4)
    assert result.convention == "included-angle"
    assert result.iso_term == "EC0Y" and result.iso_value_rad == result.squareness_rad
    assert math.degrees(result.included_angle_rad) == pytest.approx(90 + 20.9538 / 3600, abs=1e-8)


def test_iso_signs_per_plane():
    # DOMAIN.md section 4: EC0Y > 0 opens X-Y beyond 90 deg; EB0Z > 0 closes X-Z below 90 deg
    assert [iso_term(p) for p in ("XY", "XZ", "YZ")] == ["EC0Y", "EB0Z", "EA0Z"]
    assert iso_from_included_angle(1e-5, plane="XY") == 1e-5
    assert iso_from_included_angle(1e-5, plane="XZ") == -1e-5
    assert iso_from_included_angle(1e-5, plane="YZ") == 1e-5
    for plane in ("XY", "XZ", "YZ"):
        assert included_angle_from_iso(iso_from_included_angle(3e-5, plane=plane), plane=plane) == 3e-5


@pytest.mark.parametrize("plane,letters", [("XY", (0, 1, 2)), ("XZ", (0, 2, 1)), ("YZ", (1, 2, 0))])
def test_iso_sign_matches_a_rotated_axis(plane, letters):
    # turn the second axis by +e about the third axis (right-hand rule) and measure it
    from axiscal.instruments.optics import rotation_x, rotation_y, rotation_z

    e = 40 * ARCSEC
    first, second, third = letters
    turn = (rotation_x, rotation_y, rotation_z)[third](e)
    direction = turn @ np.eye(3)[second]
    travel = np.linspace(0, 0.5, 11)
    second_run_deviation = travel * direction[first] / direction[second]  # deviation along the first axis
    result = squareness(travel, np.zeros_like(travel), travel, second_run_deviation, plane=plane)
    assert result.iso_value_rad == pytest.approx(e, rel=1e-6)
    included = squareness(travel, np.zeros_like(travel), travel, second_run_deviation, plane=plane, convention="included-angle")
    angle = math.acos(direction[first])
    assert included.squareness_rad == pytest.approx(angle - math.pi / 2, rel=1e-6)


def test_least_squares_and_end_points_from_data():
    rng = np.random.default_rng(0)
    x = np.linspace(0, 0.8, 17)
    y = np.linspace(0, 0.6, 13)
    first = 12e-6 * x + rng.normal(0, 0.3e-6, x.size)
    second = -30e-6 * y + rng.normal(0, 0.3e-6, y.size)
    result = squareness(x, first, y, second, plane="XY")
    k1 = np.polyfit(x, first, 1)[0]
    k2 = np.polyfit(y, second, 1)[0]
    assert result.slope_first == pytest.approx(k1, rel=1e-9)
    assert result.slope_second == pytest.approx(k2, rel=1e-9)
    assert result.squareness_rad == pytest.approx(-(math.atan(k1) + math.atan(k2)), rel=1e-9)
    ends = squareness(x, first, y, second, reference="end-points")
    assert ends.slope_first == pytest.approx((first[-1] - first[0]) / (x[-1] - x[0]))
    assert ends.first_line.reference == "end-points"


def test_prism_error_tilts_the_second_run_by_itself_eq_14_to_20():
    # paper 002 eqs (14)-(20): data sheared by the prism error moves the fitted axis by that error
    rng = np.random.default_rng(0)
    y = np.linspace(0, 0.5, 21)
    deviation = 5e-6 * y + rng.normal(0, 0.5e-6, y.size)
    d = 2.7 * ARCSEC
    x = np.linspace(0, 0.5, 21)
    plain = squareness(x, 0 * x, y, deviation)
    sheared = squareness(x, 0 * x, y, deviation - y * d)  # the second axis seen d further open
    assert sheared.measured_included_angle_rad - plain.measured_included_angle_rad == pytest.approx(d, rel=1e-6)
    corrected = squareness(x, 0 * x, y, deviation - y * d, prism_deviation_rad=d)
    assert corrected.squareness_rad == pytest.approx(plain.squareness_rad, abs=1e-12)


def test_prism_reversal_paper_004():
    # paper 004, section 3.3: 9.15' - ap = 8.05', -15.5' - ap = -16.6', 28.2' - ap = 27.1' -> ap = 1.1'
    ap = 1.1 * ARCMIN
    for measured, published in ((9.15, 8.05), (-15.5, -16.6), (28.2, 27.1)):
        assert round((measured * ARCMIN - ap) / ARCMIN, 2) == published
    # eqs (2)-(3) forward, then the missing eqs (4)-(5) back
    rng = np.random.default_rng(0)
    for a0, a_p in rng.normal(0, 1e-3, size=(20, 2)):
        result = prism_reversal(a_p - a0, a0 + a_p)
        assert result.prism_deviation_rad == pytest.approx(a_p, abs=1e-15)
        assert result.squareness_rad == pytest.approx(a0, abs=1e-15)


def test_wedge_method_eq_22():
    # paper 002 eq (22): |a1 - a2| / 4; the paper's prism shows 2.7"
    assert prism_deviation_from_wedge(13.5 * ARCSEC, 2.7 * ARCSEC) / ARCSEC == pytest.approx(2.7)
    assert prism_deviation_from_wedge(2.7 * ARCSEC, 13.5 * ARCSEC) == prism_deviation_from_wedge(13.5 * ARCSEC, 2.7 * ARCSEC)


def test_psd_angular_resolution_paper_004_eq_1():
    # paper 004 eq (1): 0.3 um over 18 mm; the paper's "0.06 arcsec" is arc minutes (primer slip 5)
    r = psd_angular_resolution(0.3 * UM, 18 * MM)
    assert round(r / ARCSEC, 1) == 3.4
    assert round(r / ARCMIN, 3) == 0.057
    assert round(r / ARCMIN, 2) == 0.06
    # "1000 mm: 0.001" is arc minutes too
    assert round(psd_angular_resolution(0.3 * UM, 1000 * MM) / ARCMIN, 3) == 0.001
    with pytest.raises(AxiscalError, match="positive"):
        psd_angular_resolution(0.0, 0.018)
    with pytest.raises(AxiscalError, match="positive"):
        psd_angular_resolution(0.3e-6, -1.0)


def test_bad_input():
    x = np.array([0.0, 0.1, 0.2])
    with pytest.raises(AxiscalError, match="first run has 1 point"):
        squareness(x[:1], x[:1], x, x)
    with pytest.raises(AxiscalError, match="second run has 0 point"):
        squareness(x, x, x[:0], x[:0])
    with pytest.raises(AxiscalError, match="second run: all positions are equal"):
        squareness(x, 0 * x, np.zeros(3), x)
    with pytest.raises(AxiscalError, match="parallel"):
        squareness(x, x, x, x)  # both at 45 deg: the lines coincide
    with pytest.raises(AxiscalError, match="parallel"):
        squareness_from_slopes(0.0, 1e6)
    with pytest.raises(AxiscalError, match="unknown plane"):
        squareness_from_slopes(0.0, 0.0, plane="XW")
    with pytest.raises(AxiscalError, match="convention"):
        squareness_from_slopes(0.0, 0.0, convention="degrees")
    with pytest.raises(AxiscalError, match="not a pentaprism"):
        squareness_from_slopes(0.0, 0.0, prism_deviation_rad=math.radians(1.0))
    with pytest.raises(AxiscalError, match="finite"):
        squareness_from_slopes(0.0, float("nan"))
    with pytest.raises(AxiscalError, match="unknown reference"):
        squareness(x, 0 * x, x, 0 * x, reference="best")


@settings(max_examples=80, deadline=None)
@given(
    st.floats(-1e-3, 1e-3),
    st.floats(-1e-3, 1e-3),
    st.floats(-1e-4, 1e-4),
    st.sampled_from(["XY", "XZ", "YZ"]),
)
def test_conventions_agree_property(k1, k2, d, plane):
    iso = squareness_from_slopes(k1, k2, plane=plane, prism_deviation_rad=d, convention="iso")
    incl = squareness_from_slopes(k1, k2, plane=plane, prism_deviation_rad=d)  # the default
    assert incl.convention == "included-angle"
    assert incl.squareness_rad == pytest.approx(incl.included_angle_rad - math.pi / 2, abs=1e-15)
    assert iso.squareness_rad == iso_from_included_angle(incl.squareness_rad, plane=plane)
    assert iso.iso_value_rad == incl.iso_value_rad
    # swapping the roles of the slopes (mirror image) leaves the included angle unchanged
    assert squareness_from_slopes(k2, k1, plane=plane).included_angle_rad == pytest.approx(
        squareness_from_slopes(k1, k2, plane=plane).included_angle_rad, abs=1e-15
    )


# every 3-axis chain: workpiece-side axes, F, tool-side axes
ALL_CHAINS = [
    "".join(order[:cut]) + "F" + "".join(order[cut:])
    for order in ("XYZ", "XZY", "YXZ", "YZX", "ZXY", "ZYX")
    for cut in range(4)
]


@pytest.mark.parametrize("chain", ALL_CHAINS)
@pytest.mark.parametrize("plane,term", [("XY", "EC0Y"), ("XZ", "EB0Z"), ("YZ", "EA0Z")])
def test_squareness_of_the_htm_model_is_its_iso_term(chain, plane, term):
    # docs/conventions.md: the HTM machine with one ISO term, two straightness runs read off it (tool
    # relative to workpiece, in the workpiece frame), and the squareness they give is that term.
    # "relative" placement keeps the named included angle in every chain; see test_cmm.py for
    # the default placement.
    from axiscal.model.machine import Axis, Machine

    value = 25 * ARCSEC
    machine = Machine(chain, {k: Axis(k) for k in "XYZ"}, squareness_rad={term: value}, squareness_placement="relative")
    first, second = ("XYZ".index(plane[0]), "XYZ".index(plane[1]))
    travel = np.linspace(-0.3, 0.5, 9)
    runs = []
    for moving, across in ((first, second), (second, first)):
        q = np.zeros((3, travel.size))
        q[moving] = travel
        positions = {k: q[i] for i, k in enumerate("XYZ")}
        nominal = machine.nominal_point(positions)
        actual = machine.actual_point(positions)
        runs.append((nominal[:, moving], actual[:, across] - nominal[:, across]))
    result = squareness(*runs[0], *runs[1], plane=plane, convention="iso")
    assert result.iso_term == term
    assert result.iso_value_rad == pytest.approx(value, rel=1e-6)
    assert result.included_angle_rad - math.pi / 2 == pytest.approx(included_angle_from_iso(value, plane=plane), rel=1e-6)


def test_squareness_from_files_reproduces_paper_002(examples, tmp_path):
    # paper 002 section 4: D = 2.7 arcsec leaves 20.9 arcsec (20.954 unrounded)
    run = squareness_from_files(
        examples / "squareness_x.csv", examples / "squareness_y.csv", prism_deviation_rad=2.7 * ARCSEC,
    )
    # the plot takes the result (the result never imports its plot)
    from axiscal.squareness.plot import plot_squareness

    plot_squareness(tmp_path / "runs.png", run.result, ((run.first.position_m, run.first.deviation_m),
                                                        (run.second.position_m, run.second.deviation_m)))
    assert math.floor(run.result.squareness_rad / ARCSEC * 10) / 10 == 20.9
    assert (tmp_path / "runs.png").read_bytes()[:4] == b"\x89PNG"
    body = run.payload()
    assert body["squareness_arcsec"] == run.result.squareness_rad / ARCSEC and body["reference"] == "least-squares"
    report = run.report().splitlines()
    assert report[0].startswith("squareness of XY: first run ") and report[0].endswith("(moves Y)")
    assert report[6] == "  squareness (included angle - 90 deg)  +20.95 arcsec"
    with pytest.raises(AxiscalError, match="least-squares or end-points"):
        squareness_from_files(examples / "squareness_x.csv", examples / "squareness_y.csv", reference="minimum-zone")
    one = tmp_path / "one.csv"
    one.write_text("position_mm,deviation_um\n0,1\n")
    with pytest.raises(AxiscalError, match="at least 2") as info:
        squareness_from_files(one, examples / "squareness_y.csv")
    assert str(one) in str(info.value)
