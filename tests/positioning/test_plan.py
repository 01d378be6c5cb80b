"""ISO 230-2 test planning: uneven targets, linear and pilgrim cycles, G-code."""

from __future__ import annotations

import json
import re

import numpy as np
import pandas as pd
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from axiscal.errors import AxiscalError
from axiscal.positioning.evaluation import iso230_2
from axiscal.positioning.plan import (
    PLAN_COLUMNS,
    cycle_csv,
    gcode_program,
    minimum_targets,
    plan_targets,
    plan_test,
    write_plan,
)
from axiscal.positioning.reader import read_positioning_run
from axiscal.units import MM, UM


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
    assert lines[0] == "step,run,direction,target_mm,move_to_mm,deviation_um"
    assert len(lines) == 1 + plan.moves.size and not any(line.startswith("#") for line in lines)
    assert all(line.endswith(",") for line in lines[1:])  # deviation_um: empty, to be typed in
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
    assert f"seed {plan.seed}" in plan.description
    assert f"seed {plan.seed})" in gcode_program(plan).splitlines()[1]


def fill_in(text: str, deviation_um) -> str:
    """Type a reading into every row of a cycle CSV that has a target, as a technician would."""
    lines = text.splitlines()
    header = lines[0].split(",")
    t, r, d = header.index("target_mm"), header.index("run"), header.index("direction")
    out = [lines[0]]
    for line in lines[1:]:
        cells = line.split(",")
        if cells[t]:
            cells[-1] = f"{deviation_um(float(cells[t]), int(cells[r]), cells[d]):.4f}"
        out.append(",".join(cells))
    return "\n".join(out) + "\n"


@pytest.mark.parametrize("cycle", ["linear", "pilgrim"])
def test_a_filled_in_plan_is_a_run_file_as_it_is(tmp_path, cycle):
    plan = plan_test(0.0, 0.8, 17, runs=3, seed=1, cycle=cycle)
    paths = write_plan(plan, tmp_path / "cycle.csv")
    assert [p.name for p in paths] == ["cycle.csv", "cycle.json"]
    path = tmp_path / "cycle.csv"
    path.write_text(fill_in(path.read_text(), lambda t, run, d: 0.01 * t + (1.0 if d == "+" else -1.0) + 0.1 * run))
    data = read_positioning_run(path)
    assert data.run.targets == pytest.approx(plan.targets, abs=1e-9) and data.run_labels == ("1", "2", "3")
    evaluation = iso230_2(data.run)
    assert evaluation.B == pytest.approx(2 * UM, abs=1e-12) and evaluation.M == pytest.approx(8 * UM, abs=1e-12)


def test_a_plan_not_filled_in_names_the_first_row_without_a_reading(tmp_path):
    plan = plan_test(0.0, 0.4, 5, runs=1, seed=1)
    path = write_plan(plan, tmp_path / "cycle.csv")[0]
    with pytest.raises(AxiscalError, match="no reading at target 0.000 .*type the deviation_um value in") as caught:
        read_positioning_run(path)
    assert caught.value.line == 3  # line 2 is the overrun move before it
    lines = path.read_text().splitlines()
    lines[1] = lines[1] + "1.5"  # a reading typed into an overrun move
    path.write_text("\n".join(lines) + "\n")
    with pytest.raises(AxiscalError, match="deviation_um value without a target") as caught:
        read_positioning_run(path)
    assert caught.value.line == 2


def test_plan_csv_reads_into_its_columns_with_pandas_and_the_sidecar_records_the_plan(tmp_path):
    plan = plan_test(0.0, 0.8, 17, runs=2, overrun_m=4 * MM, seed=7, cycle="pilgrim")
    csv_path, sidecar, gcode = write_plan(plan, tmp_path / "p" / "cycle.csv", gcode_path=tmp_path / "cycle.ngc")
    frame = pd.read_csv(csv_path)
    assert list(frame.columns) == list(PLAN_COLUMNS) and len(frame) == plan.moves.size
    assert frame["target_mm"].notna().sum() == plan.readings and frame["deviation_um"].isna().all()
    assert frame["move_to_mm"].to_numpy() == pytest.approx(plan.moves / MM)
    meta = json.loads(sidecar.read_text())
    assert meta["kind"] == "positioning test plan" and meta["file"] == "cycle.csv"
    assert meta["seed"] == 7 and meta["cycle"] == "pilgrim" and meta["runs"] == 2 and meta["overrun_mm"] == 4
    assert meta["target_mm"] == pytest.approx(plan.targets / MM)
    assert gcode.read_text() == gcode_program(plan)


def test_write_plan_checks_the_gcode_options_before_writing(tmp_path):
    plan = plan_test(0.0, 0.4, 5, seed=1)
    with pytest.raises(AxiscalError, match="one letter"):
        write_plan(plan, tmp_path / "cycle.csv", gcode_path=tmp_path / "cycle.ngc", axis="XY")
    assert list(tmp_path.iterdir()) == []


@settings(max_examples=25, deadline=None)
@given(st.integers(0, 10_000), st.integers(1, 3), st.sampled_from(["linear", "pilgrim"]), st.integers(5, 9))
def test_any_plan_filled_in_reads_back_the_readings_typed_in(tmp_path_factory, seed, runs, cycle, count):
    plan = plan_test(0.0, 0.5, count, runs=runs, seed=seed, cycle=cycle)
    rng = np.random.default_rng(seed)
    typed = {}

    def reading(t, run, d):
        return typed.setdefault((round(t, 3), run, d), round(float(rng.normal(0.0, 3.0)), 4))

    path = write_plan(plan, tmp_path_factory.mktemp("plan") / "cycle.csv")[0]
    path.write_text(fill_in(path.read_text(), reading))
    data = read_positioning_run(path)
    labels = [int(r) for r in data.run_labels]
    for i, t in enumerate(data.run.targets / MM):
        for j, run in enumerate(labels):
            assert data.run.deviations_up[i, j] == pytest.approx(typed[(round(t, 3), run, "+")] * UM, abs=1e-12)
            assert data.run.deviations_down[i, j] == pytest.approx(typed[(round(t, 3), run, "-")] * UM, abs=1e-12)


def test_a_plan_too_large_or_a_negative_seed_is_refused_before_allocating():
    from axiscal.positioning.plan import MAX_RUNS, MAX_TARGETS

    with pytest.raises(AxiscalError, match="at most"):
        plan_test(0.0, 0.1, 10**9, seed=1)
    with pytest.raises(AxiscalError, match="seed"):
        plan_test(0.0, 0.1, 10, seed=-1)
    with pytest.raises(AxiscalError, match="runs"):
        plan_test(0.0, 0.1, 10, runs=MAX_RUNS + 1, seed=1)
    assert plan_test(0.0, 10.0, MAX_TARGETS, runs=1, seed=1).targets.size == MAX_TARGETS


def test_a_plan_stays_within_what_a_controls_position_word_holds():
    """A start of 1e300 m wrote 300-digit X words; an overrun of 1e300 passed."""
    from axiscal.positioning.plan import MAX_OVERRUN_M, MAX_POSITION_M
    from axiscal.positioning.step_cycle import plan_step_cycle

    with pytest.raises(AxiscalError, match="start_m must be within"):
        plan_test(1e300, 2e300, 5, seed=1)
    with pytest.raises(AxiscalError, match="the plan.s moves reach 100004.999 mm"):
        plan_test(MAX_POSITION_M - 0.01, MAX_POSITION_M, 5, seed=1)  # the overrun of 5 mm goes beyond
    with pytest.raises(AxiscalError, match="overrun_m must be at most"):
        plan_test(0.0, 0.4, 5, seed=1, overrun_m=1e300)
    assert plan_test(0.0, 0.4, 5, seed=1, overrun_m=MAX_OVERRUN_M).overrun == MAX_OVERRUN_M
    with pytest.raises(AxiscalError, match="the plan's moves reach"):
        plan_step_cycle(1e300, 5e-3)
    for name, kwargs in (("period_m", {"period_m": 1e300}), ("overrun_m", {"period_m": 5e-3, "overrun_m": 1e300})):
        with pytest.raises(AxiscalError, match=f"{name} must be"):
            plan_step_cycle(0.0, **kwargs)
    program = gcode_program(plan_test(MAX_POSITION_M - 0.5, MAX_POSITION_M - 0.01, 5, seed=1))
    assert re.search(r"\d[eE][+-]?\d", program) is None and "X99989.999" in program


@pytest.mark.parametrize(("kwargs", "words"), [({"feed_mm_per_min": 1e6}, "feed_mm_per_min must be above 0 and at most 100000"),
                                               ({"feed_mm_per_min": 1e300}, "feed_mm_per_min"),
                                               ({"dwell_s": 1e300}, "dwell_s must be from 0 to 3600 s")])
def test_the_programs_feed_and_dwell_are_bounded(kwargs, words):
    with pytest.raises(AxiscalError, match=words):
        gcode_program(plan_test(0.0, 0.4, 5, seed=1), **kwargs)
