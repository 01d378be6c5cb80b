"""``axiscal report --history``: the campaign is stored, and the report shows the machine's trends."""

from __future__ import annotations

import datetime as _dt
import json
import shutil
from pathlib import Path

import pytest

from axiscal.history import Drift, add_results, drifting_results, list_campaigns, write_results

pytestmark = pytest.mark.filterwarnings("ignore::UserWarning")

VMC850 = Path(__file__).parents[1] / "campaign" / "data" / "vmc850"


def test_report_history_stores_the_campaign_and_shows_the_trends(run_cli, tmp_path):
    campaign = tmp_path / "campaign"
    shutil.copytree(VMC850, campaign)
    db = f"sqlite:///{tmp_path / 'h.sqlite'}"
    status, out, err = run_cli("report", campaign, "--history", "--db", db)
    assert status == 0, err
    # it says where it stored the campaign
    assert f"history: campaign 1 of VMC 850 (SN-0042) stored in {db} (1 campaign of this machine)" in out
    assert 'id="history"' not in (campaign / "report" / "report.html").read_text()
    assert len(list_campaigns(url=db)) == 1
    # two earlier campaigns of the same machine
    earlier = drifting_results({"positioning.X.E": Drift(2.0, 1.0, 0.5, 14.0), "positioning.X.A": Drift(3.0, 1.0, 0.5, 16.0)},
                               machine="VMC 850", serial="SN-0042", campaigns=2, start=_dt.date(2025, 6, 1), seed=0)
    add_results(write_results(tmp_path / "earlier", earlier), url=db)
    status, _, err = run_cli("report", campaign, "--history", "--db", db)
    assert status == 0, err
    assert len(list_campaigns(url=db)) == 3  # the same results again are stored once
    html = (campaign / "report" / "report.html").read_text()
    section = html[html.index('id="history"'):html.index("</section>", html.index('id="history"'))]
    assert "3 campaigns in the calibration history" in section
    assert "positioning.X.E" in section and "positioning.X.A" in section and section.count("<svg") == 2
    assert "Fieller" in section and "ILAC-G24" in section
    assert json.loads((campaign / "report" / "results.json").read_text())["schema"] == "axiscal-results/1"
