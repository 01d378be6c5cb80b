"""The diagnostics read back every error of a simulated machine (within 2 %), in every plane and with either sign."""

from __future__ import annotations

import math

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from axiscal.circular.diagnostics import SERVO_WARNING, backlash_signature, diagnose
from axiscal.circular.evaluation import MM_PER_MIN, BallbarTrace
from axiscal.circular.report import MS, PPM
from axiscal.circular.simulation import simulate_ballbar
from axiscal.errors import AxiscalError
from axiscal.units import ANGLE_UNITS, MM, UM

URAD = ANGLE_UNITS["urad"]
FEED = 1000.0 * MM_PER_MIN

#: a machine with every error at once, and noise of 0.1 um on each reading
MACHINE = {
    "squareness": 30.0 * URAD,
    "scale": {"X": 20 * PPM, "Y": -5 * PPM},
    "backlash": {"X": 6.0 * UM, "Y": 4.0 * UM},
    "servo_mismatch": 3 * MS,
    "reversal_spike": {"X": 5.0 * UM, "Y": 8.0 * UM},
    "cyclic_error": {"X": 1.5 * UM, "Y": 1.0 * UM},
    "cyclic_pitch": {"X": 5.0 * MM, "Y": 10.0 * MM},
    "centre_offset": {"X": 12.0 * UM, "Y": -7.0 * UM},
}


@pytest.fixture(scope="module")
def found():
    trace = simulate_ballbar(radius=100.0 * MM, plane="XY", feed=FEED, noise=0.1 * UM, seed=3, **MACHINE)
    return diagnose(trace, feed=FEED)


def test_squareness_within_2_percent(found):
    assert found.squareness == pytest.approx(MACHINE["squareness"], rel=0.02)


def test_scale_mismatch_within_2_percent(found):
    assert found.scale_mismatch == pytest.approx(20 * PPM - (-5 * PPM), rel=0.02)


def test_servo_mismatch_within_2_percent(found):
    assert found.servo_mismatch == pytest.approx(MACHINE["servo_mismatch"], rel=0.02)


@pytest.mark.parametrize("axis", ["X", "Y"])
def test_backlash_within_2_percent(found, axis):
    assert found.backlash[axis] == pytest.approx(MACHINE["backlash"][axis], rel=0.02)


@pytest.mark.parametrize("axis", ["X", "Y"])
@pytest.mark.parametrize("direction", ["ccw", "cw"])
def test_reversal_spike_within_2_percent(found, axis, direction):
    assert found.reversal_spike[axis][direction] == pytest.approx(MACHINE["reversal_spike"][axis], rel=0.02)


@pytest.mark.parametrize("axis", ["X", "Y"])
def test_cyclic_error_and_its_pitch_within_2_percent(found, axis):
    assert found.cyclic_error[axis] == pytest.approx(MACHINE["cyclic_error"][axis], rel=0.02)
    assert found.cyclic_pitch[axis] == pytest.approx(MACHINE["cyclic_pitch"][axis], rel=0.02)


def test_what_is_left_is_the_noise(found):
    assert found.residual_rms == pytest.approx(0.1 * UM, rel=0.1)
    assert found.warnings == ()


def test_another_plane_radius_feed_and_negative_errors():
    feed = 2500.0 * MM_PER_MIN
    errors = {
        "squareness": -45.0 * URAD,
        "scale": {"Z": -12 * PPM, "X": 8 * PPM},
        "backlash": {"Z": -3.0 * UM, "X": 7.0 * UM},
        "servo_mismatch": -1.5 * MS,
        "reversal_spike": {"Z": 6.0 * UM, "X": -5.0 * UM},
        "cyclic_error": {"Z": 2.0 * UM},
        "cyclic_pitch": {"Z": 4.0 * MM},
    }
    trace = simulate_ballbar(radius=150.0 * MM, plane="ZX", feed=feed, noise=0.05 * UM, seed=7, **errors)
    d = diagnose(trace, feed=feed)
    assert d.squareness == pytest.approx(-45.0 * URAD, rel=0.02)
    assert d.scale_mismatch == pytest.approx(-20 * PPM, rel=0.02)
    assert d.servo_mismatch == pytest.approx(-1.5 * MS, rel=0.02)
    assert d.backlash["Z"] == pytest.approx(-3.0 * UM, rel=0.02)
    assert d.backlash["X"] == pytest.approx(7.0 * UM, rel=0.02)
    for direction in ("ccw", "cw"):
        assert d.reversal_spike["Z"][direction] == pytest.approx(6.0 * UM, rel=0.02)
        assert d.reversal_spike["X"][direction] == pytest.approx(-5.0 * UM, rel=0.02)
    assert d.cyclic_error["Z"] == pytest.approx(2.0 * UM, rel=0.02)
    assert d.cyclic_pitch["Z"] == pytest.approx(4.0 * MM, rel=0.02)
    assert d.cyclic_error["X"] < 0.02 * UM  # none simulated: the noise floor, and no pitch
    assert math.isnan(d.cyclic_pitch["X"])


def test_one_direction_gives_squareness_but_no_servo_mismatch_and_says_why():
    trace = simulate_ballbar(squareness=20.0 * URAD, backlash={"X": 5.0 * UM}, directions=("cw",), noise=0.1 * UM)
    d = diagnose(trace, feed=FEED)
    assert d.squareness == pytest.approx(20.0 * URAD, rel=0.02)
    assert d.backlash["X"] == pytest.approx(5.0 * UM, rel=0.02)
    assert math.isnan(d.servo_mismatch) and d.warnings == (SERVO_WARNING,)
    assert set(d.reversal_spike["X"]) == {"cw"}


def test_without_feed_no_servo_mismatch():
    trace = simulate_ballbar(servo_mismatch=2 * MS, step=math.radians(0.5))
    assert math.isnan(diagnose(trace).servo_mismatch)


def test_first_order_signatures_of_the_docs():
    """dR = -(R q / 2) sin 2a for a squareness q and (R (s1 - s2) / 2) cos 2a + const for scale, to first order."""
    R = 0.1
    q = 40.0 * URAD
    trace = simulate_ballbar(radius=R, squareness=q, directions=("ccw",), step=math.radians(1.0))
    a = trace.angles
    np.testing.assert_allclose(trace.deviations, -R * q / 2 * np.sin(2 * a), atol=1e-10)
    s1, s2 = 10 * PPM, -4 * PPM
    trace = simulate_ballbar(radius=R, scale={"X": s1, "Y": s2}, directions=("ccw",), step=math.radians(1.0))
    np.testing.assert_allclose(trace.deviations, R * (s1 + s2) / 2 + R * (s1 - s2) / 2 * np.cos(2 * a), atol=1e-10)


def test_backlash_steps_outwards_at_the_reversals():
    """A positive backlash b of the first axis reads +b/2 just after 0 and 180 deg and -b/2 just before, ccw."""
    a = np.radians([-0.5, 0.5, 179.5, 180.5])
    np.testing.assert_allclose(backlash_signature(a, np.ones(4), 0), [-1, 1, -1, 1], atol=1e-3)
    np.testing.assert_allclose(backlash_signature(a, -np.ones(4), 0), [1, -1, 1, -1], atol=1e-3)
    b = np.radians([89.5, 90.5, 269.5, 270.5])
    np.testing.assert_allclose(backlash_signature(b, np.ones(4), 1), [-1, 1, -1, 1], atol=1e-3)


@settings(max_examples=12, deadline=None)
@given(
    q=st.floats(-100.0, 100.0),
    s1=st.floats(-50.0, 50.0),
    s2=st.floats(-50.0, 50.0),
    bx=st.floats(-10.0, 10.0),
    by=st.floats(-10.0, 10.0),
    lag=st.floats(-5.0, 5.0),
)
def test_noise_free_errors_come_back(q, s1, s2, bx, by, lag):
    trace = simulate_ballbar(
        squareness=q * URAD, scale={"X": s1 * PPM, "Y": s2 * PPM}, backlash={"X": bx * UM, "Y": by * UM},
        servo_mismatch=lag * MS, step=math.radians(0.5),
    )
    d = diagnose(trace, feed=FEED)
    assert d.squareness == pytest.approx(q * URAD, rel=0.01, abs=0.05 * URAD)
    assert d.scale_mismatch == pytest.approx((s1 - s2) * PPM, rel=0.01, abs=0.05 * PPM)
    assert d.backlash["X"] == pytest.approx(bx * UM, rel=0.01, abs=0.01 * UM)
    assert d.backlash["Y"] == pytest.approx(by * UM, rel=0.01, abs=0.01 * UM)
    assert d.servo_mismatch == pytest.approx(lag * MS, rel=0.01, abs=0.005 * MS)


def test_bad_feed_and_window_are_refused():
    trace = simulate_ballbar(step=math.radians(1.0))
    with pytest.raises(AxiscalError, match="feed"):
        diagnose(trace, feed=-1.0)
    with pytest.raises(AxiscalError, match="window"):
        diagnose(trace, spike_window=math.radians(60.0))


def test_a_trace_built_by_hand_works_too():
    a = np.radians(np.arange(0.25, 360.0, 0.5))
    t = BallbarTrace(a, ("ccw",) * a.size, 2 * UM * np.cos(2 * a), radius=0.05, plane="YZ")
    d = diagnose(t)
    assert d.scale_mismatch == pytest.approx(2 * 2 * UM / 0.05, rel=1e-9)
    assert set(d.backlash) == {"Y", "Z"}
