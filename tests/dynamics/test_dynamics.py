"""Dynamics of a recording: worked examples from a second-order system's step response, and the virtual machine."""

from __future__ import annotations

import math

import numpy as np
import pytest

from axiscal.capture import Recording, simulate_motions, VirtualAxis
from axiscal.dynamics import DynamicsSettings, axis_dynamics, derivatives, savgol_bandwidth_hz, welch_spectrum
from axiscal.io.gcode import program_motions
from axiscal.model import load_machine
from axiscal.positioning import gcode_program, plan_test


def test_savgol_bandwidth_agrees_with_schafers_approximation():
    # Schafer, "What is a Savitzky-Golay filter?", IEEE Signal Processing Magazine 28(4) 2011, eq. (15):
    # f_c ~ (N + 1) / (3.2 M - 4.6) * f_s / 2 for a window of 2M + 1 samples and even N (an approximation: within
    # 10 % here); degree N + 1 smooths as degree N does
    for m, n in ((25, 2), (40, 4), (50, 4), (30, 6), (60, 2)):
        approx = (n + 1) / (3.2 * m - 4.6) * 1000.0 / 2
        assert savgol_bandwidth_hz(2 * m + 1, n, 1000.0) == pytest.approx(approx, rel=0.10)
        assert savgol_bandwidth_hz(2 * m + 1, n + 1, 1000.0) == pytest.approx(savgol_bandwidth_hz(2 * m + 1, n, 1000.0))


def test_derivatives_of_a_cubic_are_exact():
    t = np.arange(0, 1, 1e-3)
    x = 0.1 * t**3 - 0.02 * t**2 + 0.003 * t
    d = derivatives(t, x, window_s=0.021, polyorder=3)
    assert d.velocity_m_s == pytest.approx(0.3 * t**2 - 0.04 * t + 0.003, abs=1e-12)
    assert d.acceleration_m_s2 == pytest.approx(0.6 * t - 0.04, abs=1e-9)
    assert d.jerk_m_s3 == pytest.approx(np.full_like(t, 0.6), abs=1e-6)


def test_welch_finds_a_sine():
    t = np.arange(0, 8, 1e-3)
    spectrum = welch_spectrum(t, 1e-6 * np.sin(2 * np.pi * 37.0 * t), segment_s=1.0)
    assert spectrum.peak_hz == pytest.approx(37.0, abs=spectrum.resolution_hz)


def test_welch_density_of_white_noise():
    # hand-computed: white noise of standard deviation s sampled at f_s has the one-sided density s^2 / (f_s / 2),
    # so 20 nm at 1 kHz is 20 nm * sqrt(2 / 1000 Hz) = 0.894 nm/sqrt(Hz) (Welch 1967: the averaged periodogram)
    rng = np.random.default_rng(1)
    t = np.arange(0, 60, 1e-3)
    spectrum = welch_spectrum(t, rng.normal(0.0, 20e-9, t.size), segment_s=1.0)
    assert 20e-9 * math.sqrt(2 / 1000) == pytest.approx(0.894e-9, rel=1e-3)
    assert np.median(spectrum.density_m_rthz[1:-1]) == pytest.approx(0.894e-9, rel=0.05)


def second_order_step(zeta: float, fn_hz: float, step_m: float, rate_hz: float = 5000.0):
    """Position of an under-damped second-order axis after a step command (Ogata, Modern Control Engineering, eq. 5-17)."""
    wn = 2 * np.pi * fn_hz
    wd = wn * math.sqrt(1 - zeta**2)
    t = np.arange(0, 3.0, 1 / rate_hz)
    after = t - 0.5  # the step at 0.5 s
    resp = step_m * (1 - np.exp(-zeta * wn * after) * (np.cos(wd * after) + zeta / math.sqrt(1 - zeta**2) * np.sin(wd * after)))
    return t, np.where(after <= 0, 0.0, resp)


def test_step_response_overshoot_ringing_and_damping():
    # Ogata, Modern Control Engineering (5th ed.), eqs. 5-21 and 5-22: maximum overshoot
    # M_p = exp(-pi zeta / sqrt(1 - zeta^2)) of the step; ringing at f_d = f_n sqrt(1 - zeta^2).
    zeta, fn, step = 0.2, 20.0, 1e-3
    t, x = second_order_step(zeta, fn, step)
    result = axis_dynamics(Recording(t, x), settings=DynamicsSettings(window_s=0.002, moving_m_s=0.5e-3, band_m=0.02 * step,
                                                                      ring_s=0.5))
    stop = result.stops[-1]
    overshoot = math.exp(-math.pi * zeta / math.sqrt(1 - zeta**2))  # 0.5266
    assert overshoot == pytest.approx(0.5266, abs=1e-4)
    assert stop.overshoot_m == pytest.approx(overshoot * step, rel=0.01)
    assert stop.ringing_hz == pytest.approx(fn * math.sqrt(1 - zeta**2), rel=0.01)
    assert stop.damping_ratio == pytest.approx(zeta, abs=0.01)
    # 2 % settling: about 4 / (zeta wn) = 0.159 s (Ogata eq. 5-25); the exact last exit of the band is a little earlier
    assert 0.1 < stop.settling_s < 4 / (zeta * 2 * np.pi * fn) * 1.05


def test_virtual_machine_ringing_is_recovered():
    # the virtual axis rings at 25 Hz with a decay time of 0.06 s: zeta = (1/0.06) / hypot(1/0.06, 2 pi 25) = 0.1055
    machine = load_machine("examples/xz_module/machine.toml")
    plan = plan_test(0.0, 0.19, 5, runs=1, seed=7)
    spec = VirtualAxis(noise_m=5e-9, creep_m=0.0, reversal_m=0.0)  # no reversal step: the acceleration is the profile's
    sim = simulate_motions(program_motions(gcode_program(plan, dwell_s=1.0, feed_mm_per_min=2000), dialect="linuxcnc"),
                           machine, axis="X", spec=spec, rate_hz=2000.0)
    result = axis_dynamics(sim.recording, plan, settings=DynamicsSettings(window_s=0.01, band_m=0.5e-6))
    zeta = (1 / 0.06) / math.hypot(1 / 0.06, 2 * math.pi * 25)
    assert zeta == pytest.approx(0.1055, abs=1e-4)
    assert len(result.stops) == plan.readings
    assert [s.step for s in result.stops] == [k + 1 for k in range(plan.moves.size) if np.isfinite(plan.move_target[k])]
    assert np.median([s.ringing_hz for s in result.stops]) == pytest.approx(25.0, rel=0.02)
    assert result.spectrum.over == "stops" and result.spectrum.peak_hz == pytest.approx(25.0, abs=result.spectrum.resolution_hz)
    assert np.median([s.damping_ratio for s in result.stops]) == pytest.approx(zeta, abs=0.01)
    summary = result.summary()
    assert summary["peak_velocity_mm_s"] == pytest.approx(2000 / 60, rel=0.01)
    assert summary["peak_acceleration_m_s2"] == pytest.approx(1.0, rel=0.05)
    # settling to 0.5 um from 2 um of ringing: 0.06 ln(4) = 0.083 s at most
    assert 0.0 < summary["settling_s"] <= 0.06 * math.log(4) + 0.01
