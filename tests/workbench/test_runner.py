"""The run adapter on the virtual machine: a plan captured whole, paused, cut and resumed, every sample traced."""

from __future__ import annotations

import time

import numpy as np
import pytest

from axiscal.capture.files import partial_path
from axiscal.errors import AxiscalError
from axiscal.io.tabular import read_csv
from axiscal.positioning.plan import plan_test, write_plan
from axiscal.workbench import SIM_RATE_HZ, PlanRun, connect

SPEED = 40.0


@pytest.fixture
def plan_csv(tmp_path):
    write_plan(plan_test(0.0, 0.15, 5, runs=1, seed=1), tmp_path / "plan_x.csv", gcode_path=tmp_path / "x.ngc", dwell_s=1.0)
    return tmp_path / "plan_x.csv"


def test_connect_to_the_virtual_machine_lights_both():
    c = connect("sim", "sim")
    assert (c.instrument_state, c.controller_state) == ("ok", "ok")
    assert abs(c.reading_m) < 1e-6 and c.position_m == 0.0


def test_a_whole_plan_is_captured_and_every_sample_is_traced(plan_csv, tmp_path):
    run = PlanRun(plan_csv, tmp_path / "positioning_x.csv", speed=SPEED).start()
    assert run.wait(30) == "done", run.message
    assert run.result is not None and run.result.run_csv.is_file() and not partial_path(run.result.run_csv).exists()
    assert len(run.stops) == run.total == 10
    t, x, n = run.samples_since(0)
    # every sample the laser gave, in order, none dropped or repeated (1 kHz: steps of 1 ms)
    assert n == t.size == x.size and n > 1000
    assert np.allclose(np.diff(t), 1.0 / SIM_RATE_HZ)
    tail_t, _, again = run.samples_since(n - 10)
    assert again == n and np.array_equal(tail_t, t[-10:])
    assert run.snapshot()["state"] == "done" and run.snapshot()["remaining_s"] == 0.0
    table = read_csv(tmp_path / "positioning_x.csv")
    assert np.allclose(table.numeric("deviation_um"), [s["deviation_um"] for s in run.stops], atol=1e-4)


def test_pause_holds_the_machine_and_resume_goes_on(plan_csv, tmp_path):
    run = PlanRun(plan_csv, tmp_path / "positioning_x.csv", speed=SPEED).start()
    time.sleep(0.3)
    run.pause()
    assert run.state == "paused"
    time.sleep(0.1)
    held = run.samples_since(0)[2]
    time.sleep(0.3)
    assert run.samples_since(0)[2] == held  # no sample while held
    run.resume()
    assert run.wait(30) == "done"


def test_a_cut_connection_keeps_the_stops_and_resume_completes_the_same_run(plan_csv, tmp_path):
    whole = PlanRun(plan_csv, tmp_path / "whole" / "positioning_x.csv", speed=SPEED).start()
    assert whole.wait(30) == "done"
    output = tmp_path / "positioning_x.csv"
    run = PlanRun(plan_csv, output, speed=SPEED).start()
    while len(run.stops) < 3:
        time.sleep(0.01)
    run.cut_connection()
    assert run.wait(10) == "broken"
    assert "connection to the instrument was lost" in run.message
    assert run.snapshot()["lights"]["instrument"] == "lost"
    kept = len(read_csv(partial_path(output)).numeric("step"))
    assert kept >= 3
    with pytest.raises(AxiscalError, match="resume it"):
        PlanRun(plan_csv, output, speed=SPEED)
    again = PlanRun(plan_csv, output, speed=SPEED, resume=True)
    assert len(again.stops) == kept
    assert again.start().wait(30) == "done", again.message
    assert [s["step"] for s in again.stops] == [s["step"] for s in whole.stops]
    # the same virtual machine and seed: the resumed run reads what the whole run read
    assert np.allclose([s["deviation_um"] for s in again.stops], [s["deviation_um"] for s in whole.stops], atol=0.05)


def test_abort_keeps_the_partial_file(plan_csv, tmp_path):
    output = tmp_path / "positioning_x.csv"
    run = PlanRun(plan_csv, output, speed=SPEED).start()
    while len(run.stops) < 1:
        time.sleep(0.01)
    run.abort()
    assert run.wait(10) == "aborted" and "kept" in run.message
    assert partial_path(output).is_file() and not output.exists()


def test_a_run_starts_once(plan_csv, tmp_path):
    run = PlanRun(plan_csv, tmp_path / "positioning_x.csv", speed=SPEED).start()
    with pytest.raises(AxiscalError, match="cannot start again"):
        run.start()
    run.abort()
    run.wait(10)


def test_a_dwell_too_short_for_the_stop_detector_stops_the_run_at_its_first_target(tmp_path):
    # 0.5 s: the capture's window with no time to settle; the program is 5 runs (about 80 s of the machine's clock)
    write_plan(plan_test(0.0, 0.15, 5, runs=5, overrun_m=0.005, seed=1), tmp_path / "plan_x.csv", dwell_s=0.5)
    output = tmp_path / "positioning_x.csv"
    run = PlanRun(tmp_path / "plan_x.csv", output, speed=200.0, dwell_s=0.5).start()
    assert run.wait(60) == "failed"
    assert run.message.startswith("step 2 (target 0.000 mm, run 1, +): no stop over its 0.5 s dwell: the reading did not"
                                  " hold within 1 µm for a whole 0.5 s window (the least dwell is 0.7 s)"), run.message
    assert "no stop was taken before it" in run.message
    last_s = run.samples_since(0)[0][-1]
    assert last_s < 5.0 < 70.0 < run._end_s  # stopped when it happened, not at the program's end
    assert run.snapshot()["sim_time_s"] < 5.0  # and the page shows the machine's clock stopped there
    assert not run.snapshot()["resumable"] and not partial_path(output).exists() and not output.exists()


def test_a_step_that_cannot_be_taken_stops_the_run_there_and_resume_completes_it(plan_csv, tmp_path):
    whole = PlanRun(plan_csv, tmp_path / "whole" / "positioning_x.csv", speed=SPEED).start()
    assert whole.wait(30) == "done"
    output = tmp_path / "positioning_x.csv"
    run = PlanRun(plan_csv, output, speed=SPEED)
    # the machine rings through its whole dwell at the 4th target (5 um at 30 Hz): that stop never holds still
    begin, leave = run._dwells[3, 0], run._dwells[3, 1]
    t = run.source._t
    during = (t >= begin) & (t <= leave)
    run.source._values[during, 0] += 0.005 * np.sin(2 * np.pi * 30.0 * t[during])
    assert run.start().wait(30) == "failed"
    assert run.message == ("step 5 (target 120.912 mm, run 1, +): no stop over its 1 s dwell: the reading did not hold"
                           " within 1 µm for a whole 0.5 s window (the machine did not settle: check the set-up, or"
                           " lengthen the dwell); the 3 stops taken before it are kept: resume to go on")
    assert run.samples_since(0)[0][-1] < run._dwells[4, 1]  # before the next target's dwell was over
    assert run.snapshot()["resumable"] and len(read_csv(partial_path(output)).numeric("step")) == 3
    again = PlanRun(plan_csv, output, speed=SPEED, resume=True)  # the ringing has stopped
    assert again.start().wait(30) == "done", again.message
    assert [s["step"] for s in again.stops] == [s["step"] for s in whole.stops]
    assert np.allclose([s["deviation_um"] for s in again.stops], [s["deviation_um"] for s in whole.stops], atol=0.05)
