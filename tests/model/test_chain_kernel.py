"""The compiled chain: the plain per-point 4x4 product over seeded random machines, every table lookup, threads."""

from __future__ import annotations

import importlib.util
from pathlib import Path

import numpy as np
import pytest

from axiscal.errors import AxiscalError
from axiscal.model import chain_kernel
from axiscal.model.kinematics import pose_error, volumetric_error
from axiscal.model.machine import Axis, Machine
from axiscal.model.machine import load_machine
from axiscal.model.tables import ErrorTable


def sibling(name: str):
    """A test module beside this one (for its random machines and its plain 4x4 references)."""
    spec = importlib.util.spec_from_file_location(f"_{name}", Path(__file__).with_name(f"{name}.py"))
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


random_machine, random_positions = sibling("test_machine").random_machine, sibling("test_machine").random_positions
reference_pose = sibling("test_rotary").reference_pose


def test_many_points_across_chunks_and_threads_equal_the_plain_loop():
    """More points than one chunk: every chunk, on one thread or several, gives the plain loop's numbers."""
    rng = np.random.default_rng(7)
    machine = random_machine("XFYZ", rng)
    n = 2 * chain_kernel.CHUNK + 123
    q = random_positions(machine, rng, n)
    threads = machine.volumetric_error(q, workers=2)
    np.testing.assert_array_equal(threads, machine.volumetric_error(q, workers=1))
    sample = np.r_[0:5, chain_kernel.CHUNK - 2 : chain_kernel.CHUNK + 3, n - 5 : n]
    reference = machine.reference_volumetric_error({k: v[sample] for k, v in q.items()})
    np.testing.assert_allclose(threads[sample], reference, rtol=0, atol=1e-15)


@pytest.mark.parametrize("kind", ["uniform", "binned", "searched", "cubic", "held"])
def test_every_table_lookup_gives_the_tables_own_interpolation(kind):
    """Even steps, uneven steps (bins), steps too uneven for bins (a search of the rows), a cubic
    spline and a table holding its ends: the kernel's motions are ErrorTable.evaluate's."""
    rng = np.random.default_rng(3)
    position = {
        "uniform": np.linspace(0.0, 0.4, 9),
        "binned": np.sort(np.r_[0.0, rng.uniform(0.0, 0.4, 7), 0.4]),
        "searched": np.r_[0.0, 1e-8, 0.1, 0.4],
        "cubic": np.linspace(0.0, 0.4, 9),
        "held": np.linspace(0.1, 0.3, 5),
    }[kind]
    table = ErrorTable("X", position, rng.normal(size=(6, position.size)) * np.array([1e-5] * 3 + [1e-4] * 3)[:, None],
                       interpolation="cubic" if kind == "cubic" else "linear", hold_ends=kind == "held")
    assert (table._uniform_step is not None) == (kind in ("uniform", "cubic", "held"))
    assert (table._bin_rows is not None) == (kind == "binned")
    machine = Machine("FX", {"X": Axis("X", table)}, tool_m=(0.01, -0.02, 0.3))
    q = {"X": np.r_[rng.uniform(0.0, 0.4, 500), position, 0.0, 0.4]}
    errors = {"X": np.zeros((6, q["X"].size))}
    motions = table.evaluate(q["X"])
    np.testing.assert_allclose(machine.volumetric_error(q), machine.volumetric_error(q, errors={"X": motions}), rtol=0, atol=1e-18)
    np.testing.assert_allclose(machine.volumetric_error(q), machine.reference_volumetric_error(q), rtol=0, atol=1e-15)
    assert not machine.volumetric_error(q, errors=errors).any()


def test_a_position_outside_a_table_is_refused_naming_it():
    machine = Machine("FX", {"X": Axis("X", ErrorTable("X", [0.0, 0.2], np.zeros((6, 2))))})
    with pytest.raises(AxiscalError, match="X = 250 mm is outside the error table of axis X"):
        machine.volumetric_error({"X": np.r_[np.zeros(70_000), 0.25]})


def test_the_kinematics_functions_run_the_same_kernel_as_the_machine():
    rng = np.random.default_rng(11)
    machine = random_machine("YXFZ", rng)
    q = random_positions(machine, rng, 50)
    tool, workpiece = np.array(machine.tool_m), np.array(machine.workpiece_m)
    direct = volumetric_error(machine._tool_links, machine._workpiece_links, tool, workpiece, q)
    np.testing.assert_array_equal(direct, machine.volumetric_error(q))
    error, orientation = pose_error(machine._tool_links, machine._workpiece_links, tool, q)
    np.testing.assert_array_equal(error, direct)
    np.testing.assert_array_equal(orientation, machine.pose_error(q)[1])
    assert pose_error(machine._tool_links, machine._workpiece_links, tool, q, orientation=False)[1] is None


def test_a_five_axis_machine_over_many_points_equals_the_plain_loop():
    """The trunnion of the examples, periodic C and bounded A, at points spread over chunks and threads."""
    machine = load_machine(Path(__file__).resolve().parents[2] / "examples" / "trunnion_machine" / "machine.toml")
    rng = np.random.default_rng(5)
    n = chain_kernel.CHUNK + 17
    q = {k: rng.uniform(*machine.travel_m(k), n) for k in machine.letters}
    q["C"] = rng.uniform(-4 * np.pi, 4 * np.pi, n)  # any turn of the periodic C table
    error, orientation = machine.pose_error(q, workers=2)
    for i in (0, 1, chain_kernel.CHUNK - 1, chain_kernel.CHUNK, n - 1):
        ref_error, ref_orientation = reference_pose(machine, q, i)
        np.testing.assert_allclose(error[i], ref_error, atol=1e-13)
        np.testing.assert_allclose(orientation[i], ref_orientation, atol=1e-12)
    np.testing.assert_array_equal(machine.volumetric_error(q, workers=1), error)


def test_read_only_strided_and_other_typed_positions_are_taken():
    rng = np.random.default_rng(2)
    machine = random_machine("XFYZ", rng)
    q = random_positions(machine, rng, 40)
    expected = machine.volumetric_error(q)
    block = np.stack([q[k] for k in machine.letters], axis=1)  # columns of a 2-D array: strided views
    block.flags.writeable = False
    odd = {k: block[:, i] for i, k in enumerate(machine.letters)}
    odd[machine.letters[0]] = odd[machine.letters[0]].astype(">f8")
    np.testing.assert_array_equal(machine.volumetric_error(odd), expected)
    motions = {k: machine.table(k).evaluate(q[k]) for k in machine.letters}
    frozen = {k: np.asfortranarray(v) for k, v in motions.items()}
    for v in frozen.values():
        v.flags.writeable = False
    np.testing.assert_array_equal(machine.volumetric_error(q, errors=frozen), machine.volumetric_error(q, errors=motions))
