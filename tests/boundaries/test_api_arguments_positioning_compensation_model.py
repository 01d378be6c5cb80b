"""Every public callable of the positioning, compensation and model rooms refuses bad arguments with
AxiscalError naming the argument: never an AttributeError or TypeError from deep inside, an
IndexError, a NumPy broadcast error, "the truth value of an empty array is ambiguous", a stray
RuntimeWarning or a silent NaN.

The table lists, per public name, calls with the kinds of bad values a user passes: None where a
run, curve, machine or table is expected, NaN and inf, empty and mismatched arrays, wrong shapes, a
string or a bool for a number, a float for a whole number, unknown option strings, values out of
range. A coverage check fails when a public callable of these rooms has no case (or an explicit
exemption below).
"""

from __future__ import annotations

import inspect
import warnings
from collections.abc import Callable
from importlib import import_module
from pathlib import Path

import numpy as np
import pytest

from axiscal.errors import AxiscalError

EXAMPLES = Path(__file__).resolve().parents[2] / "examples"
NEVER = Path("/tmp/axiscal-never-written")

ROOMS = ("positioning", "compensation", "model")
NAN, INF = float("nan"), float("inf")

CASES: list[tuple[str, str, Callable[[], object], str]] = []  # (room, public name, call, words of the message)


def bad(room: str, name: str, words: str, *calls: Callable[[], object]) -> None:
    """Add one case per call: each must raise AxiscalError whose message holds ``words``."""
    CASES.extend((room, name, call, words) for call in calls)


def api(room: str):
    return import_module(f"axiscal.{room}")


# ---------------------------------------------------------------- positioning
po = api("positioning")
P = "positioning"
T2 = np.array([0.0, 0.1])
D25 = np.zeros((2, 5))
RUN = po.paper003_table4_run()
ISO = po.iso230_2(RUN)
PLAN = po.plan_test(0.0, 0.4, 5, seed=1)

bad(P, "PositioningRun", "targets", lambda: po.PositioningRun("x", D25, D25), lambda: po.PositioningRun(None, D25, D25),
    lambda: po.PositioningRun([[0.0, "a"]], D25, D25))
bad(P, "PositioningRun", "deviations_up", lambda: po.PositioningRun(T2, "x", D25), lambda: po.PositioningRun(T2, [[0.0, 1.0], [2.0]], None))
bad(P, "PositioningRun", "deviations_down", lambda: po.PositioningRun(T2, D25, "x"))
bad(P, "PositioningRun", "finite", lambda: po.PositioningRun([0.0, NAN], D25, D25), lambda: po.PositioningRun(T2, np.full((2, 5), INF), None))
bad(P, "PositioningRun", "shape", lambda: po.PositioningRun(T2, np.zeros((3, 5)), None), lambda: po.PositioningRun(T2, np.zeros(2), None))
bad(P, "PositioningRun", "unequal run counts", lambda: po.PositioningRun(T2, D25, np.zeros((2, 4))))
bad(P, "PositioningRun", "at least 2 target", lambda: po.PositioningRun([], np.zeros((0, 5)), None), lambda: po.PositioningRun([0.0], np.zeros((1, 5)), None))
bad(P, "PositioningRun", "no deviations", lambda: po.PositioningRun(T2, None, None))
bad(P, "PositioningRun", "strictly increasing", lambda: po.PositioningRun([0.1, 0.0], D25, D25))
bad(P, "PositioningRun", "source", lambda: po.PositioningRun(T2, D25, D25, source=None))
bad(P, "PositioningRun", "rotary", lambda: po.PositioningRun(T2, D25, D25, rotary="yes"))
bad(P, "target_statistics", "run must be a PositioningRun, not None", lambda: po.target_statistics(None))
bad(P, "target_statistics", "run", lambda: po.target_statistics("positioning_run.csv"), lambda: po.target_statistics(np.zeros((2, 5))))
bad(P, "iso230_2", "run must be a PositioningRun", lambda: po.iso230_2(None), lambda: po.iso230_2({"targets": T2}))
bad(P, "iso230_2", "edition", lambda: po.iso230_2(RUN, edition="2020"), lambda: po.iso230_2(RUN, edition=2014), lambda: po.iso230_2(RUN, edition=None),
    lambda: po.iso230_2(RUN, edition=np.array([])))
bad(P, "vdi3441", "run must be a PositioningRun", lambda: po.vdi3441(None), lambda: po.vdi3441(-1))
bad(P, "vdi3441", "bidirectional", lambda: po.vdi3441(po.PositioningRun(T2, D25, None)))
bad(P, "iso_edition", "standard", lambda: po.iso_edition(None), lambda: po.iso_edition("iso230-2:2020"), lambda: po.iso_edition(2014),
    lambda: po.iso_edition(np.array([])))
bad(P, "covers_circle", "targets_rad", lambda: po.covers_circle(None), lambda: po.covers_circle([]), lambda: po.covers_circle([0.0]),
    lambda: po.covers_circle([0.0, NAN]), lambda: po.covers_circle("x"), lambda: po.covers_circle(np.zeros((2, 2))))
bad(P, "require_finite", "end_m", lambda: po.require_finite(end_m=NAN), lambda: po.require_finite(end_m=np.float64(INF)))
bad(P, "read_positioning_run", "path", lambda: po.read_positioning_run(None), lambda: po.read_positioning_run(5))
bad(P, "read_positioning_run", "wavelength_nm", lambda: po.read_positioning_run(EXAMPLES / "laser_raw_run.csv", wavelength_nm=NAN),
    lambda: po.read_positioning_run(EXAMPLES / "laser_raw_run.csv", wavelength_nm=-633.0), lambda: po.read_positioning_run(EXAMPLES / "laser_raw_run.csv", wavelength_nm="he-ne"))
bad(P, "read_positioning_run", "co2_ppm", lambda: po.read_positioning_run(EXAMPLES / "laser_raw_run.csv", co2_ppm=NAN),
    lambda: po.read_positioning_run(EXAMPLES / "laser_raw_run.csv", co2_ppm=-1.0))
bad(P, "read_positioning_run", "expansion_per_k", lambda: po.read_positioning_run(EXAMPLES / "laser_raw_run.csv", expansion_per_k=INF),
    lambda: po.read_positioning_run(EXAMPLES / "laser_raw_run.csv", expansion_per_k="steel"))
bad(P, "read_positioning_run", "method", lambda: po.read_positioning_run(EXAMPLES / "laser_raw_run.csv", method="magic"),
    lambda: po.read_positioning_run(EXAMPLES / "laser_raw_run.csv", method=None))
bad(P, "minimum_targets", "length_m", lambda: po.minimum_targets(None), lambda: po.minimum_targets(NAN), lambda: po.minimum_targets(-1.0),
    lambda: po.minimum_targets("1"), lambda: po.minimum_targets(np.array([])))
bad(P, "plan_targets", "start_m", lambda: po.plan_targets(None, 0.4, 5), lambda: po.plan_targets("0", 0.4, 5), lambda: po.plan_targets(NAN, 0.4, 5))
bad(P, "plan_targets", "end_m", lambda: po.plan_targets(0.0, INF, 5), lambda: po.plan_targets(0.0, None, 5))
bad(P, "plan_targets", "count", lambda: po.plan_targets(0.0, 0.4, 5.5), lambda: po.plan_targets(0.0, 0.4, None), lambda: po.plan_targets(0.0, 0.4, "5"),
    lambda: po.plan_targets(0.0, 0.4, True))
bad(P, "plan_targets", "needs at least", lambda: po.plan_targets(0.0, 0.4, 2), lambda: po.plan_targets(0.0, 0.4, -1))
bad(P, "plan_targets", "beyond the start", lambda: po.plan_targets(0.4, 0.0, 5))
bad(P, "plan_targets", "seed", lambda: po.plan_targets(0.0, 0.4, 5, seed=-1), lambda: po.plan_targets(0.0, 0.4, 5, seed=1.5), lambda: po.plan_targets(0.0, 0.4, 5, seed="a"))
bad(P, "plan_test", "runs", lambda: po.plan_test(0.0, 0.4, 5, runs=0), lambda: po.plan_test(0.0, 0.4, 5, runs=2.5), lambda: po.plan_test(0.0, 0.4, 5, runs=None))
bad(P, "plan_test", "overrun", lambda: po.plan_test(0.0, 0.4, 5, overrun_m=0.0), lambda: po.plan_test(0.0, 0.4, 5, overrun_m=NAN),
    lambda: po.plan_test(0.0, 0.4, 5, overrun_m="5"), lambda: po.plan_test(0.0, 0.4, 5, overrun_m=None))
bad(P, "plan_test", "unknown cycle", lambda: po.plan_test(0.0, 0.4, 5, cycle="zigzag"), lambda: po.plan_test(0.0, 0.4, 5, cycle=None),
    lambda: po.plan_test(0.0, 0.4, 5, cycle=np.array([])))
bad(P, "plan_test", "end_m", lambda: po.plan_test(0.0, NAN, 5))
bad(P, "cycle_csv", "plan must be a PositioningTestPlan, not None", lambda: po.cycle_csv(None))
bad(P, "cycle_csv", "plan", lambda: po.cycle_csv(RUN))
bad(P, "gcode_program", "plan must be a PositioningTestPlan", lambda: po.gcode_program(None), lambda: po.gcode_program("plan"))
bad(P, "gcode_program", "axis", lambda: po.gcode_program(PLAN, axis=None), lambda: po.gcode_program(PLAN, axis="XY"), lambda: po.gcode_program(PLAN, axis=1))
bad(P, "gcode_program", "dwell", lambda: po.gcode_program(PLAN, dwell_s=NAN), lambda: po.gcode_program(PLAN, dwell_s=-1.0), lambda: po.gcode_program(PLAN, dwell_s="2"))
bad(P, "gcode_program", "feed", lambda: po.gcode_program(PLAN, feed_mm_per_min=0.0), lambda: po.gcode_program(PLAN, feed_mm_per_min=None))
bad(P, "write_plan", "plan must be a PositioningTestPlan", lambda: po.write_plan(None, NEVER / "p.csv"))
bad(P, "write_plan", "csv_path", lambda: po.write_plan(PLAN, 5), lambda: po.write_plan(PLAN, ""))
bad(P, "write_plan", "gcode_path", lambda: po.write_plan(PLAN, gcode_path=5))
bad(P, "write_plan", "feed", lambda: po.write_plan(PLAN, NEVER / "p.csv", gcode_path=NEVER / "p.ngc", feed_mm_per_min=-1.0))
bad(P, "plot_positioning", "run must be a PositioningRun", lambda: po.plot_positioning(None, ISO, NEVER / "p.png"))
bad(P, "plot_positioning", "result", lambda: po.plot_positioning(RUN, None, NEVER / "p.png"), lambda: po.plot_positioning(RUN, {"A": 1.0}, NEVER / "p.png"))
bad(P, "plot_positioning", "path", lambda: po.plot_positioning(RUN, ISO, None), lambda: po.plot_positioning(RUN, ISO, 5))
bad(P, "plot_positioning", "title", lambda: po.plot_positioning(RUN, ISO, NEVER / "p.png", title=5))
bad(P, "plot_positioning", "targets", lambda: po.plot_positioning(po.PositioningRun([0.0, 0.1, 0.2], np.zeros((3, 2)), np.zeros((3, 2))), ISO, NEVER / "p.png"))
bad(P, "plot_positioning", "overlay", lambda: po.plot_positioning(RUN, ISO, NEVER / "p.png", overlay=[1, 2]),
    lambda: po.plot_positioning(RUN, ISO, NEVER / "p.png", overlay={"target_mm": "x", "mean_up_um": [1.0, 2.0]}),
    lambda: po.plot_positioning(RUN, ISO, NEVER / "p.png", overlay={"target_mm": [0.0, 20.0], "mean_up_um": [1.0]}))
bad(P, "evaluate_positioning_file", "path", lambda: po.evaluate_positioning_file(None), lambda: po.evaluate_positioning_file(3))
bad(P, "evaluate_positioning_file", "unknown standard", lambda: po.evaluate_positioning_file(EXAMPLES / "positioning_run.csv", standard="iso9000"),
    lambda: po.evaluate_positioning_file(EXAMPLES / "positioning_run.csv", standard=None))
bad(P, "evaluate_positioning_file", "wavelength_nm", lambda: po.evaluate_positioning_file(EXAMPLES / "laser_raw_run.csv", wavelength_nm=NAN),
    lambda: po.evaluate_positioning_file(EXAMPLES / "laser_raw_run.csv", wavelength_nm=0.0), lambda: po.evaluate_positioning_file(EXAMPLES / "laser_raw_run.csv", wavelength_nm="x"))
bad(P, "evaluate_positioning_file", "expansion_per_k", lambda: po.evaluate_positioning_file(EXAMPLES / "laser_raw_run.csv", expansion_per_k="x"))
bad(P, "render_template", "template", lambda: po.render_template(None), lambda: po.render_template("positioning/none.txt.j2"),
    lambda: po.render_template("positioning_report.txt.j2"))


# ---------------------------------------------------------------- the check
EXEMPT = {
    # result records: the library fills them with what a function computed (per-target statistics,
    # the ISO 230-2 and VDI 3441 figures, a run file's contents, a plan, an evaluation); a user
    # reads them and does not build them, so they take no user values to check
    "positioning": {"TargetStatistics", "Iso230Result", "Vdi3441Result", "RunFile", "PositioningTestPlan", "PositioningEvaluation",
                    # a function of no arguments: the table of paper 003
                    "paper003_table4_run"},
}


def _public_callables(room: str) -> set[str]:
    module = api(room)
    names = set()
    for name in module.__all__:
        value = getattr(module, name)
        if callable(value) and not (inspect.isclass(value) and issubclass(value, (int, str))):
            names.add(name)
    return names


def _ids():
    counts: dict[str, int] = {}
    for room, name, _, _ in CASES:
        key = f"{room}.{name}"
        counts[key] = counts.get(key, 0) + 1
        yield f"{key}-{counts[key]}"


@pytest.mark.parametrize(("room", "name", "call", "words"), CASES, ids=list(_ids()))
def test_bad_arguments_raise_axiscal_error_naming_them(room, name, call, words):
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        with pytest.raises(AxiscalError) as caught:
            call()
    assert words.lower() in caught.value.message.lower(), caught.value.message


@pytest.mark.parametrize("room", ROOMS)
def test_every_public_callable_has_a_bad_argument_case(room):
    covered = {name for r, name, _, _ in CASES if r == room}
    missing = sorted(_public_callables(room) - covered - EXEMPT.get(room, set()))
    assert not missing, f"public callables of axiscal.{room} without a bad-argument case: {missing}"
