"""End-to-end runs of `axiscal thermal etve` and `axiscal thermal drift` on the shipped examples."""

from __future__ import annotations

import json


def test_etve_json(run_cli, examples):
    status, out, err = run_cli("thermal", "etve", examples / "thermal" / "etve_run.csv", "--json", "--max-lag-h", "2")
    assert status == 0, err
    payload = json.loads(out)
    assert set(payload["etve_um"]) == {"X", "Y", "Z"}
    assert {"temperature_range_c", "correlations", "duration_h"} <= set(payload)
    assert all(abs(c["lag_h"]) <= 2 for c in payload["correlations"])


def test_drift_text_and_plot(run_cli, examples, tmp_path):
    plot = tmp_path / "drift.png"
    status, out, err = run_cli("thermal", "drift", examples / "thermal" / "drift_run.csv", "--plot", plot)
    assert status == 0, err
    assert "2 heating phase(s)" in out and plot.stat().st_size > 0


def test_a_bad_lag_and_a_bad_file_are_one_line(run_cli, examples, tmp_path):
    status, _, err = run_cli("thermal", "etve", examples / "thermal" / "etve_run.csv", "--max-lag-h", "-1")
    assert status == 2 and "--max-lag-h" in err and len(err.strip().splitlines()) == 1
    path = tmp_path / "run.csv"
    path.write_text("time_h,z_um\n0,1\n1,2\n0.5,3\n")
    status, _, err = run_cli("thermal", "drift", path)
    assert status == 2 and f"{path}:4:" in err and len(err.strip().splitlines()) == 1
