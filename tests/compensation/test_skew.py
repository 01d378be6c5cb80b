"""Skew correction lines for Klipper, Marlin and RepRapFirmware, checked against each firmware's own formula.

The firmware side is re-implemented here from its source: Klipper ``klippy/extras/skew_correction.py``
(``calc_skew_factor``, ``calc_skew``), Marlin ``Planner::skew`` (planner.h) with the factors of
``M852``, RepRapFirmware ``M556`` (``SetAxisCompensation``: X -> tanXY, Y -> tanYZ, Z -> tanXZ,
each deviation / S) and ``Move::AxisTransform``. A skewed machine (its axes at the measured
included angles) then runs the corrected commands of a square (a cube) and must draw it square.
"""

from __future__ import annotations

import math

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from axiscal.compensation.skew import (
    MAX_SKEW_RAD,
    klipper_lengths,
    skew_correction,
    squareness_from_results,
)
from axiscal.errors import AxiscalError
from axiscal.io.jsonio import write_json
from axiscal.units import ARCSEC, MM

# --- the firmware, as its source reads ---------------------------------------------------------


def klipper_calc_skew_factor(ac, bd, ad):
    side = math.sqrt(2 * ac * ac + 2 * bd * bd - 4 * ad * ad) / 2.0
    return math.tan(math.pi / 2 - math.acos((ac * ac - side * side - ad * ad) / (2 * side * ad)))


def klipper_factors(line):
    assert line.startswith("SET_SKEW ")
    factors = {"xy": 0.0, "xz": 0.0, "yz": 0.0}
    for word in line.split()[1:]:
        plane, _, lengths = word.partition("=")
        factors[plane.lower()] = klipper_calc_skew_factor(*(float(v) for v in lengths.split(",")))
    return factors


def marlin_factors(line):
    assert line.startswith("M852 ")
    names = {"I": "xy", "J": "xz", "K": "yz"}
    factors = {"xy": 0.0, "xz": 0.0, "yz": 0.0}
    for word in line.split()[1:]:
        factors[names[word[0]]] = float(word[1:])
    return factors


def shear_klipper_marlin(f, p):
    # Klipper calc_skew == Marlin Planner::skew: the commanded position sent to the motors
    x, y, z = p
    return np.array([x - y * f["xy"] - z * (f["xz"] - f["xy"] * f["yz"]), y - z * f["yz"], z])


def rrf_tangents(line):
    words = line.split()
    assert words[0] == "M556"
    values = {w[0]: float(w[1:]) for w in words[1:]}
    s = values.pop("S")
    names = {"X": "xy", "Y": "yz", "Z": "xz"}
    tangents = {"xy": 0.0, "xz": 0.0, "yz": 0.0}
    for letter, v in values.items():
        tangents[names[letter]] = v / s
    return tangents


def shear_rrf(t, p):
    x, y, z = p
    return np.array([x + t["xy"] * y + t["xz"] * z, y + t["yz"] * z, z])


def machine(xy, xz=0.0, yz=0.0):
    """Axis direction vectors of a machine whose axes meet at 90 deg + the given squareness."""
    ex = np.array([1.0, 0.0, 0.0])
    ey = np.array([-math.sin(xy), math.cos(xy), 0.0])
    ezx = -math.sin(xz)
    ezy = (-math.sin(yz) - ey[0] * ezx) / ey[1]
    ez = np.array([ezx, ezy, math.sqrt(1 - ezx**2 - ezy**2)])
    return np.column_stack([ex, ey, ez])


def included_angle(u, v):
    return math.acos(float(u @ v) / float(np.linalg.norm(u) * np.linalg.norm(v)))


def drawn(axes, correct, points):
    return [axes @ correct(p) for p in points]


def corners(length):
    return [np.array(p, dtype=float) * length for p in ((0, 0, 0), (1, 0, 0), (0, 1, 0), (0, 0, 1))]


FIRMWARE_SHEAR = {
    "klipper": lambda line: (lambda p: shear_klipper_marlin(klipper_factors(line), p)),
    "marlin": lambda line: (lambda p: shear_klipper_marlin(marlin_factors(line), p)),
    "rrf": lambda line: (lambda p: shear_rrf(rrf_tangents(line), p)),
}


@pytest.mark.parametrize("firmware", ["klipper", "marlin", "rrf"])
def test_skewed_printer_draws_a_square_again(firmware):
    s = 120 * ARCSEC
    axes = machine(s)
    o, a, b, _ = drawn(axes, lambda p: p, corners(100 * MM))
    assert math.degrees(included_angle(a - o, b - o)) - 90 == pytest.approx(120 / 3600, rel=1e-9)
    line = skew_correction(firmware, xy_rad=s).lines[0]
    o, a, b, _ = drawn(axes, FIRMWARE_SHEAR[firmware](line), corners(100 * MM))
    # third-order residual: (tan s - sin s) ~ s^3 / 2, and the printed digits
    assert abs(included_angle(a - o, b - o) - math.pi / 2) < 0.01 * ARCSEC


@pytest.mark.parametrize("firmware", ["klipper", "marlin", "rrf"])
def test_skewed_machine_draws_a_cube_again(firmware):
    xy, xz, yz = 60 * ARCSEC, -45 * ARCSEC, 30 * ARCSEC
    axes = machine(xy, xz, yz)
    line = skew_correction(firmware, xy_rad=xy, xz_rad=xz, yz_rad=yz).lines[0]
    o, a, b, c = drawn(axes, FIRMWARE_SHEAR[firmware](line), corners(100 * MM))
    for u, v in ((a - o, b - o), (a - o, c - o), (b - o, c - o)):
        # second order at most (products of two squareness values, ~1e-8 rad)
        assert abs(included_angle(u, v) - math.pi / 2) < 0.02 * ARCSEC
    o, a, b, c = drawn(axes, lambda p: p, corners(100 * MM))
    assert abs(included_angle(a - o, c - o) - math.pi / 2) == pytest.approx(45 * ARCSEC, rel=1e-6)


def test_signs_against_ours():
    s = 100 * ARCSEC
    klipper = skew_correction("klipper", xy_rad=s)
    marlin = skew_correction("marlin", xy_rad=s)
    rrf = skew_correction("rrf", xy_rad=s)
    assert klipper.factors["xy"] == marlin.factors["xy"] == pytest.approx(-math.tan(s))
    assert rrf.factors["xy"] == pytest.approx(math.tan(s))
    # an obtuse XY angle (s > 0) lengthens BD: Klipper's documentation example has BD > AC for the same reason
    ac, bd, ad = (float(v) for v in klipper.lines[0].split("=")[1].split(","))
    assert bd > ac and ad == 100.0
    assert klipper_factors(klipper.lines[0])["xy"] == pytest.approx(-math.tan(s), rel=1e-6)
    assert marlin.lines == ("M852 I-0.00048481",)
    assert rrf.lines == ("M556 S100 X0.048481",)
    assert any("[skew_correction]" in note for note in klipper.notes)
    assert any("#define XY_SKEW_FACTOR -0.00048481" in note for note in marlin.notes)


def test_rrf_documentation_example():
    # RepRapFirmware G-code documentation, M556: "M556 S100 X0.7 Y-0.2 Z0.6" reports
    # "XY: 0.00700, YZ: -0.00200, ZX: 0.00600"
    t = rrf_tangents("M556 S100 X0.7 Y-0.2 Z0.6")
    assert (round(t["xy"], 5), round(t["yz"], 5), round(t["xz"], 5)) == (0.007, -0.002, 0.006)
    back = skew_correction("rrf", xy_rad=math.atan(0.007), yz_rad=math.atan(-0.002), xz_rad=math.atan(0.006))
    assert back.lines == ("M556 S100 X0.700000 Y-0.200000 Z0.600000",)


def test_iso_convention_flips_xz_only():
    s = 30 * ARCSEC
    iso = skew_correction("marlin", xy_rad=s, xz_rad=s, yz_rad=s, convention="iso")
    included = skew_correction("marlin", xy_rad=s, xz_rad=-s, yz_rad=s)
    assert iso.lines == included.lines


@settings(max_examples=50, deadline=None)
@given(st.floats(-MAX_SKEW_RAD, MAX_SKEW_RAD), st.floats(0.01, 0.3))
def test_klipper_lengths_invert(s, square_m):
    ac, bd, ad = klipper_lengths(s, square_m)
    assert klipper_calc_skew_factor(ac, bd, ad) == pytest.approx(-math.tan(s), abs=1e-9)


def test_refusals():
    with pytest.raises(AxiscalError, match="unknown firmware"):
        skew_correction("grbl", xy_rad=0.0)
    with pytest.raises(AxiscalError, match="no squareness"):
        skew_correction("klipper")
    with pytest.raises(AxiscalError, match="square the frame"):
        skew_correction("klipper", xy_rad=math.radians(6))
    with pytest.raises(AxiscalError, match="square size"):
        skew_correction("rrf", xy_rad=0.0, square_m=0.0)
    with pytest.raises(AxiscalError, match="convention"):
        skew_correction("rrf", xy_rad=0.0, convention="left")


def test_squareness_from_results(tmp_path):
    xy = write_json(tmp_path / "xy.json", {"plane": "XY", "included_angle_deg": 90 + 36 / 3600})
    planes = squareness_from_results([xy])
    assert planes["XY"] / ARCSEC == pytest.approx(36, abs=1e-6)
    bad = write_json(tmp_path / "bad.json", {"plane": "XY"})
    with pytest.raises(AxiscalError, match="not a squareness result") as info:
        squareness_from_results([bad])
    assert "bad.json" in str(info.value)
    with pytest.raises(AxiscalError, match="second XY"):
        squareness_from_results([xy, xy])


def test_marlin_configuration_defaults_are_square():
    # Marlin Configuration.h ships XY_DIAG_AC = XY_DIAG_BD = 282.8427124746 and XY_SIDE_AD = 200:
    # a square of 200 mm, skew factor 0
    assert klipper_calc_skew_factor(282.8427124746, 282.8427124746, 200.0) == pytest.approx(0.0, abs=1e-12)
    ac, bd, ad = (v / MM for v in klipper_lengths(0.0, 200 * MM))
    assert (round(ac, 10), round(bd, 10), ad) == (282.8427124746, 282.8427124746, 200.0)
    assert skew_correction("klipper", xy_rad=0.0, square_m=200 * MM).lines == ("SET_SKEW XY=282.842712,282.842712,200.000000",)
