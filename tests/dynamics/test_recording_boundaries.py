"""What the dynamics cannot use is refused, naming the sample's line: two samples at one time, a gap the
differentiator would draw a straight line across, samples too sparse for an even grid, a plan no stop is at,
a sensor's column given as the reading."""

from __future__ import annotations

import tracemalloc

import numpy as np
import pytest

from axiscal.capture import Recording
from axiscal.dynamics import axis_dynamics, derivatives, dynamics_from_file, welch_spectrum
from axiscal.errors import AxiscalError

RECORDING = "examples/capture/recording_x.csv"
PLAN = "examples/capture/plan_x.csv"


def _edited(tmp_path, change) -> tuple[str, list[str]]:
    """The example recording with its data rows (line k + 2 holds sample k) changed by ``change(rows)``."""
    lines = open(RECORDING).read().splitlines()
    rows = lines[1:]
    change(rows)
    path = tmp_path / "recording.csv"
    path.write_text("\n".join([lines[0], *rows]) + "\n")
    return str(path), rows


def _set_time(rows, k, time_s):
    cells = rows[k].split(",")
    cells[0] = f"{time_s:.6f}"
    rows[k] = ",".join(cells)


def test_a_time_given_twice_is_refused_naming_its_line(tmp_path):
    """A repeated stamp in a move distorted every figure (a velocity of 44.45 instead of 33.81 mm/s)."""
    path, _ = _edited(tmp_path, lambda rows: _set_time(rows, 300, float(rows[299].split(",")[0])))
    with pytest.raises(AxiscalError) as caught:
        dynamics_from_file(path)
    assert caught.value.message == "the time 2.99 s is given twice: two samples at one time"
    assert caught.value.path == path and caught.value.line == 302


def test_a_huge_gap_is_refused_before_anything_is_allocated(tmp_path):
    """A gap of 10^6 s made it allocate 763 MiB (an even grid at 10 ms) and end in a traceback."""
    def shift(rows):
        for k in range(1500, len(rows)):
            _set_time(rows, k, float(rows[k].split(",")[0]) + 1e6)

    path, _ = _edited(tmp_path, shift)
    tracemalloc.start()
    try:
        with pytest.raises(AxiscalError, match="a gap of 1e\\+06 s, longer than the differentiator's window") as caught:
            dynamics_from_file(path)
        peak = tracemalloc.get_traced_memory()[1]
    finally:
        tracemalloc.stop()
    assert caught.value.line == 1502 and peak < 20 * 2**20


def test_a_few_missing_samples_and_jitter_are_still_read():
    """Jitter and a gap within the window are interpolated onto the grid, as before."""
    rng = np.random.default_rng(0)
    t = np.arange(2000) * 1e-3 + rng.uniform(-2e-5, 2e-5, 2000)
    keep = np.ones(2000, bool)
    keep[1000:1003] = False  # three samples lost: a gap of 4 ms within a 5 ms window
    x = 0.01 * np.sin(2 * np.pi * t)
    d = derivatives(t[keep], x[keep], window_s=0.005)
    assert d.resampled and np.max(np.abs(d.velocity_m_s - 0.02 * np.pi * np.cos(2 * np.pi * d.time_s))) < 1e-4


@pytest.mark.parametrize(("time_s", "words"), [
    (np.r_[np.arange(10.0), 9.0, 10.0, 11.0] * 1e-3, r"time_s\[10\]: the time 0.009 s is given twice"),
    (np.r_[np.arange(10.0), 1e9] * 1e-3, r"time_s\[10\]: the time jumps from 0.009 s to 1e\+06 s"),
])
def test_the_python_entries_refuse_the_same(time_s, words):
    with pytest.raises(AxiscalError, match=words):
        derivatives(time_s, np.zeros(time_s.size))
    with pytest.raises(AxiscalError, match=words if "twice" in words else "most of it would be made up"):
        welch_spectrum(time_s, np.zeros(time_s.size))
    with pytest.raises(AxiscalError, match=words.replace(r"time_s\[10\]", r"sample 10")):
        axis_dynamics(Recording(time_s, np.zeros(time_s.size)))


def test_a_plan_no_stop_is_at_is_refused(tmp_path):
    """A plan 3 mm off the recording was accepted, every stop unnamed."""
    lines = open(PLAN).read().splitlines()
    out = [lines[0]]
    for line in lines[1:]:
        cells = line.split(",")
        cells[3:5] = [f"{float(c) + 3:.3f}" if c else c for c in cells[3:5]]
        out.append(",".join(cells))
    plan = tmp_path / "plan.csv"
    plan.write_text("\n".join(out) + "\n")
    with pytest.raises(AxiscalError, match="none of its 10 stops is within 0.5 mm of a step's position") as caught:
        dynamics_from_file(RECORDING, plan)
    assert caught.value.path == str(plan) and "Is it the plan the program ran?" in caught.value.message
    assert [s.step for s in dynamics_from_file(RECORDING, PLAN).stops][:2] == [2, 3]


def test_a_sensor_column_is_not_a_reading():
    """--channel air_temperature_c --unit mm was read as a length (nan results)."""
    with pytest.raises(AxiscalError, match="the channel air_temperature_c is a sensor's column") as caught:
        dynamics_from_file(RECORDING, channel="air_temperature_c", unit="mm")
    assert caught.value.path == RECORDING
