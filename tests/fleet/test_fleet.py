"""``axiscal fleet report``: campaigns reported in parallel on Dask, a failing one listed, the fleet page."""

from __future__ import annotations

import json
import re

import pytest

from axiscal.fleet import fleet_report, generated_fleet
from axiscal.history import list_campaigns

pytestmark = pytest.mark.filterwarnings("ignore::UserWarning")


@pytest.fixture
def plant(tmp_path):
    folder = tmp_path / "plant"
    generated_fleet(folder, machines=2, campaigns=3, drift_um_per_year=12.0, tolerance_um=12.0)
    broken = folder / "zz-broken"
    broken.mkdir()
    (broken / "campaign.toml").write_text("[campaign]\ntitle = 'no date'\n")
    return folder


def test_threads_report_every_campaign_and_list_the_failing_one(run_cli, plant, tmp_path):
    out = tmp_path / "out"
    status, stdout, err = run_cli("fleet", "report", plant, "-o", out, "--scheduler", "threads")
    assert status == 1, err
    assert "7 campaigns of 2 machines" in stdout and "1 failed" in stdout
    assert re.search(r"failed .*zz-broken: .*campaign\.toml:\d+: \[campaign\] needs 'date'", stdout)
    assert all((out / f"m00{m}-c0{k}" / "report.html").is_file() for m in range(2) for k in range(3))
    fleet = json.loads((out / "fleet.json").read_text())
    assert fleet["schema"] == "axiscal-fleet/1" and len(fleet["machines"]) == 2
    assert [e["folder"].endswith("zz-broken") for e in fleet["errors"]] == [True]
    for machine in fleet["machines"]:
        assert machine["last_date"] == "2024-09-04" and machine["worst"]["figure"].startswith("positioning.X.")
        assert machine["drift"]["per_year"] is not None and machine["next_due"] >= "2024-09-04"
    # the faster-drifting machine is due first
    assert fleet["machines"][0]["machine"] == "Machine 001 (G-001)"
    html = (out / "fleet.html").read_text()
    assert html.count("<tr class=") == 2 and "zz-broken" in html and "<script>" in html
    assert not re.search(r'(src|href)="https?:', html)
    assert 'href="m001-c02/report.html"' in html


def test_a_two_worker_local_cluster_gives_the_same_rows(plant, tmp_path):
    threads = fleet_report(plant, tmp_path / "a", scheduler="threads")
    cluster = fleet_report(plant, tmp_path / "b", scheduler="local", workers=2, processes=False)
    assert cluster.run.scheduler == "local" and cluster.failed == threads.failed == 1
    strip = lambda rows: [(r.machine, r.worst_figure, r.worst_value, r.drift_per_year, r.next_due) for r in rows]  # noqa: E731
    assert strip(cluster.machines) == strip(threads.machines)


def test_history_stores_every_campaign_and_trends_use_the_stored_ones(plant, tmp_path):
    db = f"sqlite:///{tmp_path / 'h.sqlite'}"
    fleet = fleet_report(plant, tmp_path / "out", scheduler="threads", history=True, db=db)
    assert len(list_campaigns(url=db)) == 6
    assert all(row.campaigns == 3 for row in fleet.machines)
    # each stored campaign names its report where the fleet left it, not the folder it was built in
    import sqlalchemy

    with sqlalchemy.create_engine(db).connect() as connection:
        sources = [row[0] for row in connection.execute(sqlalchemy.text("SELECT source FROM campaigns"))]
    out = tmp_path / "out"
    assert sorted(sources) == sorted(str(out / f"m00{m}-c0{k}" / "results.json") for m in range(2) for k in range(3))
    assert 'id="history"' in (tmp_path / "out" / "m000-c02" / "report.html").read_text() or \
        'id="history"' in (tmp_path / "out" / "m000-c01" / "report.html").read_text()


def test_a_scheduler_that_does_not_answer_is_one_line(run_cli, plant, tmp_path):
    status, _, err = run_cli("fleet", "report", plant, "-o", tmp_path / "out", "--scheduler", "tcp://127.0.0.1:1",
                             "--scheduler-timeout-s", "1")
    assert status == 2 and len(err.splitlines()) == 1 and "no dask scheduler answered at 'tcp://127.0.0.1:1'" in err


def test_a_folder_without_campaigns_is_one_line(run_cli, tmp_path):
    status, _, err = run_cli("fleet", "report", tmp_path, "-o", tmp_path / "out", "--scheduler", "threads")
    assert status == 2 and "no campaign (a folder with campaign.toml)" in err
