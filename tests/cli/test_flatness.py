"""End-to-end runs of `axiscal flatness` on the shipped examples."""

from __future__ import annotations

import json

import pytest


def test_json_of_the_union_jack(run_cli, examples):
    status, out, err = run_cli("flatness", examples / "flatness" / "union_jack_levels.toml", "--json")
    assert status == 0, err
    payload = json.loads(out)
    assert {"flatness_um", "flatness_least_squares_um", "closure_max_um", "closures", "evaluation"} <= set(payload)
    assert payload["flatness_um"] == pytest.approx(4.0, abs=0.05)


def test_moody_text_report_with_plot_and_surface(run_cli, examples, tmp_path):
    plot, surface = tmp_path / "plate.svg", tmp_path / "plate.csv"
    status, out, err = run_cli("flatness", examples / "flatness" / "moody_1955.toml", "--evaluation", "moody",
                               "--plot", plot, "-o", surface)
    assert status == 0, err
    assert "flatness (Moody)" in out and "4.5317 um" in out and "warning:" in out
    assert plot.stat().st_size > 0 and surface.with_suffix(".json").exists()


def test_a_bad_file_is_one_line(run_cli, tmp_path):
    path = tmp_path / "lines.toml"
    path.write_text('[[lines]]\nname = "a"\nfrom_mm = [0, 0]\nto_mm = [1, 0]\nangle_urad = [1, 2]\n')
    status, out, err = run_cli("flatness", path)
    assert status == 2 and out == ""
    assert f"{path}:5:" in err and "foot_mm" in err and len(err.strip().splitlines()) == 1
