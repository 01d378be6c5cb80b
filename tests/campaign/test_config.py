"""campaign.toml: every mistake is one error naming campaign.toml and its line; nothing is run."""

from __future__ import annotations

import shutil
from pathlib import Path

import pytest

from axiscal.campaign import load_campaign
from axiscal.errors import AxiscalError

GOOD = """\
[campaign]
title = "Acceptance"
date = 2026-11-20
operator = "A. Technician"

[machine]
name = "VMC 850"
controller = "linuxcnc"

[tolerances]
positioning = { A_um = 12.0, E_um = 8.0 }
straightness_um = 5.0

[[tests]]
kind = "positioning"
axis = "X"
file = "run.csv"
tolerances = { A_um = 10.0 }

[[tests]]
kind = "straightness"
axis = "X"
direction = "Y"
file = "profile.csv"
"""


@pytest.fixture
def folder(tmp_path, examples):
    shutil.copy(examples / "positioning_run.csv", tmp_path / "run.csv")
    shutil.copy(examples / "straightness_profile.csv", tmp_path / "profile.csv")
    (tmp_path / "campaign.toml").write_text(GOOD)
    return tmp_path


def test_a_good_campaign_reads(folder):
    campaign = load_campaign(folder)
    assert [t.id for t in campaign.tests] == ["positioning-X-1", "straightness-X-1"]
    assert campaign.campaign["date"] == "2026-11-20"
    assert campaign.controller == "linuxcnc"
    positioning, straightness = campaign.tests
    assert positioning.tolerances == {"A_um": 10.0, "E_um": 8.0}  # the test's own overrides the campaign's
    assert straightness.tolerances == {"straightness_um": 5.0}
    assert positioning.options["file"] == (folder / "run.csv").resolve()
    assert straightness.options["direction"] == "Y"


def _error(folder: Path, old: str, new: str) -> AxiscalError:
    (folder / "campaign.toml").write_text(GOOD.replace(old, new, 1))
    with pytest.raises(AxiscalError) as caught:
        load_campaign(folder)
    return caught.value


@pytest.mark.parametrize(
    ("old", "new", "line", "words"),
    [
        ('operator = "A. Technician"', 'operator = "A. Technician"\nshoe_size = 44', 5, "unknown key 'shoe_size'"),
        ('file = "run.csv"', 'file = "missing.csv"', 17, "not found"),
        ('file = "run.csv"', 'file = "../run.csv"', 17, "leaves the campaign folder"),
        ('file = "run.csv"', 'file = "/etc/passwd"', 17, "absolute path"),
        ('file = "run.csv"', "file = 3", 17, "must be a file name"),
        ('kind = "positioning"', 'kind = "telepathy"', 15, "unknown kind"),
        ('axis = "X"\nfile = "run.csv"', 'axis = "X"\nfile = "run.csv"\nmethod = "stp"', 18, "unknown key 'method'"),
        ('date = 2026-11-20', 'date = "yesterday"', 3, "must be a date"),
        ('controller = "linuxcnc"', 'controller = "abacus"', 8, "controller"),
        ("A_um = 12.0, E_um", "A_um = -1.0, E_um", 11, "positive number"),
        ("A_um = 12.0, E_um", 'A_um = "12", E_um', 11, "positive number"),
        ("straightness_um = 5.0", "roundness_um = 5.0", 12, "unknown key 'roundness_um' in [tolerances]"),
        ('title = "Acceptance"', 'title = "Acceptance', 2, "malformed TOML"),
        ('kind = "straightness"\naxis = "X"', 'kind = "straightness"\naxis = "Q"', 22, "axis letter"),
    ],
)
def test_each_mistake_names_the_line(folder, old, new, line, words):
    error = _error(folder, old, new)
    assert error.path is not None and error.path.endswith("campaign.toml")
    assert error.line == line, str(error)
    assert words in error.message


def test_a_kind_without_its_data_is_an_error(folder):
    error = _error(folder, 'file = "profile.csv"\n', "")
    assert "needs 'file'" in error.message and error.line == 20  # the test's [[tests]] line


def test_a_diagonal_test_needs_the_model(folder):
    text = GOOD + '\n[[tests]]\nkind = "diagonal"\nfrom = "X=0"\nto = "X=100"\n'
    (folder / "campaign.toml").write_text(text)
    with pytest.raises(AxiscalError, match="machine model"):
        load_campaign(folder)


def test_a_missing_folder_is_an_error(tmp_path):
    with pytest.raises(AxiscalError, match="no such campaign folder|not found"):
        load_campaign(tmp_path / "nowhere")
