"""The flatness lines file: level, profile and inline lines read in their units, mistakes refused
naming the file, the line and the key, and the shipped examples evaluated."""

from __future__ import annotations

import json
from importlib import util

import numpy as np
import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as hs

from axiscal.errors import AxiscalError
from axiscal.flatness import evaluate_flatness, read_flatness_lines
from axiscal.units import INCH, MM, UM

HEADER = 'foot_mm = 100\n'


def write(tmp_path, text, name="lines.toml"):
    path = tmp_path / name
    path.write_text(text, encoding="utf-8")
    return path


def line(name="a", start="[0, 0]", end="[200, 0]", body="angle_urad = [10, -10]"):
    return f'[[lines]]\nname = "{name}"\nfrom_mm = {start}\nto_mm = {end}\n{body}\n'


def test_the_three_kinds_of_line_are_read(tmp_path):
    (tmp_path / "edge.csv").write_text("position_mm,deviation_um\n0,0\n100,2\n200,0\n")
    text = HEADER + line() + line("b", body='profile = "edge.csv"') + line(
        "c", body="position_mm = [0, 200]\ndeviation_um = [1, 1]") + line("d", body="foot_mm = 50\nangle_arcsec = [1, 1, 1, 1]")
    lines = read_flatness_lines(write(tmp_path, text)).lines
    np.testing.assert_allclose(lines[0].height_m, [0, 1e-6, 0])
    np.testing.assert_allclose(lines[1].height_m, [0, 2e-6, 0])
    np.testing.assert_allclose(lines[2].distance_m, [0, 0.2])
    np.testing.assert_allclose(lines[3].height_m[-1], 4 * 50 * MM * np.pi / 648000)


@pytest.mark.parametrize(("text", "line_no", "words"), [
    (HEADER + "colour = 1\n" + line(), 2, "unknown key 'colour'"),
    (HEADER + line(body="angle_urad = [10, -10]\nspeed = 3"), 7, "unknown key 'speed'"),
    (HEADER + line(start="[0]"), 4, "from_mm must be 2 finite numbers, not [0]"),
    (HEADER + line(body="angle_urad = [1, \"x\"]"), 6, "angle_urad must be a list of finite numbers"),
    (HEADER + line(body=""), 2, "has no readings"),
    (HEADER + line(body="angle_urad = [1, 2]\ndeviation_um = [1, 2]"), 2, "more than one kind"),
    (line(), 5, "give its foot_mm"),
    (HEADER + line() + line(), 8, "two lines are named 'a'"),
    (HEADER + line(body='profile = "../outside.csv"'), 6, "leaves the folder"),
    (HEADER + line(body='profile = "missing.csv"'), None, "not found"),
    (HEADER + line(body="deviation_um = [1, 2]"), 6, "give position_mm"),
    (HEADER + line(body="position_mm = [0, 300]\ndeviation_um = [1, 2]"), 7, "distances reach"),
    (HEADER + line(end="[0, 0]"), 6, "same point"),
    (HEADER, None, "no [[lines]]"),
    ("foot_mm = -1\n" + line(), 1, "foot_mm must be positive"),
    (HEADER + line(body="foot_mm = 0\nangle_urad = [1, 2]"), 6, "foot_mm must be positive"),
    ("title = 3\n" + line(), 1, "title must be a string in quotes, not 3"),
    # a position repeated was refused at deviation_um without naming it
    (HEADER + line(body="position_mm = [0, 100, 100, 200]\ndeviation_um = [0, 1, 2, 0]"), 6,
     "line 'a': position_mm: position 100 mm is given twice (station 2 and station 3)"),
    (HEADER + line(body="position_mm = [0, 100, 90, 200]\ndeviation_um = [0, 1, 2, 0]"), 6,
     "line 'a': position_mm: the positions must increase: 90 mm after 100 mm (station 3)"),
])
def test_mistakes_are_refused_naming_the_line(tmp_path, text, line_no, words):
    path = write(tmp_path, text)
    with pytest.raises(AxiscalError) as caught:
        read_flatness_lines(path)
    assert words in caught.value.message
    if line_no is not None:
        assert caught.value.path == str(path) and caught.value.line == line_no
    elif words != "not found":
        assert caught.value.path is not None


@pytest.mark.parametrize(("rows", "words"), [
    ("0,0\n100,1\n100,2\n200,0\n", "line 'a': position 100 mm is given twice (line 3 and line 4)"),
    ("0,0\n100,1\n90,2\n200,0\n", "line 'a': the positions must increase: 90 mm after 100 mm (line 4)"),
])
def test_a_profile_file_with_a_position_repeated_names_its_line_and_the_position(tmp_path, rows, words):
    profile = write(tmp_path, "position_mm,deviation_um\n" + rows, "a.csv")
    path = write(tmp_path, HEADER + line(body='profile = "a.csv"'))
    with pytest.raises(AxiscalError) as caught:
        read_flatness_lines(path)
    assert caught.value.message == words and caught.value.path == str(profile) and caught.value.line == 4


def test_moodys_example_in_micrometres(examples):
    result = evaluate_flatness(examples / "flatness" / "moody_1955.toml", evaluation="moody")
    payload = result.payload()
    # Moody's plate: 17.84 tens of microinches above its lowest point at the highest (Allen's worksheets)
    assert payload["flatness_moody_um"] == pytest.approx(17.841145e-5 * INCH / UM, abs=1e-3)
    assert len(payload["closures"]) == 2 and len(payload["warnings"]) == 2  # the diagonals' 4-inch rises
    assert payload["flatness_um"] <= payload["flatness_least_squares_um"]


@pytest.mark.parametrize("name", ["union_jack_levels", "grid"])
def test_the_simulated_plate_is_recovered_from_its_examples(examples, name):
    spec = util.spec_from_file_location("make_flatness", examples / "make_flatness_examples.py")
    module = util.module_from_spec(spec)
    spec.loader.exec_module(module)
    surface = evaluate_flatness(examples / "flatness" / f"{name}.toml").surface
    truth = module.plate_um(surface.x_m / MM, surface.y_m / MM)
    design = np.column_stack([surface.x_m, surface.y_m, np.ones_like(surface.x_m)])
    coef, *_ = np.linalg.lstsq(design, truth, rcond=None)
    # readings rounded (0.01 um/m) and straightedge noise (0.01 um) leave a few hundredths of a um
    np.testing.assert_allclose(surface.z_m / UM, truth - design @ coef, atol=0.05)
    assert surface.closure_max_m < 0.05 * UM


def test_output_plot_and_report(examples, tmp_path):
    out, plot = tmp_path / "surface.csv", tmp_path / "surface.png"
    result = evaluate_flatness(examples / "flatness" / "union_jack_levels.toml", output=out, plot_path=plot)
    assert out.read_text().splitlines()[0] == "x_mm,y_mm,height_um"
    sidecar = json.loads(out.with_suffix(".json").read_text())
    assert sidecar["flatness_um"] == pytest.approx(result.payload()["flatness_um"])
    assert plot.stat().st_size > 0
    assert "flatness (minimum zone)" in result.report()


def test_an_unknown_evaluation_is_refused(examples):
    with pytest.raises(AxiscalError, match="unknown evaluation"):
        evaluate_flatness(examples / "flatness" / "grid.toml", evaluation="best")


def test_moody_on_a_grid_is_refused_naming_the_file(examples):
    path = examples / "flatness" / "grid.toml"
    with pytest.raises(AxiscalError) as caught:
        evaluate_flatness(path, evaluation="moody")
    assert caught.value.path == str(path) and "Union Jack" in caught.value.message


SNIPPETS = hs.sampled_from(["", "x", "[", "]", "=", '"', "1e999", "nan", "-1", "[1]", "[1, 2, 3]", "true", "\n", "#",
                            "[[lines]]", "foot_mm", "name", "0"])


@settings(max_examples=80, deadline=None, suppress_health_check=[HealthCheck.function_scoped_fixture])
@given(hs.lists(hs.tuples(hs.floats(0, 1), SNIPPETS, hs.booleans()), min_size=1, max_size=3))
def test_mutated_files_are_refused_or_read(tmp_path, examples, mutations):
    text = (examples / "flatness" / "union_jack_levels.toml").read_text()
    for where, snippet, replace in mutations:
        at = int(where * len(text))
        text = text[:at] + snippet + text[at + (len(snippet) if replace else 0):]
    path = write(tmp_path, text, "mutated.toml")
    try:
        lines = read_flatness_lines(path).lines
    except AxiscalError as exc:
        assert exc.path == str(path)
        return
    assert all(np.all(np.isfinite(line.height_m)) for line in lines)


def test_gravity_is_read_at_the_top_and_per_line(tmp_path):
    text = "foot_mm = 100\ngravity = true\n" + line() + line("b", body="gravity = false\nangle_urad = [1, 1]")
    lines = read_flatness_lines(write(tmp_path, text)).lines
    assert [line.gravity for line in lines] == [True, False]
    path = write(tmp_path, HEADER + line(body="gravity = 1\nangle_urad = [1, 1]"), "bad.toml")
    with pytest.raises(AxiscalError) as caught:
        read_flatness_lines(path)
    assert caught.value.line == 6 and "gravity must be true or false" in caught.value.message
