"""Level readings to a straightness profile: known angles give the known profile (foot chain and
midpoint integration), the differential set-up removes the machine's tilt, and the vectorised
integration agrees with a plain loop over seeded random readings."""

from __future__ import annotations

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as hs

from axiscal.errors import AxiscalError
from axiscal.levels import level_profile
from axiscal.straightness import reference_line
from axiscal.units import MM, UM, URAD


def true_profile(x):
    """A guideway: a bow of 3 um over 1 m and a 0.4 um wave, metres."""
    u = x / 1.0
    return 12e-6 * u * (1 - u) + 0.4e-6 * np.sin(2 * np.pi * x / 0.25)


def test_a_profile_from_known_angles_is_recovered_by_the_foot_chain():
    foot = 100 * MM
    stations = np.arange(11) * foot
    z = true_profile(stations)
    angles = np.diff(z) / foot
    p = level_profile(stations[:-1], angles, foot_m=foot)
    assert p.integration == "foot-chain"
    np.testing.assert_allclose(p.position_m, stations)
    np.testing.assert_allclose(p.deviation_m, z - z[0], atol=1e-15)
    expected = reference_line(stations, z, reference="minimum-zone").straightness_m
    got = reference_line(p.position_m, p.deviation_m, reference="minimum-zone").straightness_m
    assert got == pytest.approx(expected, rel=1e-12)


def test_the_reference_level_takes_out_the_tilt_of_the_machine():
    foot = 50 * MM
    stations = np.arange(21) * foot
    angles = np.diff(true_profile(stations)) / foot
    tilt = 7 * URAD * np.sin(np.linspace(0, 3, angles.size)) + 3 * URAD
    plain = level_profile(stations[:-1], angles, foot_m=foot)
    differential = level_profile(stations[:-1], angles + tilt, foot_m=foot, reference_rad=tilt)
    np.testing.assert_allclose(differential.deviation_m, plain.deviation_m, atol=1e-18)
    np.testing.assert_allclose(differential.angle_rad, angles, atol=1e-18)
    assert differential.angular_error_rad == pytest.approx(np.ptp(angles))


def test_steps_shorter_than_the_foot_integrate_the_slopes_at_the_levels_middles():
    # z = c x^2: the chord slope over [x, x + l] is exactly z'(x + l / 2), which is linear, so the
    # trapezoid rule over the middles is exact
    c, foot = 3e-6, 100 * MM
    x = np.arange(0, 0.9001, 0.025)
    angles = c * ((x + foot) ** 2 - x ** 2) / foot
    p = level_profile(x, angles, foot_m=foot)
    middles = x + foot / 2
    assert p.integration == "midpoint"
    np.testing.assert_allclose(p.position_m, middles)
    np.testing.assert_allclose(p.deviation_m, c * (middles ** 2 - middles[0] ** 2), atol=1e-15)


def plain_integration(position, angle, foot):
    """Reference: a loop over the readings, as a technician's worksheet adds the rises."""
    steps = [position[k + 1] - position[k] for k in range(len(position) - 1)]
    if all(abs(s - foot) <= 1e-6 * foot for s in steps):
        heights = [0.0]
        for a in angle:
            heights.append(heights[-1] + foot * a)
        return heights
    heights = [0.0]
    for k, s in enumerate(steps):
        heights.append(heights[-1] + s * (angle[k] + angle[k + 1]) / 2)
    return heights


@pytest.mark.parametrize("seed", range(6))
def test_the_integration_agrees_with_a_plain_loop(seed):
    rng = np.random.default_rng(seed)
    foot = rng.uniform(20, 200) * MM
    n = int(rng.integers(2, 60))
    if seed % 2:
        position = np.cumsum(rng.uniform(0.2, 1.5, n)) * foot
    else:
        position = np.arange(n) * foot + rng.uniform(-1, 1)
    angle = rng.normal(0, 20, n) * URAD
    p = level_profile(position, angle, foot_m=foot)
    np.testing.assert_allclose(p.deviation_m, plain_integration(position.tolist(), angle.tolist(), foot), atol=1e-15)


def test_bad_readings_are_refused():
    with pytest.raises(AxiscalError, match="position_m must increase"):
        level_profile([0, 0.1, 0.1], [0, 0, 0], foot_m=0.1)
    with pytest.raises(AxiscalError, match="at least 2"):
        level_profile([0.0], [0.0], foot_m=0.1)
    with pytest.raises(AxiscalError, match="foot_m"):
        level_profile([0, 0.1], [0, 0], foot_m=0.0)
    with pytest.raises(AxiscalError, match="same length|do not match|lengths"):
        level_profile([0, 0.1], [0, 0], foot_m=0.1, reference_rad=[0.0])


@settings(max_examples=80, deadline=None)
@given(hs.lists(hs.floats(allow_nan=True, allow_infinity=True), min_size=0, max_size=8),
       hs.floats(allow_nan=True, allow_infinity=True))
def test_any_numbers_give_a_finite_profile_or_are_refused(angles, foot):
    position = np.arange(len(angles)) * 0.1
    try:
        p = level_profile(position, angles, foot_m=foot)
    except AxiscalError:
        return
    assert np.all(np.isfinite(p.deviation_m)) and p.deviation_m[0] == 0.0
    assert p.deviation_m.size in (len(angles), len(angles) + 1)
    assert abs(p.deviation_m).max() <= foot * len(angles) * 1.0 + 1e-9 * UM
