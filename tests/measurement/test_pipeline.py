"""The measurement pipeline: raw frames -> errors -> Abbe-Bryan -> HTM (paper 000, sections 2-3)."""

from __future__ import annotations

import json

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from axiscal.errors import AxiscalError
from axiscal.measurement.display import to_display
from axiscal.measurement.faults import Fault
from axiscal.measurement.pipeline import spatial_error
from axiscal.measurement.virtual import VirtualModule


@pytest.fixture(scope="module")
def exact():
    module = VirtualModule(noise=False)
    return module, module.measurement_system()


_NOISY_MODULE = VirtualModule(seed=4)
_NOISY = (_NOISY_MODULE, _NOISY_MODULE.measurement_system())


@pytest.fixture(scope="module")
def noisy():
    return _NOISY


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
    truth = to_display(truth)
    out = to_display(system.process(frames))
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
    truth = to_display(truth)
    out = to_display(system.process(frames))
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
    out = to_display(system.process(frames))
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
    out = to_display(system.process(frames))
    assert np.all(out["fault"] & Fault.MISSING)
    frames["z_roll_um"] = np.zeros(6)
    out = to_display(system.process(frames))
    assert out["fault"][0] == 0
    assert out["fault"][1] == Fault.MISSING
    assert out["fault"][2] == Fault.RANGE
    assert out["fault"][3] == Fault.POSITION
    for k in (1, 2, 3):
        assert np.isnan(out["ex_um"][k]) and np.isnan(out["EXX_um"][k])
        assert out["t_s"][k] == frames["t_s"][k]
    assert np.isfinite(out["ex_um"][0])
    assert system.fault_text(0) == "ok"
    assert system.fault_text(Fault.MISSING | Fault.POSITION) == "missing channel; position outside the error model"


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


# --- the shipped example, the TOML reader and the command line ---------------------------------

def test_example_machine_is_the_virtual_module(examples):
    from axiscal.measurement.pipeline import MeasurementSystem

    system = MeasurementSystem.from_toml(examples / "xz_module" / "sensors_machine.toml")
    module = VirtualModule(seed=0)
    assert system.channels == module.measurement_system().channels
    for letter, head in module.heads.items():
        read = system.heads[letter]
        np.testing.assert_allclose(read.offsets_m(), head.offsets_m(), atol=1e-15)
        assert (read.qd_u, read.qd_v, read.roll) == (head.qd_u, head.qd_v, head.roll)
        assert read.qd_focal_m == pytest.approx(head.qd_focal_m) and read.roll_focal_m == pytest.approx(head.roll_focal_m)
        assert read.psd_range_m == pytest.approx(head.psd_range_m)
    assert system.calibration.channel("x_psd_y_um").gain == pytest.approx(module.calibration.channel("x_psd_y_um").gain)
    frames, truth = module.frames(np.linspace(0.0, 4.0, 300), path="raster")
    truth = to_display(truth)
    out = to_display(system.process(frames))
    good = out["fault"] == 0
    assert np.max(np.abs(out["ex_um"] - truth["ex_um"])[good]) < 2.0


def test_measure_command_matches_the_pipeline(examples, run_cli, tmp_path):
    from axiscal.io.tabular import read_csv
    from axiscal.measurement.offline import read_frames

    frames_path = examples / "xz_module" / "sensors_frames.csv"
    output = tmp_path / "out.csv"
    status, out, err = run_cli("measure", frames_path, "--machine", examples / "xz_module" / "sensors_machine.toml", "-o", output)
    assert status == 0, err
    assert "200 frames, 2 faulty" in out
    system = VirtualModule(seed=0).measurement_system()
    expected = to_display(system.process(read_frames(frames_path, system.channels)))
    table = read_csv(output)
    fault = table.numeric("fault")
    assert list(np.flatnonzero(fault)) == [50, 120]
    assert fault[50] == 1 and fault[120] == 2
    good = fault == 0
    written = np.array([float(c) for c in table.text("ex_um")])
    np.testing.assert_allclose(written[good], expected["ex_um"][good], rtol=1e-8)
    assert table.text("ex_um")[50] == "nan"


def test_measure_command_default_system_and_json(examples, run_cli):
    status, out, err = run_cli("measure", examples / "xz_module" / "sensors_frames.csv", "--json")
    assert status == 0, err
    assert '"faulty_frames": 2' in out
    status, out, _ = run_cli("measure", examples / "xz_module" / "sensors_frames.csv")
    assert status == 0 and out.startswith("t_s,fault,") and "ex_um" in out.splitlines()[0]


def test_measure_command_bad_input(examples, run_cli, tmp_path):
    bad = tmp_path / "frames.csv"
    bad.write_text("t_s,x_cmd_mm\n0,1\n")
    status, _, err = run_cli("measure", bad)
    assert status == 2
    assert err.startswith("axiscal: error:") and "missing column 'x_scale_mm'" in err and err.count("\n") == 1
    status, _, err = run_cli("measure", tmp_path / "none.csv")
    assert status == 2 and "file not found" in err
    text = (examples / "xz_module" / "sensors_frames.csv").read_text().splitlines()
    header = next(i for i, line in enumerate(text) if not line.startswith("#"))
    text[header + 3] = "abc" + text[header + 3][text[header + 3].index(","):]
    bad.write_text("\n".join(text) + "\n")
    status, out, err = run_cli("measure", bad, "--json")
    assert status == 0, err  # a time stamp that cannot be read makes a malformed frame (as the replay source does), not an error
    assert json.loads(out)["faulty_frames"] == 3  # the two faulty frames of the file and the malformed one
    text[header + 3] = text[header + 3] + ",1"
    bad.write_text("\n".join(text) + "\n")
    status, _, err = run_cli("measure", bad)
    assert status == 2 and "cells where the header has" in err and f"frames.csv:{header + 4}:" in err


def test_simulate_frames_then_measure(run_cli, tmp_path):
    frames = tmp_path / "sim.csv"
    status, out, err = run_cli("simulate", "frames", "--path", "raster", "--rate", "200", "--duration", "2", "--truth", "-o", frames)
    assert status == 0, err
    status, out, err = run_cli("measure", frames, "-o", tmp_path / "r.csv")
    assert status == 0, err
    from axiscal.io.tabular import read_csv

    results, truth = read_csv(tmp_path / "r.csv"), read_csv(frames)
    good = results.numeric("fault") == 0
    for key in ("ex_um", "ez_um"):
        measured = np.array([float(c) for c in results.text(key)])[good]
        assert np.max(np.abs(measured - truth.numeric(f"truth_{key}")[good])) < 2.0
    status, _, err = run_cli("simulate", "frames", "--rate", "1e9", "--duration", "1")
    assert status == 2 and "frames; allowed" in err


def test_calibrate_commands_on_the_examples(examples, run_cli, tmp_path):
    folder = examples / "xz_module"
    output = tmp_path / "cal.json"
    status, out, err = run_cli("calibrate", "sensitivity", folder / "sensors_psd_run.csv", "--channel", "x_psd_y_um", "-o", output, "--json")
    assert status == 0, err
    module = VirtualModule(seed=0)
    truth = module.sensor_truth["x_psd_y_um"]
    from axiscal.instruments.calibration import load_calibration

    fit = load_calibration(output).channel("x_psd_y_um")
    assert abs(fit.gain - truth.gain) < 0.003 and abs(fit.offset - truth.offset) < 0.2
    # the interferometer's beam is 45 mm above and 20 mm beside the read head: transferring it (section 4.2) matters
    status, out, err = run_cli(
        "calibrate", "sensitivity", folder / "sensors_scale_run.csv", "--channel", "x_scale_mm", "--reference-offset-mm", "0,-45,-20", "-o", output, "--json"
    )
    assert status == 0, err
    import json

    transferred = json.loads(out)
    status, out, _ = run_cli("calibrate", "sensitivity", folder / "sensors_scale_run.csv", "--channel", "x_scale_mm", "--json")
    plain = json.loads(out)
    assert transferred["residual_max_mm"] < 0.5e-3 < plain["residual_max_mm"]
    status, out, err = run_cli("calibrate", "sensitivity", folder / "sensors_qd_run.csv", "--channel", "x_qd_u_um", "--json")
    assert status == 0 and json.loads(out)["residual_max_arcsec"] < 1.0
    status, out, err = run_cli("calibrate", "mirror", folder / "sensors_mirror_run.csv", "--axis", "x", "-o", output, "--json")
    assert status == 0, err
    saved = load_calibration(output)
    assert set(saved.channels) == {"x_psd_y_um", "x_scale_mm"} and "X" in saved.mirrors
    q = np.linspace(0.0, 0.19, 50)
    assert np.max(np.abs(saved.mirrors["X"].evaluate(q) - module.mirror_error("X", q))) < 1.5e-6


@pytest.mark.parametrize(
    ("args", "message"),
    [
        (("calibrate", "sensitivity", "sensors_psd_run.csv", "--channel", "x_nope_um"), "unknown channel 'x_nope_um'"),
        (("calibrate", "sensitivity", "sensors_qd_run.csv", "--channel", "x_psd_y_um"), "missing column 'x_psd_y_um'"),
        (("calibrate", "sensitivity", "sensors_psd_run.csv", "--channel", "x_psd_y_um", "--reference-offset-mm", "1,2"), "expected three numbers"),
        (("calibrate", "sensitivity", "sensors_psd_run.csv", "--channel", "x_psd_y_um", "--reference-offset-mm", "1,2,3"), "missing column 'EAX_urad'"),
        (("calibrate", "sensitivity", "sensors_qd_run.csv", "--channel", "x_qd_u_um", "--reference-offset-mm", "1,2,3"), "translation channels"),
        (("calibrate", "mirror", "sensors_psd_run.csv", "--axis", "X"), "missing column 'position_mm'"),
        (("calibrate", "mirror", "sensors_mirror_run.csv", "--axis", "Y"), "axis Y has no sensors"),
        (("experiment", "diagonal", "--load-kg", "-1"), "load-kg"),
        (("measure", "sensors_frames.csv", "--machine", "machine.toml"), "no sensors section"),
    ],
)
def test_bad_command_lines(examples, run_cli, monkeypatch, args, message):
    monkeypatch.chdir(examples / "xz_module")
    status, _, err = run_cli(*args)
    assert status == 2
    assert message in err


def test_calibrate_psd_with_angle_reference_is_refused(examples, run_cli, tmp_path):
    run = tmp_path / "run.csv"
    run.write_text("x_psd_y_um,reference_arcsec\n1,1\n2,2\n3,3\n")
    status, _, err = run_cli("calibrate", "sensitivity", run, "--channel", "x_psd_y_um")
    assert status == 2 and "reference unit must be one of nm, um, mm" in err


def test_experiment_diagonal_command(run_cli, tmp_path):
    import json

    plot = tmp_path / "diagonal.png"
    status, out, err = run_cli("experiment", "diagonal", "--json", "--plot", plot)
    assert status == 0, err
    result = json.loads(out)
    assert 60.0 < result["before_max_um"] < 75.0
    assert result["after_max_um"] < 2.0
    assert len(result["points"]) == 20
    assert plot.stat().st_size > 10_000
    status, out, err = run_cli("experiment", "diagonal", "--load-kg", "2")
    assert status == 0 and "paper 000: 56 -> 14 um" in out


# --- the fast pipeline against a plain per-frame reference, and batching invariance ------------

def _reference_frame(system, frame: dict[str, float]) -> np.ndarray:
    """One frame by hand: calibration, eqs 1-3, eq 12, the vector Abbe-Bryan transfer and the
    4x4 product of paper 000 eq (9), P'_0 = T01 dT01 Cxz T12 dT12 P2, minus the nominal point."""
    from axiscal.model.kinematics import error_matrix, translation_matrix

    errors = {}
    for letter in ("X", "Z"):
        head = system.heads[letter]
        names = head.channels
        value = {role: system.calibration.channel(name).apply(frame[name]) for role, name in names.items()}
        cmd = value["cmd"] * 1e-3
        eps = np.zeros(3)
        eps[head.qd_u.index - 3] = head.qd_u.sign * value["qd_u"] * 1e-6 / head.qd_focal_m
        eps[head.qd_v.index - 3] = head.qd_v.sign * value["qd_v"] * 1e-6 / head.qd_focal_m
        roll = head.roll.sign * value["roll"] * 1e-6 / (2 * head.roll_focal_m)
        eps[head.roll.index - 3] = roll - head.roll.sign * system.calibration.mirrors[letter].evaluate(np.array([cmd]))[0]
        at_scale = np.zeros(3)
        at_scale[head.index] = value["scale"] * 1e-3 - cmd
        at_psd = np.zeros(3)
        for d in head.cross_directions:
            at_psd["xyz".index(d)] = value[f"psd_{d}"] * 1e-6
        delta = at_psd + np.cross(eps, -np.asarray(head.psd_point_m))
        delta[head.index] = (at_scale + np.cross(eps, -np.asarray(head.scale_point_m)))[head.index]
        errors[letter] = (cmd, np.concatenate([delta, eps]))
    (xm, ex), (zm, ez) = errors["X"], errors["Z"]
    alpha = system.machine.squareness_rad["EB0Z"]
    c_xz = np.eye(4)
    c_xz[0, 2], c_xz[2, 0] = alpha, -alpha
    p2 = np.array([*system.machine.tool_m, 1.0])
    t01, t12 = translation_matrix([xm, 0, 0]), translation_matrix([0, 0, zm + 0.05])
    actual = t01 @ error_matrix(*ex) @ c_xz @ t12 @ error_matrix(*ez) @ p2
    nominal = t01 @ t12 @ p2
    return (actual - nominal)[:3]


def test_pipeline_against_plain_reference(noisy):
    module, system = noisy
    frames, _ = module.frames(np.random.default_rng(0).uniform(0.0, 60.0, 40), path="raster")
    out = to_display(system.process(frames))
    for k in range(40):
        expected = _reference_frame(system, {name: frames[name][k] for name in system.channels})
        np.testing.assert_allclose([out["ex_um"][k], out["ey_um"][k], out["ez_um"][k]], expected * 1e6, atol=1e-6)


@settings(max_examples=30, deadline=None)
@given(st.lists(st.integers(1, 299), max_size=6))
def test_splitting_a_stream_into_batches_changes_nothing(cuts):
    # the same code path serves a file (one batch) and a stream (many small ones)
    module, system = _NOISY
    frames, _ = module.frames(np.linspace(0.0, 9.0, 300), path="back-and-forth")
    frames["x_psd_z_um"][17] = np.nan
    whole = to_display(system.process(frames))
    edges = [0, *sorted(set(cuts)), 300]
    parts = [to_display(system.process({k: v[a:b] for k, v in frames.items()})) for a, b in zip(edges[:-1], edges[1:]) if b > a]
    for key, value in whole.items():
        np.testing.assert_array_equal(np.concatenate([p[key] for p in parts]), value)


def test_large_batches_are_chunked_transparently(exact):
    module, system = exact
    frames, _ = module.frames(np.linspace(0.0, 30.0, 40_000), path="raster")
    whole = to_display(system.process(frames))
    small = to_display(system.process({k: v[30_000:30_100] for k, v in frames.items()}))
    for key in ("ex_um", "fault", "EBZ_urad", "t_s"):
        np.testing.assert_array_equal(whole[key][30_000:30_100], small[key])
    assert whole["ex_um"].shape == (40_000,)


def test_simulate_laser_command(run_cli, tmp_path):
    output = tmp_path / "laser.csv"
    status, out, err = run_cli("simulate", "laser", "-o", output)
    assert status == 0 and "20 readings" in out, err
    from axiscal.io.tabular import read_csv

    table = read_csv(output)
    assert table.numeric("nominal_mm")[-1] == pytest.approx(268.7005768, abs=1e-6)
    status, _, err = run_cli("simulate", "laser", "--steps", "20")
    assert status == 2 and "leave the 190 mm travel" in err


# --- any chain: a 3-axis XFYZ machine read from TOML ---------------------------------------------

def _xfyz_system(tmp_path, examples, extra: str = ""):
    import shutil

    from axiscal.measurement.pipeline import MeasurementSystem

    for name in ("x_errors.csv", "y_errors.csv", "z_errors.csv"):  # tables are named relative to the machine file
        shutil.copy(examples / "xfyz_machine" / name, tmp_path / name)
    text = f"""
chain = "XFYZ"
tool_mm = [0.0, 0.0, -150.0]
[axes.X]
errors = "x_errors.csv"
[axes.X.sensors]
scale_point_mm = [0.0, -40.0, -60.0]
psd_point_mm = [10.0, 30.0, 20.0]
[axes.Y]
errors = "y_errors.csv"
[axes.Y.sensors]
scale_point_mm = [25.0, 0.0, -30.0]
psd_point_mm = [-20.0, 5.0, 40.0]
qd_focal_mm = 150.0
[axes.Z]
errors = "z_errors.csv"
[axes.Z.sensors]
scale_point_mm = [30.0, 15.0, 0.0]
psd_point_mm = [-10.0, 25.0, 5.0]
roll_focal_mm = 60.0
{extra}
[squareness]
EC0Y_arcsec = 4.0
EB0Z_arcsec = -6.5
EA0Z_arcsec = 3.2
"""
    path = tmp_path / "xfyz_sensors.toml"
    path.write_text(text)
    return MeasurementSystem.from_toml(path), path


def test_any_chain_matches_the_table_model(tmp_path, examples):
    # readings made from known constant error motions at P must give Machine.volumetric_error of a
    # machine whose tables hold those constants, workpiece-side axis included
    from axiscal.model.machine import Axis, Machine
    from axiscal.model.tables import ErrorTable

    system, _ = _xfyz_system(tmp_path, examples)
    assert system.axes == ("X", "Y", "Z") and len(system.channels) == 21
    rng = np.random.default_rng(0)
    n = 50
    positions = {k: rng.uniform(*system.machine.travel_m(k), n) for k in system.axes}
    frames = {"t_s": np.arange(n) * 1e-3}
    axes = {}
    for letter in system.axes:
        head = system.heads[letter]
        errors = np.concatenate([rng.normal(0, 5e-6, 3), rng.normal(0, 30e-6, 3)])
        start, end = system.machine.travel_m(letter)
        table = ErrorTable(letter, np.array([start, end]), np.tile(errors[:, None], (1, 2)))
        axes[letter] = Axis(letter, table, system.machine.axes[letter].origin_m)
        eps = errors[3:]
        at_scale = errors[:3] + np.cross(eps, head.scale_point_m)
        at_psd = errors[:3] + np.cross(eps, head.psd_point_m)
        names = head.channels
        q = positions[letter]
        frames[names["cmd"]] = q * 1e3
        frames[names["scale"]] = (q + at_scale[head.index]) * 1e3
        for d in head.cross_directions:
            frames[names[f"psd_{d}"]] = np.full(n, at_psd["xyz".index(d)] * 1e6)
        for role, focal in (("qd_u", head.qd_focal_m), ("qd_v", head.qd_focal_m), ("roll", 2 * head.roll_focal_m)):
            component = getattr(head, role)
            frames[names[role]] = np.full(n, component.sign * errors[component.index] * focal * 1e6)
    machine = Machine(chain="XFYZ", axes=axes, squareness_rad=system.machine.squareness_rad, tool_m=system.machine.tool_m)
    out = to_display(system.process(frames))
    assert np.all(out["fault"] == 0)
    expected = machine.volumetric_error(positions) * 1e6
    np.testing.assert_allclose(np.column_stack([out["ex_um"], out["ey_um"], out["ez_um"]]), expected, atol=1e-9)
    np.testing.assert_allclose(np.column_stack([out["px_mm"], out["py_mm"], out["pz_mm"]]), machine.actual_point(positions) * 1e3, atol=1e-12)


@pytest.mark.parametrize(
    ("extra", "message"),
    [
        ("[axes.Y.sensors.extra]\nfoo = 1", "unknown key extra"),
        ("[axes.Z.sensors.more]\nprefix = 1", "unknown key more"),
    ],
)
def test_bad_sensor_section_names_the_file(tmp_path, examples, extra, message):
    with pytest.raises(AxiscalError, match=message) as info:
        _xfyz_system(tmp_path, examples, extra)
    assert "xfyz_sensors.toml" in str(info.value)


@pytest.mark.parametrize(
    ("change", "message"),
    [
        (("[axes.Z.sensors]\n", '[axes.Z.sensors]\nprefix = "x"\n'), "channel name 'x_cmd_mm' is used twice"),
        (("[axes.Z.sensors]\n", '[axes.Z.sensors]\ncalibration = "none.json"\n'), "file not found"),
        (("[axes.Z.sensors]\n", "[axes.Z.sensors\n"), "malformed TOML"),
        (("[axes.Z.sensors]\n", "[axes.Z.nothing]\n"), "unknown key .?nothing"),
    ],
)
def test_bad_machine_files(tmp_path, examples, change, message):
    from axiscal.measurement.pipeline import MeasurementSystem

    _, path = _xfyz_system(tmp_path, examples)
    path.write_text(path.read_text().replace(*change))
    with pytest.raises(AxiscalError, match=message) as info:
        MeasurementSystem.from_toml(path)
    assert str(path) in str(info.value) or "none.json" in str(info.value)


@settings(max_examples=40, deadline=None)
@given(
    st.lists(st.tuples(st.integers(0, 19), st.integers(0, 13), st.sampled_from(["nan", "high", "low"])), max_size=8),
)
def test_injected_faults_are_flagged_exactly(injections):
    module, system = _NOISY
    frames, _ = module.frames(np.linspace(0.0, 3.0, 20), path="diagonal")
    frames = {k: v.copy() for k, v in frames.items()}
    expected = np.zeros(20, dtype=np.int64)
    for frame, channel_index, kind in injections:
        name = system.channels[channel_index]
        low, high = system.channel_limits[name]
        frames[name][frame] = {"nan": np.nan, "high": high + 1.0, "low": low - 1.0}[kind]
    for name in system.channels:
        value = frames[name]
        low, high = system.channel_limits[name]
        expected |= np.isnan(value).astype(np.int64)
        expected |= ((value < low) | (value > high)).astype(np.int64) << 1
        if name.endswith("_cmd_mm"):
            letter = name[0].upper()
            start, end = (v * 1e3 for v in system.machine.travel_m(letter))
            expected |= ((value < start) | (value > end)).astype(np.int64) << 2
    out = to_display(system.process(frames))
    np.testing.assert_array_equal(out["fault"], expected)
    assert np.all(np.isnan(out["ex_um"][expected != 0]))
    assert np.all(np.isfinite(out["ex_um"][expected == 0]))


def test_measure_drops_a_line_cut_by_a_crash(run_cli, tmp_path):
    record = tmp_path / "live.csv"
    status, out, err = run_cli("live", "--no-server", "--duration", "0.2", "--rate", "500", "--record", record)
    assert status == 0, err
    text = record.read_text()
    frames = len([line for line in text.splitlines() if line[:1].isdigit()])
    cut = tmp_path / "cut.csv"
    cut.write_text(text[: text.rindex("\n") - 40])  # killed while writing the last line
    status, out, err = run_cli("measure", cut, "--json")
    assert status == 0, err
    assert f'"frames": {frames - 1}' in out


def test_measure_keeps_the_last_frame_of_a_file_without_a_final_newline(examples, run_cli, tmp_path):
    text = (examples / "xz_module" / "sensors_frames.csv").read_text()
    bare = tmp_path / "bare.csv"
    bare.write_text(text.rstrip("\n"))  # written by a tool that does not end the last line
    status, out, err = run_cli("measure", bare, "--json")
    assert status == 0, err
    assert '"frames": 200' in out
    bare.write_text(text[: text.rindex("\n") - 40])  # a short last line in a file that is not a live record is an error
    status, out, err = run_cli("measure", bare, "--json")
    assert status == 2 and "bare.csv:" in err and err.count("\n") == 1


@pytest.mark.parametrize(
    "args",
    [
        ("measure", "{frames}", "-o", "{bad}/out.csv"),
        ("simulate", "laser", "-o", "{bad}/laser.csv"),
        ("calibrate", "sensitivity", "{psd}", "--channel", "x_psd_y_um", "-o", "{bad}/cal.json"),
        ("experiment", "diagonal", "--plot", "{bad}/figure.png"),
    ],
)
def test_an_output_that_cannot_be_written_is_one_error_line(run_cli, examples, tmp_path, args):
    blocker = tmp_path / "a_file"
    blocker.write_text("not a folder\n")
    names = {"frames": examples / "xz_module" / "sensors_frames.csv", "psd": examples / "xz_module" / "sensors_psd_run.csv", "bad": blocker}
    status, out, err = run_cli(*(a.format(**names) for a in args))
    assert status == 2 and err.count("\n") == 1 and err.startswith(f"axiscal: error: {blocker}/")
