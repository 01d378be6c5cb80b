"""Campaign kinds that need the machine model (diagonal) or raw frames (sixdof), and the volumetric
section: the numbers equal what the single commands print."""

from __future__ import annotations

import json
import shutil
from importlib import resources
from pathlib import Path

import pytest

from axiscal.campaign import run_campaign

XZ = Path(str(resources.files("axiscal") / "data" / "xz_module"))

CAMPAIGN = """\
[campaign]
title = "XZ module"
date = 2026-11-20
operator = "A. Technician"

[machine]
name = "XZ linear module"
model = "machine.toml"

[tolerances]
diagonal_um = 50.0

[[tests]]
kind = "diagonal"
from = "X=0,Z=0"
to = "X=190,Z=190"
interferometer = "diagonal_laser.csv"

[[tests]]
kind = "sixdof"
file = "sensors_frames.csv"
"""


@pytest.fixture
def campaign(tmp_path):
    for name in ("machine.toml", "x_errors.csv", "z_errors.csv", "diagonal_laser.csv", "sensors_frames.csv"):
        shutil.copy(XZ / name, tmp_path / name)
    (tmp_path / "campaign.toml").write_text(CAMPAIGN)
    return tmp_path


def test_diagonal_and_sixdof_equal_their_commands(campaign, run_cli):
    results = run_campaign(campaign)
    diagonal, sixdof = results.tests
    _, out, _ = run_cli("diagonal", "--machine", campaign / "machine.toml", "--from", "X=0,Z=0", "--to", "X=190,Z=190",
                        "--interferometer", campaign / "diagonal_laser.csv", "--json")
    single = json.loads(out)
    for key in ("model_error_range_um", "E_BD_range_um", "E_AD_range_um"):
        assert diagonal.figures[key] == pytest.approx(single[key], rel=1e-12)
    assert diagonal.verdict == "fail"  # E_BD 56.4 um against 50 um
    _, out, _ = run_cli("measure", campaign / "sensors_frames.csv", "--json")
    single = json.loads(out)
    assert sixdof.figures["faults"] == single.pop("faults")
    assert {k: v for k, v in sixdof.figures.items() if k != "faults"} == pytest.approx(single)
    assert sixdof.verdict == "not assessed"


def test_the_volumetric_section_comes_from_the_model(campaign, run_cli):
    results = run_campaign(campaign)
    assert results.model["figures"]["max_um"] == pytest.approx(84.33, abs=0.01)  # the demo's 84.33 um at X = Z = 190 mm
    assert results.model["figures"]["max_at_mm"] == {"X": 190.0, "Z": 190.0}
    status, _, _ = run_cli("report", campaign)
    assert status == 0
    written = json.loads((campaign / "report" / "results.json").read_text())
    assert written["volumetric"]["max_um"] == pytest.approx(84.33, abs=0.01)
    html = (campaign / "report" / "report.html").read_text()
    assert 'id="volumetric"' in html and "X / mm" in html and "Z / mm" in html
