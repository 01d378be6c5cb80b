"""Customer-facing pages cite methods by standard and method name, and write µm."""

from __future__ import annotations

import re
import shutil
from pathlib import Path

import axiscal.campaign
from axiscal.campaign import load_campaign, run_campaign
from axiscal.report import display_unit
from axiscal.report.html import render_html

CAMPAIGN = """\
[campaign]
title = "straightness and squareness"
date = 2026-11-20
operator = "test"

[machine]
name = "XZ module"

[tolerances]
squareness_arcsec = 20.0
straightness_um = 5.0

[[tests]]
kind = "squareness"
axes = "XZ"
first = "square_x.csv"
second = "square_z.csv"
"""


def test_the_methods_of_every_test_kind_name_no_paper():
    folder = Path(axiscal.campaign.__file__).parent
    methods = [m for path in folder.glob("*.py") for m in re.findall(r'method=f?"([^"]*)"', path.read_text())]
    assert len(methods) >= 8
    assert [m for m in methods if re.search(r"paper \d", m, re.I)] == []


def test_a_report_writes_micrometres_and_cites_standards(examples, tmp_path):
    for file in ("square_x.csv", "square_z.csv", "square_x.json", "square_z.json"):
        shutil.copy(examples / "campaign" / file, tmp_path / file)
    (tmp_path / "campaign.toml").write_text(CAMPAIGN)
    html = render_html(run_campaign(load_campaign(tmp_path)))
    text = re.sub(r"<(svg|style|script).*?</\1>", "", html, flags=re.S)
    assert "paper 0" not in text and "ISO 230-1" in text
    assert re.findall(r">um<|/ um<", text) == []
    assert display_unit("um") == "µm" and display_unit("urad") == "µrad" and display_unit("arcsec") == "arcsec"
