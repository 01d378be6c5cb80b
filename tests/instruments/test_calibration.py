"""Calibration against reference instruments (paper 000 section 4.1, eqs 11-12; section 4.2 transfer)."""

from __future__ import annotations

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from axiscal.errors import AxiscalError
from axiscal.instruments.calibration import (
    Calibration,
    fit_mirror,
    fit_sensitivity,
    load_calibration,
    save_calibration,
    transfer_reference,
)
from axiscal.units import ARCSEC


def test_sensitivity_recovers_gain_and_offset_within_noise():
    rng = np.random.default_rng(0)
    raw = np.linspace(-100.0, 100.0, 41)
    noise = 0.3
    reference = 0.97 * raw + 4.2 + rng.normal(0.0, noise, raw.size)
    fit = fit_sensitivity("x_psd_y_um", raw, reference)
    # standard errors of the slope and intercept of a straight-line fit
    assert abs(fit.gain - 0.97) < 4 * noise / np.sqrt(np.sum((raw - raw.mean()) ** 2))
    assert abs(fit.offset - 4.2) < 4 * noise / np.sqrt(raw.size)
    assert fit.residual_rms == pytest.approx(noise, rel=0.35)
    assert fit.residual_max < 4 * noise
    assert fit.points == 41


@settings(max_examples=50, deadline=None)
@given(st.floats(0.5, 2.0), st.floats(-50.0, 50.0))
def test_sensitivity_exact_without_noise(gain, offset):
    raw = np.linspace(-10.0, 10.0, 7)
    fit = fit_sensitivity("c", raw, gain * raw + offset)
    assert fit.gain == pytest.approx(gain, rel=1e-12)
    assert fit.offset == pytest.approx(offset, abs=1e-10)


@pytest.mark.parametrize(
    ("raw", "reference", "message"),
    [
        (np.ones(5), np.arange(5.0), "do not vary"),
        (np.arange(2.0), np.arange(2.0), "at least 3"),
        (np.arange(4.0), np.arange(3.0), "same length"),
        (np.array([0.0, 1.0, np.nan]), np.arange(3.0), "non-finite"),
    ],
)
def test_sensitivity_bad_input(raw, reference, message):
    with pytest.raises(AxiscalError, match=message):
        fit_sensitivity("c", raw, reference)


def test_transfer_reference_is_the_abbe_term():
    # paper 000 section 4.2.1: interferometer beam 45 mm above the read head, pitch 10 urad:
    # the read head sees eps x (M - R): x-component = eb * dz - ec * dy
    eps = np.array([[0.0, 10e-6, 0.0], [0.0, 0.0, 5e-6]])
    moved = transfer_reference(np.zeros(2), eps, np.array([0.0, 0.0, -0.045]), 0)
    np.testing.assert_allclose(moved, [-0.45e-6, 0.0], atol=1e-15)
    moved = transfer_reference(np.zeros(2), eps, np.array([0.0, 0.020, 0.0]), 0)
    np.testing.assert_allclose(moved, [0.0, -0.1e-6], atol=1e-15)


def test_mirror_map_eq11_fit_and_eq12_subtraction():
    # eq (11): eps_error = module - level; eq (12): roll = module - eps_error(q)
    rng = np.random.default_rng(1)
    q = np.linspace(0.0, 0.19, 39)
    form = 4e-6 * np.sin(2 * np.pi * 0.7 * q / 0.19 + 0.4) + 1.5e-6 * np.sin(2 * np.pi * 1.6 * q / 0.19)
    roll = 8e-6 * np.sin(2 * np.pi * 0.5 * q / 0.19)
    level_noise = 0.2 * ARCSEC
    level = roll + rng.normal(0.0, level_noise, q.size)
    module = roll + form + rng.normal(0.0, 0.3e-6, q.size)
    mirror = fit_mirror("X", q, module, level)
    dense = np.linspace(0.0, 0.19, 500)
    truth = 4e-6 * np.sin(2 * np.pi * 0.7 * dense / 0.19 + 0.4) + 1.5e-6 * np.sin(2 * np.pi * 1.6 * dense / 0.19)
    assert np.max(np.abs(mirror.evaluate(dense) - truth)) < 1.5 * level_noise
    assert 2 <= mirror.order <= 10
    assert len(mirror.cv_rms_rad) >= mirror.order + 1
    assert mirror.cv_rms_rad[mirror.order] == min(mirror.cv_rms_rad)
    corrected = module - mirror.evaluate(q)
    assert np.std(corrected - roll) < 1.5 * level_noise


def test_mirror_order_follows_the_data():
    # a straight form error must not be fitted with a high order; a wavy one needs one
    rng = np.random.default_rng(2)
    q = np.linspace(0.0, 0.19, 40)
    straight = fit_mirror("X", q, 2e-6 * q / 0.19 + rng.normal(0, 0.2e-6, q.size), np.zeros(q.size))
    wavy = fit_mirror("X", q, 3e-6 * np.sin(2 * np.pi * 2.0 * q / 0.19) + rng.normal(0, 0.2e-6, q.size), np.zeros(q.size))
    assert straight.order <= 2
    assert wavy.order >= 6


def test_mirror_needs_positions():
    with pytest.raises(AxiscalError, match="at least 4 distinct"):
        fit_mirror("X", np.array([0.0, 0.0, 1.0]), np.zeros(3), np.zeros(3))


def test_calibration_file_round_trip(tmp_path):
    q = np.linspace(0.0, 0.19, 20)
    mirror = fit_mirror("Z", q, 1e-6 * (q / 0.19) ** 2, np.zeros(q.size))
    calibration = Calibration({"x_psd_y_um": fit_sensitivity("x_psd_y_um", np.arange(5.0), 2 * np.arange(5.0) + 1)}, {"Z": mirror})
    path = tmp_path / "cal.json"
    save_calibration(calibration, path)
    back = load_calibration(path)
    assert back.channel("x_psd_y_um").gain == pytest.approx(2.0)
    assert back.channel("x_psd_y_um").offset == pytest.approx(1.0)
    assert back.channel("never_calibrated").gain == 1.0
    np.testing.assert_allclose(back.mirrors["Z"].evaluate(q), mirror.evaluate(q), atol=1e-18)


@pytest.mark.parametrize(
    ("text", "message"),
    [
        ("{", "malformed JSON"),
        ('{"format": "other"}', "not a sensor calibration file"),
        ('{"format": "axiscal-sensor-calibration", "version": 9}', "version 9"),
        ('{"format": "axiscal-sensor-calibration", "version": 1, "channels": {"a": {"gain": 0, "offset": 0}}}', "gain must not be zero"),
        ('{"format": "axiscal-sensor-calibration", "version": 1, "channels": {"a": {"gain": "x", "offset": 0}}}', "'gain' must be a finite number"),
        ('{"format": "axiscal-sensor-calibration", "version": 1, "mirrors": {"X": {"start_mm": 5, "end_mm": 1, "legendre_urad": [1]}}}', "end_mm"),
    ],
)
def test_bad_calibration_files(tmp_path, text, message):
    path = tmp_path / "bad.json"
    path.write_text(text)
    with pytest.raises(AxiscalError, match=message) as info:
        load_calibration(path)
    assert str(path) in str(info.value)


@settings(max_examples=25, deadline=None)
@given(st.floats(1e-3, 10.0), st.floats(-1.0, 1.0))
def test_mirror_fit_does_not_depend_on_where_the_travel_starts_or_its_unit(scale, shift):
    rng = np.random.default_rng(3)
    s = np.linspace(0.0, 1.0, 30)
    eps = 2e-6 * np.sin(2 * np.pi * 1.3 * s) + rng.normal(0.0, 0.3e-6, s.size)
    base = fit_mirror("X", s, eps, np.zeros(s.size))
    moved = fit_mirror("X", shift + scale * s, eps, np.zeros(s.size))
    assert moved.order == base.order
    np.testing.assert_allclose(moved.evaluate(shift + scale * s), base.evaluate(s), atol=1e-12)
