"""The head of the report states every field of [campaign], [machine] and [instrument] the schema accepts."""

from __future__ import annotations

import datetime as dt
import re
import shutil

import pytest

from axiscal.campaign import load_campaign
from axiscal.campaign.config import TABLE_KEYS
from axiscal.campaign.results import CampaignResults
from axiscal.report.html import render_html, report_facts


def toml_value(table: str, key: str, kind: type, index: int):
    """A distinct value of the key's type, as TOML text and as the report shows it."""
    if kind is dt.date:
        day = dt.date(2030, 1, 1) + dt.timedelta(days=index)
        return day.isoformat(), day.isoformat()
    if kind is float:
        number = 600.0 + index + 0.125
        return repr(number), repr(number)
    if (table, key) == ("machine", "model"):
        return '"machine.toml"', "machine.toml"
    if (table, key) == ("machine", "controller"):
        return '"fanuc"', "fanuc"
    if (table, key) == ("machine", "compensation"):
        return '{ X = "X.comp" }', "X X.comp"
    return f'"value of {table} {key}"', f"value of {table} {key}"


@pytest.fixture
def everything(tmp_path, examples, run_cli):
    """The example campaign with every field of the three tables stated."""
    folder = tmp_path / "campaign"
    shutil.copytree(examples / "campaign", folder, ignore=shutil.ignore_patterns("report"))
    status, _, err = run_cli("compensate", folder / "positioning_x.csv", "--format", "fanuc", "-o", folder / "X.comp")
    assert status == 0, err
    text = (folder / "campaign.toml").read_text()
    shown = {}
    index = 0
    for table, keys in TABLE_KEYS.items():
        lines = [f"[{table}]"]
        for key, (kind, _) in keys.items():
            written, shown[(table, key)] = toml_value(table, key, kind, index)
            lines.append(f"{key} = {written}")
            index += 1
        text = re.sub(rf"(?ms)^\[{table}\]\n.*?(?=^\[)", "\n".join(lines) + "\n\n", text, count=1)
    (folder / "campaign.toml").write_text(text)
    campaign = load_campaign(folder)
    return CampaignResults(campaign.campaign, campaign.machine, campaign.instrument, []), shown


def test_every_stated_field_is_printed(everything):
    results, shown = everything
    facts = "\n".join(f"{label}: {text}" for label, text in report_facts(results))
    html = render_html(results, generated="2030-01-01 00:00 UTC")
    for (table, key), value in shown.items():
        if (table, key) != ("campaign", "title"):  # the title heads the page
            assert value in facts, (table, key)
        assert value in html, (table, key)


def test_the_wavelength_has_its_line(everything):
    results, shown = everything
    assert ("Vacuum wavelength", f"{shown[('instrument', 'vacuum_wavelength_nm')]} nm") in report_facts(results)
    html = render_html(results, generated="2030-01-01 00:00 UTC")
    assert f"<th>Vacuum wavelength</th><td>{shown[('instrument', 'vacuum_wavelength_nm')]} nm</td>" in html


def test_the_example_campaign_states_its_wavelength(examples):
    campaign = load_campaign(examples / "campaign")
    facts = dict(report_facts(CampaignResults(campaign.campaign, campaign.machine, campaign.instrument, [])))
    assert facts["Vacuum wavelength"] == "632.99137 nm" and facts["Machine model"] == "machine.toml"
    assert facts["Instrument"].startswith("Laser interferometer") and "serial virtual" in facts["Instrument"]


def test_an_unstated_instrument_says_so():
    facts = report_facts(CampaignResults({"title": "t", "date": "2030-01-01", "operator": "o"}, {"name": "m"}, {}, []))
    assert facts == [("Machine", "m"), ("Date", "2030-01-01"), ("Operator", "o"), ("Instrument", "not stated")]
