"""End-to-end runs of `axiscal straightness`, `separate` and `simulate probes` on the shipped examples."""

from __future__ import annotations

import json

import numpy as np
import pandas as pd
import pytest

from axiscal.io.tabular import parse_csv
from axiscal.straightness.reference import reference_line


def table(text):
    return parse_csv(text.splitlines())


def test_straightness_json_matches_the_api(run_cli, examples):
    status, out, err = run_cli("straightness", examples / "straightness_profile.csv", "--json")
    assert status == 0, err
    result = json.loads(out)
    assert set(result) == {"straightness_um", "slope_urad", "intercept_um", "reference"}
    data = table((examples / "straightness_profile.csv").read_text())
    line = reference_line(data.numeric("position_mm") * 1e-3, data.numeric("deviation_um") * 1e-6)
    assert result["straightness_um"] == pytest.approx(line.straightness_m * 1e6)
    assert result["slope_urad"] == pytest.approx(line.slope * 1e6)
    assert result["reference"] == "least-squares"


def test_minimum_zone_is_narrowest_and_plot_is_written(run_cli, examples, tmp_path):
    widths = {}
    for reference in ("least-squares", "end-points", "minimum-zone"):
        status, out, _ = run_cli("straightness", examples / "straightness_profile.csv", "--reference", reference, "--json")
        assert status == 0
        widths[reference] = json.loads(out)["straightness_um"]
    assert widths["minimum-zone"] <= min(widths["least-squares"], widths["end-points"])
    plot = tmp_path / "zone.png"
    status, out, _ = run_cli("straightness", examples / "straightness_profile.csv", "--reference", "minimum-zone", "--plot", plot)
    assert status == 0 and "straightness" in out and plot.stat().st_size > 0


@pytest.mark.parametrize(
    ("method", "yaw"), [("stp", False), ("strp", True), ("gtp", False), ("frequency", True), ("combined", True)]
)
def test_separate_writes_the_output_columns(run_cli, examples, tmp_path, method, yaw):
    out_csv = tmp_path / f"{method}.csv"
    status, _, err = run_cli("separate", examples / "probe_readings.csv", "--method", method, "--spacing-mm", "15", "-o", out_csv)
    assert status == 0, err
    result = table(out_csv.read_text())
    expected = ["position_mm", "profile_um", "motion_um"] + (["yaw_urad"] if yaw else [])
    assert list(result.header) == expected
    profile = result.numeric("profile_um")
    assert np.ptp(profile) > 0.1  # the example's profile bows by about 1 um
    assert np.all(np.diff(result.numeric("position_mm")) > 0)


@pytest.mark.parametrize("method", ["strp", "combined"])
def test_separation_plot_with_yaw(run_cli, examples, tmp_path, method):
    plot = tmp_path / f"{method}.png"
    status, _, err = run_cli("separate", examples / "probe_readings.csv", "--method", method, "--spacing-mm", "15", "--plot", plot)
    assert status == 0, err
    assert plot.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"


def test_frequency_options_reach_the_method(run_cli, examples, tmp_path):
    out_csv = tmp_path / "bowed.csv"
    status, _, _ = run_cli("separate", examples / "probe_readings.csv", "--method", "frequency", "--spacing-mm", "15", "-o", out_csv)
    assert status == 0 and json.loads(out_csv.with_suffix(".json").read_text())["lost_wavelength_mm"]
    bowed = out_csv.read_text()
    status, periodic, _ = run_cli(
        "separate", examples / "probe_readings.csv", "--method", "frequency", "--spacing-mm", "15", "--periodic", "--two-probe"
    )
    assert status == 0 and "yaw_urad" not in periodic
    assert table(bowed).numeric("profile_um")[-1] != table(periodic).numeric("profile_um")[-1]


def test_combined_recovers_the_shipped_profile(run_cli, examples):
    status, out, _ = run_cli("separate", examples / "probe_readings.csv", "--spacing-mm", "15", "--calibration-mm", "0", "255")
    assert status == 0
    result = table(out)
    x = result.numeric("position_mm")
    truth = table((examples / "separation_profile.csv").read_text())
    r = np.interp(x, truth.numeric("position_mm"), truth.numeric("deviation_um"))
    error = result.numeric("profile_um") - r
    residual = reference_line(x, error).residuals(x, error)
    assert np.ptp(residual) < 0.2  # um: mostly the 0.005 um probe noise, summed twice as in STRP
    status, out, _ = run_cli("separate", examples / "probe_readings.csv", "--method", "strp", "--spacing-mm", "15")
    strp = table(out)
    xs = strp.numeric("position_mm")
    error = strp.numeric("profile_um") - np.interp(xs, truth.numeric("position_mm"), truth.numeric("deviation_um"))
    assert np.ptp(reference_line(xs, error).residuals(xs, error)) > 1.0  # the zero offsets, eq (10)


def test_what_separate_writes_is_a_straightness_input(run_cli, examples, tmp_path):
    separated = tmp_path / "separated.csv"
    status, _, err = run_cli("separate", examples / "probe_readings.csv", "--method", "strp", "--spacing-mm", "15", "-o", separated)
    assert status == 0, err
    frame = pd.read_csv(separated)
    assert list(frame.columns) == ["position_mm", "profile_um", "motion_um", "yaw_urad"]
    sidecar = json.loads(separated.with_suffix(".json").read_text())
    assert sidecar["kind"] == "separation" and sidecar["method"] == "strp"
    status, out, err = run_cli("straightness", separated, "--json")
    assert status == 0, err
    x, r = frame["position_mm"].to_numpy() * 1e-3, frame["profile_um"].to_numpy() * 1e-6
    assert json.loads(out)["straightness_um"] == pytest.approx(reference_line(x, r).straightness_m * 1e6)


def test_simulate_probes_writes_a_plain_csv_and_sidecar(run_cli, examples, tmp_path):
    readings = tmp_path / "readings.csv"
    status, _, err = run_cli(
        "simulate", "probes", "--profile", examples / "separation_profile.csv", "--motion", examples / "separation_motion.csv",
        "--spacing-mm", "15", "--step-mm", "1", "--probes", "2", "-o", readings,
    )
    assert status == 0, err
    assert list(pd.read_csv(readings).columns) == ["position_mm", "a_um", "b_um"]
    sidecar = json.loads(readings.with_suffix(".json").read_text())
    assert sidecar["kind"] == "probe readings" and sidecar["spacing_bc_mm"] is None


def test_simulate_then_separate_round_trip_with_fstrp(run_cli, examples, tmp_path):
    readings = tmp_path / "fstrp.csv"
    status, _, err = run_cli(
        "simulate", "probes", "--profile", examples / "separation_profile.csv", "--motion", examples / "separation_motion.csv",
        "--spacing-mm", "7", "--spacing-bc-mm", "4", "--step-mm", "1", "-o", readings,
    )
    assert status == 0, err
    status, out, err = run_cli(
        "separate", readings, "--method", "fstrp", "--spacing-mm", "7", "--spacing-bc-mm", "4", "--plot", tmp_path / "f.png"
    )
    assert status == 0, err
    assert (tmp_path / "f.png").exists()
    assert len(table(out)) == len(table(readings.read_text())) + 11  # every step, up to probe C's reach


def test_simulate_probes_matches_the_shipped_readings(run_cli, examples, same_text_to_precision):
    status, out, _ = run_cli(
        "simulate", "probes", "--profile", examples / "separation_profile.csv", "--motion", examples / "separation_motion.csv",
        "--spacing-mm", "15", "--step-mm", "1", "--noise-um", "0.005", "--offsets-um", "0", "0.05", "0.02",
    )
    assert status == 0
    same_text_to_precision((examples / "probe_readings.csv").read_text(), out, name="probe_readings.csv")


def test_two_probe_simulation_and_reversal(run_cli, examples, tmp_path):
    status, out, _ = run_cli(
        "simulate", "probes", "--profile", examples / "separation_profile.csv", "--motion", examples / "separation_motion.csv",
        "--spacing-mm", "15", "--step-mm", "1", "--probes", "2",
    )
    assert status == 0 and out.splitlines()[0] == "position_mm,a_um,b_um"
    normal = tmp_path / "normal.csv"
    turned = tmp_path / "turned.csv"
    normal.write_text("position_mm,a_um\n0,0.5\n10,1.0\n20,0.0\n")
    turned.write_text("position_mm,a_um\n0,1.5\n10,1.0\n20,2.0\n")
    status, out, err = run_cli("separate", normal, "--method", "reversal", "--reversed", turned)
    assert status == 0, err
    result = table(out)
    np.testing.assert_allclose(result.numeric("profile_um"), [1.0, 1.0, 1.0])
    np.testing.assert_allclose(result.numeric("motion_um"), [0.5, 0.0, 1.0])


def one_line_error(run_cli, *argv):
    status, out, err = run_cli(*argv)
    assert status == 2, (out, err)
    lines = err.strip().splitlines()
    assert len(lines) == 1 and "Traceback" not in err
    return lines[0]


def test_bad_input(run_cli, examples, tmp_path):
    two = tmp_path / "two.csv"
    two.write_text("position_mm,a_um,b_um\n0,0,0\n1,0.1,0.2\n2,0.2,0.1\n3,0.1,0.1\n")
    assert "c_um" in one_line_error(run_cli, "separate", two, "--method", "strp", "--spacing-mm", "1")
    assert "c_um" in one_line_error(run_cli, "separate", two, "--method", "combined", "--spacing-mm", "1")
    uneven = tmp_path / "uneven.csv"
    uneven.write_text("position_mm,a_um,b_um\n0,0,0\n1,0.1,0.2\n2.5,0.2,0.1\n3.5,0.1,0.1\n")
    assert "evenly stepped" in one_line_error(run_cli, "separate", uneven, "--method", "stp", "--spacing-mm", "1")
    assert "whole number of steps" in one_line_error(run_cli, "separate", two, "--method", "stp", "--spacing-mm", "1.5")
    assert "whole number of steps" in one_line_error(
        run_cli, "separate", examples / "probe_readings.csv", "--method", "strp", "--spacing-mm", "15.5"
    )
    assert "--spacing-mm" in one_line_error(run_cli, "separate", two, "--method", "stp")
    assert "--reversed" in one_line_error(run_cli, "separate", two, "--method", "reversal")
    assert "same positions" in one_line_error(run_cli, "separate", two, "--method", "reversal", "--reversed", uneven)
    missing = tmp_path / "missing.csv"
    missing.write_text("position_mm,a_um\n0,0\n1,0\n")
    assert "b_um" in one_line_error(run_cli, "separate", missing, "--method", "stp", "--spacing-mm", "1")
    short = tmp_path / "short.csv"
    short.write_text("position_mm,deviation_um\n0,0\n5,1\n")
    assert "too short" in one_line_error(
        run_cli, "simulate", "probes", "--profile", short, "--motion", short, "--spacing-mm", "15", "--step-mm", "1"
    )
    assert "probes reach" in one_line_error(
        run_cli, "simulate", "probes", "--profile", examples / "separation_profile.csv", "--motion", short,
        "--spacing-mm", "15", "--step-mm", "1",
    )
    flat = tmp_path / "flat.csv"
    flat.write_text("position_mm,deviation_um\n1,0\n1,1\n")
    assert "distinct positions" in one_line_error(run_cli, "straightness", flat)
    bad = tmp_path / "bad.csv"
    bad.write_text("position_mm,deviation_um\n0,0\n1,abc\n")
    assert "bad.csv:3" in one_line_error(run_cli, "straightness", bad)
    status, _, _ = run_cli("straightness", examples / "straightness_profile.csv", "--reference", "chebyshev")
    assert status == 2


@pytest.mark.parametrize(
    ("argv", "needle"),
    [
        (["--method", "stp", "--spacing-mm", "inf"], "--spacing-mm must be a finite number"),
        (["--method", "strp", "--spacing-mm", "15", "--spacing-bc-mm", "nan"], "--spacing-bc-mm must be a finite number"),
        (["--method", "frequency", "--spacing-mm", "1000"], "more readings than the probes span"),
        (["--method", "frequency", "--spacing-mm", "15", "--min-gain", "-1"], "--min-gain"),
        (["--method", "frequency", "--spacing-mm", "15", "--min-gain", "nan"], "--min-gain"),
        (["--method", "fstrp", "--spacing-mm", "1000", "--spacing-bc-mm", "1"], "families to meet"),
        (["--method", "combined", "--spacing-mm", "15", "--calibration-mm", "100", "50"], "START < END"),
        (["--method", "combined", "--spacing-mm", "300"], "two readings per group"),
    ],
)
def test_bad_separation_options(run_cli, examples, argv, needle):
    assert needle in one_line_error(run_cli, "separate", examples / "probe_readings.csv", *argv)


def test_uneven_positions_are_named_by_their_line(run_cli, tmp_path):
    repeated = tmp_path / "repeated.csv"
    repeated.write_text("# comment\nposition_mm,a_um,b_um\n0,0,0\n1,0.1,0.1\n1,0.2,0.1\n3,0.1,0.1\n")
    message = one_line_error(run_cli, "separate", repeated, "--method", "gtp", "--spacing-mm", "1")
    assert "repeated.csv:5:" in message and "evenly stepped" in message
    falling = tmp_path / "falling.csv"
    falling.write_text("position_mm,a_um,b_um\n3,0,0\n2,0.1,0.1\n1,0.2,0.1\n")
    assert "falling.csv:3:" in one_line_error(run_cli, "separate", falling, "--method", "stp", "--spacing-mm", "1")


@pytest.mark.parametrize(
    ("argv", "needle"),
    [
        (["--step-mm", "1", "--noise-um", "nan"], "--noise-um"),
        (["--step-mm", "1", "--noise-um", "-0.1"], "--noise-um"),
        (["--step-mm", "1", "--offsets-um", "nan", "0", "0"], "--offsets-um"),
        (["--step-mm", "-1"], "--step-mm must be a positive number"),
        (["--step-mm", "1e-9"], "at most"),
        (["--step-mm", "1", "--spacing-bc-mm", "inf"], "--spacing-bc-mm"),
    ],
)
def test_bad_simulation_options(run_cli, examples, argv, needle):
    line = one_line_error(
        run_cli, "simulate", "probes", "--profile", examples / "separation_profile.csv",
        "--motion", examples / "separation_motion.csv", "--spacing-mm", "15", *argv,
    )
    assert needle in line


@pytest.mark.parametrize(
    ("text", "needle"),
    [
        ("", "empty file"),
        ("position_mm,deviation_um\n", "at least 2"),
        ("position_mm,deviation_um\n0,1\n", "at least 2"),
        ("position_mm,deviation_um\n0,1\n1,nan\n", "p.csv:3: column 'deviation_um': nan is not a finite number"),
        ("position_mm,deviation_um\n0,1\n1,inf\n", "p.csv:3:"),
        ("position_mm,height_um\n0,1\n1,2\n", "p.csv:1: missing column deviation_um"),
        ("position_mm,deviation_um\n0,1\n1,2,3\n", "p.csv:3:"),
        ("position_mm,deviation_um\n0,1\n0,2\n1,3\n", "end-point line"),
    ],
)
def test_bad_profile_files(run_cli, tmp_path, text, needle):
    path = tmp_path / "p.csv"
    path.write_text(text)
    assert needle in one_line_error(run_cli, "straightness", path, "--reference", "end-points")
