"""``axiscal report --exit-code``: status 1 on a failed verdict, with the report written all the same."""

from __future__ import annotations

import json
import shutil


def test_exit_code_follows_the_verdict_only_when_asked(run_cli, examples, tmp_path):
    campaign = tmp_path / "campaign"
    shutil.copytree(examples / "campaign", campaign)
    status, out, _ = run_cli("report", campaign, "-o", tmp_path / "plain")
    assert status == 0 and out.startswith("FAIL:")
    status, out, err = run_cli("report", campaign, "-o", tmp_path / "gated", "--exit-code")
    assert status == 1 and out.startswith("FAIL:") and "error" not in err
    assert json.loads((tmp_path / "gated" / "results.json").read_text())["verdict"] == "fail"
