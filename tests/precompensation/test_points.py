"""Pre-compensated points: the model's actual point at each command is the nominal point of the programmed one."""

from __future__ import annotations

import numpy as np
import pytest

from axiscal.errors import AxiscalError
from axiscal.precompensation import precompensate_points

from .machines import ideal, machines

MACHINES = machines()


@pytest.mark.parametrize("name", ["xfyz", "cmm", "router"])
def test_the_tool_lands_on_the_nominal_point(name):
    machine = MACHINES[name]
    rng = np.random.default_rng(4)
    low = [machine.travel_m(k)[0] + 0.01 for k in "XYZ"]
    high = [machine.travel_m(k)[1] - 0.01 for k in "XYZ"]
    points = rng.uniform(low, high, size=(500, 3))
    result = precompensate_points(machine, points)
    q = {k: result.command_m[:, i] for i, k in enumerate("XYZ")}
    nominal = machine.nominal_point({k: points[:, i] for i, k in enumerate("XYZ")})
    assert np.abs(machine.actual_point(q) - nominal).max() < 1e-10
    assert result.residual_m.max() < 1e-10 and np.abs(result.correction_m).max() > 1e-6
    # the same commands as the model's inverse, called directly
    direct = machine.command_for(nominal)
    assert np.abs(np.column_stack([direct[k] for k in "XYZ"]) - result.command_m).max() < 1e-11


def test_a_trunnion_with_its_rotary_axes_standing_still():
    machine = MACHINES["trunnion"]
    rng = np.random.default_rng(5)
    points = rng.uniform([-0.2, -0.2, -0.4], [0.2, 0.2, -0.1], size=(200, 3))
    angles = {"A": -0.4, "C": 1.1}
    result = precompensate_points(machine, points, rotary_rad=angles)
    n = len(points)
    programmed = {k: points[:, i] for i, k in enumerate("XYZ")} | {k: np.full(n, v) for k, v in angles.items()}
    command = {k: result.command_m[:, i] for i, k in enumerate("XYZ")} | {k: np.full(n, v) for k, v in angles.items()}
    assert np.abs(machine.actual_point(command) - machine.nominal_point(programmed)).max() < 1e-10


def test_an_ideal_machine_needs_no_correction_and_a_two_axis_module_corrects_what_it_can_reach():
    result = precompensate_points(ideal(), [[0.1, 0.2, 0.3]])
    assert np.abs(result.correction_m).max() < 1e-15
    module = MACHINES["module"]
    result = precompensate_points(module, [[0.1, 0.25, 0.1]])
    assert result.command_m[0, 1] == 0.25          # no Y axis: the column passes through
    command = {"X": result.command_m[:, 0], "Z": result.command_m[:, 2]}
    miss = module.actual_point(command) - module.nominal_point({"X": [0.1], "Z": [0.1]})
    assert abs(miss[0, 0]) < 1e-10 and abs(miss[0, 2]) < 1e-10


def test_bad_points_and_commands_outside_the_tables_are_refused():
    with pytest.raises(AxiscalError, match="points_m"):
        precompensate_points(MACHINES["xfyz"], [[0.1, 0.2]])
    with pytest.raises(AxiscalError, match="point 2: needs X = .* outside the error table of axis X"):
        precompensate_points(MACHINES["xfyz"], [[0.1, 0.2, 0.1], [0.0, 0.2, 0.1]])
    with pytest.raises(AxiscalError, match="not a rotary axis"):
        precompensate_points(MACHINES["xfyz"], [[0.1, 0.2, 0.1]], rotary_rad={"C": 0.1})
