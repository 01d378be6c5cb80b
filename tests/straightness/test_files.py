"""The straightness room's files: the one profile reader, probe readings, and the file-level calls."""

from __future__ import annotations

import json

import numpy as np
import pandas as pd
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from axiscal.errors import AxiscalError
from axiscal.straightness.files import (
    evaluate_straightness_file,
    read_probe_readings,
    read_profile,
    read_reversal_runs,
    separate_file,
    separation_columns,
    simulate_probe_readings,
)
from axiscal.straightness.reference import reference_line
from axiscal.straightness.separation import reversal
from axiscal.units import MM, UM


def test_read_profile_in_the_units_the_columns_spell(tmp_path):
    good = tmp_path / "run.csv"
    good.write_text("# a run\nposition_mm,deviation_um\n0,1\n100,2\n200,2.5\n")
    profile = read_profile(good)
    np.testing.assert_allclose(profile.position_m, [0, 0.1, 0.2])
    np.testing.assert_allclose(profile.deviation_m, [1e-6, 2e-6, 2.5e-6])
    assert profile.yaw_rad is None and profile.lines == (3, 4, 5)
    other = tmp_path / "other.csv"
    other.write_text("deviation_nm,position_m,note\n1000,0,a\n2000,0.1,b\n")
    profile = read_profile(other)
    np.testing.assert_allclose(profile.position_m, [0, 0.1])
    np.testing.assert_allclose(profile.deviation_m, [1e-6, 2e-6])
    yawed = tmp_path / "yawed.csv"
    yawed.write_text("position_mm,deviation_um,yaw_urad\n0,0,1\n1,0,2\n")
    np.testing.assert_allclose(read_profile(yawed).yaw_rad, [1e-6, 2e-6])


@pytest.mark.parametrize(
    ("text", "message", "line"),
    [
        ("position_mm,deviation_um\n0,1\n", "at least 2", 1),
        ("position_in,deviation_um\n0,1\n1,2\n", "unknown length unit", 1),
        ("position_mm,height_um\n0,1\n1,2\n", "missing column deviation_um", 1),
        ("position_mm,deviation_um,deviation_nm\n0,1,1\n1,2,2\n", "more than one column", 1),
        ("position_mm,deviation_um\n5,1\n5,2\n", "distinct positions", 2),
        ("position_mm,deviation_um\n0,1\n1,x\n", "not a number", 3),
    ],
)
def test_read_profile_names_file_and_line(tmp_path, text, message, line):
    path = tmp_path / "p.csv"
    path.write_text(text)
    with pytest.raises(AxiscalError, match=message) as info:
        read_profile(path)
    assert info.value.line == line and info.value.path is not None


def test_read_profile_increasing(tmp_path):
    path = tmp_path / "p.csv"
    path.write_text("position_mm,deviation_um\n0,1\n2,1\n1,1\n")
    read_profile(path)
    with pytest.raises(AxiscalError, match="must increase") as info:
        read_profile(path, increasing=True)
    assert info.value.line == 4


def test_read_probe_readings_and_reversal_runs(tmp_path):
    path = tmp_path / "r.csv"
    path.write_text("position_mm,a_um,b_um,c_um\n0,1,2,3\n1,1,2,3\n2,1,2,3\n")
    data = read_probe_readings(path, spacing_ab_m=1 * MM)
    assert data.spacing_bc_m == data.spacing_ab_m == 1 * MM
    np.testing.assert_allclose(data.c_m, [3e-6] * 3)
    assert read_probe_readings(path, spacing_ab_m=1 * MM, spacing_bc_m=2 * MM).spacing_bc_m == 2 * MM
    path.write_text("position_mm,a_um,b_um\n0,1,2\n1,1,2\n3,1,2\n")
    with pytest.raises(AxiscalError, match="evenly stepped") as info:
        read_probe_readings(path, spacing_ab_m=1 * MM)
    assert info.value.line == 4
    normal, turned = tmp_path / "n.csv", tmp_path / "t.csv"
    normal.write_text("position_mm,a_um\n0,0.5\n10,1.0\n")
    turned.write_text("position_mm,a_um\n0,1.5\n11,1.0\n")
    with pytest.raises(AxiscalError, match="same positions") as info:
        read_reversal_runs(normal, turned)
    assert info.value.line == 3


def test_evaluate_straightness_file_matches_the_api(examples):
    run = evaluate_straightness_file(examples / "straightness_profile.csv", reference="minimum-zone")
    line = reference_line(run.profile.position_m, run.profile.deviation_m, reference="minimum-zone")
    assert run.line == line
    assert run.payload()["straightness_um"] == pytest.approx(line.straightness_m / UM)
    assert run.report().splitlines()[0] == f"straightness  {line.straightness_m / UM:.4f} um  (minimum-zone reference line)"


@pytest.mark.parametrize("method", ["stp", "strp", "gtp", "frequency", "combined"])
def test_separate_writes_a_plain_csv_with_a_sidecar(examples, tmp_path, method):
    out = tmp_path / f"{method}.csv"
    run = separate_file(examples / "probe_readings.csv", method=method, spacing_ab_m=15 * MM, output=out)
    text = out.read_text()
    assert text == run.csv_text and not text.startswith("#")
    frame = pd.read_csv(out)
    assert list(frame.columns) == list(separation_columns(run.separation))
    np.testing.assert_allclose(frame["profile_um"], run.separation.profile_m / UM, atol=1e-5)
    sidecar = json.loads(out.with_suffix(".json").read_text())
    assert sidecar["kind"] == "separation" and sidecar["method"] == run.separation.method
    assert sidecar["sources"] == [str(examples / "probe_readings.csv")]
    if method == "frequency":
        assert sidecar["lost_wavelength_mm"]  # harmonics at the zeros of the gain are left out


def test_what_separate_writes_is_a_straightness_input(examples, tmp_path):
    out = tmp_path / "separated.csv"
    run = separate_file(examples / "probe_readings.csv", method="strp", spacing_ab_m=15 * MM, output=out)
    evaluation = evaluate_straightness_file(out, reference="least-squares")
    expected = reference_line(run.separation.position_m, run.separation.profile_m)
    assert evaluation.line.straightness_m == pytest.approx(expected.straightness_m, abs=1e-11)
    np.testing.assert_allclose(evaluation.profile.position_m, run.separation.position_m, atol=1e-10)


def test_reversal_from_files(tmp_path):
    normal, turned = tmp_path / "n.csv", tmp_path / "t.csv"
    normal.write_text("position_mm,a_um\n0,0.5\n10,1.0\n20,0.0\n")
    turned.write_text("position_mm,a_um\n0,1.5\n10,1.0\n20,2.0\n")
    run = separate_file(normal, method="reversal", reversed_path=turned)
    expected = reversal(*read_reversal_runs(normal, turned))
    np.testing.assert_allclose(run.separation.profile_m, expected.profile_m)
    with pytest.raises(AxiscalError, match="reversed_path"):
        separate_file(normal, method="reversal")
    with pytest.raises(AxiscalError, match="spacing_ab_m"):
        separate_file(normal, method="stp")


def test_simulate_probe_readings_writes_a_plain_csv_with_a_sidecar(examples, tmp_path, same_text_to_precision):
    out = tmp_path / "readings.csv"
    simulated = simulate_probe_readings(
        examples / "separation_profile.csv",
        examples / "separation_motion.csv",
        spacing_ab_m=15 * MM,
        step_m=1 * MM,
        noise_m=0.005 * UM,
        offsets_m=(0.0, 0.05 * UM, 0.02 * UM),
        output=out,
    )
    assert out.read_text() == simulated.csv_text
    same_text_to_precision((examples / "probe_readings.csv").read_text(), out.read_text(), name="probe_readings.csv")
    frame = pd.read_csv(out)
    assert list(frame.columns) == ["position_mm", "a_um", "b_um", "c_um"]
    sidecar = json.loads(out.with_suffix(".json").read_text())
    assert sidecar["kind"] == "probe readings" and sidecar["spacing_ab_mm"] == pytest.approx(15)
    assert sidecar["noise_um"] == pytest.approx(0.005) and sidecar["seed"] == 0
    # the readings read back are the readings simulated, to the printed precision
    back = read_probe_readings(out, spacing_ab_m=15 * MM)
    np.testing.assert_allclose(back.b_m, simulated.readings.b_m, atol=1e-12)


def test_a_motion_with_a_gap_in_its_yaw_is_refused(examples, tmp_path):
    motion = tmp_path / "motion.csv"
    motion.write_text("position_mm,deviation_um,yaw_urad\n0,0,1\n100,0,\n300,0,1\n")
    with pytest.raises(AxiscalError, match="yaw_urad") as info:
        simulate_probe_readings(examples / "separation_profile.csv", motion, spacing_ab_m=15 * MM, step_m=1 * MM)
    assert info.value.line == 3


@settings(max_examples=40, deadline=None)
@given(
    st.sampled_from([("mm", MM), ("m", 1.0), ("um", UM)]),
    st.sampled_from([("um", UM), ("nm", 1e-9), ("mm", MM)]),
    st.lists(st.floats(-1e3, 1e3, allow_nan=False), min_size=2, max_size=20),
)
def test_read_profile_round_trips_any_unit(tmp_path_factory, position_unit, deviation_unit, values):
    (p_name, p_factor), (d_name, d_factor) = position_unit, deviation_unit
    positions = [7.0 * k for k in range(len(values))]
    path = tmp_path_factory.mktemp("units") / "p.csv"
    rows = "".join(f"{p!r},{v!r}\n" for p, v in zip(positions, values))
    path.write_text(f"position_{p_name},deviation_{d_name}\n{rows}")
    profile = read_profile(path)
    np.testing.assert_allclose(profile.position_m, np.array(positions) * p_factor, rtol=1e-15)
    np.testing.assert_allclose(profile.deviation_m, np.array(values) * d_factor, rtol=1e-15)
