"""Paper 000's diagonal experiment on recorded data: laser readings and the 6-DOF frames at the same stops."""

from __future__ import annotations

import numpy as np
import pytest

from axiscal.errors import AxiscalError
from axiscal.measurement.sensor_diagonal import sensor_diagonal
from axiscal.measurement.experiment import diagonal_experiment
from axiscal.measurement.virtual import VirtualModule
from axiscal.units import MM, UM

ENDS = {"start": {"X": 0.0, "Z": 0.0}, "end": {"X": 0.19, "Z": 0.19}}


def run(campaign, load):
    return sensor_diagonal(campaign / f"diagonal_{load}kg.csv", campaign / f"sixdof_stops_{load}kg.csv",
                           machine=campaign / "sensors_machine.toml", **ENDS)


@pytest.mark.parametrize("load", [0, 2])
def test_eq_13_against_a_plain_loop(examples, load):
    campaign = examples / "campaign"
    result = run(campaign, load)
    lines = (campaign / f"diagonal_{load}kg.csv").read_text().splitlines()[1:]
    for k, line in enumerate(lines):
        nominal_mm, measured_mm = (float(v) for v in line.split(","))
        x = z = nominal_mm / np.sqrt(2.0) * MM
        assert result.x_m[k] == pytest.approx(x, abs=1e-12) and result.z_m[k] == pytest.approx(z, abs=1e-12)
        assert result.before_m[k] == pytest.approx((x * x + z * z) ** 0.5 - measured_mm * MM, abs=1e-12)


@pytest.mark.parametrize("load", [0.0, 2.0])
def test_the_recorded_experiment_tells_the_simulated_one_s_story(examples, load):
    """E_BD as the paper's experiment simulated on the same module; E_AD within a micrometre (noise draws differ)."""
    recorded = run(examples / "campaign", f"{load:g}").figures()
    simulated = diagonal_experiment(VirtualModule(seed=0, load_kg=load))
    assert recorded["E_BD_max_um"] == pytest.approx(simulated.before_max_m / UM, abs=0.01)
    assert recorded["E_AD_max_um"] < 1.0 and simulated.after_max_m / UM < 1.0
    assert recorded["stops"] == 20 and recorded["samples_per_stop"] == 1


def test_several_frames_per_stop_are_averaged(examples, tmp_path):
    campaign = examples / "campaign"
    lines = (campaign / "sixdof_stops_2kg.csv").read_text().splitlines()
    doubled = tmp_path / "frames.csv"
    doubled.write_text("\n".join([lines[0]] + [row for row in lines[1:] for _ in range(2)]) + "\n")
    twice = sensor_diagonal(campaign / "diagonal_2kg.csv", doubled, machine=campaign / "sensors_machine.toml", **ENDS)
    once = run(campaign, 2)
    assert twice.samples == 2 and np.allclose(twice.after_m, once.after_m, atol=1e-15)


def test_bad_inputs(examples, tmp_path):
    campaign = examples / "campaign"
    lines = (campaign / "sixdof_stops_2kg.csv").read_text().splitlines()
    short = tmp_path / "frames.csv"
    short.write_text("\n".join(lines[:-1]) + "\n")
    with pytest.raises(AxiscalError, match="19 frames are not the same number at each of the 20 stops") as info:
        sensor_diagonal(campaign / "diagonal_2kg.csv", short, machine=campaign / "sensors_machine.toml", **ENDS)
    assert info.value.path == str(short)
    with pytest.raises(AxiscalError, match="the diagonal has no length"):
        sensor_diagonal(campaign / "diagonal_2kg.csv", campaign / "sixdof_stops_2kg.csv", start={"X": 0.0}, end={"X": 0.0})
    with pytest.raises(AxiscalError, match="XZ plane"):
        sensor_diagonal(campaign / "diagonal_2kg.csv", campaign / "sixdof_stops_2kg.csv", start={"Y": 0.0}, end={"X": 0.1})


def _scaled_nominal(source, target, factor):
    lines = source.read_text().splitlines()
    rows = [line.split(",") for line in lines[1:]]
    target.write_text("\n".join([lines[0]] + [f"{float(n) * factor:.6f},{m}" for n, m in rows]) + "\n")
    return target


def test_readings_whose_nominal_positions_do_not_match_the_stops_are_refused(examples, tmp_path):
    """Doubled nominal positions gave an E_BD of 268 768 um with exit 0: the stops the scales read are at
    half those distances along the diagonal."""
    campaign = examples / "campaign"
    doubled = _scaled_nominal(campaign / "diagonal_0kg.csv", tmp_path / "diagonal.csv", 2.0)
    with pytest.raises(AxiscalError) as info:
        sensor_diagonal(doubled, campaign / "sixdof_stops_0kg.csv", machine=campaign / "sensors_machine.toml", **ENDS)
    assert info.value.path == str(doubled) and info.value.line == 3
    assert info.value.message == ("nominal_mm 28.2843 puts stop 2 at X=20 Z=20 mm on the diagonal, but the scales of"
                                  " sixdof_stops_0kg.csv put it at X=9.99877 Z=9.99936 mm: the readings do not match"
                                  " the diagonal's stops")


def test_stops_beyond_the_diagonal_s_end_are_refused(examples, tmp_path):
    """The scales agree with the readings, but the campaign's `to` ends the diagonal at the sixth stop."""
    campaign = examples / "campaign"
    with pytest.raises(AxiscalError) as info:
        sensor_diagonal(campaign / "diagonal_0kg.csv", campaign / "sixdof_stops_0kg.csv",
                        machine=campaign / "sensors_machine.toml", start={"X": 0.0, "Z": 0.0}, end={"X": 0.05, "Z": 0.05})
    assert info.value.line == 8 and info.value.message.startswith("nominal_mm 84.8528 is off the diagonal from X=0 Z=0"
                                                                  " to X=50 Z=50 mm, which is 70.7107 mm long")


def test_report_refuses_such_a_test_in_one_line(examples, tmp_path, run_cli):
    campaign = examples / "campaign"
    for name in ("sixdof_stops_0kg.csv", "sensors_machine.toml", "sensors_calibration.json", "sensors_x_errors.csv",
                 "sensors_z_errors.csv"):
        (tmp_path / name).write_bytes((campaign / name).read_bytes())
    _scaled_nominal(campaign / "diagonal_0kg.csv", tmp_path / "diagonal_0kg.csv", 2.0)
    (tmp_path / "campaign.toml").write_text(
        '[campaign]\ntitle = "t"\ndate = 2026-11-20\noperator = "o"\n\n[machine]\nname = "XZ"\n\n'
        '[[tests]]\nkind = "sixdof_diagonal"\nfile = "diagonal_0kg.csv"\nframes = "sixdof_stops_0kg.csv"\n'
        'machine = "sensors_machine.toml"\nfrom = "X=0,Z=0"\nto = "X=190,Z=190"\n')
    status, out, err = run_cli("report", tmp_path, "-o", tmp_path / "report")
    assert status == 2 and err.count("\n") == 1, err
    assert err.startswith(f"axiscal: error: {tmp_path / 'diagonal_0kg.csv'}:3: nominal_mm 28.2843 puts stop 2 at X=20 Z=20")
    assert not (tmp_path / "report").exists()
