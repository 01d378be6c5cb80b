"""One sign for one squareness figure: the verdict table, the section and the plot agree (docs/conventions.md)."""

from __future__ import annotations

import shutil

import pytest

from axiscal.campaign import load_campaign, run_campaign
from axiscal.report.html import verdict_rows
from axiscal.squareness import squareness_name

CAMPAIGN = """\
[campaign]
title = "squareness only"
date = 2026-11-20
operator = "test"

[machine]
name = "XZ module"

[tolerances]
squareness_arcsec = 20.0

[[tests]]
kind = "squareness"
axes = "XZ"
first = "square_x.csv"
second = "square_z.csv"
prism_deviation_arcsec = 2.50
convention = "{convention}"
"""


@pytest.mark.parametrize(("convention", "name", "value"), [
    ("iso", "EB0Z (ISO 230-1)", "-42.404"),
    ("included-angle", "XZ included angle - 90 deg", "42.404"),
])
def test_verdict_table_section_and_plot_show_one_signed_figure(examples, tmp_path, convention, name, value):
    for file in ("square_x.csv", "square_z.csv", "square_x.json", "square_z.json"):
        shutil.copy(examples / "campaign" / file, tmp_path / file)
    (tmp_path / "campaign.toml").write_text(CAMPAIGN.format(convention=convention))
    results = run_campaign(load_campaign(tmp_path))
    (row,) = verdict_rows(results, None)
    assert (row["figure"], row["value"], row["result"]) == (f"{name} / arcsec", value, "fail")
    (test,) = results.tests
    # the section: the same figure under the same name, and the included angle (no sign to read)
    assert [(f.label, f"{f.value:.3f}", f.unit) for f in test.table] == [
        (name, f"{float(value):.3f}", "arcsec"), ("included angle of X and Z", "90.012", "deg")]
    # the plot's title (paper 000 section 5: EB0Z = -42.4 arcsec)
    assert f"{name} = {float(value):+.2f} arcsec" in test.plots[0].svg


def test_squareness_name_says_the_convention():
    assert squareness_name("XZ", "iso") == "EB0Z (ISO 230-1)"
    assert squareness_name("yz", "included-angle") == "YZ included angle - 90 deg"
