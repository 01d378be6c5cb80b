"""Uncertainty in a campaign: U (k = 2) beside every figure the budget covers, and the decision rule
(simple acceptance, or guard-banded per ISO 14253-1) stated and applied."""

from __future__ import annotations

import json
import shutil
from pathlib import Path

import pytest

from axiscal.campaign import load_campaign, run_campaign
from axiscal.campaign.results import Check
from axiscal.errors import AxiscalError


@pytest.fixture
def campaign(tmp_path, examples):
    folder = tmp_path / "campaign"
    shutil.copytree(Path(__file__).parent / "data" / "vmc850", folder)
    shutil.copy(examples / "uncertainty_budget.toml", folder / "budget.toml")
    return folder


def _with(folder, block: str) -> None:
    """Add a table before [tolerances], or a top-level key at the top of the file (TOML puts a bare
    key into the table above it)."""
    text = (folder / "campaign.toml").read_text()
    if block.startswith("["):
        text = text.replace("[tolerances]", block + "\n\n[tolerances]", 1)
    else:
        text = block + "\n\n" + text
    (folder / "campaign.toml").write_text(text)


def test_u_equals_the_positioning_command_with_the_same_budget(campaign, run_cli):
    _with(campaign, 'uncertainty = "budget.toml"')
    results = run_campaign(campaign)
    positioning = results.tests[0]
    _, out, _ = run_cli("positioning", campaign / "positioning_x.csv", "--uncertainty", campaign / "budget.toml", "--json")
    single = json.loads(out)["uncertainty"]
    for figure in ("E", "R", "B", "A", "M"):
        assert positioning.uncertainty[figure] == pytest.approx(single[figure]["U"], rel=1e-12)
    assert all(c.U is not None and c.rule == "simple" for c in positioning.checks)
    assert results.decision_rule == "simple"


def test_guard_band_makes_figures_near_their_limit_inconclusive(campaign, run_cli):
    _with(campaign, '[uncertainty]\nbudget = "budget.toml"\ndecision_rule = "guard-band"')
    status, _, _ = run_cli("report", campaign)  # the campaign run once: its verdicts as results.json writes them
    assert status == 0
    written = json.loads((campaign / "report" / "results.json").read_text())
    by_id = {t["id"]: t for t in written["tests"]}
    # E = 13.43 um, U(E) = 6.87 um, limit 14 um: inside the limit but not by U
    assert by_id["positioning-X-1"]["verdict"] == "inconclusive"
    assert by_id["straightness-X-1"]["verdict"] == "pass"
    assert written["verdict"] == "fail"  # the squareness fails outright
    assert written["decision_rule"] == "guard-band"
    assert written["tests"][0]["uncertainty"]["k"] == 2
    html = (campaign / "report" / "report.html").read_text()
    assert "U (k=2)" in html and "ISO 14253-1" in html


@pytest.mark.parametrize(
    ("value", "U", "limit", "rule", "expected"),
    [
        (9.0, 0.5, 10.0, "guard-band", "pass"),
        (9.8, 0.5, 10.0, "guard-band", "inconclusive"),
        (10.4, 0.5, 10.0, "guard-band", "inconclusive"),
        (10.6, 0.5, 10.0, "guard-band", "fail"),
        (9.8, 0.5, 10.0, "simple", "pass"),
        (-10.2, 0.5, 10.0, "simple", "fail"),
        (float("nan"), 0.5, 10.0, "simple", "fail"),
    ],
)
def test_decision_rules(value, U, limit, rule, expected):
    assert Check("E", "E_um", value, limit, "um", U, rule).result == expected


@pytest.mark.parametrize(
    ("block", "words"),
    [
        ('[uncertainty]\nbudget = "budget.toml"\ndecision_rule = "lenient"', "decision_rule must be 'simple' or 'guard-band'"),
        ('uncertainty = "../budget.toml"', "leaves the campaign folder"),
        ('uncertainty = "nope.toml"', "not found"),
        ("uncertainty = 3", "budget file name or an [uncertainty] table"),
    ],
)
def test_a_bad_uncertainty_entry_names_its_line(campaign, block, words):
    _with(campaign, block)
    with pytest.raises(AxiscalError) as caught:
        load_campaign(campaign)
    assert words in caught.value.message and caught.value.line is not None
