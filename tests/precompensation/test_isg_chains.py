"""The ISG volumetric table, the ISG axis lists and pre-compensation move every axis the same way, whatever side it is on.

What the kernel does, from Beckhoff's TF5280 / TF5200 documentation (Volumetric Compensation):
``chain`` (P-VOLC-00007) orders the axes from the workpiece to the tool (the manual's machine with
B and C in the workpiece is ``CBYXZ``); ``workpiece_axes`` (P-VOLC-00008, default 0: "all axes lie in
the tool") says how many of them, from the start of the chain, lie on the workpiece side; an error
parameter is the error motion of its own axis, and the manual's rule is to treat an axis as the
measurement did. A workpiece-side axis moves the workpiece: its error motion moves the tool relative
to the workpiece the opposite way, and the axis is moved the opposite way to move the tool. The
kernel below is that model for translational parameters (the only ones the table holds); the axis
lists are the leadscrew compensation, which subtracts each axis's own error from its setpoint.
"""

from __future__ import annotations

from dataclasses import replace
from pathlib import Path

import numpy as np
import pytest

from axiscal.compensation import parse_twincat_table, read_isg_csv
from axiscal.errors import AxiscalError
from axiscal.model.machine import Axis, Machine, load_machine
from axiscal.model.tables import ErrorTable
from axiscal.precompensation import export_isg, precompensate_points
from axiscal.precompensation.isg import isg_chain, isg_volumetric_table, parse_axis_numbers
from axiscal.units import UM

EXAMPLES = Path(__file__).resolve().parents[2] / "examples"
GRID = "X=0:800:200,Y=0:400:200,Z=0:400:200"


def kernel(listing: str, csv: Path) -> tuple[np.ndarray, dict[str, np.ndarray]]:
    """The ISG kernel's model read from the files alone: the nodes (SI) and each axis's setpoint correction there.

    For translational component errors ``EKK`` only, the tool's error relative to the workpiece is
    the sum of each axis's error along its own direction, with the sign of its side (+ tool, -
    workpiece); the kernel moves each axis so that the tool goes back: a tool-side axis by minus
    the tool error along it, a workpiece-side axis by plus it.
    """
    keys = dict(line.split() for line in listing.splitlines())
    chain, workpiece_axes = keys.get("chain", "XYZ"), int(keys.get("workpiece_axes", "0"))
    side = {k: -1.0 if i < workpiece_axes else 1.0 for i, k in enumerate(chain)}
    (table,) = read_isg_csv(csv)
    tool_error = {p[1]: side[p[1]] * table.parameter_si[:, j] for j, p in enumerate(table.parameters)}
    return table.argument_si, {k: -side[k] * tool_error[k] for k in tool_error}


def positioning_only(chain: str) -> Machine:
    """X, Y and Z with a positioning error each (different slopes), nothing else."""
    slope = {"X": 20.625, "Y": -12.5, "Z": 7.5}
    axes = {k: Axis(k, ErrorTable.from_components(k, [-0.1, 0.9], {f"E{k}{k}": [-slope[k] * 0.1 * UM, slope[k] * 0.9 * UM]}))
            for k in "XYZ"}
    return Machine(chain, axes)


@pytest.mark.parametrize("chain, expected", [("XFYZ", ("XYZ", 1)), ("FXYZ", ("XYZ", 0)), ("YXFZ", ("YXZ", 2)),
                                             ("XYZF", ("XYZ", 3)), ("CAFXYZ", ("XYZ", 0)), ("FZXY", ("ZXY", 0))])
def test_the_list_declares_the_chain_and_its_workpiece_axes(chain, expected):
    axes = {k: Axis(k) for k in chain if k != "F"}
    assert isg_chain(Machine(chain, axes)) == expected


@pytest.mark.parametrize("chain", ["XFYZ", "FXYZ", "YXFZ", "XYZF"])
def test_table_lists_and_precompensation_move_each_axis_alike(chain, tmp_path):
    # a table X (XFYZ) 16.5 um long at 800 mm was corrected by +8.25 um at 400 mm by the kernel (the
    # table's EXX was -8.25 um with workpiece_axes 0), by -8.25 um by the lists and pre-compensation
    machine = positioning_only(chain)
    export_isg(machine, GRID, tmp_path / "v.csv")
    export_isg(machine, GRID, tmp_path / "a", kind="axis")
    nodes, by_kernel = kernel((tmp_path / "v.lis").read_text(), tmp_path / "v.csv")
    by_points = precompensate_points(machine, nodes).correction_m
    for j, k in enumerate("XYZ"):
        by_list = parse_twincat_table((tmp_path / f"a_{k}.lis").read_text()).correction(nodes[:, j], "+")
        expected = -machine.table(k).evaluate(nodes[:, j])[j]  # each axis moved by minus its own error
        np.testing.assert_allclose(by_kernel[k], expected, rtol=0, atol=0.051e-9)
        np.testing.assert_allclose(by_list, expected, rtol=0, atol=0.051 * UM)
        # pre-compensation solves the model exactly (the error where the axis lands, not at the setpoint):
        # second order, the error's slope (2e-5) times the error
        np.testing.assert_allclose(by_points[:, j], expected, rtol=0, atol=0.001 * UM)
    x = np.isclose(nodes[:, 0], 0.4) & (nodes[:, 1] == 0) & (nodes[:, 2] == 0)
    assert by_kernel["X"][x] == pytest.approx(-8.25 * UM, abs=1e-12)


@pytest.mark.parametrize("chain", ["XFYZ", "FXYZ"])
def test_the_kernels_correction_puts_the_tool_where_precompensation_does(chain, tmp_path):
    # the example machine's 21 errors (straightness, angles, squareness): what the kernel does with
    # the table leaves the tool on its nominal point to second order, and agrees with pre-compensation
    machine = replace(load_machine(EXAMPLES / "xfyz_machine" / "machine.toml"), chain=chain)
    export_isg(machine, "X=50:750:100,Y=50:450:100,Z=50:350:100", tmp_path / "v.csv")
    nodes, by_kernel = kernel((tmp_path / "v.lis").read_text(), tmp_path / "v.csv")
    q = {k: nodes[:, j] for j, k in enumerate("XYZ")}
    corrected = {k: q[k] + by_kernel[k] for k in "XYZ"}
    before = np.abs(machine.volumetric_error(q)).max()
    left = np.abs(machine.actual_point(corrected) - machine.nominal_point(q)).max()
    assert before > 20 * UM and left < 0.01 * UM
    by_points = precompensate_points(machine, nodes).correction_m
    np.testing.assert_allclose(np.column_stack([by_kernel[k] for k in "XYZ"]), by_points, rtol=0, atol=0.01 * UM)


def test_a_turned_rotary_table_is_written_in_the_frames_directions(tmp_path):
    # the trunnion's C table at 30 degrees on its A cradle at 10: the workpiece frame is turned; the
    # kernel moves X, Y, Z along the frame's directions, and puts the tool back on its point
    machine = load_machine(EXAMPLES / "trunnion_machine" / "machine.toml")
    export_isg(machine, "X=-200:200:200,Y=-200:200:200,Z=-300:-100:100,C=30,A=10", tmp_path / "v.csv")
    nodes, by_kernel = kernel((tmp_path / "v.lis").read_text(), tmp_path / "v.csv")
    n = len(nodes)
    angles = {"C": np.full(n, np.radians(30.0)), "A": np.full(n, np.radians(10.0))}
    q = {k: nodes[:, j] for j, k in enumerate("XYZ")} | angles
    corrected = {k: q[k] + by_kernel[k] for k in "XYZ"} | angles
    before = np.abs(machine.volumetric_error(q)).max()
    left = np.abs(machine.actual_point(corrected) - machine.nominal_point(q)).max()
    assert before > 10 * UM and left < 0.01 * UM
    by_points = precompensate_points(machine, nodes, rotary_rad={"C": np.radians(30.0), "A": np.radians(10.0)}).correction_m
    np.testing.assert_allclose(np.column_stack([by_kernel[k] for k in "XYZ"]), by_points, rtol=0, atol=0.01 * UM)


def test_a_rotary_axis_that_carries_a_linear_axis_stands_at_zero():
    machine = Machine("XCFYZ", {k: Axis(k) for k in "XCYZ"})
    with pytest.raises(AxiscalError, match=r"rotary axis C carries X in chain 'XCFYZ'"):
        isg_volumetric_table(machine, "X=0:100:50,Y=0:100:50,Z=0:100:50,C=30")
    assert isg_volumetric_table(machine, "X=0:100:50,Y=0:100:50,Z=0:100:50,C=0").parameters == ("EXX", "EYY", "EZZ")


@pytest.mark.parametrize("text, message", [
    ("X=1,Y=1,Z=3", "axes X and Y are both given logical axis number 1"),
    ("X=1,X=2,Z=3", "axis_numbers names X twice"),
    ("x=2,Y=3,X=4", "axis_numbers names X twice"),
])
def test_an_axis_number_is_given_once(text, message, tmp_path):
    with pytest.raises(AxiscalError, match=message):
        parse_axis_numbers(text)
    machine = positioning_only("XFYZ")
    numbers = {"X": 1, "Y": 1, "Z": 3}
    for kind in ("volumetric", "axis"):
        with pytest.raises(AxiscalError, match="axes X and Y are both given logical axis number 1"):
            export_isg(machine, GRID, tmp_path / "v.csv", kind=kind, axis_numbers=numbers)
    assert not list(tmp_path.iterdir())


def test_duplicate_axis_numbers_on_the_command_line(run_cli, tmp_path):
    machine = EXAMPLES / "xfyz_machine" / "machine.toml"
    for fmt in ("isg", "isg-axis"):
        for numbers, message in [("X=1,Y=1,Z=3", "axes X and Y are both given logical axis number 1"),
                                 ("X=1,X=2,Y=2,Z=3", "--axis-numbers names X twice")]:
            status, stdout, err = run_cli("export", "grid", "--machine", machine, "--grid", "X=50:750:350,Y=50:450:200,Z=50:350:150",
                                          "--format", fmt, "--axis-numbers", numbers, "-o", tmp_path / "v.csv")
            assert status == 2 and stdout == "" and err.count("\n") == 1 and message in err, err
    assert not list(tmp_path.iterdir())


def test_the_list_refuses_an_axis_number_for_an_axis_not_in_the_chain(tmp_path):
    with pytest.raises(AxiscalError, match=r"axis_numbers names C, not a linear axis of chain 'XFYZ'"):
        export_isg(positioning_only("XFYZ"), GRID, tmp_path / "v.csv", axis_numbers={"X": 1, "Y": 2, "Z": 3, "C": 7})


def test_the_xfyz_example_table_holds_the_error_with_the_sign_of_each_side(tmp_path):
    machine = load_machine(EXAMPLES / "xfyz_machine" / "machine.toml")
    written = export_isg(machine, "X=50:750:350,Y=50:450:200,Z=50:350:150", tmp_path / "v.csv")
    assert (written.chain, written.workpiece_axes) == ("XYZ", 1)
    q = {k: written.volumetric.argument_si[:, j] for j, k in enumerate("XYZ")}
    np.testing.assert_allclose(written.volumetric.parameter_si, machine.volumetric_error(q) * [-1, 1, 1], rtol=0, atol=1e-15)
