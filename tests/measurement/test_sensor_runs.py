"""Calibration runs of every sensor channel at once (paper 000 section 4.1), on the demo campaign's runs."""

from __future__ import annotations

import numpy as np
import pytest

from axiscal.errors import AxiscalError
from axiscal.instruments.calibration import load_calibration
from axiscal.measurement.offline import load_system
from axiscal.measurement.sensor_runs import calibrate_sensor_runs
from axiscal.units import ARCSEC, UM


@pytest.fixture
def campaign(examples):
    return examples / "campaign"


def test_each_channel_is_a_least_squares_line(campaign):
    """Against a plain fit of each channel's rows (numpy.polyfit, degree 1)."""
    runs = calibrate_sensor_runs(campaign / "sensor_calibration_runs.csv", machine=campaign / "sensors_machine.toml")
    text = (campaign / "sensor_calibration_runs.csv").read_text().splitlines()[1:]
    rows = [line.split(",") for line in text]
    assert list(runs.fits) == list(dict.fromkeys(r[0] for r in rows))
    for channel, fit in runs.fits.items():
        raw = np.array([float(r[1]) for r in rows if r[0] == channel])
        reference = np.array([float(r[2]) for r in rows if r[0] == channel])
        gain, offset = np.polyfit(raw, reference, 1)
        residual = reference - (gain * raw + offset)
        assert fit.gain == pytest.approx(gain, rel=1e-10) and fit.offset == pytest.approx(offset, rel=1e-9, abs=1e-9)
        assert fit.residual_max == pytest.approx(np.max(np.abs(residual)), rel=1e-8) and fit.points == raw.size


def test_the_fits_are_the_calibration_the_campaign_uses(campaign):
    """sensors_calibration.json was fitted from the same runs (before they were rounded into the CSV)."""
    runs = calibrate_sensor_runs(campaign / "sensor_calibration_runs.csv", machine=campaign / "sensors_machine.toml")
    used = load_calibration(campaign / "sensors_calibration.json")
    for channel, fit in runs.fits.items():
        assert fit.gain == pytest.approx(used.channel(channel).gain, rel=1e-6)


def test_angle_channels_are_also_angles(campaign):
    """Paper 000 eq 2 (quadrant detector: shift / f) and eq 3 (roll: shift / 2f)."""
    machine = campaign / "sensors_machine.toml"
    runs = calibrate_sensor_runs(campaign / "sensor_calibration_runs.csv", machine=machine)
    head = load_system(machine).heads["X"]
    qd, roll = head.channels["qd_u"], head.channels["roll"]
    assert runs.residual_arcsec(qd) == pytest.approx(runs.fits[qd].residual_max * UM / head.qd_focal_m / ARCSEC)
    assert runs.residual_arcsec(roll) == pytest.approx(runs.fits[roll].residual_max * UM / (2 * head.roll_focal_m) / ARCSEC)
    assert runs.residual_arcsec(head.channels["psd_y"]) is None
    figures = runs.figures()
    assert figures["channels"] == 10
    assert figures["calibration_arcsec"] == pytest.approx(max(runs.residual_arcsec(c) for c in runs.angle_m))
    assert 0 < figures["calibration_um"] < 1.0 and 0 < figures["calibration_arcsec"] < 1.0  # paper 000: +-1 um, +-1 arcsec


@pytest.mark.parametrize("text, line, words", [
    ("channel,raw,reference\nx_psd_y_um,1,1\nx_psd_y_um,2,2\nw_psd_y_um,3,3\n", 4, "unknown channel 'w_psd_y_um'"),
    ("channel,raw,reference\nx_psd_y_um,1,1\nx_psd_y_um,2,2\nx_psd_y_um,3,3\nx_qd_u_um,3,3\n", 5, "x_qd_u_um: at least 3 calibration points"),
    ("channel,raw,reference\nx_psd_y_um,1,1\nx_psd_y_um,1,2\nx_psd_y_um,1,3\n", 2, "do not vary"),
    ("channel,raw\nx_psd_y_um,1\nx_psd_y_um,2\nx_psd_y_um,3\n", 1, "missing column 'reference'"),
])
def test_bad_runs_name_the_file_and_line(tmp_path, text, line, words):
    path = tmp_path / "runs.csv"
    path.write_text(text)
    with pytest.raises(AxiscalError, match=words) as info:
        calibrate_sensor_runs(path)
    assert info.value.path == str(path) and info.value.line == line
