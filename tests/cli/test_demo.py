"""``axiscal demo``: one call to the library, its lines printed."""

from __future__ import annotations

import json

import pytest

pytestmark = pytest.mark.filterwarnings("ignore::UserWarning")


def test_demo_writes_the_campaign_and_its_report(run_cli, tmp_path):
    """Into a folder that does not exist yet (its parents made): the demo's own test of its writing option."""
    out = tmp_path / "no" / "such" / "dir" / "demo"
    status, out_text, err = run_cli("demo", "--output", out)
    assert status == 0, err
    for name in ("as-found/campaign/campaign.toml", "as-found/report/report.html", "as-found/report/results.json",
                 "as-left/report/report.html", "summary.json"):
        assert (out / name).is_file(), name
    assert json.loads((out / "as-found" / "report" / "results.json").read_text())["verdict"] == "fail"
    assert json.loads((out / "as-left" / "report" / "results.json").read_text())["verdict"] == "pass"
    lines = out_text.splitlines()
    assert lines[1] == f"report        {out / 'as-found' / 'report' / 'report.html'}" and len(lines) == 13


def test_demo_takes_o_for_output():
    """-o is the same option as --output (the demo itself runs once, above: it takes seconds)."""
    from axiscal.cli.main import cli

    option = next(p for p in cli.commands["demo"].params if p.name == "output")
    assert set(option.opts) == {"-o", "--output"}


def test_demo_into_a_file_is_one_line_error(run_cli, tmp_path):
    blocker = tmp_path / "file"
    blocker.write_text("")
    status, _, err = run_cli("demo", "--output", blocker / "demo")
    assert status == 2 and len(err.strip().splitlines()) == 1 and "Traceback" not in err
