"""The compiled inverse (model/inverse_kernel.py) against the plain NumPy iteration and the plain 4x4 product.

Seeded random machines of every linear chain, with tables of uneven, binned and even steps and
tables that hold their ends: the compiled commands equal the NumPy iteration's to 3e-12 m (each stops within 1e-12 m) and put
the tool, by the plain per-point 4x4 product, on the target to 1e-11 m; points that leave a table
or do not converge are reported as the NumPy iteration reports them.
"""

from __future__ import annotations

import importlib.util
from pathlib import Path

import numpy as np
import pytest

from axiscal.errors import AxiscalError
from axiscal.model import kinematics
from axiscal.model.machine import Axis, Machine, load_machine
from axiscal.model.tables import ErrorTable


def _sibling(name: str):
    spec = importlib.util.spec_from_file_location(f"_{name}", Path(__file__).with_name(f"{name}.py"))
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


_machines = _sibling("test_machine")
CHAINS = _machines.CHAINS


def _solve(machine, target, compiled: bool, monkeypatch, **options):
    monkeypatch.setattr(kinematics, "_COMPILED_FROM", 0 if compiled else 1 << 62)
    return machine.command_for(target, **options)


def _even_machine(chain, rng, *, hold_ends=False):
    """Tables of even steps (the direct lookup), some holding their ends."""
    letters = [c for c in chain if c != "F"]
    scale = np.array([10e-6] * 3 + [100e-6] * 3)[:, None]
    axes = {k: Axis(k, ErrorTable(k, np.linspace(-0.05, 0.35, 9), rng.normal(size=(6, 9)) * scale, hold_ends=hold_ends),
                    tuple(rng.normal(size=3) * 0.1)) for k in letters}
    return Machine(chain, axes, tool_m=tuple(rng.normal(size=3) * 0.1), workpiece_m=tuple(rng.normal(size=3) * 0.1))


@pytest.mark.parametrize("chain", CHAINS)
@pytest.mark.parametrize("tables", ["uneven", "binned", "even", "held"])
def test_the_compiled_inverse_equals_the_numpy_iteration_and_lands_on_the_target(chain, tables, monkeypatch):
    rng = np.random.default_rng(sum(map(ord, chain + tables)))
    if tables == "uneven":
        machine = _machines.random_machine(chain, rng)
    elif tables == "binned":
        machine = _machines.random_machine(chain, rng, rows=80)
    else:
        machine = _even_machine(chain, rng, hold_ends=tables == "held")
    q = {k: rng.uniform(0.0, 0.3, 300) for k in machine.letters}
    target = machine.nominal_point(q) + rng.normal(size=(300, 3)) * 20e-6
    fast = _solve(machine, target, True, monkeypatch)
    plain = _solve(machine, target, False, monkeypatch)
    for k in machine.letters:
        np.testing.assert_allclose(fast[k], plain[k], rtol=0, atol=3e-12)  # each within 1e-12 m of the exact one
    # the tool at the commands, by the plain per-point 4x4 product, on the target along the axes
    landed = machine.nominal_point(fast) + machine.reference_volumetric_error(fast)
    along = [kinematics.AXIS_INDEX[k] for k in machine.letters]
    np.testing.assert_allclose(landed[:, along], target[:, along], rtol=0, atol=1e-11)


def test_a_point_outside_a_table_and_one_that_does_not_converge_are_named_as_the_numpy_iteration_names_them(monkeypatch):
    rng = np.random.default_rng(5)
    machine = _machines.random_machine("XFYZ", rng)
    q = {k: rng.uniform(0.0, 0.3, 50) for k in machine.letters}
    target = machine.nominal_point(q)
    target[17, 1] += 1.0  # Y one metre past its table
    messages = []
    for compiled in (True, False):
        with pytest.raises(AxiscalError) as caught:
            _solve(machine, target, compiled, monkeypatch)
        messages.append(str(caught.value))
    assert messages[0] == messages[1] and messages[0].startswith("point 18: needs Y = ")
    target[17, 1] -= 1.0
    for compiled in (True, False):
        with pytest.raises(AxiscalError, match=r"^point \d+: inverse kinematics did not converge \(miss "):
            _solve(machine, target, compiled, monkeypatch, tolerance_m=1e-30, max_iterations=2)


def test_a_large_input_runs_compiled_on_threads(examples, monkeypatch):
    machine = load_machine(examples / "xfyz_machine" / "machine.toml")
    rng = np.random.default_rng(32)
    n = 3 * 65536 + 11
    q = {"X": rng.uniform(0.05, 0.75, n), "Y": rng.uniform(0.05, 0.45, n), "Z": rng.uniform(0.05, 0.35, n)}
    target = machine.actual_point(q)
    fast = machine.command_for(target)  # from 65536 points on: compiled, chunks on threads
    for k in "XYZ":
        np.testing.assert_allclose(fast[k], q[k], rtol=0, atol=1e-11)
    picks = rng.choice(n, 200, replace=False)
    plain = _solve(machine, target[picks], False, monkeypatch)
    for k in "XYZ":
        np.testing.assert_allclose(fast[k][picks], plain[k], rtol=0, atol=3e-12)
