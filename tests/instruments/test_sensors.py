"""Sensor equations of paper 000 (eqs 1-3) and the sensor geometry read from a machine TOML."""

from __future__ import annotations

import numpy as np
import pytest
from hypothesis import given
from hypothesis import strategies as st

from axiscal.errors import AxiscalError
from axiscal.instruments.sensors import (
    angle_from_quadrant,
    autocollimation_shift,
    parse_signed_component,
    quadrant_shift,
    roll_from_autocollimation,
    sensor_head_from_dict,
    straightness_from_psd,
)
from axiscal.units import ARCSEC


def test_eq1_psd_shift_is_the_straightness():
    # paper 000 eq (1): delta_y1 = Delta_y1, delta_z1 = Delta_z1
    shift = np.array([-3e-6, 0.0, 1.25e-6])
    np.testing.assert_array_equal(straightness_from_psd(shift), shift)


def test_eq2_quadrant_detector_angle():
    # paper 000 eq (2): eps = Delta / f1; 100 arcsec behind a 100 mm lens is a 48.48 um spot shift
    shift = quadrant_shift(100 * ARCSEC, 0.100)
    assert shift == pytest.approx(48.4814e-6, abs=1e-10)
    assert angle_from_quadrant(shift, 0.100) == pytest.approx(100 * ARCSEC)


def test_eq3_autocollimated_roll_is_half_the_angle():
    # paper 000 eq (3): eps_x = Delta_z2 / (2 f2): the mirror doubles the angle
    assert roll_from_autocollimation(16e-6, 0.080) == pytest.approx(100e-6)
    assert autocollimation_shift(100e-6, 0.080) == pytest.approx(16e-6)


@given(st.floats(-1e-3, 1e-3), st.floats(0.01, 1.0))
def test_sensor_equations_round_trip(angle, focal):
    assert angle_from_quadrant(quadrant_shift(angle, focal), focal) == pytest.approx(angle, abs=1e-18)
    assert roll_from_autocollimation(autocollimation_shift(angle, focal), focal) == pytest.approx(angle, abs=1e-18)


def test_signed_component():
    assert parse_signed_component("-EBX", "X", what="qd_v").index == 4
    assert parse_signed_component("-EBX", "X", what="qd_v").sign == -1.0
    assert parse_signed_component("ecz", "Z", what="roll").sign == 1.0
    with pytest.raises(AxiscalError, match="qd_u = 'EBZ'"):
        parse_signed_component("EBZ", "X", what="qd_u")


def test_sensor_head_defaults_and_channels():
    head = sensor_head_from_dict("Z", {"scale_point_mm": [20.0, -25.0, 0.0], "psd_point_mm": [-15.0, 20.0, 0.0]})
    assert list(head.channels.values()) == [
        "z_cmd_mm", "z_scale_mm", "z_psd_x_um", "z_psd_y_um", "z_qd_u_um", "z_qd_v_um", "z_roll_um",
    ]
    assert head.qd_focal_m == pytest.approx(0.1)
    # rows P - M: the z (positioning) row from the read head, x and y from the PSD
    np.testing.assert_allclose(head.offsets_m(), [[15e-3, -20e-3, 0.0], [15e-3, -20e-3, 0.0], [-20e-3, 25e-3, 0.0]])


@pytest.mark.parametrize(
    ("section", "message"),
    [
        ({"qd_focal_mm": -1.0}, "qd_focal_mm must be a positive number"),
        ({"scale_point_mm": [1.0, 2.0]}, "scale_point_mm must be a list of 3 numbers"),
        ({"qd_u": "EXX"}, "must name a rotation"),
        ({"qd_u": "EAX", "roll": "EAX"}, "three different rotations"),
        ({"focal": 3}, "unknown key focal"),
        ({"prefix": "x-1"}, "prefix 'x-1'"),
    ],
)
def test_bad_sensor_sections(section, message):
    with pytest.raises(AxiscalError, match=message):
        sensor_head_from_dict("X", section)


def test_abbe_bryan_transfer_is_paper_eqs_4_and_5():
    # paper 000 eq (5), Z axis, term by term; eq (4), X axis, with its slip fixed (second line
    # L_bz where the paper prints L_bx twice, docs/papers.md). L = P - M: the functional point
    # minus the read head (L_a) or the PSD spot (L_b). For X the paper's Abbe offsets are named
    # L_ax, L_ay, but an offset along the motion does nothing: its "L_ax" multiplies the pitch in
    # the x line, so it is the offset along z (docs/measurement.md).
    from axiscal.instruments.abbe import transfer_components

    rng = np.random.default_rng(0)
    for letter in ("X", "Z"):
        head = sensor_head_from_dict(
            letter, {"scale_point_mm": list(rng.uniform(-50, 50, 3)), "psd_point_mm": list(rng.uniform(-50, 50, 3))}
        )
        la = -np.asarray(head.scale_point_m)
        lb = -np.asarray(head.psd_point_m)
        d = rng.normal(0, 5e-6, (3, 7))
        ex, ey, ez = rng.normal(0, 50e-6, (3, 7))
        errors = np.vstack([d, ex, ey, ez])
        errors[:3] = transfer_components(errors[:3].T, errors[3:].T, head.offsets_m()).T
        if letter == "Z":
            expected = [
                d[0] - ez * lb[1] + ey * lb[2],
                d[1] + ez * lb[0] - ex * lb[2],
                d[2] - ey * la[0] + ex * la[1],
            ]
        else:
            expected = [
                d[0] + ey * la[2] - ez * la[1],
                d[1] - ex * lb[2] + ez * lb[0],
                d[2] + ex * lb[1] - ey * lb[0],
            ]
        np.testing.assert_allclose(errors[:3], expected, atol=1e-18)
