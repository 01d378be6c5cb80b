"""The campaign kinds of paper 000's sensors: their calibration runs, and the diagonal they explain under load."""

from __future__ import annotations

import re
import shutil

import pytest

from axiscal.campaign import load_campaign, run_campaign
from axiscal.errors import AxiscalError

TESTS = '''
[[tests]]
id = "sensors"
kind = "sensor_calibration"
file = "sensor_calibration_runs.csv"
machine = "sensors_machine.toml"

[[tests]]
id = "loaded"
kind = "sixdof_diagonal"
file = "diagonal_2kg.csv"
frames = "sixdof_stops_2kg.csv"
machine = "sensors_machine.toml"
from = "X=0,Z=0"
to = "X=190,Z=190"
'''


@pytest.fixture
def folder(tmp_path, examples):
    """The example campaign holding only the two tests, with limits on the calibration residuals."""
    target = tmp_path / "campaign"
    shutil.copytree(examples / "campaign", target, ignore=shutil.ignore_patterns("report"))
    text = (target / "campaign.toml").read_text()
    text = text[: text.index("[[tests]]")] + TESTS.lstrip()
    text = re.sub(r"(?m)^calibration_arcsec = .*$", "calibration_arcsec = 0.25", text)
    assert "calibration_um = 1.0" in text and "calibration_arcsec = 0.25" in text
    (target / "campaign.toml").write_text(text)
    return target


def test_the_sensor_kinds_run_and_are_held_against_their_limits(folder):
    results = {t.id: t for t in run_campaign(folder).tests}
    sensors, loaded = results["sensors"], results["loaded"]
    assert [(c.tolerance_key, c.result) for c in sensors.checks] == [("calibration_um", "pass"), ("calibration_arcsec", "fail")]
    assert sensors.verdict == "fail" and sensors.figures["channels"] == 10
    assert round(loaded.figures["E_BD_max_um"], 1) == 56.4 and loaded.figures["E_AD_max_um"] < 1.0
    assert loaded.verdict == "not assessed" and loaded.checks == [] and len(loaded.plots) == 1
    assert loaded.files == ["diagonal_2kg.csv", "sixdof_stops_2kg.csv", "sensors_machine.toml"]


@pytest.mark.parametrize("old, new, key, words", [
    ('from = "X=0,Z=0"', 'from = "Y=0,Z=0"', "from", "XZ plane"),
    ('to = "X=190,Z=190"', 'to = "X=190;Z=190"', "to", "expected axis positions in mm"),
    ('frames = "sixdof_stops_2kg.csv"', 'frames = "no_such.csv"', "frames", "not found"),
    ('kind = "sixdof_diagonal"', 'kind = "sixdof_diagonal"\nwhere = 1', "where", "unknown key 'where'"),
])
def test_a_mistake_names_its_line(folder, old, new, key, words):
    path = folder / "campaign.toml"
    text = path.read_text().replace(old, new, 1)
    path.write_text(text)
    with pytest.raises(AxiscalError, match=words) as info:
        load_campaign(folder)
    assert re.match(rf"{key}\s*=", text.splitlines()[info.value.line - 1])


def test_a_sixdof_diagonal_test_needs_its_frames(folder):
    path = folder / "campaign.toml"
    path.write_text(path.read_text().replace('frames = "sixdof_stops_2kg.csv"\n', ""))
    with pytest.raises(AxiscalError, match="a sixdof_diagonal test needs 'frames'"):
        load_campaign(folder)
