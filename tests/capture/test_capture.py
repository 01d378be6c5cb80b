"""Capture against the truth of the virtual machine: every stop found, the right value, the one-line errors, resume."""

from __future__ import annotations

from dataclasses import replace

import numpy as np
import pytest

from axiscal.capture import capture, capture_run, capture_to_file, plan_steps, read_recording
from axiscal.capture.recording import Recording
from axiscal.capture.files import partial_path
from axiscal.capture.run import CaptureSettings
from axiscal.capture.sources import plan_motions
from axiscal.capture.virtual import VirtualAxis, simulate_motions, write_recording
from axiscal.cli.main import main
from axiscal.errors import AxiscalError
from axiscal.io.gcode import Motion
from axiscal.model.machine import load_machine
from axiscal.positioning.evaluation import iso230_2
from axiscal.positioning.plan import plan_test, write_plan
from axiscal.report.demo import builtin_example
from axiscal.units import MM, UM

WINDOW_S = 0.5


@pytest.fixture(scope="module")
def machine():
    return load_machine(builtin_example() / "machine.toml")


def small_plan(seed=1):
    return plan_test(0.0, 0.19, 5, runs=2, seed=seed)


def simulate(machine, plan, *, seed=0, motions=None, rate_hz=500.0, spec=None):
    motions = plan_motions(plan_steps(plan), dwell_s=1.2) if motions is None else motions
    return simulate_motions(motions, machine, axis="X", rate_hz=rate_hz, seed=seed, spec=spec)


def true_run(plan, simulated, captured):
    """The run made of the true stop means (noise-free reading over each dwell's last window), compensated as captured."""
    truth = simulated.true_stop_means(WINDOW_S)
    steps = plan_steps(plan)
    readings = [replace(r, deviation_m=float(truth[k] - steps.target_m[r.index])) for k, r in enumerate(captured.readings)]
    return replace(captured, readings=tuple(readings)).run


@pytest.mark.parametrize("seed", range(20))
def test_capture_finds_every_stop_and_its_true_value(machine, seed):
    # noise, ringing, creep and a slow air drift: every stop found, within 0.05 um of its true mean
    plan = small_plan(seed=seed + 1)
    simulated = simulate(machine, plan, seed=seed)
    captured = capture(plan, simulated.recording)
    assert len(captured.readings) == plan.readings == len(simulated.dwells)
    truth = simulated.true_stop_means(WINDOW_S)
    steps = captured.steps
    got = np.array([steps.target_m[r.index] + r.deviation_m for r in captured.readings])
    assert np.abs(got - truth).max() < 0.05 * UM
    # ISO 230-2 figures within 0.1 um of the true run's
    mine, true = iso230_2(captured.run).figures(), iso230_2(true_run(plan, simulated, captured)).figures()
    for name in ("A", "E", "R", "B", "M"):
        assert mine[name] == pytest.approx(true[name], abs=0.1 * UM), name


def test_the_run_is_the_axis_error_the_model_gives(machine):
    # no noise, no scatter, no air drift: the captured mean deviation is the model's error plus the reversal
    plan = small_plan()
    quiet = VirtualAxis(noise_m=0.0, repeatability_m=0.0, air_drift_c=0.0)
    run = capture_run(plan, simulate(machine, plan, spec=quiet).recording)
    positions = {"X": plan.targets, "Z": np.zeros_like(plan.targets)}
    error = machine.volumetric_error(positions)[:, 0]
    assert run.deviations_up[:, 0] == pytest.approx(error - 2e-6, abs=0.02 * UM)
    assert run.deviations_down[:, 0] == pytest.approx(error + 2e-6, abs=0.02 * UM)


def dwell_indices(motions):
    return [k for k, m in enumerate(motions) if m.kind == "dwell"]


def test_a_missing_stop_is_named(machine, tmp_path):
    plan = small_plan()
    motions = list(plan_motions(plan_steps(plan), dwell_s=1.2))
    del motions[dwell_indices(motions)[3]]  # the axis goes on without stopping at the 4th target
    recording = simulate(machine, plan, motions=motions).recording
    out = tmp_path / "run.csv"
    with pytest.raises(AxiscalError, match=r"step 5 \(target .* mm, run 1, \+\): no stop there: the axis went on"):
        capture_to_file(plan, recording, out)
    partial = partial_path(out).read_text().splitlines()
    assert len(partial) == 1 + 3 and not out.exists()


def test_an_extra_stop_is_named(machine):
    plan = small_plan()
    motions = list(plan_motions(plan_steps(plan), dwell_s=1.2))
    k = dwell_indices(motions)[2] + 1
    odd = Motion(0, "feed", {"X": 0.1234}, 2000 * MM / 60, 0.0)
    motions[k:k] = [odd, Motion(0, "dwell", {"X": 0.1234}, None, 1.2)]
    with pytest.raises(AxiscalError, match=r"step \d+ \(target .* mm, run 1, \+\): the axis stopped at 123\.4\d* mm"):
        capture(plan, simulate(machine, plan, motions=motions).recording)


def test_a_recording_cut_short_then_resumed_finishes_the_run(machine, tmp_path):
    plan = small_plan()
    simulated = simulate(machine, plan)
    rec = simulated.recording
    cut = int(np.searchsorted(rec.time_s, simulated.dwells[7, 1] + 0.3))  # just after the 8th stop
    first = Recording(rec.time_s[:cut], rec.reading_m[:cut], {k: v[:cut] for k, v in rec.channels.items()}, "first.csv")
    rest = Recording(rec.time_s[cut:], rec.reading_m[cut:], {k: v[cut:] for k, v in rec.channels.items()}, "rest.csv")
    out = tmp_path / "run.csv"
    with pytest.raises(AxiscalError, match=r"step \d+ \(target .* mm, run 1, -\): the recording ends before it \(8 of 20"):
        capture_to_file(plan, first, out)
    assert len(partial_path(out).read_text().splitlines()) == 1 + 8
    with pytest.raises(AxiscalError, match="resume=True"):
        capture_to_file(plan, rest, out)
    files = capture_to_file(plan, rest, out, resume=True)
    whole = capture_to_file(plan, rec, tmp_path / "whole.csv").capture
    assert not partial_path(out).exists()
    assert [r.deviation_m for r in files.capture.readings] == pytest.approx([r.deviation_m for r in whole.readings], abs=1e-11)
    assert out.read_text() == (tmp_path / "whole.csv").read_text()


def dwell_ends(simulated):
    """When the axis leaves each dwell (the last: it stays until the recording ends)."""
    return [*simulated.dwells[:-1, 1], simulated.recording.time_s[-1]]


def ringing_recording(machine, plan, rate_hz=200.0):
    """The plan run with a 10 Hz ringing and a 3 um creep after every arrival: the peak to peak over the
    window hovers at the stability and crosses it several times at every stop."""
    quiet = VirtualAxis(settle_m=0.0, creep_m=0.0, noise_m=0.0, repeatability_m=0.0, air_drift_c=0.0)
    simulated = simulate_motions(plan_motions(plan_steps(plan), dwell_s=6.0), machine, axis="X", rate_hz=rate_hz, spec=quiet)
    t, x = simulated.recording.time_s, simulated.recording.reading_m.copy()
    for (arrive, _, _), leave, direction in zip(simulated.dwells, dwell_ends(simulated), simulated.directions):
        on = (t >= arrive) & (t <= leave)
        d = t[on] - arrive
        x[on] += -(1 if direction == "+" else -1) * 3e-6 * np.exp(-d / 2.0) + 0.3e-6 * np.exp(-d / 10.0) * np.sin(2 * np.pi * 10 * d)
    return simulated, Recording(t, x, {}, "ringing.csv")


def test_a_ringing_axis_gives_one_stop_per_dwell(machine, tmp_path):
    from axiscal.capture import detect_stops

    plan = small_plan()
    simulated, recording = ringing_recording(machine, plan)
    stops = detect_stops(recording.time_s, recording.reading_m, stability_m=1e-6, window_s=WINDOW_S)
    assert len(stops) == 1 + len(simulated.dwells)  # the standing start, then one per dwell
    assert all(b.first_index > a.last_index for a, b in zip(stops, stops[1:]))
    captured = capture(plan, recording)
    t, x = recording.time_s, recording.reading_m
    settled = [x[(t >= leave - WINDOW_S) & (t <= leave)].mean() for leave in dwell_ends(simulated)]
    steps = captured.steps
    got = [steps.target_m[r.index] + r.deviation_m for r in captured.readings]
    assert got == pytest.approx(settled, abs=0.01 * UM)
    # the same through the command line
    write_plan(plan, tmp_path / "plan.csv")
    lines = [f"{a:.6f},{b / MM:.9f}" for a, b in zip(t, x)]
    (tmp_path / "ring.csv").write_text("time_s,reading_mm\n" + "\n".join(lines) + "\n")
    assert main(["capture", str(tmp_path / "plan.csv"), "--from", str(tmp_path / "ring.csv"), "--stability-um", "1",
                 "--window-s", str(WINDOW_S), "-o", str(tmp_path / "run.csv")]) == 0


def test_capture_refuses_settings_out_of_range():
    with pytest.raises(AxiscalError, match="tolerance_m"):
        CaptureSettings(tolerance_m=-1.0)


def test_the_command_line_cycle_and_its_one_line_error(machine, tmp_path, capsys):
    plan = small_plan()
    write_plan(plan, tmp_path / "plan.csv")
    simulated = simulate(machine, plan)
    write_recording(simulated, tmp_path / "rec.csv")
    assert main(["capture", str(tmp_path / "plan.csv"), "--from", str(tmp_path / "rec.csv"), "-o", str(tmp_path / "run.csv")]) == 0
    assert main(["positioning", str(tmp_path / "run.csv"), "--json"]) == 0
    rec = read_recording(tmp_path / "rec.csv")
    assert rec.time_s.size == simulated.recording.time_s.size
    # cut the recording: one line, naming the file, the step, its target, run and direction; exit 2
    lines = (tmp_path / "rec.csv").read_text().splitlines()
    (tmp_path / "cut.csv").write_text("\n".join(lines[: len(lines) // 2]) + "\n")
    capsys.readouterr()
    assert main(["capture", str(tmp_path / "plan.csv"), "--from", str(tmp_path / "cut.csv"), "-o", str(tmp_path / "r2.csv")]) == 2
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 1 and "cut.csv" in err[0] and "the recording ends before it" in err[0] and "run " in err[0]
    assert main(["capture", str(tmp_path / "plan.csv"), "--from", str(tmp_path / "rec.csv"), "-o", str(tmp_path / "r2.csv"), "--resume"]) == 0


@pytest.mark.parametrize("trailer", [b"\r\nEOF::", b"EOF::\r\n"])
def test_the_same_recording_as_rtx_captures_to_the_same_run(machine, tmp_path, trailer):
    # an .rtx capture holds the reading alone, at a fixed rate: the run is that of the CSV without the air columns
    from axiscal.io.importers.rtx import write_rtx

    plan = small_plan()
    simulated = simulate(machine, plan)
    rec = simulated.recording
    write_rtx(tmp_path / "rec.rtx", rec.reading_m / MM, sample_rate_hz=500.0, unit="mm", trailer=trailer,
              header={"Owner": "CARTO-Dynamic", "Version no": "4.13.9237.28405", "Date": "10/02/2025 12:58:22",
                      "Flags": "0 1 2 0 2", "Machine": ""})
    from_rtx = capture_to_file(plan, tmp_path / "rec.rtx", tmp_path / "run.csv", unit="mm").capture
    bare = Recording(rec.time_s, rec.reading_m, {}, "rec.csv")
    from_csv = capture(plan, bare)
    assert [r.deviation_m for r in from_rtx.readings] == pytest.approx([r.deviation_m for r in from_csv.readings], abs=1e-12)
    # the capture's header travels into the run's sidecar
    import json

    header = json.loads((tmp_path / "run.json").read_text())["recording_header"]
    assert header["Owner"] == "CARTO-Dynamic" and header["Machine"] == ""
