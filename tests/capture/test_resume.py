"""Resume and the one-line refusals of a capture: what a partial file may hold, and which stops a resume takes."""

from __future__ import annotations

import numpy as np
import pytest

from axiscal.capture import capture, capture_to_file, partial_path, plan_steps
from axiscal.capture.recording import Recording
from axiscal.capture.sources import plan_motions
from axiscal.capture.steps import PlanSteps
from axiscal.capture.virtual import simulate_motions, write_recording
from axiscal.cli.main import main
from axiscal.errors import AxiscalError
from axiscal.model.machine import load_machine
from axiscal.positioning.plan import plan_test, write_plan
from axiscal.report.demo import builtin_example


@pytest.fixture(scope="module")
def case(tmp_path_factory):
    """A 1-run plan, its recording on the virtual machine, the run captured whole, and a partial of its first 4 stops."""
    folder = tmp_path_factory.mktemp("resume")
    plan = plan_test(0.0, 0.19, 5, runs=1, seed=2)
    write_plan(plan, folder / "plan.csv")
    machine = load_machine(builtin_example() / "machine.toml")
    simulated = simulate_motions(plan_motions(plan_steps(plan), dwell_s=1.2), machine, axis="X", rate_hz=200.0, seed=1)
    write_recording(simulated, folder / "rec.csv")
    whole = capture_to_file(folder / "plan.csv", folder / "rec.csv", folder / "whole.csv")
    rec = simulated.recording
    k = int(np.searchsorted(rec.time_s, simulated.dwells[3, 1] + 0.3))
    first = Recording(rec.time_s[:k], rec.reading_m[:k], {n: v[:k] for n, v in rec.channels.items()}, "first.csv")
    with pytest.raises(AxiscalError, match="the recording ends before it"):
        capture_to_file(folder / "plan.csv", first, folder / "part.csv")
    return {"folder": folder, "plan": folder / "plan.csv", "rec": folder / "rec.csv", "whole": whole,
            "partial": partial_path(folder / "part.csv").read_text(), "recording": rec, "cut": k}


def start(case, tmp_path, text=None):
    """A run to be resumed in tmp_path: its partial file holds ``text`` (default: the first 4 stops)."""
    out = tmp_path / "run.csv"
    partial_path(out).write_text(case["partial"] if text is None else text)
    return out


def test_resuming_with_the_same_whole_recording_skips_to_after_the_partial(case, tmp_path, capsys):
    # the recording is the one the partial was taken from, from its beginning: its first 4 stops are the partial's
    out = start(case, tmp_path)
    assert main(["capture", str(case["plan"]), "--from", str(case["rec"]), "-o", str(out), "--resume"]) == 0
    assert out.read_text() == case["whole"].run_csv.read_text()
    assert not partial_path(out).exists()


def test_resuming_with_the_same_recording_whose_axis_also_stops_at_the_overruns(tmp_path):
    # a program that dwells at the end of each overrun move too: those stops are the partial's as well
    plan = plan_test(0.0, 0.19, 5, runs=2, seed=6)
    steps = plan_steps(plan)
    motions = []
    for m in plan_motions(steps, dwell_s=1.0):
        motions.append(m)
        if m.kind == "feed" and not np.isfinite(steps.target_m[m.line - 1]):
            motions.append(type(m)(m.line, "dwell", m.end_m, None, 1.0))
    machine = load_machine(builtin_example() / "machine.toml")
    simulated = simulate_motions(motions, machine, axis="X", rate_hz=200.0, seed=3)
    rec = simulated.recording
    whole = capture(plan, rec)
    k = int(np.searchsorted(rec.time_s, simulated.dwells[6, 1] + 0.3))  # after a few targets and overruns
    first = Recording(rec.time_s[:k], rec.reading_m[:k], {n: v[:k] for n, v in rec.channels.items()}, "first.csv")
    out = tmp_path / "run.csv"
    with pytest.raises(AxiscalError, match="the recording ends before it"):
        capture_to_file(plan, first, out)
    resumed = capture_to_file(plan, rec, out, resume=True).capture
    assert [r.deviation_m for r in resumed.readings] == pytest.approx([r.deviation_m for r in whole.readings], abs=1e-11)


@pytest.mark.parametrize("shift_s", [0.0, None, 2.0])
def test_resuming_with_the_rest_whatever_its_clock(case, tmp_path, shift_s):
    # the rest of the run recorded on: its clock goes on (None), or starts again at 0 or at 2 s (a new
    # recording file, an .rtx capture): every stop of it is the run's
    rec, k = case["recording"], case["cut"]
    t = rec.time_s[k:] if shift_s is None else rec.time_s[k:] - rec.time_s[k] + shift_s
    rest = Recording(t, rec.reading_m[k:], {n: v[k:] for n, v in rec.channels.items()}, "rest.csv")
    out = start(case, tmp_path)
    files = capture_to_file(case["plan"], rest, out, resume=True)
    assert out.read_text() == case["whole"].run_csv.read_text()
    assert [r.start_s for r in files.capture.readings[4:]] == pytest.approx([s.start_s for s in case["whole"].capture.readings[4:]]
                                                                            if shift_s is None else
                                                                            [s.start_s - rec.time_s[k] + shift_s
                                                                             for s in case["whole"].capture.readings[4:]])


def test_a_partial_holding_only_its_header_is_resumed_or_started_afresh(case, tmp_path, capsys):
    header = case["partial"].splitlines()[0] + "\n"
    for text in (header, ""):  # killed between its header and its first stop, or before its header reached the disk
        for resume in (["--resume"], []):
            out = start(case, tmp_path, text)
            assert main(["capture", str(case["plan"]), "--from", str(case["rec"]), "-o", str(out), *resume]) == 0, (text, resume)
            assert out.read_text() == case["whole"].run_csv.read_text()
            assert not partial_path(out).exists()
    # a partial that holds a stop is kept: a new capture refuses to overwrite it
    out = start(case, tmp_path)
    capsys.readouterr()
    assert main(["capture", str(case["plan"]), "--from", str(case["rec"]), "-o", str(out)]) == 2
    assert "--resume continues the partial capture" in capsys.readouterr().err
    assert partial_path(out).read_text() == case["partial"]


def rows(text):
    lines = text.splitlines()
    return lines[0].split(","), [line.split(",") for line in lines[1:]]


def edited(text, column, change):
    header, cells = rows(text)
    k = header.index(column)
    for row in cells:
        row[k] = change(row[k])
    return "\n".join([",".join(header)] + [",".join(row) for row in cells]) + "\n"


@pytest.mark.parametrize("column, change, words", [
    ("target_mm", lambda v: f"{float(v) + 3:.6f}", r"step 2 has target 3 mm, not 0 mm"),
    ("direction", lambda v: "-", r"step 2 has direction '-', not '\+'"),
    ("run", lambda v: "2", r"step 2 has run 2, not 1"),
])
def test_a_partial_of_another_plan_is_refused_naming_its_row(case, tmp_path, capsys, column, change, words):
    # targets 3 mm off, every direction -, run 2 of a 1-run plan: the deviations belong to another plan
    text = edited(case["partial"], column, change)
    out = start(case, tmp_path, text)
    with pytest.raises(AxiscalError, match=words + r" in the plan .*plan.csv: this partial capture is not of that plan") as info:
        capture_to_file(case["plan"], case["rec"], out, resume=True)
    assert info.value.path == str(partial_path(out)) and info.value.line == 2  # the first row
    capsys.readouterr()
    assert main(["capture", str(case["plan"]), "--from", str(case["rec"]), "-o", str(out), "--resume"]) == 2
    err = capsys.readouterr().err.splitlines()
    assert len(err) == 1 and "run.csv.partial:2: step 2 has" in err[0]
    assert partial_path(out).read_text() == text and not out.exists()


def test_the_other_side_is_named_as_a_direction(case):
    # the plan's steps with every direction turned over: the axis came up to the first target, the step comes down
    steps = plan_steps(case["plan"])
    flipped = PlanSteps(steps.step, steps.run, np.where(steps.direction == "+", "-", "+"), steps.target_m, steps.move_to_m)
    with pytest.raises(AxiscalError) as info:
        capture(flipped, case["rec"])
    assert info.value.message.endswith(
        "-): the axis came to the target moving in the + direction (from below), not moving in the - direction (from above)")


@pytest.mark.parametrize("window", ["1e300", "1e9", "1000"])
def test_a_window_longer_than_the_recording_is_one_line(case, tmp_path, capsys, window):
    assert main(["capture", str(case["plan"]), "--from", str(case["rec"]), "-o", str(tmp_path / "r.csv"), "--window-s", window]) == 2
    err = capsys.readouterr().err.splitlines()
    if float(window) > 3600:  # beyond any window (an hour): refused as the flag's range
        assert len(err) == 1 and "--window-s" in err[0] and "3600" in err[0], err
    else:
        assert len(err) == 1 and f"rec.csv: --window-s {float(window):g} s is longer than the recording" in err[0]


def test_a_stream_with_a_window_beyond_any_count_of_samples_finds_no_stop():
    from axiscal.capture import StopDetector

    t = np.arange(0, 10, 0.01)
    detector = StopDetector(stability_m=1e-6, window_s=1e300)
    assert [detector.feed(t[k : k + 100], np.zeros(100)) for k in range(0, 1000, 100)] == [[]] * 10
    assert detector.finish() == [] and detector.samples == 1000


@pytest.mark.parametrize("program", ["G21 G90\nG1 Z10 F1000\nG4 P1\nG1 Z0\nM30\n", "G21 G90\nG4 P1\nM30\n",
                                     "G21 G90\nG1 X0 F1000\nG4 P1\nM30\n"])
def test_simulating_a_program_that_never_moves_the_axis_is_one_line(tmp_path, capsys, program):
    (tmp_path / "p.ngc").write_text(program)
    machine = str(builtin_example() / "machine.toml")
    assert main(["simulate", "capture", str(tmp_path / "p.ngc"), "--machine", machine, "--axis", "X",
                 "-o", str(tmp_path / "r.csv")]) == 2
    assert capsys.readouterr().err == f"axiscal: error: {tmp_path / 'p.ngc'}: the program never moves X\n"
