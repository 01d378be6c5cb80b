"""``axiscal demo``: one call to the library, its lines printed."""

from __future__ import annotations

import json

import pytest

pytestmark = pytest.mark.filterwarnings("ignore::UserWarning")


@pytest.mark.parametrize("flag", ["-o", "--output"])
def test_demo_writes_the_campaign_and_its_report(run_cli, tmp_path, flag):
    status, out, err = run_cli("demo", flag, tmp_path / "demo")
    assert status == 0, err
    for name in ("as-found/campaign/campaign.toml", "as-found/report/report.html", "as-found/report/results.json",
                 "as-left/report/report.html", "summary.json"):
        assert (tmp_path / "demo" / name).is_file(), name
    assert json.loads((tmp_path / "demo" / "as-found" / "report" / "results.json").read_text())["verdict"] == "fail"
    assert json.loads((tmp_path / "demo" / "as-left" / "report" / "results.json").read_text())["verdict"] == "pass"
    lines = out.splitlines()
    assert lines[1] == f"report        {tmp_path / 'demo' / 'as-found' / 'report' / 'report.html'}" and len(lines) == 13


def test_demo_into_a_file_is_one_line_error(run_cli, tmp_path):
    blocker = tmp_path / "file"
    blocker.write_text("")
    status, _, err = run_cli("demo", "--output", blocker / "demo")
    assert status == 2 and len(err.strip().splitlines()) == 1 and "Traceback" not in err
