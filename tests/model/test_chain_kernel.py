"""The compiled chain and the NumPy one: the plain per-point 4x4 product over seeded random machines, every table lookup, threads.

Below 65536 points the model runs as NumPy arrays, from there on compiled; the fixture ``path``
runs a test at any size on either.
"""

from __future__ import annotations

import importlib.util
from pathlib import Path

import numpy as np
import pytest

from axiscal.errors import AxiscalError
from axiscal.model import chain_kernel, kinematics
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
random_five_axis = sibling("test_rotary").random_table
CHAINS = sibling("test_machine").CHAINS


@pytest.fixture(params=["numpy", "compiled"])
def path(request, monkeypatch):
    """Run the model on one path whatever the number of points."""
    monkeypatch.setattr(kinematics, "_COMPILED_FROM", 0 if request.param == "compiled" else 1 << 62)
    return request.param


@pytest.mark.parametrize("chain", CHAINS)
def test_both_paths_equal_the_plain_4x4_product(chain, path):
    rng = np.random.default_rng(sum(map(ord, chain)))
    for _ in range(3):
        machine = random_machine(chain, rng)
        q = random_positions(machine, rng, 40)
        np.testing.assert_allclose(machine.volumetric_error(q), machine.reference_volumetric_error(q), rtol=0, atol=1e-15)


@pytest.mark.parametrize("chain", ["CAFXYZ", "FXYZBC", "CFXYZ", "XFYZC", "BFXZ", "AFYZ", "CBFXYZ", "YFXZAC"])
def test_both_paths_of_five_axis_chains_equal_the_plain_4x4_product(chain, path):
    from axiscal.conventions import location_names

    rng = np.random.default_rng(sum(map(ord, chain)) + 1)
    letters = [k for k in chain if k != "F"]
    axes = {k: Axis(k, random_five_axis(k, rng), tuple(rng.normal(size=3) * 0.1)) for k in letters}
    location = {}
    for k in letters:
        if k in "ABC":
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
    np.testing.assert_array_equal(machine.volumetric_error(q), error)


def test_the_two_paths_agree_to_the_rounding_of_the_coordinates():
    """The same machine and points on both paths: equal but for the rounding of coordinates of
    some 0.5 m (one unit in the last place is 1.1e-16 m), which the nominal point subtracts."""
    rng = np.random.default_rng(21)
    machine = random_machine("XFYZ", rng)
    q = random_positions(machine, rng, 1000)
    numpy_error = machine.volumetric_error(q)
    kinematics._COMPILED_FROM, saved = 0, kinematics._COMPILED_FROM
    try:
        compiled_error = machine.volumetric_error(q)
    finally:
        kinematics._COMPILED_FROM = saved
    np.testing.assert_allclose(compiled_error, numpy_error, rtol=0, atol=5e-16)


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
def test_every_table_lookup_gives_the_tables_own_interpolation(kind, path):
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
    np.testing.assert_allclose(machine.volumetric_error(q, errors=errors), 0.0, atol=1e-16)


def test_a_position_outside_a_table_is_refused_naming_it(path):
    machine = Machine("FX", {"X": Axis("X", ErrorTable("X", [0.0, 0.2], np.zeros((6, 2))))})
    with pytest.raises(AxiscalError, match="X = 250 mm is outside the error table of axis X"):
        machine.volumetric_error({"X": np.r_[np.zeros(70), 0.25]})


def test_the_kinematics_functions_run_the_same_path_as_the_machine(path):
    rng = np.random.default_rng(11)
    machine = random_machine("YXFZ", rng)
    q = random_positions(machine, rng, 50)
    tool, workpiece = np.array(machine.tool_m), np.array(machine.workpiece_m)
    direct = volumetric_error(machine._tool_links, machine._workpiece_links, tool, workpiece, q)
    np.testing.assert_array_equal(direct, machine.volumetric_error(q))
    error, orientation = pose_error(machine._tool_links, machine._workpiece_links, tool, q)
    np.testing.assert_allclose(error, direct, rtol=0, atol=1e-15)
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


def test_read_only_strided_and_other_typed_positions_are_taken(path):
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
