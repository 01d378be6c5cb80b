"""A fleet finishes whatever one machine does: a drift that barely moves, a machine whose trends fail;
and a LocalCluster closes without killing its workers."""

from __future__ import annotations

import json
import logging
import re
import shutil

import pytest

from axiscal.fleet import fleet_report, generated_fleet

pytestmark = pytest.mark.filterwarnings("ignore::UserWarning")


def _still(folder, name, shift_um):
    """Campaign ``name``: a copy of ``folder`` whose first reading is moved by ``shift_um`` (a figure that barely moves)."""
    target = folder.parent / name
    shutil.copytree(folder, target)
    csv = target / "positioning_x.csv"
    lines = csv.read_text().splitlines()
    cells = lines[1].split(",")
    cells[-1] = f"{float(cells[-1]) + shift_um:.4f}"
    lines[1] = ",".join(cells)
    csv.write_text("\n".join(lines) + "\n")
    return target


@pytest.fixture
def plant(tmp_path):
    folder = tmp_path / "plant"
    generated_fleet(folder, machines=2, campaigns=3, drift_um_per_year=12.0, tolerance_um=12.0)
    # machine 001's three visits: the same readings but for 0.1 nm, then 0.2 nm on the first point
    first = folder / "m001-c00"
    for k, name in enumerate(["m001-c01", "m001-c02"], start=1):
        shutil.rmtree(folder / name)
        copy = _still(first, name, 0.0001 * k)
        toml = copy / "campaign.toml"
        toml.write_text(re.sub(r"date = \d{4}-\d\d-\d\d", f"date = {2024 + k}-01-08", toml.read_text()))
    return folder


def test_a_figure_that_barely_moves_does_not_stop_the_fleet(run_cli, plant, tmp_path):
    out = tmp_path / "out"
    status, stdout, err = run_cli("fleet", "report", plant, "-o", out, "--scheduler", "threads")
    assert status == 0, err + stdout
    fleet = json.loads((out / "fleet.json").read_text())
    assert [m["machine"] for m in fleet["machines"]] == ["Machine 000 (G-000)", "Machine 001 (G-001)"]
    assert all(m["error"] is None and m["next_due"] for m in fleet["machines"])


def test_a_machine_whose_trends_fail_is_listed_and_the_others_finish(run_cli, plant, tmp_path, monkeypatch):
    import axiscal.fleet.page as page

    real = page.machine_trends

    def failing(history, **kwargs):
        if history.machine == "Machine 001":
            raise OverflowError("date value out of range")
        return real(history, **kwargs)

    monkeypatch.setattr(page, "machine_trends", failing)
    out = tmp_path / "out"
    status, stdout, err = run_cli("fleet", "report", plant, "-o", out, "--scheduler", "threads")
    assert status == 1 and err == ""
    assert "failed machine Machine 001 (G-001): OverflowError: date value out of range" in stdout.splitlines()
    fleet = json.loads((out / "fleet.json").read_text())
    rows = {m["machine"]: m for m in fleet["machines"]}
    assert rows["Machine 000 (G-000)"]["next_due"] and rows["Machine 000 (G-000)"]["error"] is None
    failing_row = rows["Machine 001 (G-001)"]
    assert failing_row["error"] == "OverflowError: date value out of range" and failing_row["next_due"] is None
    assert failing_row["last_date"] == "2026-01-08" and failing_row["worst"]["figure"].startswith("positioning.X.")
    html = (out / "fleet.html").read_text()
    assert "Machines whose drift could not be worked out" in html and "date value out of range" in html


def test_a_local_cluster_lets_its_workers_exit_without_killing_them(plant, tmp_path):
    # each worker takes 4.5 s to exit (more than the 4 s Dask gives by default, as a loaded machine does)
    import dask

    preload = tmp_path / "slow_exit.py"
    preload.write_text("import atexit, time\n\ndef dask_setup(worker):\n    atexit.register(time.sleep, 4.5)\n")
    messages = []

    class Catch(logging.Handler):
        def emit(self, record):
            messages.append(record.getMessage())

    catch = Catch(logging.WARNING)
    logging.getLogger("distributed.nanny").addHandler(catch)
    try:
        with dask.config.set({"distributed.worker.preload": [str(preload)]}):
            fleet = fleet_report(plant / "m000-c00", tmp_path / "out", scheduler="local", workers=1)
    finally:
        logging.getLogger("distributed.nanny").removeHandler(catch)
    assert fleet.failed == 0 and len(fleet.machines) == 1
    assert not [m for m in messages if "still alive" in m], messages
