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


@pytest.mark.parametrize("evaluation", ["moody", "least-squares"])
def test_a_union_jack_whose_centre_line_has_no_middle_station_is_one_line(run_cli, examples, tmp_path, evaluation):
    """The shipped Union Jack with its W-E centre line read in 11 steps of 109.09 mm: Moody's evaluation
    interpolated its middle, least squares spoke of rows and columns."""
    text = (examples / "flatness" / "union_jack_levels.toml").read_text()
    head, rest = text.split('name = "W-E"', 1)
    body, tail = rest.split("[[lines]]", 1)
    body = body.replace("angle_um_per_m = [", 'foot_mm = 109.0909\nangle_um_per_m = [').split("angle_um_per_m")[0]
    path = tmp_path / "lines.toml"
    path.write_text(head + 'name = "W-E"' + body + "angle_um_per_m = [" + ", ".join(["0.5"] * 11) + "]\n\n[[lines]]" + tail)
    status, out, err = run_cli("flatness", path, "--evaluation", evaluation)
    assert status == 2 and out == "" and err.count("\n") == 1, err
    assert err.startswith(f"axiscal: error: {path}: lines 'SW-NE' and 'W-E' cross at x = 600 mm, y = 400 mm, where 'W-E'"
                          " has no station")
