"""On-the-fly capture on the virtual machine: within 0.2 um of stop-and-go at 1000 mm/min, the delay found."""

from __future__ import annotations

import numpy as np
import pytest

from axiscal.capture import FlyRecording, VirtualAxis, capture_run, estimate_delay, on_the_fly, simulate_motions
from axiscal.errors import AxiscalError
from axiscal.io.gcode import program_motions
from axiscal.model import load_machine
from axiscal.positioning import gcode_program, plan_test


@pytest.fixture(scope="module")
def runs():
    machine = load_machine("examples/xz_module/machine.toml")
    plan = plan_test(0.0, 0.19, 5, runs=2, seed=7)
    # a repeatable axis (no scatter from one arrival to the next): a pass has no arrivals at the targets, so the
    # scatter a stop-and-go run draws at each would be a difference of the machines, not of the methods
    spec = VirtualAxis(repeatability_m=0.0)
    stop_and_go = simulate_motions(program_motions(gcode_program(plan, dwell_s=1.0, feed_mm_per_min=1000), dialect="linuxcnc"),
                                   machine, axis="X", spec=spec, seed=1)
    flying = simulate_motions(program_motions(gcode_program(plan, on_the_fly=True, feed_mm_per_min=1000), dialect="linuxcnc"),
                              machine, axis="X", spec=spec, seed=2, continuous=True, position_delay_s=0.008)
    r = flying.recording
    return plan, stop_and_go, FlyRecording(r.time_s, r.reading_m, r.time_s, flying.position_m, r.channels, "<virtual>")


def test_on_the_fly_is_within_0_2_um_of_stop_and_go_at_1000_mm_min(runs):
    plan, stop_and_go, fly = runs
    reference = capture_run(plan, stop_and_go.recording)
    result = on_the_fly(plan, fly)
    assert result.delay_estimated and result.delay_s == pytest.approx(0.008, abs=2e-6)
    assert np.abs(result.speed_m_s) == pytest.approx(np.full(result.speed_m_s.size, 1000 / 60e3), rel=1e-6)
    run = result.run
    for d in ("up", "down"):
        assert np.abs(getattr(run, f"deviations_{d}") - getattr(reference, f"deviations_{d}")).max() < 0.2e-6


def test_a_delay_left_in_looks_like_a_reversal(runs):
    # hand-computed: at 1000 mm/min a delay of 8 ms moves the forward readings by +133.3 um and the backward by -133.3 um
    # (of raw reading; the air compensation scales it by 1/n, 0.04 um less)
    plan, _, fly = runs
    good, none = on_the_fly(plan, fly).run, on_the_fly(plan, fly, delay_s=0.0).run
    shift = 1000 / 60 * 8e-3 * 1e-3
    assert shift == pytest.approx(133.3e-6, rel=1e-3)
    assert (none.deviations_up - good.deviations_up) == pytest.approx(np.full(good.deviations_up.shape, shift), abs=0.1e-6)
    assert (none.deviations_down - good.deviations_down) == pytest.approx(np.full(good.deviations_up.shape, -shift), abs=0.1e-6)


def test_the_delay_of_a_shifted_sine():
    t = np.arange(0, 4, 1e-3)
    rec = FlyRecording(t, 0.01 * np.sin(np.pi * t), t, 0.01 * np.sin(np.pi * (t + 0.021)))
    assert estimate_delay(rec) == pytest.approx(-0.021, abs=1e-6)


def test_a_target_the_axis_rests_at_is_refused(runs):
    plan, stop_and_go, _ = runs
    r = stop_and_go.recording
    t = r.time_s
    rec = FlyRecording(t, r.reading_m, t, np.interp(t, t, r.reading_m), r.channels, "stops.csv")
    with pytest.raises(AxiscalError, match="comes to rest at the target"):
        on_the_fly(plan, rec, delay_s=0.0)


from hypothesis import given, settings
from hypothesis import strategies as hs


@settings(max_examples=20, deadline=None)
@given(delay=hs.floats(-0.2, 0.2), offset=hs.floats(-5e-6, 5e-6))
def test_any_delay_of_a_trapezoidal_pass_is_found_whatever_the_offset(delay, offset):
    # a forward and a backward pass (1 m/s^2, 20 mm/s) with the position stream shifted by the delay; an offset of the laser
    # that changes sign with the direction (a reversal) does not move the estimate
    t = np.arange(0, 6, 1e-3)
    v = np.interp(t, [0.5, 0.52, 2.0, 2.02, 3.0, 3.02, 4.5, 4.52], [0, 0.02, 0.02, 0, 0, -0.02, -0.02, 0])
    x = np.concatenate([[0], np.cumsum((v[1:] + v[:-1]) / 2) * 1e-3])
    laser = x + offset * np.where(t < 2.5, 1.0, -1.0)
    rec = FlyRecording(t, laser, t, np.interp(t - delay, t, x))
    assert estimate_delay(rec) == pytest.approx(delay, abs=2e-6)


def test_a_file_with_the_positions_own_time_stamps(runs, tmp_path):
    # the controller streams its position at 250 Hz with its own stamps (position_time_s; other rows hold none)
    import pandas as pd

    from axiscal.capture import on_the_fly_to_file, read_fly_recording

    plan, stop_and_go, fly = runs
    every = 4
    frame = pd.DataFrame({"time_s": fly.time_s, "reading_mm": fly.reading_m * 1e3,
                          "position_time_s": np.where(np.arange(fly.time_s.size) % every == 0, fly.position_time_s, np.nan),
                          "position_mm": np.where(np.arange(fly.time_s.size) % every == 0, fly.position_m * 1e3, np.nan),
                          **fly.channels})
    path = tmp_path / "fly.csv"
    frame.to_csv(path, index=False, float_format="%.9f", na_rep="")
    rec = read_fly_recording(path)
    assert rec.position_time_s.size == (fly.time_s.size + every - 1) // every and "air_temperature_c" in rec.channels
    result, run_csv, sidecar = on_the_fly_to_file(plan, path, tmp_path / "run.csv")
    assert result.delay_s == pytest.approx(0.008, abs=5e-6)
    reference = capture_run(plan, stop_and_go.recording)
    assert np.abs(result.run.deviations_up - reference.deviations_up).max() < 0.2e-6
    assert run_csv.exists() and sidecar.exists()
