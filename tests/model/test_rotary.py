"""Rotary axes and five-axis chains: checks that need no convention, and the vectorised model against 4x4 matrices."""

from __future__ import annotations

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from axiscal.errors import AxiscalError
from axiscal.model import Axis, ErrorTable, Machine
from axiscal.model.kinematics import error_matrix, link_matrix, translation_matrix


def rot(index, angle):
    """Plain right-hand rotation matrix about coordinate axis ``index`` (ISO 841)."""
    c, s = np.cos(angle), np.sin(angle)
    m = np.eye(4)
    i, j = [(1, 2), (2, 0), (0, 1)][index]
    m[i, i], m[i, j], m[j, i], m[j, j] = c, -s, s, c
    return m


def constant(letter, **components):
    position = [0.0, 2 * np.pi] if letter in "ABC" else [-1.0, 1.0]
    return ErrorTable.from_components(letter, position, {k: [v, v] for k, v in components.items()})


@settings(max_examples=60, deadline=None)
@given(st.floats(-2 * np.pi, 2 * np.pi), st.floats(-1e-4, 1e-4), st.floats(-1e-4, 1e-4), st.sampled_from("ABC"))
def test_location_offset_of_a_table_axis_moves_a_workpiece_point_by_2_d_sin_half_theta(theta, d1, d2, letter):
    normal = {"A": ("Y", "Z"), "B": ("X", "Z"), "C": ("X", "Y")}[letter]
    location = {f"E{normal[0]}0{letter}": d1, f"E{normal[1]}0{letter}": d2}
    machine = Machine(f"{letter}FXYZ", {k: Axis(k) for k in letter + "XYZ"}, location=location, tool_m=(0.03, -0.02, 0.05))
    q = {letter: [theta], "X": [0.1], "Y": [-0.05], "Z": [0.2]}
    moved = np.linalg.norm(machine.volumetric_error(q)[0])
    assert moved == pytest.approx(2 * np.hypot(d1, d2) * abs(np.sin(theta / 2)), abs=1e-15)


@settings(max_examples=60, deadline=None)
@given(st.floats(-np.pi, np.pi), st.floats(-1e-4, 1e-4), st.floats(0.0, 0.5), st.floats(-0.3, 0.3))
def test_angular_positioning_error_moves_a_point_at_radius_r_by_r_eps(theta, eps, r, height):
    machine = Machine("CFXYZ", {k: Axis(k) for k in "CXYZ"} | {"C": Axis("C", constant("C", ECC=eps))})
    q = {"C": [theta], "X": [r], "Y": [0.0], "Z": [height]}
    # exact up to the second-order term eps²/2 of the first-order error matrix (paper 000 eq 6)
    assert np.linalg.norm(machine.volumetric_error(q)[0]) == pytest.approx(r * abs(eps), rel=1e-8, abs=1e-15)


def hand_written_trunnion(a, c, x, y, z, pivot, table, tool):
    """Tool point in the workpiece frame of an A/C trunnion (C table on an A cradle), by hand."""
    ca, sa, cc, sc = np.cos(a), np.sin(a), np.cos(c), np.sin(c)
    rx = np.array([[1, 0, 0], [0, ca, -sa], [0, sa, ca]])
    rz = np.array([[cc, -sc, 0], [sc, cc, 0], [0, 0, 1]])
    in_frame = np.array([x, y, z]) + tool
    in_cradle = rx.T @ (in_frame - pivot)
    return rz.T @ (in_cradle - table)


@settings(max_examples=40, deadline=None)
@given(st.lists(st.floats(-3.0, 3.0), min_size=2, max_size=2), st.lists(st.floats(-0.3, 0.3), min_size=3, max_size=3))
def test_trunnion_without_errors_is_the_hand_written_rigid_body_kinematics(angles, xyz):
    pivot, table, tool = np.array([0.0, 0.1, -0.2]), np.array([0.0, 0.0, 0.05]), np.array([0.0, 0.0, -0.15])
    axes = {"A": Axis("A", origin_m=tuple(pivot)), "C": Axis("C", origin_m=tuple(table))} | {k: Axis(k) for k in "XYZ"}
    machine = Machine("CAFXYZ", axes, tool_m=tuple(tool))
    q = {"A": [angles[0]], "C": [angles[1]], "X": [xyz[0]], "Y": [xyz[1]], "Z": [xyz[2]]}
    expected = hand_written_trunnion(*angles, *xyz, pivot, table, tool)
    np.testing.assert_allclose(machine.nominal_point(q)[0], expected, atol=1e-14)
    np.testing.assert_allclose(machine.volumetric_error(q), 0.0, atol=1e-15)


def rotary_matrix(link, theta, with_errors):
    """``Trans(o) · L · E(θ) · Rot(θ) · L⁻¹`` (docs/conventions.md) as plain 4x4 matrices."""
    if not with_errors:
        return translation_matrix(link.origin_m) @ rot(link.index, theta)
    location = translation_matrix(link.offset_m) @ error_matrix(0, 0, 0, *link.tilt_rad)
    errors = error_matrix(*link.table.evaluate(np.array([theta]))[:, 0])
    return translation_matrix(link.origin_m) @ location @ errors @ rot(link.index, theta) @ np.linalg.inv(location)


def reference_pose(machine, q, i):
    """Per-point product of 4x4 matrices: position error and (ei, ej) of the tool axis."""
    frames = []
    for with_errors in (True, False):
        branch = []
        for links in (machine._tool_links, machine._workpiece_links):
            t = np.eye(4)
            for link in links:
                if link.letter in "ABC":
                    t = t @ rotary_matrix(link, q[link.letter][i], with_errors)
                else:
                    t = t @ link_matrix(link, q[link.letter][i], with_errors=with_errors)
            branch.append(t)
        frames.append(np.linalg.inv(branch[1]) @ branch[0] @ translation_matrix(machine.tool_m))
    actual, nominal = frames
    cross = np.cross(nominal[:3, 2], actual[:3, 2])
    return actual[:3, 3] - nominal[:3, 3], np.array([nominal[:3, 0] @ cross, nominal[:3, 1] @ cross])


def random_table(letter, rng):
    rows = 9
    if letter in "ABC":
        position = np.sort(rng.uniform(0, 2 * np.pi, rows))
    else:
        position = np.linspace(-0.5, 0.5, rows)
    scale = np.array([10e-6] * 3 + [50e-6] * 3)[:, None]
    return ErrorTable(letter, position, rng.normal(size=(6, rows)) * scale)


@pytest.mark.parametrize("chain", ["CAFXYZ", "FXYZBC", "CFXYZ", "XFYZC", "BFXZ", "AFYZ", "CBFXYZ", "YFXZAC"])
def test_vectorised_five_axis_model_equals_plain_4x4_product(chain):
    rng = np.random.default_rng(sum(map(ord, chain)))
    letters = [k for k in chain if k != "F"]
    axes = {k: Axis(k, random_table(k, rng), tuple(rng.normal(size=3) * 0.1)) for k in letters}
    location = {}
    for k in letters:
        if k in "ABC":
            from axiscal.conventions import location_names

            names = location_names(k)
            location |= {names[0]: rng.normal() * 1e-5, names[1]: rng.normal() * 1e-5}
            location |= {names[2]: rng.normal() * 1e-4, names[3]: rng.normal() * 1e-4}
    squareness = {t: rng.normal() * 2e-5 for t, pair in {"EC0Y": "XY", "EB0Z": "XZ", "EA0Z": "YZ"}.items() if set(pair) <= set(letters)}
    machine = Machine(chain, axes, squareness_rad=squareness, location=location, tool_m=tuple(rng.normal(size=3) * 0.1))
    n = 25
    q = {k: rng.uniform(-7, 7, n) if k in "ABC" else rng.uniform(-0.5, 0.5, n) for k in letters}
    error, orientation = machine.pose_error(q)
    for i in range(n):
        ref_error, ref_orientation = reference_pose(machine, q, i)
        np.testing.assert_allclose(error[i], ref_error, atol=1e-13)
        np.testing.assert_allclose(orientation[i], ref_orientation, atol=1e-12)
    np.testing.assert_allclose(machine.volumetric_error(q), error, atol=0)


def test_tilt_of_the_table_axis_tilts_the_tool_relative_to_the_workpiece_by_that_angle():
    tilt = 40e-6
    machine = Machine("CFXYZ", {k: Axis(k) for k in "CXYZ"}, location={"EA0C": tilt})
    theta = np.linspace(0, 2 * np.pi, 13)
    q = {"C": theta, "X": 0 * theta, "Y": 0 * theta, "Z": 0 * theta}
    _, orientation = machine.pose_error(q)
    # the average line tilted by s: the table plane wobbles by 2 s sin(θ/2) against the spindle
    np.testing.assert_allclose(np.hypot(*orientation.T), 2 * tilt * np.abs(np.sin(theta / 2)), atol=1e-12)


def test_periodic_table_interpolates_across_360_degrees():
    deg = np.pi / 180
    table = ErrorTable.from_components("C", [0.0, 90 * deg, 180 * deg, 270 * deg], {"ECC": [0.0, 1e-6, 2e-6, 3e-6]})
    np.testing.assert_allclose(table.evaluate([315 * deg, -45 * deg, 405 * deg])[5], [1.5e-6, 1.5e-6, 0.5e-6], atol=1e-18)
    with pytest.raises(AxiscalError, match="360"):
        ErrorTable.from_components("C", [0.0, 400 * deg], {})
    with pytest.raises(AxiscalError, match="periodic"):
        ErrorTable("X", [0.0, 1.0], np.zeros((6, 2)), periodic=True)


def test_location_terms_are_checked():
    axes = {k: Axis(k) for k in "CXYZ"}
    with pytest.raises(AxiscalError, match="no axis A"):
        Machine("CFXYZ", axes, location={"EY0A": 1e-6})
    with pytest.raises(AxiscalError, match="unknown location term"):
        Machine("CFXYZ", axes, location={"EZ0C": 1e-6})
    with pytest.raises(AxiscalError, match="finite"):
        Machine("CFXYZ", axes, location={"EX0C": float("nan")})
    with pytest.raises(AxiscalError, match="linear chains only"):
        Machine("CFXYZ", axes).command_for([[0.0, 0.0, 0.0]])
