"""The campaign folder's path is checked once on its way from report_campaign to the report: the
public entry checks it, and everything below takes the checked Path and the validated file."""

from __future__ import annotations

import shutil
from pathlib import Path

import axiscal.io.arguments as arguments
from axiscal.report import report_campaign

GOOD = """\
[campaign]
title = "Acceptance"
date = 2026-11-20
operator = "A. Technician"

[machine]
name = "VMC 850"

[[tests]]
kind = "straightness"
axis = "X"
direction = "Y"
file = "profile.csv"
"""


def test_the_campaign_folder_is_checked_once(tmp_path, examples, monkeypatch):
    folder = tmp_path / "campaign"
    folder.mkdir()
    shutil.copy(examples / "straightness_profile.csv", folder / "profile.csv")
    (folder / "campaign.toml").write_text(GOOD)
    seen: list[str] = []
    places = (folder.resolve(), (folder / "campaign.toml").resolve())

    def counting(check):
        def counted(name, value, *args, **kwargs):
            if isinstance(value, (str, Path)) and Path(value).resolve() in places:
                seen.append(name)
            return check(name, value, *args, **kwargs)
        return counted

    import sys

    for check in (arguments.check_path, arguments.check_instance):
        for module in list(sys.modules.values()):  # every module that imported the check by name
            if getattr(module, "__name__", "").startswith("axiscal") and getattr(module, check.__name__, None) is check:
                monkeypatch.setattr(module, check.__name__, counting(check))
    files = report_campaign(folder, tmp_path / "report")
    assert files.results_data.tests and seen == ["campaign_dir"]
