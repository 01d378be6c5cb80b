"""Campaign kinds levels, flatness, thermal_etve and thermal_drift: the figures equal what the single
commands print, tolerances give the verdict, the report has their sections and results.json their
entries; a bad option names campaign.toml and the test's line."""

from __future__ import annotations

import json
import shutil

import pytest

from axiscal.campaign import run_campaign
from axiscal.errors import AxiscalError
from axiscal.report import report_campaign

CAMPAIGN = """\
[campaign]
title = "Acceptance, thermal and flatness"
date = 2026-11-25
operator = "A. Technician"

[machine]
name = "VMC 1200"

[tolerances]
straightness_um = 5.0
flatness_um = 5.0
etve_um = 5.0
thermal_drift_um = 10.0

[[tests]]
kind = "levels"
axis = "X"
direction = "Z"
file = "levels_run.csv"
foot_mm = 100

[[tests]]
kind = "flatness"
file = "union_jack_levels.toml"

[[tests]]
kind = "thermal_etve"
file = "etve_run.csv"
max_lag_h = 3

[[tests]]
kind = "thermal_drift"
file = "drift_run.csv"
"""


@pytest.fixture
def campaign(tmp_path, examples):
    for name in ("levels/levels_run.csv", "flatness/union_jack_levels.toml", "thermal/etve_run.csv", "thermal/drift_run.csv"):
        shutil.copy(examples / name, tmp_path / name.split("/")[1])
    (tmp_path / "campaign.toml").write_text(CAMPAIGN)
    return tmp_path


def command_json(run_cli, *argv):
    status, out, err = run_cli(*argv, "--json")
    assert status == 0, err
    return json.loads(out)


def test_figures_equal_the_commands_and_the_verdicts_follow(campaign, run_cli):
    results = run_campaign(campaign)
    levels, flatness, etve, drift = results.tests
    assert levels.figures == command_json(run_cli, "levels", campaign / "levels_run.csv", "--foot-mm", "100")
    assert flatness.figures == command_json(run_cli, "flatness", campaign / "union_jack_levels.toml")
    assert etve.figures == command_json(run_cli, "thermal", "etve", campaign / "etve_run.csv", "--max-lag-h", "3")
    assert drift.figures == command_json(run_cli, "thermal", "drift", campaign / "drift_run.csv")
    assert levels.verdict == "pass" and flatness.verdict == "pass"  # 3.2 um and 4.0 um against 5 um
    assert etve.verdict == "fail"                                   # Z: 6.3 um against 5 um
    assert drift.verdict == "fail"                                  # Z: -11.8 um against 10 um
    assert etve.checks[0].value == pytest.approx(max(etve.figures["etve_um"].values()))
    assert drift.checks[0].value == pytest.approx(11.78, abs=0.01)
    assert results.verdict == "fail"
    assert all(test.plots and test.plots[0].svg.startswith("<svg") for test in results.tests)


def test_the_report_has_their_sections_and_results_json_their_entries(campaign, tmp_path):
    files = report_campaign(campaign, tmp_path / "report")
    html = files.html.read_text(encoding="utf-8")
    for anchor, title in (("axis-X", "X axis"), ("flatness", "Flatness"), ("thermal", "Thermal tests (ISO 230-3)")):
        assert f'id="{anchor}"' in html and title in html
    assert "ISO 230-3 environmental temperature variation error" in html and "Moody" not in html
    data = json.loads(files.results.read_text())
    kinds = {test["kind"]: test for test in data["tests"]}
    assert set(kinds) == {"levels", "flatness", "thermal_etve", "thermal_drift"}
    assert kinds["flatness"]["figures"]["flatness_um"] == pytest.approx(4.0, abs=0.05)
    assert set(kinds["thermal_etve"]["figures"]["etve_um"]) == {"X", "Y", "Z"}
    assert kinds["thermal_drift"]["figures"]["heating_phases"] == 2


@pytest.mark.parametrize(("old", "new", "words", "line"), [
    ("foot_mm = 100", "foot_mm = -100", "foot_mm must be a positive number", 20),  # the key's line, not [[tests]]'s
    ('file = "union_jack_levels.toml"', 'file = "union_jack_levels.toml"\nevaluation = "best"', "evaluation", 25),
    ("max_lag_h = 3", "max_lag_h = -3", "max_lag_h must be a non-negative number", 29),
    ('kind = "thermal_drift"\n', 'kind = "thermal_drift"\nfoot_mm = 3\n', "unknown key 'foot_mm'", 33),
])
def test_bad_options_name_campaign_toml_and_the_line(campaign, old, new, words, line):
    toml = campaign / "campaign.toml"
    toml.write_text(CAMPAIGN.replace(old, new))
    with pytest.raises(AxiscalError) as caught:
        run_campaign(campaign)
    assert words in caught.value.message and caught.value.path == str(toml)
    assert caught.value.line == line


def test_a_levels_test_needs_its_foot_spacing(campaign):
    (campaign / "campaign.toml").write_text(CAMPAIGN.replace("foot_mm = 100\n", ""))
    with pytest.raises(AxiscalError, match="needs 'foot_mm'"):
        run_campaign(campaign)
