"""End-to-end runs of `axiscal levels` on the shipped example."""

from __future__ import annotations

import json

import pytest


def test_json_carries_the_straightness_and_the_angular_error(run_cli, examples, tmp_path):
    out = tmp_path / "profile.csv"
    status, text, err = run_cli("levels", examples / "levels" / "levels_run.csv", "--foot-mm", "100", "--json", "-o", out)
    assert status == 0, err
    payload = json.loads(text)
    assert {"straightness_um", "slope_urad", "angular_error_urad", "angular_error_arcsec", "reference"} <= set(payload)
    status, text, err = run_cli("straightness", out, "--json")
    assert status == 0, err
    assert json.loads(text)["straightness_um"] == pytest.approx(payload["straightness_um"], abs=1e-5)


def test_text_report_and_plot(run_cli, examples, tmp_path):
    plot = tmp_path / "levels.png"
    status, text, err = run_cli("levels", examples / "levels" / "levels_run.csv", "--foot-mm", "100", "--plot", plot)
    assert status == 0, err
    assert "straightness" in text and "angular error" in text and plot.stat().st_size > 0


@pytest.mark.parametrize("foot", ["0", "-5", "nan"])
def test_a_bad_foot_spacing_is_one_line(run_cli, examples, foot):
    status, out, err = run_cli("levels", examples / "levels" / "levels_run.csv", "--foot-mm", foot)
    assert status == 2 and out == ""
    assert "--foot-mm" in err and len(err.strip().splitlines()) == 1


def test_a_bad_file_is_one_line_naming_file_and_line(run_cli, tmp_path):
    path = tmp_path / "run.csv"
    path.write_text("position_mm,angle_urad\n0,1\n100,oops\n")
    status, out, err = run_cli("levels", path, "--foot-mm", "100")
    assert status == 2
    assert f"{path}:3:" in err and len(err.strip().splitlines()) == 1
