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



def test_a_figure_that_barely_moves_reaches_its_tolerance_not_within_100_years(run_cli, tmp_path):
    import re

    from axiscal.fleet import generated_fleet

    generated_fleet(tmp_path / "plant", machines=1, campaigns=1)
    first = tmp_path / "plant" / "m000-c00"
    db = f"sqlite:///{tmp_path / 'h.sqlite'}"
    # three visits with the same readings but for 0.1 nm on the first point: a drift of about 1e-4 um a year
    for k in range(3):
        campaign = tmp_path / f"visit-{k}"
        shutil.copytree(first, campaign)
        csv = campaign / "positioning_x.csv"
        lines = csv.read_text().splitlines()
        cells = lines[1].split(",")
        cells[-1] = f"{float(cells[-1]) + 0.0001 * k:.4f}"
        lines[1] = ",".join(cells)
        csv.write_text("\n".join(lines) + "\n")
        toml = campaign / "campaign.toml"
        toml.write_text(re.sub(r"date = \d{4}-\d\d-\d\d", f"date = {2024 + k}-01-08", toml.read_text()))
        status, _, err = run_cli("report", campaign, "--history", "--db", db)
        assert status == 0, err
    html = (campaign / "report" / "report.html").read_text()
    section = html[html.index('id="history"'):html.index("</section>", html.index('id="history"'))]
    assert "not within 100 years" in section
