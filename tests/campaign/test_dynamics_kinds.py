"""Campaign kinds dynamics, periodic and on_the_fly: the figures equal what the single commands print, tolerances
give the verdict, the report has their section and results.json their entries; a bad option names campaign.toml."""

from __future__ import annotations

import json
import shutil

import pytest

from axiscal.campaign import run_campaign
from axiscal.errors import AxiscalError
from axiscal.report import report_campaign

CAMPAIGN = """\
[campaign]
title = "Dynamics, screw and on the fly"
date = 2026-11-26
operator = "A. Technician"

[machine]
name = "XZ module"

[tolerances]
settling_s = 0.2
overshoot_um = 1.0
periodic_um = 1.0
positioning = { E_um = 30.0 }

[[tests]]
kind = "dynamics"
axis = "X"
file = "recording_x.csv"
plan = "plan_x.csv"

[[tests]]
kind = "periodic"
axis = "X"
file = "step_cycle_run.csv"
period_mm = 5.0

[[tests]]
kind = "on_the_fly"
axis = "X"
file = "fly_recording.csv"
plan = "fly_plan.csv"
"""


@pytest.fixture
def campaign(tmp_path, examples):
    for name in ("capture/recording_x.csv", "capture/plan_x.csv", "dynamics/step_cycle_run.csv", "dynamics/fly_recording.csv",
                 "dynamics/fly_plan.csv"):
        shutil.copy(examples / name, tmp_path / name.split("/")[1])
    (tmp_path / "campaign.toml").write_text(CAMPAIGN)
    return tmp_path


def command_json(run_cli, *argv):
    status, out, err = run_cli(*argv, "--json")
    assert status == 0, err
    return json.loads(out)


def test_figures_equal_the_commands_and_the_verdicts_follow(campaign, run_cli, tmp_path):
    results = run_campaign(campaign)
    dynamics, periodic, fly = results.tests
    assert dynamics.figures == command_json(run_cli, "dynamics", campaign / "recording_x.csv", "--plan", campaign / "plan_x.csv")
    assert periodic.figures == command_json(run_cli, "periodic", campaign / "step_cycle_run.csv", "--period-mm", "5")
    printed = command_json(run_cli, "on-the-fly", campaign / "fly_plan.csv", "--from", campaign / "fly_recording.csv",
                           "-o", tmp_path / "run.csv")
    assert fly.figures["delay_ms"] == pytest.approx(printed["delay_ms"]) == pytest.approx(8.0, abs=0.01)
    checks = {c.tolerance_key: c for c in dynamics.checks}
    assert checks["settling_s"].passed                       # 0.04 s against 0.2 s
    assert not checks["overshoot_um"].passed                 # 1.4 um against 1 um
    assert dynamics.verdict == "fail"
    assert periodic.verdict == "pass" and periodic.checks[0].value == pytest.approx(0.815, abs=0.01)  # 0.8 um made
    assert fly.verdict == "pass" and [c.tolerance_key for c in fly.checks] == ["E_um"]
    assert all(test.plots and test.plots[0].svg.startswith("<svg") for test in results.tests)


def test_the_report_has_their_section_and_results_json_their_entries(campaign, tmp_path):
    files = report_campaign(campaign, tmp_path / "report")
    html = files.html.read_text(encoding="utf-8")
    assert 'id="dynamics"' in html and "Dynamics, periodic errors and on-the-fly positioning" in html
    assert "Savitzky-Golay" in html and "ISO 230-2 Annexes B and C" in html
    data = json.loads(files.results.read_text())
    kinds = {test["kind"]: test for test in data["tests"]}
    assert set(kinds) == {"dynamics", "periodic", "on_the_fly"}
    assert kinds["periodic"]["figures"]["period_mm"] == 5.0


@pytest.mark.parametrize(("old", "new", "words", "line"), [
    ("period_mm = 5.0", "period_mm = -5.0", "period_mm must be a positive number of millimetres, not -5", 25),
    ("period_mm = 5.0", "period_mm = 500.0", "period_mm (500 mm) must lie between", None),
    ('plan = "fly_plan.csv"\n', "", "needs 'plan'", 27),
    ('plan = "plan_x.csv"\n', 'plan = "plan_x.csv"\nband_um = 0\n', "band_um must be a positive number of micrometres, not 0", 20),
    ('plan = "plan_x.csv"\n', 'plan = "plan_x.csv"\nchannel = "deviation_um"\nwindow_ms = -20\n',
     "window_ms must be a positive number of milliseconds, not -20", 21),
    ('plan = "fly_plan.csv"\n', 'plan = "fly_plan.csv"\ndelay_ms = 1e6\n', "delay_ms must be -10000 to 10000 milliseconds, not 1e+06", 32),
])
def test_bad_options_name_the_files_key_and_its_line(campaign, old, new, words, line):
    # the file's keys in the file's units, at the key's own line (not the library's window_s, band_m,
    # delay_s, period_m, nor the [[tests]] header's line)
    toml = campaign / "campaign.toml"
    toml.write_text(CAMPAIGN.replace(old, new))
    with pytest.raises(AxiscalError) as caught:
        run_campaign(campaign)
    assert words in caught.value.message, caught.value.message
    # an option refused against the data names the data file (the period against the run's targets)
    assert caught.value.path == str(toml if line is not None else campaign / "step_cycle_run.csv")
    assert not any(name in caught.value.message.replace(key, "") for name, key in
                   [("window_s", "window_ms"), ("band_m", "band_um"), ("delay_s", "delay_ms"), ("period_m", "period_mm")])
    assert caught.value.line == line
