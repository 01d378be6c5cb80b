"""CMM squareness from PSD runs, the compensation model of eq (6) and the gauge block check (paper 004)."""

from __future__ import annotations

import math

import numpy as np
import pandas as pd
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from axiscal.errors import AxiscalError
from axiscal.model.machine import Axis, Machine
from axiscal.squareness.cmm import (
    MAX_CMM_SQUARENESS_ARCMIN,
    PAPER_004_GAUGE_BLOCKS_MM,
    PAPER_004_IMPROVEMENT_UM,
    PAPER_004_SQUARENESS_ARCMIN,
    CmmSquareness,
    compensate,
    compensate_file,
    gauge_block_length,
    gauge_block_study,
    least_squares_plane,
    psd_squareness,
    readings_for,
    simulate_gauge_block,
    squareness_from_psd_runs,
)
from axiscal.units import ARCMIN, MM, UM

# paper 004, section 3.3 and conclusion: a_xy, a_xz, a_yz in arc minutes (the text's units slip)
PAPER = CmmSquareness(8.05 * ARCMIN, 27.1 * ARCMIN, -16.6 * ARCMIN)


def test_eq_6_written_out():
    x, y, z = 0.1, 0.2, 0.3
    corrected = compensate([x, y, z], PAPER)[0]
    assert corrected[0] == pytest.approx(x - y * PAPER.xy_rad - z * PAPER.xz_rad, abs=1e-16)
    assert corrected[1] == pytest.approx(y - z * PAPER.yz_rad, abs=1e-16)
    assert corrected[2] == z


def test_inverse_round_trip_over_random_points():
    rng = np.random.default_rng(0)
    points = rng.uniform(-0.5, 0.5, size=(100, 3))
    np.testing.assert_allclose(compensate(readings_for(points, PAPER), PAPER), points, atol=1e-15)
    np.testing.assert_allclose(readings_for(compensate(points, PAPER), PAPER), points, atol=1e-15)


def test_iso_terms_and_back():
    iso = PAPER.iso()
    assert iso["EC0Y"] == PAPER.xy_rad
    assert iso["EB0Z"] == -PAPER.xz_rad
    assert iso["EA0Z"] == PAPER.yz_rad
    assert CmmSquareness.from_iso(iso) == PAPER
    with pytest.raises(AxiscalError, match="unknown squareness term"):
        CmmSquareness.from_iso({"EC0X": 1e-5})


@pytest.mark.parametrize("chain", ["FXYZ", "XFYZ"])
def test_eq_6_agrees_with_the_htm_model_to_first_order(chain):
    # the HTM machine with the ISO terms puts the probe where eq (6) says the readings point to
    small = CmmSquareness(20e-6, -35e-6, 15e-6)
    machine = Machine(chain, {k: Axis(k) for k in "XYZ"}, squareness_rad=small.iso())
    rng = np.random.default_rng(0)
    q = rng.uniform(-0.4, 0.4, size=(50, 3))
    positions = {k: q[:, i] for i, k in enumerate("XYZ")}
    nominal = machine.nominal_point(positions)
    actual = machine.actual_point(positions)
    model = compensate(nominal, small)
    second_order = 0.4 * 3 * (35e-6) ** 2
    np.testing.assert_allclose(actual, model, atol=second_order)
    assert np.max(np.abs(actual - nominal)) > 100 * second_order


ALL_CHAINS = [
    "".join(order[:cut]) + "F" + "".join(order[cut:])
    for order in ("XYZ", "XZY", "YXZ", "YZX", "ZXY", "ZYX")
    for cut in range(4)
]


def _linear_map(machine):
    """The 3x3 matrix A with actual = A nominal + t (an ideal-axis machine is affine in its commands)."""
    q = np.vstack([np.zeros(3), np.eye(3)])
    positions = {k: q[:, i] for i, k in enumerate("XYZ")}
    nominal = machine.nominal_point(positions)
    actual = machine.actual_point(positions)
    return (actual[1:] - actual[0]).T @ np.linalg.inv((nominal[1:] - nominal[0]).T)


@pytest.mark.parametrize("chain", ALL_CHAINS)
def test_eq_6_agrees_with_every_chain_up_to_a_rigid_rotation(chain):
    # With squareness_placement="relative" every chain has the included angles eq (6) has: the
    # machine's map is A = R C with R a rotation, so A^T A = C^T C to first order. Eq (6) also
    # fixes X (and Y's XY direction); the HTM chain keeps fixed the axis nearest the frame, so the
    # two may differ by that small rigid rotation R (which a CMM's part alignment absorbs).
    small = CmmSquareness(20e-6, -35e-6, 15e-6)
    c = small.matrix()
    second_order = 3 * 35e-6**2
    relative = Machine(chain, {k: Axis(k) for k in "XYZ"}, squareness_rad=small.iso(), squareness_placement="relative")
    a = _linear_map(relative)
    np.testing.assert_allclose(a.T @ a, c.T @ c, atol=second_order)
    # the "guideway" placement agrees where the turned axis never carries its reference axis in
    # the same branch (docs/conventions.md, Squareness)
    guideway = _linear_map(
        Machine(chain, {k: Axis(k) for k in "XYZ"}, squareness_rad=small.iso(), squareness_placement="guideway")
    )
    carries = any(
        branch.index(turned) < branch.index(reference)
        for branch in (chain.split("F")[0][::-1], chain.split("F")[1])
        for turned, reference in (("Y", "X"), ("Z", "X"), ("Z", "Y"))
        if turned in branch and reference in branch
    )
    metric_error = np.max(np.abs(guideway.T @ guideway - c.T @ c))
    assert (metric_error > 100 * second_order) if carries else (metric_error < second_order)


def test_psd_runs_paper_004():
    # paper 004 section 3.3: Y stepped 0 to 15 mm by 3 mm; the slope of the PSD line less alpha_p
    ap = 1.1 * ARCMIN
    y = np.arange(0, 15.001, 3) * MM
    rng = np.random.default_rng(0)
    runs = {}
    for plane, measured in (("XY", 9.15), ("XZ", 28.2), ("YZ", -15.5)):
        runs[plane] = (y, math.tan(measured * ARCMIN) * y + rng.normal(0, 0.05 * UM, y.size))
    result = squareness_from_psd_runs(runs, prism_deviation_rad=ap)
    assert round(result.xy_rad / ARCMIN, 2) == 8.05
    assert round(result.xz_rad / ARCMIN, 1) == 27.1
    assert round(result.yz_rad / ARCMIN, 1) == -16.6
    ends = psd_squareness(*runs["XY"], prism_deviation_rad=ap, reference="end-points")
    assert ends == pytest.approx(result.xy_rad, abs=0.05 * ARCMIN)
    with pytest.raises(AxiscalError, match="XY, XZ and YZ"):
        squareness_from_psd_runs({"XY": runs["XY"]})
    with pytest.raises(AxiscalError, match="1 point"):
        psd_squareness(y[:1], y[:1])


def test_psd_reading_sign_follows_a_leaning_axis():
    # Y leaning towards -X (included angle > 90 deg): the detector moves to -X, the beam stays
    lean = 30e-6
    y = np.linspace(0, 0.015, 6)
    detector_x = -lean * y
    reading = 0.0 - detector_x  # beam position on the detector along +X
    assert psd_squareness(y, reading) == pytest.approx(lean, rel=1e-9)


def test_least_squares_plane_and_degenerate_cases():
    rng = np.random.default_rng(0)
    normal = np.array([0.3, -0.2, 1.0])
    normal /= np.linalg.norm(normal)
    u = np.cross(normal, [1.0, 0, 0])
    u /= np.linalg.norm(u)
    v = np.cross(normal, u)
    pts = np.array([a * u + b * v + 1e-3 * normal for a, b in rng.uniform(-0.01, 0.01, size=(12, 2))])
    plane = least_squares_plane(pts)
    np.testing.assert_allclose(plane.normal, normal, atol=1e-12)
    assert plane.rms_m < 1e-15
    with pytest.raises(AxiscalError, match="one line"):
        least_squares_plane([[0, 0, 0], [1, 1, 1], [2, 2, 2], [3, 3, 3]])
    with pytest.raises(AxiscalError, match="one line"):
        least_squares_plane([[1, 2, 3]] * 6)
    with pytest.raises(AxiscalError, match="at least 3"):
        least_squares_plane([[0, 0, 0], [1, 0, 0]])
    with pytest.raises(AxiscalError, match="shape"):
        least_squares_plane([[0, 0], [1, 0], [0, 1]])


def test_gauge_block_length_projects_on_the_face_normal():
    face = np.array([[0, y, z] for y in (-0.01, 0, 0.01) for z in (-0.003, 0.003)], dtype=float)
    # second point displaced sideways: the projection ignores the offset
    assert gauge_block_length(face, [0, 0, 0], [1e-3, 4e-3, -2e-3]) == pytest.approx(1e-3, abs=1e-18)


def test_paper_004_gauge_blocks():
    # paper 004 Table 2 (text): compensation cut the errors by 11 um (X block 0.992 mm) and 5 um
    # (Y block 1.000 mm). With the paper's own procedure (plane normal, projection) squareness moves
    # a block along a machine axis by only L (a1^2 + a2^2) / 2: 0.034 um and 0.012 um here.
    x_block = simulate_gauge_block(PAPER, 0.992 * MM, (1, 0, 0))
    y_block = simulate_gauge_block(PAPER, 1.000 * MM, (0, 1, 0))
    assert x_block.aligned_before_m / UM == pytest.approx(
        -0.992e3 * (PAPER.xy_rad**2 + PAPER.xz_rad**2) / 2, rel=1e-3
    )
    assert round(x_block.aligned_before_m / UM, 3) == -0.034
    assert round(y_block.aligned_before_m / UM, 3) == -0.012
    assert abs(x_block.aligned_after_m) < 1e-15 and abs(y_block.aligned_after_m) < 1e-15
    # probing the two end points 1 mm apart across the block without the plane alignment gives the
    # paper's order of magnitude: 10.2 um and 4.8 um, both removed by eq (6)
    x_offset = simulate_gauge_block(PAPER, 0.992 * MM, (1, 0, 0), end_offset_m=(0, 1 * MM, 1 * MM))
    y_offset = simulate_gauge_block(PAPER, 1.000 * MM, (0, 1, 0), end_offset_m=(1 * MM, 0, -1 * MM))
    assert round(x_offset.unaligned_improvement_m / UM, 1) == 10.2
    assert round(y_offset.unaligned_improvement_m / UM, 1) == 4.8
    assert x_offset.unaligned_before_m / UM == pytest.approx(1e3 * (PAPER.xy_rad + PAPER.xz_rad + PAPER.xy_rad * PAPER.yz_rad), rel=1e-9)


def test_imperfect_calibration_leaves_a_residual():
    # compensating with values off by the PSD set-up's resolution (3.4") leaves a small residual
    off = CmmSquareness(PAPER.xy_rad + 16.7e-6, PAPER.xz_rad - 16.7e-6, PAPER.yz_rad)
    check = simulate_gauge_block(PAPER, 1 * MM, (1, 0, 0), end_offset_m=(0, 1 * MM, 1 * MM), compensation=off)
    assert 0 < abs(check.unaligned_after_m) < 0.05 * UM


def test_bad_simulation_input():
    with pytest.raises(AxiscalError, match="positive"):
        simulate_gauge_block(PAPER, 0.0, (1, 0, 0))
    with pytest.raises(AxiscalError, match="non-zero"):
        simulate_gauge_block(PAPER, 1e-3, (0, 0, 0))
    with pytest.raises(AxiscalError, match="finite"):
        CmmSquareness(float("nan"), 0.0, 0.0)
    with pytest.raises(AxiscalError, match="shape"):
        compensate(np.zeros((3, 2)), PAPER)


@settings(max_examples=80, deadline=None)
@given(
    st.floats(-1e-2, 1e-2),
    st.floats(-1e-2, 1e-2),
    st.floats(-1e-2, 1e-2),
    st.lists(st.floats(-1.0, 1.0), min_size=3, max_size=3),
    st.floats(1e-4, 0.1),
)
def test_aligned_length_is_independent_of_probing_property(a, b, c, direction, length):
    # the shear maps the face to a plane; projecting on its measured normal gives L / |C^T n|
    n = np.array(direction)
    if np.linalg.norm(n) < 0.1:
        n = np.array([1.0, 0.0, 0.0])
    s = CmmSquareness(a, b, c)
    one = simulate_gauge_block(s, length, n)
    other = simulate_gauge_block(s, length, n, end_offset_m=(3e-3, -2e-3, 5e-3), centre_m=(0.1, 0.2, 0.05))
    unit = n / np.linalg.norm(n)
    expected = length / np.linalg.norm(s.matrix().T @ unit) - length
    assert one.aligned_before_m == pytest.approx(expected, abs=1e-15)
    assert other.aligned_before_m == pytest.approx(expected, abs=1e-15)


def test_published_values_name_paper_004():
    # paper 004 section 4.1 (a_xy, a_xz, a_yz in arc minutes), section 4.2 (blocks), Table 2 text
    assert PAPER_004_SQUARENESS_ARCMIN == (8.05, 27.1, -16.6)
    assert PAPER_004_GAUGE_BLOCKS_MM == {"X": 0.992, "Y": 1.000}
    assert PAPER_004_IMPROVEMENT_UM == {"X": 11.0, "Y": 5.0}


def test_gauge_block_study_is_the_simulation_of_each_block():
    study = gauge_block_study(PAPER, end_offset_m=1 * MM)
    x_offset = simulate_gauge_block(PAPER, 0.992 * MM, (1, 0, 0), end_offset_m=(0, 1 * MM, 1 * MM))
    assert study.blocks["X"].unaligned_before_m == x_offset.unaligned_before_m
    assert study.blocks["X"].aligned_before_m == x_offset.aligned_before_m
    body = study.payload()
    assert body["end_offset_mm"] == pytest.approx(1.0)
    assert round(body["blocks"]["X"]["unaligned_improvement_um"], 1) == 10.2
    assert round(body["blocks"]["Y"]["unaligned_improvement_um"], 1) == 4.8
    assert body["blocks"]["Y"]["paper_004_improvement_um"] == 5.0
    lines = study.report().splitlines()
    assert lines[4] == "  0.992 X         -0.0335    0.0000           10.2134    0.0000        10.21       11.0"
    with pytest.raises(AxiscalError, match="finite"):
        gauge_block_study(PAPER, end_offset_m=math.nan)


def test_checked_squareness_refuses_large_angles():
    assert CmmSquareness.checked(PAPER.xy_rad, PAPER.xz_rad, PAPER.yz_rad) == PAPER
    with pytest.raises(AxiscalError, match=f"{MAX_CMM_SQUARENESS_ARCMIN:g} arc minutes"):
        CmmSquareness.checked(0.0, 61 * ARCMIN, 0.0)
    with pytest.raises(AxiscalError, match="finite"):
        CmmSquareness.checked(0.0, math.inf, 0.0)


def test_compensate_file_round_trip(tmp_path, examples):
    corrected = tmp_path / "corrected.csv"
    run = compensate_file(examples / "cmm_points.csv", PAPER, output=corrected)
    np.testing.assert_allclose(run.moved_m, compensate(run.points_m, PAPER))
    back = compensate_file(corrected, PAPER, inverse=True)
    assert back.csv_text.splitlines()[0].endswith("x_reading_mm,y_reading_mm,z_reading_mm")
    frame = pd.read_csv(corrected)
    again = readings_for(frame[["x_corrected_mm", "y_corrected_mm", "z_corrected_mm"]].to_numpy() * MM, PAPER)
    np.testing.assert_allclose(again, run.points_m, atol=2e-9)
