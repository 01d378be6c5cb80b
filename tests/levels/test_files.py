"""The level run reader and the file evaluation: units, the differential column, bad files refused
naming the file and the line, the profile written readable by the straightness reader."""

from __future__ import annotations

import json

import numpy as np
import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as hs

from axiscal.errors import AxiscalError
from axiscal.levels import evaluate_levels, read_level_run
from axiscal.straightness import evaluate_straightness_file, read_profile
from axiscal.units import ARCSEC, MM, URAD


def write(tmp_path, text, name="run.csv"):
    path = tmp_path / name
    path.write_text(text, encoding="utf-8")
    return path


@pytest.mark.parametrize(("column", "factor"), [("angle_arcsec", ARCSEC), ("angle_urad", URAD), ("angle_um_per_m", 1e-6)])
def test_each_unit_is_read_as_a_slope(tmp_path, column, factor):
    path = write(tmp_path, f"position_mm,{column}\n0,1.5\n100,-2\n")
    run = read_level_run(path)
    np.testing.assert_allclose(run.angle_rad, [1.5 * factor, -2 * factor])
    np.testing.assert_allclose(run.position_m, [0, 0.1])
    assert run.reference_rad is None


@pytest.mark.parametrize(("text", "line", "words"), [
    ("position_mm,deviation_um\n0,1\n100,2\n", 1, "no reading column"),
    ("position_mm,angle_urad,angle_arcsec\n0,1,1\n100,2,2\n", 1, "more than one"),
    ("position_mm,angle_urad,reference_arcsec\n0,1,1\n100,2,2\n", 1, "reference_urad"),
    ("position_mm,angle_urad\n0,1\n100,x\n", 3, "not a number"),
    ("position_mm,angle_urad\n0,1\n100,2\n100,3\n", 4, "increase"),
    ("angle_urad\n1\n2\n", 1, "position_mm"),
    ("position_mm,angle_urad\n0,1\n", 1, "rows"),
])
def test_bad_files_are_refused_naming_the_line(tmp_path, text, line, words):
    path = write(tmp_path, text)
    with pytest.raises(AxiscalError) as caught:
        read_level_run(path)
    assert caught.value.path == str(path)
    assert words in caught.value.message
    assert caught.value.line == line


def test_the_written_profile_gives_the_same_straightness(tmp_path, examples):
    out = tmp_path / "profile.csv"
    result = evaluate_levels(examples / "levels" / "levels_run.csv", foot_m=100 * MM, reference="minimum-zone", output=out)
    again = evaluate_straightness_file(out, reference="minimum-zone")
    assert again.payload()["straightness_um"] == pytest.approx(result.payload()["straightness_um"], abs=1e-5)
    sidecar = json.loads(out.with_suffix(".json").read_text())
    assert sidecar["foot_mm"] == 100.0 and sidecar["differential"] is True
    assert read_profile(out).position_m.size == 11
    assert out.read_text().splitlines()[0] == "position_mm,deviation_um"


def test_the_example_recovers_the_guideway_it_was_made_from(examples):
    from importlib import util

    spec = util.spec_from_file_location("make_levels", examples / "make_levels_examples.py")
    module = util.module_from_spec(spec)
    spec.loader.exec_module(module)
    result = evaluate_levels(examples / "levels" / "levels_run.csv", foot_m=100 * MM)
    x = result.profile.position_m / MM
    truth = module.guideway_um(x)
    # readings rounded to 0.01 arcsec: 0.005 arcsec * 100 mm = 2.4 nm per step at most, ten steps
    np.testing.assert_allclose(result.profile.deviation_m / 1e-6, truth - truth[0], atol=0.03)


def test_report_and_plot(tmp_path, examples):
    plot = tmp_path / "levels.svg"
    result = evaluate_levels(examples / "levels" / "levels_run.csv", foot_m=100 * MM)
    from axiscal.levels.plot import plot_levels

    plot_levels(plot, result)
    text = result.report()
    assert text.startswith("straightness") and "arcsec" in text and "less the reference level" in text
    assert plot.read_text().lstrip().startswith("<?xml") or "<svg" in plot.read_text()


def test_an_unknown_reference_or_foot_is_refused(tmp_path, examples):
    with pytest.raises(AxiscalError, match="unknown reference line"):
        evaluate_levels(examples / "levels" / "levels_run.csv", foot_m=0.1, reference="best")
    with pytest.raises(AxiscalError, match="foot_m"):
        evaluate_levels(examples / "levels" / "levels_run.csv", foot_m=-0.1)


CELLS = hs.sampled_from(["", "x", "nan", "inf", "1e999", "-5", "0", "12.5", "1e13", "100", "#", "\"", ";"])


@settings(max_examples=120, deadline=None, suppress_health_check=[HealthCheck.function_scoped_fixture])
@given(hs.lists(hs.tuples(hs.integers(0, 10), hs.integers(0, 2), CELLS), min_size=1, max_size=3))
def test_mutated_runs_are_refused_with_a_line_or_read_correctly(tmp_path, examples, mutations):
    lines = (examples / "levels" / "levels_run.csv").read_text().splitlines()
    for row, column, cell in mutations:
        cells = lines[row].split(",")
        cells[column] = cell
        lines[row] = ",".join(cells)
    path = write(tmp_path, "\n".join(lines) + "\n", "mutated.csv")
    try:
        run = read_level_run(path)
    except AxiscalError as exc:
        assert exc.path == str(path)
        return
    assert np.all(np.isfinite(run.angle_rad)) and np.all(np.diff(run.position_m) > 0)


def test_level_profiles_feed_squareness_and_flatness(tmp_path, examples):
    from axiscal.flatness import evaluate_flatness
    from axiscal.squareness.evaluation import squareness_from_files

    first, second = tmp_path / "x.csv", tmp_path / "y.csv"
    evaluate_levels(examples / "levels" / "levels_run.csv", foot_m=100 * MM, output=first)
    evaluate_levels(examples / "levels" / "levels_run.csv", foot_m=100 * MM, output=second)
    assert np.isfinite(squareness_from_files(first, second, plane="XY").payload()["squareness_arcsec"])
    # two edges and a diagonal of a 1000 x 1000 mm square, each the same level profile: a flatness lines
    # file reads them as profiles and places them by their shared corners and middles
    lines = "".join(
        f'[[lines]]\nname = "{name}"\nfrom_mm = {start}\nto_mm = {end}\nprofile = "{profile}"\n'
        for name, start, end, profile in (("S", [0, 0], [1000, 0], "x.csv"), ("N", [0, 1000], [1000, 1000], "x.csv"),
                                          ("W", [0, 0], [0, 1000], "y.csv"), ("E", [1000, 0], [1000, 1000], "y.csv"),
                                          ("WE", [0, 500], [1000, 500], "x.csv"), ("SN", [500, 0], [500, 1000], "y.csv")))
    path = write(tmp_path, lines, "lines.toml")
    with pytest.raises(AxiscalError, match="twist"):
        evaluate_flatness(path)  # rows and columns only: the twist is not seen
