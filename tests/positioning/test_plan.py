"""ISO 230-2 test planning: uneven targets, linear and pilgrim cycles, G-code."""

from __future__ import annotations

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from axiscal.errors import AxiscalError
from axiscal.positioning.plan import (
    cycle_csv,
    gcode_program,
    minimum_targets,
    plan_targets,
    plan_test,
)
from axiscal.units import MM


def test_targets_are_uneven_reproducible_and_span_the_travel():
    t = plan_targets(0.0, 0.8, 17, seed=1)
    assert t[0] == 0.0 and t[-1] == 0.8 and np.all(np.diff(t) > 0)
    pitch = 0.8 / 16
    offsets = t - pitch * np.arange(17)
    assert np.abs(offsets).max() <= pitch / 4 + 1e-9
    assert np.ptp(np.diff(t)) > pitch / 10
    assert np.array_equal(t, plan_targets(0.0, 0.8, 17, seed=1))
    assert not np.array_equal(t, plan_targets(0.0, 0.8, 17, seed=2))
    assert np.allclose(np.round(t / 1e-6), t / 1e-6, atol=1e-6)


def test_uneven_targets_sample_a_periodic_screw_error():
    # a 10 mm lead with an even 50 mm spacing hits the screw at one phase only; the plan does not
    even = np.linspace(0.0, 0.8, 17)
    planned = plan_targets(0.0, 0.8, 17, seed=1)
    phase = lambda t: np.round((t / 0.010) % 1.0, 3) % 1.0  # noqa: E731
    assert np.unique(phase(even)).size == 1
    assert np.unique(phase(planned)).size >= 12


def test_minimum_targets_per_iso():
    assert minimum_targets(0.4) == 5 and minimum_targets(0.8) == 5 and minimum_targets(1.0) == 5
    assert minimum_targets(1.2) == 6 and minimum_targets(3.0) == 15
    with pytest.raises(AxiscalError, match="at least 6"):
        plan_targets(0.0, 1.2, 5)


@pytest.mark.parametrize("cycle", ["linear", "pilgrim"])
def test_each_target_is_read_runs_times_from_each_side(cycle):
    plan = plan_test(0.0, 0.8, 17, runs=5, overrun_m=5 * MM, seed=4, cycle=cycle)
    assert plan.readings == 17 * 5 * 2
    previous = None
    for k, pos in enumerate(plan.moves):
        target = plan.move_target[k]
        if np.isfinite(target):
            assert pos == target
            assert previous is not None
            # approached from below for "+", from above for "-", with no reversal on the way in
            if plan.move_direction[k] == "+":
                assert previous < target
            else:
                assert previous > target
        previous = pos
    for d in "+-":
        sel = np.isfinite(plan.move_target) & (plan.move_direction == d)
        values, counts = np.unique(plan.move_target[sel], return_counts=True)
        assert np.array_equal(values, plan.targets) and np.all(counts == 5)
    assert plan.moves.min() == pytest.approx(-5 * MM) and plan.moves.max() == pytest.approx(0.805)


def test_linear_cycle_order():
    plan = plan_test(0.0, 0.4, 5, runs=2, seed=0)
    first_run = plan.move_target[plan.move_run == 1]
    readings = first_run[np.isfinite(first_run)]
    assert np.array_equal(readings, np.concatenate([plan.targets, plan.targets[::-1]]))


def test_cycle_csv_and_gcode():
    plan = plan_test(0.0, 0.4, 5, runs=1, seed=0, cycle="pilgrim")
    text = cycle_csv(plan)
    lines = text.splitlines()
    assert lines[1] == "step,run,direction,target_mm,move_to_mm"
    assert len(lines) == 2 + plan.moves.size
    program = gcode_program(plan, axis="z", dwell_s=1.5, feed_mm_per_min=500)
    assert program.count("G4 P1.5") == plan.readings
    assert "G1 Z-5.000 F500" in program and program.endswith("M2\n%\n")


@pytest.mark.parametrize(
    "kwargs,message",
    [
        ({"runs": 0}, "runs"),
        ({"overrun_m": -1e-3}, "overrun"),
        ({"cycle": "zigzag"}, "unknown cycle"),
    ],
)
def test_bad_plans(kwargs, message):
    with pytest.raises(AxiscalError, match=message):
        plan_test(0.0, 0.8, 17, **kwargs)


def test_bad_gcode_options():
    plan = plan_test(0.0, 0.4, 5)
    for kwargs, message in (({"axis": "1"}, "one letter"), ({"dwell_s": -1}, "dwell"), ({"feed_mm_per_min": 0}, "feed")):
        with pytest.raises(AxiscalError, match=message):
            gcode_program(plan, **kwargs)


@settings(max_examples=50, deadline=None)
@given(st.floats(-1.0, 1.0), st.floats(0.05, 3.0), st.integers(0, 20), st.integers(0, 10_000))
def test_targets_always_increase_and_stay_in_the_travel(start, length, extra, seed):
    count = minimum_targets(length) + extra
    t = plan_targets(start, start + length, count, seed=seed)
    assert t.size == count and t[0] == start and t[-1] == start + length
    assert np.all(np.diff(t) > 0)


def test_a_plan_without_a_seed_records_the_one_it_used():
    plan = plan_test(0.0, 0.4, 5, runs=2)
    assert isinstance(plan.seed, int)
    assert np.array_equal(plan.targets, plan_test(0.0, 0.4, 5, runs=2, seed=plan.seed).targets)
    assert f"seed {plan.seed}" in cycle_csv(plan).splitlines()[0]
