"""``axiscal demo``: one call to the library, its lines printed."""

from __future__ import annotations

import json


def test_demo_writes_a_report(run_cli, tmp_path):
    status, out, err = run_cli("demo", "--output", tmp_path / "demo")
    assert status == 0, err
    for name in ("report.md", "summary.json", "volumetric_map.csv", "volumetric_map.png", "diagonal.png", "error_motions.png"):
        assert (tmp_path / "demo" / name).exists(), name
    summary = json.loads((tmp_path / "demo" / "summary.json").read_text())
    assert summary["diagonal_E_AD_range_um"] < summary["diagonal_E_BD_range_um"]
    assert out.splitlines()[0] == f"wrote {tmp_path / 'demo' / 'report.md'}" and len(out.splitlines()) == 3


def test_demo_into_a_file_is_one_line_error(run_cli, tmp_path):
    blocker = tmp_path / "file"
    blocker.write_text("")
    status, _, err = run_cli("demo", "--output", blocker / "demo")
    assert status == 2 and len(err.strip().splitlines()) == 1 and "Traceback" not in err
