"""The simulated campaign: each kind's file, evaluated by its own library call, gives back the virtual module's truth."""

from __future__ import annotations

import numpy as np
import pandas as pd
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from axiscal.errors import AxiscalError
from axiscal.instruments.air import refractive_index
from axiscal.materials import STEEL_EXPANSION_PER_K
from axiscal.measurement.campaign_sim import (
    PRISM_DEVIATION_RAD,
    REPEATABILITY_M,
    REVERSAL_M,
    laser_run,
    probe_readings,
    squareness_runs,
    write_campaign,
)
from axiscal.measurement.virtual import INTERFEROMETER_BEAM_M, VirtualModule
from axiscal.model.machine import load_machine
from axiscal.positioning.report import evaluate_positioning_file
from axiscal.squareness.evaluation import squareness_from_files
from axiscal.straightness.files import separate_file
from axiscal.units import ARCSEC, MM, UM

pytestmark = pytest.mark.filterwarnings("ignore::UserWarning")


@pytest.fixture(scope="module")
def campaign(tmp_path_factory):
    return write_campaign(tmp_path_factory.mktemp("campaign"), seed=0)


@pytest.fixture(scope="module")
def module():
    return VirtualModule(seed=0, noise=False)


@pytest.mark.parametrize("letter", ["X", "Z"])
def test_laser_runs_compensated_give_the_axis_error_and_reversal(campaign, module, letter):
    evaluation = evaluate_positioning_file(campaign.folder / f"positioning_{letter.lower()}.csv",
                                           wavelength_nm=632.99137)
    result = evaluation.result
    # air index and steel expansion undone: the mean deviations follow the true error at the beam,
    # and the reversal is the one the simulation put in
    assert abs(result.figures()["B_mean"]) == pytest.approx(REVERSAL_M[letter], abs=0.3 * UM)
    assert result.figures()["R"] < 5 * UM
    # the true error along the axis at the beam (Abbe-Bryan, written out), over the targets
    q = np.unique(pd.read_csv(campaign.folder / f"positioning_{letter.lower()}.csv")["target_mm"]) * MM
    e = module.true_errors(letter, q)
    beam = np.asarray(module.heads[letter].scale_point_m) + INTERFEROMETER_BEAM_M
    true = e[:3].T + np.cross(e[3:].T, beam)
    true_range = np.ptp(true[:, "XYZ".index(letter)])
    assert result.figures()["A"] == pytest.approx(true_range + REVERSAL_M[letter], abs=1.5 * UM)


def _less_parabola(q, value):
    return value - np.polyval(np.polyfit(q, value, 2), q)


def test_separation_finds_the_slide_motion(campaign, module):
    # the combined method resolves S up to the parabola of the yaw's removed slope (docs/straightness.md)
    run = separate_file(campaign.folder / "probes_x.csv", method="combined", spacing_ab_m=15 * MM)
    s = run.separation
    ok = np.isfinite(s.motion_m)
    q = s.position_m[ok]
    found = _less_parabola(q, s.motion_m[ok])
    true = _less_parabola(q, module.true_errors("X", q)[2])
    assert np.ptp(true) > 1 * UM
    assert np.max(np.abs(found - true)) < 0.3 * UM  # probe noise summed along the record (STP, eq 9)


def test_squareness_by_pentaprism_is_the_module_s(campaign):
    evaluation = squareness_from_files(campaign.folder / "square_x.csv", campaign.folder / "square_z.csv", plane="XZ",
                                       prism_deviation_rad=2.5 * ARCSEC, convention="iso")
    assert evaluation.result.iso_term == "EB0Z"
    assert evaluation.payload()["iso_value_arcsec"] == pytest.approx(-42.4, abs=0.1)  # paper 000 section 5


def test_the_loaded_diagonal_is_the_built_in_example_s(campaign, examples):
    # the same simulation the built-in diagonal_laser.csv (2 kg) was made with
    built_in = pd.read_csv(examples.parent / "src" / "axiscal" / "data" / "xz_module" / "diagonal_laser.csv")
    written = pd.read_csv(campaign.folder / "diagonal_2kg.csv")
    assert list(written.columns) == ["nominal_mm", "measured_mm"]
    np.testing.assert_allclose(written.to_numpy(), built_in.to_numpy(), atol=2e-6)


def test_the_model_is_the_built_in_xz_module(campaign):
    machine = load_machine(campaign.folder / "machine.toml")
    assert machine.chain == "FXZ" and machine.squareness_rad["EB0Z"] == pytest.approx(-42.4 * ARCSEC)


COLUMNS = {
    "positioning_x.csv": ["target_mm", "run", "direction", "actual_mm", "air_temperature_c", "pressure_pa",
                          "humidity_pct", "material_temperature_c"],
    "positioning_z.csv": ["target_mm", "run", "direction", "actual_mm", "air_temperature_c", "pressure_pa",
                          "humidity_pct", "material_temperature_c"],
    "probes_x.csv": ["position_mm", "a_um", "b_um", "c_um"],
    "square_x.csv": ["position_mm", "deviation_um"],
    "square_z.csv": ["position_mm", "deviation_um"],
    "diagonal_0kg.csv": ["nominal_mm", "measured_mm"],
    "diagonal_2kg.csv": ["nominal_mm", "measured_mm"],
    "sensor_calibration_runs.csv": ["channel", "raw", "reference"],
}


def test_data_csvs_are_plain_with_a_sidecar(campaign):
    for name, columns in COLUMNS.items():
        table = pd.read_csv(campaign.folder / name)
        assert list(table.columns) == columns, name
        assert len(table) > 10 and (campaign.folder / name).with_suffix(".json").is_file(), name
    frames = pd.read_csv(campaign.folder / "sixdof_diagonal_2kg.csv")
    assert frames.columns[0] == "t_s" and len(frames) == 380


def test_the_campaign_is_reproducible(campaign, tmp_path):
    again = write_campaign(tmp_path, seed=0)
    assert again.files == campaign.files
    for name in campaign.files:
        assert (tmp_path / name).read_bytes() == (campaign.folder / name).read_bytes(), name


def test_probe_readings_and_squareness_runs_have_one_row_per_position(module):
    probes = probe_readings(module)
    assert len({len(v) for v in probes.values()}) == 1 and probes["position_mm"][-1] == pytest.approx(190.0)
    first, second = squareness_runs(module, points=7)
    assert first["position_mm"].size == second["deviation_um"].size == 7


def test_mistakes_are_axiscal_errors(tmp_path, module):
    with pytest.raises(AxiscalError, match="no axis 'Y'"):
        laser_run(module, "Y")
    blocker = tmp_path / "file"
    blocker.write_text("")
    with pytest.raises(AxiscalError, match="campaign folder"):
        write_campaign(blocker / "campaign")


@settings(max_examples=8, deadline=None)
@given(seed=st.integers(min_value=0, max_value=10_000))
def test_any_seed_squareness_runs_give_the_module_s_squareness(seed, tmp_path_factory):
    folder = tmp_path_factory.mktemp("square")
    first, second = squareness_runs(VirtualModule(seed=seed), seed=seed)
    for name, run in (("x.csv", first), ("z.csv", second)):
        pd.DataFrame(run).to_csv(folder / name, index=False)
    evaluation = squareness_from_files(folder / "x.csv", folder / "z.csv", plane="XZ",
                                       prism_deviation_rad=PRISM_DEVIATION_RAD, convention="iso")
    # 0.1 um reading noise on 20 points over 190 mm: about 0.11 arcsec (1 sigma) on the two slopes together
    assert evaluation.payload()["iso_value_arcsec"] == pytest.approx(-42.4, abs=0.5)


@settings(max_examples=8, deadline=None)
@given(seed=st.integers(min_value=0, max_value=10_000), letter=st.sampled_from(["X", "Z"]))
def test_any_seed_laser_readings_undo_to_the_true_position(seed, letter):
    # reference implementation of the raw reading, undone: p20 = reading / ((1 + alpha dT) n_air)
    module = VirtualModule(seed=seed, noise=False)
    run = laser_run(module, letter, seed=seed)
    n_air = refractive_index(run["air_temperature_c"], run["pressure_pa"], run["humidity_pct"], 632.99137)
    p20 = run["actual_mm"] * MM / ((1 + STEEL_EXPANSION_PER_K * (run["material_temperature_c"] - 20.0)) * n_air)
    target = run["target_mm"] * MM
    e = module.true_errors(letter, target)
    beam = np.asarray(module.heads[letter].scale_point_m) + INTERFEROMETER_BEAM_M
    true = target + (e[:3].T + np.cross(e[3:].T, beam))[:, "XYZ".index(letter)]
    sign = np.where(run["direction"] == "+", -1.0, 1.0)
    left = p20 - true - sign * REVERSAL_M[letter] / 2 - 0.05 * UM * (run["run"] - 1)
    assert np.max(np.abs(left)) < 6 * REPEATABILITY_M  # only the scatter is left
