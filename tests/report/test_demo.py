"""The demo job in one call: every file written, the report rendered from its template, the numbers."""

from __future__ import annotations

import json

import numpy as np
import pandas as pd
import pytest

from axiscal.report import DEMO_FILES, builtin_example, run_demo


@pytest.fixture(scope="module")
def demo(tmp_path_factory):
    return run_demo(tmp_path_factory.mktemp("demo") / "out")


def test_every_file_is_written_and_nothing_else(demo):
    assert sorted(p.name for p in demo.folder.iterdir()) == sorted(DEMO_FILES)
    assert all(path.stat().st_size > 0 for path in demo.files.values())
    assert demo.files["volumetric_map.png"].stat().st_size > 10_000


def test_data_csvs_are_plain(demo):
    volumetric = pd.read_csv(demo.files["volumetric_map.csv"])
    assert list(volumetric.columns) == ["x_mm", "z_mm", "ex_um", "ey_um", "ez_um", "e_um"] and len(volumetric) == 39 * 39
    diagonal = pd.read_csv(demo.files["diagonal.csv"])
    assert list(diagonal.columns) == ["x_mm", "z_mm", "nominal_mm", "measured_mm", "model_error_um", "E_BD_um", "E_AD_um"]
    # actual minus nominal (docs/conventions.md)
    np.testing.assert_allclose(diagonal["E_BD_um"], (diagonal["measured_mm"] - diagonal["nominal_mm"]) * 1e3, atol=2e-3)


def test_summary_holds_the_headline_numbers(demo):
    summary = json.loads(demo.files["summary.json"].read_text())
    assert summary["machine"] == demo.summary["machine"] == "XZ linear module (paper 000)"
    assert summary["chain"] == "FXZ" and summary["squareness_EB0Z_arcsec"] == pytest.approx(-42.4)
    assert round(summary["volumetric_max_um"], 2) == 84.33 and summary["volumetric_max_at_mm"] == {"X": 190.0, "Z": 190.0}
    assert round(summary["diagonal_E_BD_range_um"], 2) == 56.42 and round(summary["diagonal_E_AD_range_um"], 2) == 11.08
    # paper 000 section 5: 68 -> 13 um without load, 56 -> 14 um with 2 kg (the simulation leaves less after)
    assert round(summary["experiment"]["0kg"]["before_max_um"]) == 68
    assert round(summary["experiment"]["2kg"]["before_max_um"]) == 56
    assert summary["experiment"]["2kg"]["after_max_um"] < 1.5


def test_report_is_rendered_from_the_template(demo):
    report = demo.files["report.md"].read_text()
    lines = report.splitlines()
    assert len(lines) == 45
    assert lines[0] == "# axiscal demo: XZ linear module (paper 000)"
    assert "Largest |e| = 84.33 um at X = 190 mm," in report
    assert f"`{builtin_example() / 'x_errors.csv'}`" in report
    assert "| 0 kg | 67.5 um | 0.61 um | 25.1 um |" in lines and "| 2 kg | 56.4 um | 0.61 um | 13.0 um |" in lines
    for name in DEMO_FILES:
        if name.endswith(".png") or name == "diagonal.csv":
            assert name in report, name


def test_console_text(demo):
    assert demo.text().splitlines() == [
        f"wrote {demo.folder / 'report.md'}",
        "  paper 000 experiment (simulated): 67.5 -> 0.61 um, 2 kg: 56.4 -> 0.61 um",
        "  volumetric |e| max 84.33 um; diagonal P-V 56.42 um before model, 11.08 um after",
    ]
