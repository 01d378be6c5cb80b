"""Thermal run files: the reader's units and refusals (file and line named), the shipped examples
recovering the sensitivities and the time constant they were made with."""

from __future__ import annotations

import numpy as np
import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as hs

from axiscal.errors import AxiscalError
from axiscal.thermal import evaluate_drift, evaluate_etve, read_thermal_run


def write(tmp_path, text, name="run.csv"):
    path = tmp_path / name
    path.write_text(text, encoding="utf-8")
    return path


def test_units_of_the_columns(tmp_path):
    run = read_thermal_run(write(tmp_path, "time_s,z_um,a_urad,temperature_bed_c,running,note\n0,1,2,20,1,x\n60,2,3,21,0,y\n"
                                            "120,3,4,22,0,z\n"))
    assert run.time_s.tolist() == [0, 60, 120]
    assert run.displacements["Z"].tolist() == pytest.approx([1e-6, 2e-6, 3e-6])
    assert run.displacements["A"].tolist() == pytest.approx([2e-6, 3e-6, 4e-6])
    assert list(run.temperatures_c) == ["bed"] and run.running.tolist() == [1, 0, 0]


@pytest.mark.parametrize(("text", "line", "words"), [
    ("z_um,temperature_a_c\n1,20\n2,20\n3,20\n", 1, "no time column"),
    ("time_s,time_h,z_um\n0,0,1\n1,1,2\n2,2,3\n", 1, "both time_s and time_h"),
    ("time_s,temperature_a_c\n0,20\n1,20\n2,20\n", 1, "no displacement column"),
    ("time_s,z_um\n0,1\n1,2\n1,3\n", 4, "times must increase"),
    ("time_s,z_um\n0,1\n1,x\n2,3\n", 3, "not a number"),
    ("time_s,z_um,running\n0,1,1\n1,2,0.5\n2,3,0\n", 3, "running"),
    ("time_s,z_um\n0,1\n1,2\n", 1, "rows"),
])
def test_bad_files_are_refused_naming_the_line(tmp_path, text, line, words):
    path = write(tmp_path, text)
    with pytest.raises(AxiscalError) as caught:
        read_thermal_run(path)
    assert caught.value.path == str(path) and caught.value.line == line and words in caught.value.message


def test_etve_needs_a_temperature(tmp_path):
    path = write(tmp_path, "time_s,z_um\n0,1\n1,2\n2,3\n")
    with pytest.raises(AxiscalError) as caught:
        evaluate_etve(path)
    assert caught.value.path == str(path) and "temperature" in caught.value.message
    assert evaluate_drift(path).payload()["drift_end_um"]["Z"] == pytest.approx(2.0)


def test_the_etve_example_recovers_its_sensitivities(examples, tmp_path):
    plot = tmp_path / "etve.svg"
    result = evaluate_etve(examples / "thermal" / "etve_run.csv", max_lag_s=3 * 3600)
    from axiscal.thermal.plot import plot_etve

    plot_etve(plot, result)
    payload = result.payload()
    assert set(payload["etve_um"]) == {"X", "Y", "Z"} and set(payload["etve_urad"]) == {"A", "B"}
    by = {(c["direction"], c["sensor"]): c for c in payload["correlations"]}
    # made with 1.5, -0.6, -4.0 um/K and 0.8 urad/K of the column's temperature, 0.05 um of noise
    assert by[("X", "column")]["sensitivity_um_per_k"] == pytest.approx(1.5, abs=0.03)
    assert by[("Y", "column")]["sensitivity_um_per_k"] == pytest.approx(-0.6, abs=0.03)
    assert by[("Z", "column")]["sensitivity_um_per_k"] == pytest.approx(-4.0, abs=0.03)
    assert by[("A", "column")]["sensitivity_urad_per_k"] == pytest.approx(0.8, abs=0.03)
    assert by[("Z", "column")]["lag_h"] == 0.0 and by[("Z", "column")]["r"] < -0.99
    # the column follows the air through a 1.5 h lag: Z follows the air about that late
    assert 0.75 <= by[("Z", "air")]["lag_h"] <= 1.75
    assert abs(by[("B", "column")]["r"]) < 0.3
    assert payload["etve_um"]["Z"] == pytest.approx(4.0 * payload["temperature_range_c"]["column"], rel=0.05)
    assert "ETVE Z" in result.report() and plot.stat().st_size > 0


def test_the_drift_example_recovers_its_time_constant(examples, tmp_path):
    plot = tmp_path / "drift.png"
    result = evaluate_drift(examples / "thermal" / "drift_run.csv")
    from axiscal.thermal.plot import plot_drift

    plot_drift(plot, result)
    payload = result.payload()
    assert payload["heating_phases"] == 2
    assert payload["time_constant_h"]["Z"] == pytest.approx(0.8, rel=0.03)
    assert payload["time_constant_h"]["X"] == pytest.approx(0.8, rel=0.05)
    # after 3 h at 0.8 h the drift is 1 - exp(-3.75) = 97.6 % of -12 um
    assert payload["drift_heating_end_um"]["Z"] == pytest.approx(-12 * (1 - np.exp(-3 / 0.8)), abs=0.15)
    assert "time constant" in result.report() and plot.stat().st_size > 0


CELLS = hs.sampled_from(["", "x", "nan", "inf", "1e999", "-5", "0", "1", "2", "0.5", "1e13", "#", "\"", ";"])


@settings(max_examples=100, deadline=None, suppress_health_check=[HealthCheck.function_scoped_fixture])
@given(hs.lists(hs.tuples(hs.integers(0, 12), hs.integers(0, 5), CELLS), min_size=1, max_size=3))
def test_mutated_runs_are_refused_with_a_line_or_read_correctly(tmp_path, examples, mutations):
    lines = (examples / "thermal" / "drift_run.csv").read_text().splitlines()[:13]
    for row, column, cell in mutations:
        cells = lines[row].split(",")
        cells[column] = cell
        lines[row] = ",".join(cells)
    path = write(tmp_path, "\n".join(lines) + "\n", "mutated.csv")
    try:
        run = read_thermal_run(path)
    except AxiscalError as exc:
        assert exc.path == str(path)
        return
    assert np.all(np.diff(run.time_s) > 0) and all(np.all(np.isfinite(v)) for v in run.displacements.values())


@pytest.mark.parametrize("tilts", ["a_urad", "b_urad", "a_urad,b_urad"])
def test_a_run_of_tilts_alone_is_refused_as_the_docs_say(tmp_path, tilts):
    """docs/thermal.md: one of x_um, y_um, z_um at least. A run of tilts alone was taken, and in a campaign its
    `etve_um` tolerance was then checked against nothing."""
    cells = ",".join("1" for _ in tilts.split(","))
    path = write(tmp_path, f"time_s,{tilts},temperature_air_c\n0,{cells},20\n60,{cells},21\n120,{cells},22\n")
    with pytest.raises(AxiscalError) as caught:
        read_thermal_run(path)
    assert caught.value.path == str(path) and caught.value.line == 1
    assert "no displacement column: give one of x_um, y_um, z_um" in caught.value.message


def test_the_command_refuses_a_run_of_tilts_alone_in_one_line(run_cli, tmp_path):
    path = write(tmp_path, "time_h,a_urad,temperature_air_c\n0,0,20\n1,-2,21\n2,-3,21.5\n")
    for command in ("etve", "drift"):
        status, out, err = run_cli("thermal", command, path)
        assert status == 2 and out == "" and err == (
            f"axiscal: error: {path}:1: no displacement column: give one of x_um, y_um, z_um"
            " (the tilts a_urad, b_urad are read beside one, never alone)\n")
