"""`axiscal ballbar` on the shipped example and on bad input; `simulate ballbar` through its command object."""

from __future__ import annotations

import json

import pandas as pd
import pytest
from click.testing import CliRunner

from axiscal.cli.ballbar import simulate_ballbar_command

EXAMPLE_ERRORS = {"squareness_urad": 25.0, "scale_mismatch_ppm": 20.0, "servo_mismatch_ms": 2.0}


def test_ballbar_json_reads_back_the_example_machine(run_cli, examples):
    status, out, err = run_cli("ballbar", examples / "ballbar" / "ballbar_run.csv", "--radius-mm", "100", "--plane", "XY",
                               "--feed-mm-min", "1000", "--json")
    assert status == 0 and err == ""
    body = json.loads(out)
    for key, value in EXAMPLE_ERRORS.items():
        assert body[key] == pytest.approx(value, rel=0.02)
    assert body["backlash_um"] == pytest.approx({"X": 4.0, "Y": 6.0}, rel=0.02)
    assert body["cyclic_error_um"]["X"] == pytest.approx(1.2, rel=0.02)
    assert body["centre_x_um"] == pytest.approx(8.0, abs=0.05) and body["centre_y_um"] == pytest.approx(-5.0, abs=0.05)
    assert body["G_ccw_um"] > 0 and body["H_um"] > 0 and body["F_max_um"] > body["F_min_um"]


def test_ballbar_text_and_plot(run_cli, examples, tmp_path):
    plot = tmp_path / "polar.png"
    status, out, err = run_cli("ballbar", examples / "ballbar" / "ballbar_run.csv", "--radius-mm", "100", "--plane", "xy",
                               "--plot", plot)
    assert status == 0 and err == ""
    assert "ISO 230-4 figures" in out and "servo mismatch" in out and "n/a" in out  # no feed: no servo mismatch
    assert plot.stat().st_size > 0


def test_one_direction_warns(run_cli, tmp_path):
    path = tmp_path / "ccw.csv"
    CliRunner().invoke(simulate_ballbar_command, ["--direction", "ccw", "--step-deg", "1", "-o", str(path)])
    status, out, err = run_cli("ballbar", path, "--radius-mm", "100", "--plane", "XY", "--json")
    assert status == 0 and "warning" in err and json.loads(out)["H_um"] is None


def test_bad_input_is_one_line(run_cli, tmp_path):
    status, _, err = run_cli("ballbar", tmp_path / "missing.csv", "--radius-mm", "100", "--plane", "XY")
    assert status == 2 and err.count("\n") == 1 and "missing.csv: file not found" in err
    bad = tmp_path / "bad.csv"
    bad.write_text("angle_deg,direction,radius_deviation_um\n0,sideways,1\n")
    status, _, err = run_cli("ballbar", bad, "--radius-mm", "100", "--plane", "XY")
    assert status == 2 and "bad.csv:2:" in err and err.count("\n") == 1
    status, _, err = run_cli("ballbar", bad, "--radius-mm", "100", "--plane", "XQ")
    assert status == 2 and "--plane" in err


def test_simulate_writes_a_plain_csv_and_its_sidecar(tmp_path):
    path = tmp_path / "sim.csv"
    result = CliRunner().invoke(simulate_ballbar_command, ["--plane", "YZ", "--backlash-um", "y=3", "--scale-ppm", "Z=-4",
                                                           "--step-deg", "0.5", "-o", str(path)])
    assert result.exit_code == 0, result.output
    frame = pd.read_csv(path)
    assert list(frame.columns) == ["angle_deg", "direction", "radius_deviation_um"] and len(frame) == 1440
    sidecar = json.loads(path.with_suffix(".json").read_text())
    assert sidecar["plane"] == "YZ" and sidecar["simulated"]["backlash_um"] == {"Y": 3.0}


def test_simulate_to_standard_output():
    result = CliRunner().invoke(simulate_ballbar_command, ["--step-deg", "1", "--direction", "cw"])
    assert result.exit_code == 0
    lines = result.output.splitlines()
    assert lines[0] == "angle_deg,direction,radius_deviation_um" and len(lines) == 361


@pytest.mark.parametrize("args, message", [(["--backlash-um", "X4"], "AXIS=UM|X=4"), (["--backlash-um", "Q=4"], "X=4"),
                                            (["--backlash-um", "Z=4"], "not in the plane")])
def test_simulate_refuses_bad_axes(args, message):
    result = CliRunner().invoke(simulate_ballbar_command, args)
    assert result.exit_code != 0
    text = result.output + (str(result.exception) if result.exception else "")
    assert any(m in text for m in message.split("|"))


def test_the_report_shown_in_the_docs_is_what_the_command_prints(run_cli, examples):
    import re
    from pathlib import Path

    docs = (Path(__file__).resolve().parents[2] / "docs" / "ballbar.md").read_text()
    shown = re.search(r"\$ (axiscal ballbar examples/\S+ [^\n]*)\n(.*?)\n```", docs, re.S)
    argv = shown.group(1).split()[1:]
    argv[1] = str(examples / "ballbar" / "ballbar_run.csv")
    status, out, _ = run_cli(*argv)
    assert status == 0
    assert out.rstrip("\n").replace(argv[1], "examples/ballbar/ballbar_run.csv") == shown.group(2)


@pytest.mark.parametrize("radius", ["1e300", "10001", "0", "-5", "inf"])
def test_a_radius_no_ballbar_has_is_one_line(run_cli, examples, radius):
    status, out, err = run_cli("ballbar", examples / "ballbar" / "ballbar_run.csv", "--radius-mm", radius, "--plane", "XY")
    assert status == 2 and "Traceback" not in err and len(err.strip().splitlines()) == 1, err
