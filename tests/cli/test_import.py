"""End to end: ``axiscal import map`` and ``axiscal import rtx`` on the shipped examples."""

from __future__ import annotations

import json

import numpy as np
import pandas as pd

from axiscal.positioning import read_positioning_run
from axiscal.units import UM


def test_import_map_runs_per_column(run_cli, examples, tmp_path):
    folder = examples / "imports"
    out = tmp_path / "run.csv"
    status, _, err = run_cli("import", "map", folder / "runs_per_column.toml", folder / "runs_per_column.csv", "-o", out)
    assert status == 0, err
    assert err == f"axiscal: note: 110 readings of 5 runs written to {out}\n"  # success says what it wrote
    frame = pd.read_csv(out)
    assert list(frame.columns) == ["target_mm", "run", "direction", "deviation_um"]
    assert len(frame) == 11 * 2 * 5
    run = read_positioning_run(out).run
    assert run.deviations_up.shape == (11, 5)
    # the export's first data line: target 0, runs 1..5 of the forward pass
    np.testing.assert_allclose(run.deviations_up[0] / UM, [1.514, 2.044, 1.990, 1.296, 1.381])
    sidecar = json.loads((tmp_path / "run.json").read_text())
    assert sidecar["kind"] == "positioning readings (imported)" and sidecar["runs"] == ["1", "2", "3", "4", "5"]
    status, text, _ = run_cli("positioning", out)
    assert status == 0 and "11 targets, 5 runs each way" in text


def test_import_map_reading_per_row_to_stdout(run_cli, examples):
    folder = examples / "imports"
    status, out, err = run_cli("import", "map", folder / "reading_per_row.toml", folder / "reading_per_row.txt")
    assert status == 0, err
    lines = out.splitlines()
    assert lines[0] == "target_mm,run,direction,deviation_um"
    assert lines[1].startswith("0.000000,1,+,")
    assert len(lines) == 1 + 3 * 2 * 6


def test_import_map_bad_file_one_line(run_cli, examples, tmp_path):
    bad = tmp_path / "bad.csv"
    bad.write_text("a\nb\nc\nTarget (mm);Run 1\n0,000;1,0\n50,000;x\n")
    status, out, err = run_cli("import", "map", examples / "imports" / "runs_per_column.toml", bad)
    assert status == 2 and out == ""
    assert err == f"axiscal: error: {bad}:4: the map names the reading column 'Run 2', which the file does not have (columns are: Target (mm), Run 1)\n"


def test_import_rtx(run_cli, examples, tmp_path):
    out = tmp_path / "capture.csv"
    status, _, err = run_cli("import", "rtx", examples / "imports" / "capture.rtx", "--unit", "mm", "-o", out)
    assert status == 0, err
    frame = pd.read_csv(out)
    assert list(frame.columns) == ["time_s", "reading_mm"] and len(frame) == 200
    assert frame["time_s"].iloc[-1] == 0.199
    assert abs(frame["reading_mm"].mean() - 100.0) < 0.001
    assert json.loads((tmp_path / "capture.json").read_text())["sample_rate_hz"] == 1000.0


def test_import_rtx_bad_file(run_cli, tmp_path):
    bad = tmp_path / "bad.rtx"
    bad.write_bytes(b"not a capture")
    status, _, err = run_cli("import", "rtx", bad, "--unit", "um")
    assert status == 2
    assert err == f"axiscal: error: {bad}:1: not an .rtx capture: it does not start with 'HEADER::'\n"
