"""``axiscal dynamics``, ``axiscal periodic``, ``axiscal on-the-fly`` and ``axiscal plan --step-cycle`` end to end."""

from __future__ import annotations

import json

import pandas as pd
import pytest


def test_dynamics_prints_json_and_draws(run_cli, examples, tmp_path):
    status, out, err = run_cli("dynamics", examples / "capture" / "recording_x.csv", "--plan", examples / "capture" / "plan_x.csv",
                               "--json", "--plot", tmp_path / "d.png")
    assert status == 0, err
    body = json.loads(out)
    assert body["differentiator"]["method"] == "Savitzky-Golay" and body["differentiator"]["bandwidth_hz"] > 0
    assert len(body["stops"]) == 10 and body["stops"][0]["step"] == 2
    assert body["peak_velocity_mm_s"] == pytest.approx(2000 / 60, rel=0.02)
    assert (tmp_path / "d.png").stat().st_size > 0


def test_dynamics_text_names_the_bandwidth(run_cli, examples):
    status, out, _ = run_cli("dynamics", examples / "capture" / "recording_x.csv")
    assert status == 0 and "bandwidth" in out and "settling to +/-1 um" in out and "step   arrival_s" in out


def test_periodic_of_the_step_cycle_example(run_cli, examples, tmp_path):
    # the example's screw error is 0.4 um sin(2 pi m / 5 mm) (examples/dynamics/make_examples.sh): 0.8 um peak to peak
    status, out, err = run_cli("periodic", examples / "dynamics" / "step_cycle_run.csv", "--json", "--plot", tmp_path / "p.svg")
    assert status == 0, err
    body = json.loads(out)
    assert body["period_mm"] == pytest.approx(5.0, rel=0.03)
    assert body["periodic_um"] == pytest.approx(0.8, abs=0.05)
    assert (tmp_path / "p.svg").exists()


def test_on_the_fly_writes_a_run_positioning_reads(run_cli, examples, tmp_path):
    out_csv = tmp_path / "run.csv"
    status, out, err = run_cli("on-the-fly", examples / "dynamics" / "fly_plan.csv", "--from", examples / "dynamics" / "fly_recording.csv",
                               "-o", out_csv, "--json", "--plot", tmp_path / "f.png")
    assert status == 0, err
    body = json.loads(out)
    assert body["delay_ms"] == pytest.approx(8.0, abs=0.01) and body["delay_estimated"]
    assert body["speed_mm_min"] == pytest.approx(1000.0, rel=1e-6)
    frame = pd.read_csv(out_csv)
    assert list(frame.columns[:4]) == ["target_mm", "run", "direction", "deviation_um"] and len(frame) == 10
    assert json.loads(out_csv.with_suffix(".json").read_text())["kind"] == "positioning run (captured on the fly)"
    assert run_cli("positioning", out_csv)[0] == 0


def test_on_the_fly_of_a_recording_without_position_is_one_line(run_cli, examples, tmp_path):
    status, out, err = run_cli("on-the-fly", examples / "capture" / "plan_x.csv", "--from", examples / "capture" / "recording_x.csv",
                               "-o", tmp_path / "r.csv")
    assert status == 2 and out == "" and "position_mm" in err and err.count("\n") == 1


def test_plan_step_cycle(run_cli, tmp_path):
    status, out, err = run_cli("plan", "--step-cycle", "--start-mm", 100, "--period-mm", 5, "--steps-per-period", 4,
                               "--gcode", tmp_path / "s.ngc")
    assert status == 0, err
    lines = out.splitlines()
    assert lines[1] == "1,1,-,,99.000," and lines[2] == "2,1,+,100.000,100.000," and lines[3] == "3,1,+,101.250,101.250,"
    assert "step cycle (Annexes B and C), 9 targets every 1.25 mm" in err and "seed" not in err


def test_plan_step_cycle_options_are_checked(run_cli):
    status, _, err = run_cli("plan", "--step-cycle", "--start-mm", 0, "--period-mm", 5, "--end-mm", 100)
    assert status == 2 and "--step-cycle plans from --start-mm and --period-mm" in err
    status, _, err = run_cli("plan", "--start-mm", 0, "--end-mm", 100)
    assert status == 2 and "needs --end-mm and --targets" in err
    status, _, err = run_cli("plan", "--step-cycle", "--start-mm", 0, "--period-mm", -5)
    assert status == 2 and "--period-mm" in err


def test_plan_on_the_fly_program_runs_past_the_last_target(run_cli, tmp_path):
    status, _, err = run_cli("plan", "--start-mm", 0, "--end-mm", 100, "--targets", 5, "--runs", 1, "--seed", 1,
                             "--gcode", tmp_path / "f.ngc", "--on-the-fly")
    assert status == 0, err
    program = (tmp_path / "f.ngc").read_text()
    moves = [line for line in program.splitlines() if line.startswith("G1")]
    assert "G4" not in program and moves[-2].startswith("G1 X0.000") and moves[-1].startswith("G1 X-5.000")
