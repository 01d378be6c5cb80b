"""The measurement pipeline: raw frames -> errors -> Abbe-Bryan -> HTM (paper 000, sections 2-3)."""

from __future__ import annotations

import numpy as np
import pytest

from axiscal.errors import AxiscalError
from axiscal.measurement import FAULT_MISSING, FAULT_POSITION, FAULT_RANGE, spatial_error
from axiscal.virtual import VirtualModule


@pytest.fixture(scope="module")
def exact():
    module = VirtualModule(noise=False)
    return module, module.measurement_system()


@pytest.fixture(scope="module")
def noisy():
    module = VirtualModule(seed=4)
    return module, module.measurement_system()


def test_contract_attributes(exact):
    _, system = exact
    assert system.axes == ("X", "Z")
    assert system.channels[:7] == ("x_cmd_mm", "x_scale_mm", "x_psd_y_um", "x_psd_z_um", "x_qd_u_um", "x_qd_v_um", "x_roll_um")
    assert set(system.channel_limits) == set(system.channels)
    for low, high in system.channel_limits.values():
        assert low < high


@pytest.mark.parametrize("path", ["diagonal", "raster", "back-and-forth"])
def test_noise_free_frames_give_the_truth(exact, path):
    module, system = exact
    frames, truth = module.frames(np.linspace(0.0, 20.0, 4001), path=path)
    out = system.process(frames)
    assert np.all(out["fault"] == 0)
    for key, tolerance in (("ex_um", 1e-4), ("ey_um", 1e-4), ("ez_um", 1e-4), ("e_um", 1e-4), ("px_mm", 1e-7), ("pz_mm", 1e-7), ("x_mm", 1e-7)):
        np.testing.assert_allclose(out[key], truth[key], atol=tolerance, err_msg=key)
    for letter in ("X", "Z"):
        for name in ("EXX", "EYX", "EZX") if letter == "X" else ("EXZ", "EYZ", "EZZ"):
            np.testing.assert_allclose(out[f"{name}_um"], truth[f"{name}_um"], atol=1e-4)
        for name in ("EAX", "EBX", "ECX") if letter == "X" else ("EAZ", "EBZ", "ECZ"):
            np.testing.assert_allclose(out[f"{name}_urad"], truth[f"{name}_urad"], atol=1e-3)


def test_noisy_frames_within_the_noise(noisy):
    # paper 000 abstract: +-1.2 um positioning, +-1.3 um straightness, +-1 arcsec angles
    module, system = noisy
    frames, truth = module.frames(np.linspace(0.0, 15.0, 3000), path="raster")
    out = system.process(frames)
    good = out["fault"] == 0
    assert good.mean() > 0.95
    for name in ("EXX_um", "EZZ_um"):
        assert np.max(np.abs(out[name] - truth[name])[good]) < 1.2
    for name in ("EYX_um", "EZX_um", "EXZ_um", "EYZ_um"):
        assert np.max(np.abs(out[name] - truth[name])[good]) < 1.3
    for name in ("EAX_urad", "EBX_urad", "ECX_urad", "EAZ_urad", "EBZ_urad", "ECZ_urad"):
        assert np.max(np.abs(out[name] - truth[name])[good]) < 4.85  # 1 arcsec
    for name in ("ex_um", "ey_um", "ez_um"):
        assert np.max(np.abs(out[name] - truth[name])[good]) < 2.0


def test_pipeline_matches_machine_model_at_table_nodes(exact):
    # the per-frame HTM equals the lead's table-driven Machine.volumetric_error where the table is exact
    module, system = exact
    q = np.linspace(0.0, 0.19, 39)
    positions = {"X": q, "Z": q[::-1].copy()}
    frames, _ = module.frames_at(positions)
    out = system.process(frames)
    expected = module.machine.volumetric_error(positions) * 1e6
    np.testing.assert_allclose(np.column_stack([out["ex_um"], out["ey_um"], out["ez_um"]]), expected, atol=1e-4)


def test_spatial_error_reduces_to_paper_eq_10(exact):
    # paper 000 eq (10), first order: with only X pitch and squareness, ex = (zm + z0)(eps_y(x) + alpha_xz)
    module, _ = exact
    n = 5
    zm = np.linspace(0.0, 0.19, n)
    errors = {"X": np.zeros((6, n)), "Z": np.zeros((6, n))}
    errors["X"][4] = 20e-6
    e = spatial_error(module.machine, {"X": np.full(n, 0.1), "Z": zm}, errors)
    alpha = module.machine.squareness_rad["EB0Z"]
    np.testing.assert_allclose(e[:, 0], (zm + 0.05) * (20e-6 + alpha), rtol=1e-6)
    # y2 (epsilon_z(x) + epsilon_z(z)) term: yaw of either axis times the 40 mm tool offset
    errors = {"X": np.zeros((6, n)), "Z": np.zeros((6, n))}
    errors["X"][5] = 10e-6
    errors["Z"][5] = 5e-6
    e = spatial_error(module.machine, {"X": np.zeros(n), "Z": zm}, errors)
    np.testing.assert_allclose(e[:, 0] - (zm + 0.05) * alpha, 0.040 * 15e-6, rtol=1e-4)


def test_faults_are_flagged_not_raised(exact):
    module, system = exact
    frames, _ = module.frames(np.linspace(0.0, 1.0, 6))
    frames = {k: v.copy() for k, v in frames.items()}
    frames["x_psd_y_um"][1] = np.nan
    frames["z_qd_u_um"][2] = 1e6
    frames["x_cmd_mm"][3] = 191.0
    del frames["z_roll_um"]
    out = system.process(frames)
    assert np.all(out["fault"] & FAULT_MISSING)
    frames["z_roll_um"] = np.zeros(6)
    out = system.process(frames)
    assert out["fault"][0] == 0
    assert out["fault"][1] == FAULT_MISSING
    assert out["fault"][2] == FAULT_RANGE
    assert out["fault"][3] == FAULT_POSITION
    for k in (1, 2, 3):
        assert np.isnan(out["ex_um"][k]) and np.isnan(out["EXX_um"][k])
        assert out["t_s"][k] == frames["t_s"][k]
    assert np.isfinite(out["ex_um"][0])
    assert system.fault_text(0) == "ok"
    assert system.fault_text(FAULT_MISSING | FAULT_POSITION) == "missing channel; position outside the error model"


def test_ragged_batch_is_a_user_error(exact):
    _, system = exact
    with pytest.raises(AxiscalError, match="different lengths"):
        system.process({"t_s": np.zeros(3), "x_cmd_mm": np.zeros(2)})


def test_channel_faults(exact):
    module, system = exact
    frames, _ = module.frames(np.linspace(0.0, 1.0, 4))
    frames = dict(frames)
    frames["x_roll_um"] = np.array([0.0, np.nan, 1e9, 0.0])
    bits = system.channel_faults(frames)
    assert list(bits["x_roll_um"]) == [0, 1, 2, 0]
    assert not np.any(bits["x_psd_y_um"])
