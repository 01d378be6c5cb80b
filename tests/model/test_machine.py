"""The HTM machine model: contract of axiscal.model.kinematics, paper 000 eqs (6)-(10), inverse."""

from __future__ import annotations

import itertools

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from axiscal.errors import AxiscalError
from axiscal.model.machine import Axis, Machine, parse_chain
from axiscal.model.tables import ErrorTable
from axiscal.units import ARCSEC

CHAINS = ["FX", "XF", "FXZ", "XFYZ", "YXFZ", "ZYXF", "FZYX", "YFX"]


def random_table(letter, rng, *, translation=10e-6, rotation=100e-6, rows=12, start=-0.05, end=0.35):
    position = np.sort(rng.uniform(start, end, rows))
    position[0], position[-1] = start, end
    scale = np.array([translation] * 3 + [rotation] * 3)[:, None]
    return ErrorTable(letter, position, rng.normal(size=(6, rows)) * scale)


def random_machine(chain, rng, **table_options):
    letters = [c for c in chain if c != "F"]
    axes = {k: Axis(k, random_table(k, rng, **table_options), tuple(rng.normal(size=3) * 0.1)) for k in letters}
    pairs = {"EC0Y": "XY", "EB0Z": "XZ", "EA0Z": "YZ"}  # a term needs both its axes in the chain
    squareness = {t: float(rng.normal() * 50 * ARCSEC) for t, axes_of in pairs.items() if set(axes_of) <= set(letters)}
    return Machine(
        chain, axes, squareness_rad=squareness, tool_m=tuple(rng.normal(size=3) * 0.1), workpiece_m=tuple(rng.normal(size=3) * 0.1)
    )


def random_positions(machine, rng, n):
    return {k: rng.uniform(0.0, 0.3, n) for k in machine.letters}


@pytest.mark.parametrize("chain", CHAINS)
def test_vectorised_model_equals_plain_4x4_product(chain):
    rng = np.random.default_rng(0)
    for _ in range(3):
        machine = random_machine(chain, rng)
        q = random_positions(machine, rng, 40)
        np.testing.assert_allclose(machine.volumetric_error(q), machine.reference_volumetric_error(q), rtol=0, atol=1e-15)


def test_chain_parsing():
    assert parse_chain("XFYZ") == (("X",), ("Y", "Z"))
    assert parse_chain("YXFZ") == (("X", "Y"), ("Z",))
    assert parse_chain("FXZ") == ((), ("X", "Z"))
    assert parse_chain("CAFXYZ") == (("A", "C"), ("X", "Y", "Z"))
    assert parse_chain("FXYZBC") == ((), ("X", "Y", "Z", "B", "C"))
    for bad in ("XYZ", "FXFZ", "XFX", "AFA", "F", "WXFYZ", "UFX"):
        with pytest.raises(AxiscalError):
            parse_chain(bad)


def constant_table(letter, values):
    return ErrorTable(letter, np.array([-1.0, 1.0]), np.repeat(np.asarray(values, dtype=float)[:, None], 2, axis=1))


def paper000_eq10(x, z, z0, y2, alpha, ex, ez):
    """Paper 000 eq (10): first-order spatial error of the FXZ module (delta' = translations)."""
    dx_x, dy_x, dz_x, a_x, b_x, c_x = ex
    dx_z, dy_z, dz_z, a_z, b_z, c_z = ez
    return np.array(
        [
            dx_x + dx_z + (z + z0) * (b_x + alpha) + y2 * (c_z + c_x),
            dy_x + dy_z - (z + z0) * a_x,
            dz_z + dz_x - y2 * (a_x + a_z),
        ]
    )


def test_paper000_eq9_10_term_by_term_to_first_order():
    # paper 000 eqs (6)-(10): P'0 = T01 dT01 Cxz T12 dT12 P2 with P2 = (0, -y2, 0)
    rng = np.random.default_rng(1)
    for _ in range(20):
        ex, ez = rng.normal(size=6), rng.normal(size=6)
        ex[:3] *= 5e-6
        ez[:3] *= 5e-6
        ex[3:] *= 20e-6
        ez[3:] *= 20e-6
        alpha = rng.normal() * 40 * ARCSEC
        z0, y2 = rng.uniform(0.0, 0.1), rng.uniform(0.0, 0.1)
        x, z = rng.uniform(0, 0.19), rng.uniform(0, 0.19)
        machine = Machine(
            "FXZ",
            {"X": Axis("X", constant_table("X", ex)), "Z": Axis("Z", constant_table("Z", ez), (0.0, 0.0, z0))},
            squareness_rad={"EB0Z": alpha},
            tool_m=(0.0, -y2, 0.0),
        )
        model = machine.volumetric_error({"X": [x], "Z": [z]})[0]
        first_order = paper000_eq10(x, z, z0, y2, alpha, ex, ez)
        # what is left is second order: products of two errors times an arm of at most 0.3 m
        eps = max(np.abs(ex[3:]).max(), np.abs(ez[3:]).max(), abs(alpha))
        assert np.abs(model - first_order).max() < 4 * eps * (eps * 0.3 + 5e-6 * 3)


def test_full_product_and_first_order_differ_at_second_order():
    rng = np.random.default_rng(2)
    ex, ez = rng.normal(size=6) * 1e-4, rng.normal(size=6) * 1e-4
    alpha = 1e-4
    gaps = []
    for scale in (1.0, 0.1, 0.01):
        machine = Machine(
            "FXZ",
            {"X": Axis("X", constant_table("X", ex * scale)), "Z": Axis("Z", constant_table("Z", ez * scale), (0, 0, 0.05))},
            squareness_rad={"EB0Z": alpha * scale},
            tool_m=(0.0, -0.04, 0.0),
        )
        model = machine.volumetric_error({"X": [0.1], "Z": [0.15]})[0]
        gaps.append(np.abs(model - paper000_eq10(0.1, 0.15, 0.05, 0.04, alpha * scale, ex * scale, ez * scale)).max())
    # the gap falls by 100 for each factor 10: it is second order
    assert gaps[0] / gaps[1] == pytest.approx(100, rel=0.05)
    assert gaps[1] / gaps[2] == pytest.approx(100, rel=0.05)


def test_single_errors_by_hand():
    # pure yaw ECX of the X carriage, tool 40 mm below it (Abbe arm along -Y): ex = -ECX * (-0.04)
    yaw = 10e-6
    machine = Machine("FX", {"X": Axis("X", constant_table("X", [0, 0, 0, 0, 0, yaw]))}, tool_m=(0.0, -0.04, 0.0))
    np.testing.assert_allclose(machine.volumetric_error({"X": [0.1]})[0], [0.4e-6, 0.0, 0.0], atol=1e-18)
    # pure pitch EBX with the tool 100 mm above: ex = EBX * 0.1, ez = -EBX * 0 (no X arm)
    machine = Machine("FX", {"X": Axis("X", constant_table("X", [0, 0, 0, 0, 20e-6, 0]))}, tool_m=(0.0, 0.0, 0.1))
    np.testing.assert_allclose(machine.volumetric_error({"X": [0.05]})[0], [2e-6, 0.0, 0.0], atol=1e-18)
    # squareness EB0Z > 0 turns Z towards +X: ex = EB0Z * (z0 + z)
    machine = Machine("FXZ", {"X": Axis("X"), "Z": Axis("Z", origin_m=(0, 0, 0.05))}, squareness_rad={"EB0Z": 1e-4})
    np.testing.assert_allclose(machine.volumetric_error({"X": [0.0], "Z": [0.15]})[0], [2e-5, 0.0, 0.0], atol=1e-15)
    # EC0Y > 0 turns Y about +Z: a Y move of 0.2 m shifts the tool by -EC0Y * 0.2 in X
    machine = Machine("FXY", {"X": Axis("X"), "Y": Axis("Y")}, squareness_rad={"EC0Y": 1e-4})
    np.testing.assert_allclose(machine.volumetric_error({"X": [0.0], "Y": [0.2]})[0], [-2e-5, 0.0, 0.0], atol=1e-15)


def test_workpiece_side_axis_mirrors_tool_side_axis():
    rng = np.random.default_rng(3)
    table = random_table("X", rng, rotation=10e-6)
    tool = np.array([0.01, -0.04, 0.12])
    q = rng.uniform(0, 0.3, 30)
    tool_side = Machine("FX", {"X": Axis("X", table)}, tool_m=tuple(tool)).volumetric_error({"X": q})
    work_side = Machine("XF", {"X": Axis("X", table)}, tool_m=tuple(tool)).volumetric_error({"X": q})
    v = table.evaluate(q).T
    delta, eps = v[:, :3], v[:, 3:]
    # tool side: delta + eps x tool; workpiece side: the carriage error undone at the tool point
    # seen from the moving table, -(delta + eps x (tool - q u)), to first order
    np.testing.assert_allclose(tool_side, delta + np.cross(eps, tool), atol=1e-14)
    arm = np.tile(tool, (q.size, 1))
    arm[:, 0] -= q
    # second-order terms are |eps|^2 * arm: below 1e-9 m here
    np.testing.assert_allclose(work_side, -(delta + np.cross(eps, arm)), atol=1e-9)
    # pure translation errors mirror exactly
    pure = ErrorTable("X", table.position_m, table.values * np.array([1, 1, 1, 0, 0, 0])[:, None])
    np.testing.assert_allclose(
        Machine("XF", {"X": Axis("X", pure)}).volumetric_error({"X": q}),
        -Machine("FX", {"X": Axis("X", pure)}).volumetric_error({"X": q}),
        atol=1e-18,
    )


def test_workpiece_point_does_not_change_the_error():
    rng = np.random.default_rng(4)
    machine = random_machine("XFYZ", rng)
    q = random_positions(machine, rng, 10)
    moved = Machine(machine.chain, machine.axes, squareness_rad=machine.squareness_rad, tool_m=machine.tool_m, workpiece_m=(0.3, -0.2, 0.1))
    np.testing.assert_allclose(machine.volumetric_error(q), moved.volumetric_error(q), atol=1e-16)


@pytest.mark.parametrize("chain", ["FXZ", "XFYZ", "ZYXF", "FX"])
def test_inverse_puts_the_tool_on_the_target_within_a_nanometre(chain):
    rng = np.random.default_rng(5)
    machine = random_machine(chain, rng)
    q = random_positions(machine, rng, 200)
    target = machine.actual_point(q)
    command = machine.command_for(target)
    reached = machine.actual_point(command)
    for letter in machine.letters:
        i = "XYZ".index(letter)
        assert np.abs(reached[:, i] - target[:, i]).max() < 1e-9
        assert np.abs(command[letter] - q[letter]).max() < 1e-9


@settings(max_examples=30, deadline=None)
@given(st.floats(-0.05, 0.35), st.integers(0, 2**31 - 1))
def test_nominal_plus_error_is_actual(q, seed):
    rng = np.random.default_rng(seed)
    machine = random_machine("YFXZ", rng)
    positions = {k: np.array([q]) for k in machine.letters}
    np.testing.assert_allclose(
        machine.actual_point(positions), machine.nominal_point(positions) + machine.volumetric_error(positions)
    )


def test_bad_machine_descriptions():
    table = ErrorTable.zeros("X")
    with pytest.raises(AxiscalError, match="no axis description"):
        Machine("FXZ", {"X": Axis("X", table)})
    with pytest.raises(AxiscalError, match="not in chain"):
        Machine("FX", {"X": Axis("X"), "Y": Axis("Y")})
    with pytest.raises(AxiscalError, match="unknown squareness"):
        Machine("FX", {"X": Axis("X")}, squareness_rad={"EC0X": 1.0})
    with pytest.raises(AxiscalError, match="error table of axis X"):
        Machine("FY", {"Y": Axis("Y", table)})
    machine = Machine("FXZ", {"X": Axis("X"), "Z": Axis("Z")})
    with pytest.raises(AxiscalError, match="no positions given for axis Z"):
        machine.volumetric_error({"X": [0.0]})
    with pytest.raises(AxiscalError, match="same number"):
        machine.volumetric_error({"X": [0.0], "Z": [0.0, 1.0]})
    with pytest.raises(AxiscalError, match="non-finite"):
        machine.volumetric_error({"X": [np.nan], "Z": [0.0]})


def test_chunked_and_threaded_evaluation_equals_one_pass():
    from axiscal.model.kinematics import volumetric_error

    rng = np.random.default_rng(6)
    machine = random_machine("XFYZ", rng)
    q = random_positions(machine, rng, 200_000)
    one_pass = volumetric_error(
        machine._tool_links, machine._workpiece_links, np.array(machine.tool_m), np.array(machine.workpiece_m), q
    )
    np.testing.assert_array_equal(machine.volumetric_error(q, workers=2), one_pass)
    np.testing.assert_array_equal(machine.volumetric_error(q, workers=1), one_pass)
    q["Y"][150_000] = 9.0
    with pytest.raises(AxiscalError, match="Y = 9000 mm is outside"):
        machine.volumetric_error(q)


def test_worked_example_of_docs_conventions():
    # docs/conventions.md, "Worked two-axis example": ex = -44.1 um at X = 100 mm, Z = 190 mm
    machine = Machine(
        "FXZ",
        {"X": Axis("X", constant_table("X", [0, 0, 0, 0, 20e-6, 10e-6])), "Z": Axis("Z", origin_m=(0, 0, 0.05))},
        squareness_rad={"EB0Z": -42.4 * ARCSEC},
        tool_m=(0.0, -0.04, 0.0),
    )
    error_um = machine.volumetric_error({"X": [0.1], "Z": [0.19]})[0] * 1e6
    assert round(error_um[0], 1) == -44.1
    assert abs(error_um[1]) < 1e-3 and abs(error_um[2]) < 1e-2


#: every 3-axis chain: workpiece-side axes, F, tool-side axes
ALL_CHAINS = ["".join(order[:cut]) + "F" + "".join(order[cut:]) for order in itertools.permutations("XYZ") for cut in range(4)]


def linear_map(machine):
    """Actual move of the tool relative to the workpiece per nominal move along X, Y, Z (columns)."""
    positions = {k: np.array([0.0, *(0.1 * (k == m) for m in "XYZ")]) for k in "XYZ"}
    nominal, actual = machine.nominal_point(positions), machine.actual_point(positions)
    return (actual[1:] - actual[0]).T @ np.linalg.inv((nominal[1:] - nominal[0]).T)


def included_angles(machine):
    """Included angles (rad) between the positive directions of X-Y, X-Z and Y-Z as the machine moves."""
    a = linear_map(machine)
    unit = a / np.linalg.norm(a, axis=0)
    return {pair: float(np.arccos(unit[:, "XYZ".index(pair[0])] @ unit[:, "XYZ".index(pair[1])])) for pair in ("XY", "XZ", "YZ")}


def test_there_are_24_three_axis_chains():
    assert len(set(ALL_CHAINS)) == 24
    for chain in ALL_CHAINS:
        parse_chain(chain)


@pytest.mark.parametrize("chain", ALL_CHAINS)
def test_default_placement_keeps_the_measured_included_angles(chain):
    # docs/conventions.md, Squareness: angle(+X, +Y) = 90 deg + EC0Y, angle(+X, +Z) = 90 deg - EB0Z,
    # angle(+Y, +Z) = 90 deg + EA0Z, whatever the chain; all three terms at once, to first order
    terms = {"EC0Y": 30 * ARCSEC, "EB0Z": -42.4 * ARCSEC, "EA0Z": 12 * ARCSEC}
    machine = Machine(chain, {k: Axis(k) for k in "XYZ"}, squareness_rad=terms)
    assert machine.squareness_placement == "relative"
    angles = included_angles(machine)
    second_order = 3 * (42.4 * ARCSEC) ** 2
    assert angles["XY"] - np.pi / 2 == pytest.approx(terms["EC0Y"], abs=second_order)
    assert angles["XZ"] - np.pi / 2 == pytest.approx(-terms["EB0Z"], abs=second_order)
    assert angles["YZ"] - np.pi / 2 == pytest.approx(terms["EA0Z"], abs=second_order)


@pytest.mark.parametrize("chain", ALL_CHAINS)
@pytest.mark.parametrize("term, pair", [("EC0Y", "XY"), ("EB0Z", "XZ"), ("EA0Z", "YZ")])
def test_guideway_placement_loses_the_term_where_the_turned_axis_carries_its_reference(chain, term, pair):
    # the "guideway" option turns the named axis' guideway; where that axis carries its reference
    # axis in the same branch, both turn together and the included angle stays 90 degrees
    value = 1e-3
    guideway = Machine(chain, {k: Axis(k) for k in "XYZ"}, squareness_rad={term: value}, squareness_placement="guideway")
    relative = Machine(chain, {k: Axis(k) for k in "XYZ"}, squareness_rad={term: value})
    turned, reference = {"EC0Y": ("Y", "X"), "EB0Z": ("Z", "X"), "EA0Z": ("Z", "Y")}[term]
    workpiece_side, tool_side = parse_chain(chain)
    carries = any(
        turned in branch and reference in branch and branch.index(turned) < branch.index(reference)
        for branch in (workpiece_side, tool_side)
    )
    lost = included_angles(guideway)[pair] == pytest.approx(np.pi / 2, abs=1e-12)
    assert lost == carries
    if not carries:
        np.testing.assert_allclose(linear_map(guideway), linear_map(relative), atol=1e-15)
    with pytest.raises(AxiscalError, match="unknown squareness placement"):
        Machine(chain, {k: Axis(k) for k in "XYZ"}, squareness_placement="sideways")


def test_error_motions_given_per_point_equal_the_tables():
    rng = np.random.default_rng(7)
    machine = random_machine("YFXZ", rng)
    for n in (50, 150_000):
        q = random_positions(machine, rng, n)
        given = {k: machine.table(k).evaluate(q[k]) for k in machine.letters}
        np.testing.assert_array_equal(machine.volumetric_error(q, errors=given), machine.volumetric_error(q))
    with pytest.raises(AxiscalError, match=r"errors of axis Z must have shape \(6, 150000\)"):
        machine.volumetric_error(q, errors={k: v for k, v in given.items() if k != "Z"})


def test_machine_file_placement_defaults_to_relative(tmp_path):
    from axiscal.model.machine import machine_from_dict

    for letter in "XYZ":
        (tmp_path / f"{letter}.csv").write_text(f"position_mm,E{letter}{letter}_um\n-1000,0\n1000,0\n")
    axes = {k: {"errors": f"{k}.csv"} for k in "XYZ"}
    data = {"chain": "FYXZ", "axes": axes, "squareness": {"EC0Y_arcsec": 20.0}}
    machine = machine_from_dict(data, base_dir=tmp_path)
    assert machine.squareness_placement == "relative"
    assert included_angles(machine)["XY"] - np.pi / 2 == pytest.approx(20 * ARCSEC, rel=1e-6)
    guideway = machine_from_dict(data | {"squareness_placement": "guideway"}, base_dir=tmp_path)
    assert included_angles(guideway)["XY"] == pytest.approx(np.pi / 2, abs=1e-12)
    with pytest.raises(AxiscalError, match="machine.toml: squareness_placement must be 'relative' or 'guideway', not 'sideways'"):
        machine_from_dict(data | {"squareness_placement": "sideways"}, base_dir=tmp_path, source="machine.toml")
