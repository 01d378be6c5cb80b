"""Periodic error: a hand-computed worked example, the step cycle plan, and the virtual machine's run."""

from __future__ import annotations

import numpy as np
import pytest

from axiscal.dynamics import amplitude_spectrum, periodic_error
from axiscal.positioning import PositioningRun, plan_step_cycle


def test_hand_computed_example():
    # hand-computed: 2 periods of 4 mm in 8 steps a period; mean deviations
    # 1.0 + 0.002 um/mm * P + 0.35 sin(2 pi P / 4 mm + 0.3) um; the fit and the spectrum give A = 0.35 um, p = 4 mm
    p = np.arange(17) * 0.5e-3
    x = (1.0 + 2.0 * p / 1e-3 * 1e-3 + 0.35 * np.sin(2 * np.pi * p / 4e-3 + 0.3)) * 1e-6
    run = PositioningRun(p, np.column_stack([x, x]), np.column_stack([x - 2e-6, x - 2e-6]))
    result = periodic_error(run)
    for c in result.components:
        assert c.amplitude_m == pytest.approx(0.35e-6, rel=1e-6)
        assert c.period_m == pytest.approx(4e-3, rel=1e-6)
        assert c.spectrum_period_m == pytest.approx(4e-3, rel=1e-9)
        assert c.spectrum_amplitude_m == pytest.approx(0.35e-6, rel=1e-6)
    assert result.components[0].phase_rad == pytest.approx(0.3, abs=1e-6)
    assert result.payload()["periodic_um"] == pytest.approx(0.70, abs=1e-6)


def test_the_dft_amplitude_of_a_whole_number_of_periods():
    # evenly spaced over whole periods (the DFT's own grid): the least-squares spectrum is the DFT's 2|X_k|/N
    p = np.arange(24) * 0.25e-3  # 6 mm, periods of 1.5 mm: bin 4
    y = 0.8e-6 * np.cos(2 * np.pi * p / 1.5e-3 - 1.0)
    periods, amps = amplitude_spectrum(p, y, oversample=1)
    dft = 2 * np.abs(np.fft.rfft(y)) / y.size
    k = int(np.argmin(np.abs(periods - 1.5e-3)))
    assert amps[k] == pytest.approx(dft[4], rel=1e-9)
    assert dft[4] == pytest.approx(0.8e-6, rel=1e-12)


def test_a_known_period_is_kept():
    p = np.arange(25) * (5e-3 / 12)
    x = 0.5e-6 * np.sin(2 * np.pi * p / 5e-3) + 0.05e-6 * np.sin(2 * np.pi * p / 1.1e-3)
    result = periodic_error(PositioningRun(p, x[:, None], None), period_m=5e-3)
    assert result.period_given and result.main.period_m == 5e-3
    assert result.main.amplitude_m == pytest.approx(0.5e-6, abs=0.02e-6)


def test_step_cycle_plan_is_even_over_whole_periods():
    plan = plan_step_cycle(0.1, 5e-3, periods=2, steps_per_period=12, runs=2)
    assert plan.targets.size == 25
    assert np.diff(plan.targets) == pytest.approx(np.full(24, 5e-3 / 12), abs=1.01e-6)  # targets to 1 um
    assert plan.targets[-1] - plan.targets[0] == pytest.approx(10e-3)
    assert plan.readings == 2 * 2 * 25 and plan.cycle == "step"


def test_a_screw_error_on_the_virtual_machine_through_the_step_cycle():
    # the virtual axis carries 0.4 um sin(2 pi m / 5 mm): the step cycle's captured run gives it back (periodic 0.8 um p-p)
    from axiscal.capture import VirtualAxis, capture_run, simulate_motions
    from axiscal.io.gcode import program_motions
    from axiscal.model import load_machine
    from axiscal.positioning import gcode_program

    plan = plan_step_cycle(0.1, 5e-3, periods=2, steps_per_period=8)
    spec = VirtualAxis(periodic_m=0.4e-6, pitch_m=5e-3, repeatability_m=0.02e-6)
    simulated = simulate_motions(program_motions(gcode_program(plan, dwell_s=0.8, feed_mm_per_min=600), dialect="linuxcnc"),
                                 load_machine("examples/xz_module/machine.toml"), axis="X", spec=spec, rate_hz=200.0)
    result = periodic_error(capture_run(plan, simulated.recording))
    assert result.main.amplitude_m == pytest.approx(0.4e-6, abs=0.03e-6)
    assert result.main.period_m == pytest.approx(5e-3, rel=0.03)
    assert result.main.spectrum_period_m == pytest.approx(5e-3, rel=0.1)


from hypothesis import given, settings
from hypothesis import strategies as hs


def plain_spectrum(p, y, periods):
    """The reference: one least-squares fit of line, cosine and sine per trial period."""
    out = []
    for q in periods:
        a = np.column_stack([np.ones_like(p), p, np.cos(2 * np.pi * p / q), np.sin(2 * np.pi * p / q)])
        coef = np.linalg.lstsq(a, y, rcond=None)[0]
        out.append(np.hypot(coef[2], coef[3]))
    return np.array(out)


@settings(max_examples=25, deadline=None)
@given(amplitude=hs.floats(0.05, 5.0), period=hs.floats(2.0, 8.0), phase=hs.floats(-3.0, 3.0), slope=hs.floats(-5.0, 5.0),
       seed=hs.integers(0, 1000))
def test_any_sine_on_uneven_targets_is_found_and_the_spectrum_equals_the_plain_fits(amplitude, period, phase, slope, seed):
    rng = np.random.default_rng(seed)
    p = np.sort(rng.uniform(0.0, 20e-3, 40))
    p = p[np.r_[True, np.diff(p) > 1e-6]]
    x = (slope * p / 1e-3 * 1e-3 + amplitude * np.sin(2 * np.pi * p / (period * 1e-3) + phase)) * 1e-6
    result = periodic_error(PositioningRun(p, x[:, None], None))
    assert result.main.amplitude_m == pytest.approx(amplitude * 1e-6, rel=1e-5)
    assert result.main.period_m == pytest.approx(period * 1e-3, rel=1e-5)
    periods, amps = amplitude_spectrum(p, x)
    assert amps == pytest.approx(plain_spectrum(p, x, periods), rel=1e-6, abs=1e-15)
