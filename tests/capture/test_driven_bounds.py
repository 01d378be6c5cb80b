"""A driven run holds every reading against its target, and its plan's rows against how the axis reaches them."""

from __future__ import annotations

import numpy as np
import pytest

from axiscal.capture.connected import open_run_devices, run_to_file
from axiscal.capture.drive import DriveSettings
from axiscal.capture.files import partial_path
from axiscal.capture.run import CaptureSettings
from axiscal.capture.steps import plan_steps
from axiscal.errors import AxiscalError
from axiscal.positioning.plan import plan_test, write_plan

DRIVE = DriveSettings(axis="X", feed_m_per_s=0.2, dwell_s=0.25)


@pytest.fixture(scope="module")
def plan_csv(tmp_path_factory):
    path = tmp_path_factory.mktemp("plan") / "plan.csv"
    write_plan(plan_test(0.020, 0.120, 5, runs=1, overrun_m=0.002, seed=2), path)
    return path


@pytest.mark.parametrize(("settings", "source", "reads"), [
    (CaptureSettings(window_s=0.1, offset_m=0.1), "sim:umd", "-80.01"),  # --offset-mm 100: -100 mm written before
    (CaptureSettings(window_s=0.1, stability_m=20e-6), "sim:sylvac", "507.6"),  # a gauge showing mm read as inches
])
def test_a_reading_not_near_its_target_stops_the_run_naming_the_step(plan_csv, tmp_path, settings, source, reads):
    from axiscal.devices.instruments import InstrumentOptions

    options = InstrumentOptions(unit="in") if source == "sim:sylvac" else None
    controller, instrument = open_run_devices("sim", source, options=options)
    try:
        with pytest.raises(AxiscalError, match=r"step 2 \(target 20.000 mm, run 1, \+\): the instrument reads .* not within"
                                               r" tolerance_m 0.5 mm of the target") as info:
            run_to_file(plan_csv, controller, instrument, tmp_path / "run.csv", drive=DRIVE, settings=settings)
    finally:
        instrument.close()
        controller.close()
    if reads:
        assert f"reads {reads}" in info.value.message
    assert not (tmp_path / "run.csv").exists()


def test_a_reading_within_a_raised_tolerance_is_taken(plan_csv, tmp_path):
    """The tolerance is the capture's: raised, the same run (a 1 mm offset) is taken, each deviation 1 mm off."""
    controller, instrument = open_run_devices("sim", "sim:umd")
    try:
        files = run_to_file(plan_csv, controller, instrument, tmp_path / "run.csv", drive=DRIVE,
                            settings=CaptureSettings(window_s=0.1, offset_m=-1e-3, tolerance_m=2e-3))
    finally:
        instrument.close()
        controller.close()
    deviations = np.array([r.deviation_m for r in files.capture.readings])
    assert np.all(np.abs(deviations - 1e-3) < 50e-6)


@pytest.mark.parametrize(("kwargs", "words"), [({"window_s": 1e300}, "window_s must be at most 3600"),
                                               ({"stability_m": 1e300}, "stability_m must be at most 0.001"),
                                               ({"offset_m": 1e300}, "offset_m must be between -100 and 100"),
                                               ({"tolerance_m": 1.0}, "tolerance_m must be at most 0.1")])
def test_the_capture_settings_are_bounded(kwargs, words):
    with pytest.raises(AxiscalError, match=words):
        CaptureSettings(**kwargs)


def test_a_feed_no_control_word_holds_is_refused():
    with pytest.raises(AxiscalError, match="at most 100000 mm/min"):
        DriveSettings(feed_m_per_s=1e300)
    assert DriveSettings(feed_m_per_s=100_000 * 1e-3 / 60).feed_m_per_s > 0


@pytest.mark.parametrize(("row", "was", "becomes", "came"), [(9, "9,1,-,", "9,1,+,", "-"), (3, "3,1,+,", "3,1,-,", "+"),
                                                            (12, "12,1,-,", "12,1,+,", "-")])
def test_a_row_whose_direction_contradicts_how_the_axis_reaches_it_is_refused_naming_it(plan_csv, tmp_path, row, was, becomes, came):
    lines = plan_csv.read_text().splitlines()
    assert lines[row].startswith(was)
    lines[row] = becomes + lines[row][len(was):]
    bad = tmp_path / "plan.csv"
    bad.write_text("\n".join(lines) + "\n")
    with pytest.raises(AxiscalError, match=rf"step {row} \(.*, run 1, \{becomes[-2]}\): the axis reaches it moving in the"
                                           rf" \{came} direction .* its direction must be \{came}") as info:
        plan_steps(bad)
    assert info.value.line == row + 1 and str(bad) in str(info.value.path)


def test_every_planned_cycle_gives_rows_in_the_direction_the_axis_reaches_them(tmp_path):
    from axiscal.positioning.step_cycle import plan_step_cycle

    for n, plan in enumerate((plan_test(0.0, 0.4, 5, seed=1), plan_test(0.0, 0.4, 5, seed=1, cycle="pilgrim", runs=3),
                              plan_step_cycle(0.1, 5e-3, steps_per_period=4))):
        path = tmp_path / f"plan{n}.csv"
        write_plan(plan, path)
        assert plan_steps(path).step.size == plan.moves.size
    assert not partial_path(tmp_path / "plan0.csv").exists()


class _Stalling:
    """A source whose samples stop arriving for ``stall_s`` from ``begin()`` on, then come in one burst (a loaded computer)."""

    def __init__(self, source, stall_s: float):
        self.source, self.stall_s, self.until = source, stall_s, None
        self.held: list = []
        self.channels, self.status = source.channels, source.status

    def begin(self) -> None:
        import time

        self.until = time.monotonic() + self.stall_s

    def read(self, timeout_s):
        import time

        from axiscal.live.protocol import FrameBatch

        batch = self.source.read(timeout_s)
        if self.until is not None and time.monotonic() < self.until:
            self.held.append(batch)
            return FrameBatch.empty(len(self.channels))
        if self.held:
            batch, self.held = FrameBatch.concatenate([*self.held, batch], len(self.channels)), []
        return batch

    def close(self):
        self.source.close()


class _LastPassStalls:
    """The virtual controller, stalling the instrument's stream as its last pass begins."""

    def __init__(self, controller, source, passes: int):
        self.controller, self.source, self.passes, self.moved = controller, source, passes, 0

    def move_to(self, axis, position_m, feed_m_per_s):
        self.moved += 1
        if self.moved == self.passes + 1:
            self.source.begin()
        return self.controller.move_to(axis, position_m, feed_m_per_s)

    def __getattr__(self, name):
        return getattr(self.controller, name)


def test_an_on_the_fly_recording_covers_the_last_pass_though_the_samples_come_late(tmp_path):
    """The samples of the last pass arrive 2.5 s late: the recording waits for them (it closed 0.2 s after the motion)."""
    from axiscal.capture.fly_drive import fly_plan, pass_moves

    plan = tmp_path / "plan.csv"
    write_plan(plan_test(0.005, 0.065, 5, runs=1, seed=1), plan)
    passes = len(pass_moves(plan_steps(plan))) - 1
    controller, instrument = open_run_devices("sim", "sim:umd")
    source = _Stalling(instrument, 2.5)
    try:
        flown = fly_plan(plan, _LastPassStalls(controller, source, passes), source, tmp_path / "fly.csv",
                         drive=DriveSettings(feed_m_per_s=3000 / 60e3))
    finally:
        source.close()
        controller.close()
    deviations = np.array([r.deviation_m for r in flown.result.capture.readings])
    assert deviations.size == 10 and np.all(np.abs(deviations) < 50e-6)


def test_an_on_the_fly_reading_not_near_its_target_is_refused_as_a_stop_is():
    from pathlib import Path

    from axiscal.capture.on_the_fly import on_the_fly

    examples = Path(__file__).resolve().parents[2] / "examples" / "dynamics"
    plan, recording = examples / "fly_plan.csv", examples / "fly_recording.csv"
    assert on_the_fly(plan, recording).capture.readings
    with pytest.raises(AxiscalError, match=r"step \d+ \(target .*\): the instrument reads .* not within tolerance_m 0.5 mm"):
        on_the_fly(plan, recording, offset_m=0.1)  # a 100 mm offset wrote deviations of -100 mm
    assert on_the_fly(plan, recording, offset_m=1e-3, tolerance_m=2e-3).capture.readings
