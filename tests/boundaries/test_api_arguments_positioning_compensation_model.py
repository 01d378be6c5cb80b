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

import warnings
from pathlib import Path
from types import SimpleNamespace

import numpy as np
from hypothesis import given, settings
from hypothesis import strategies as hs

from api_cases import EXAMPLES, CaseTable, api, finite_or_refused


NEVER = Path("/tmp/axiscal-never-written")

ROOMS = ("positioning", "compensation", "model")
NAN, INF = float("nan"), float("inf")

TABLE = CaseTable(ROOMS)
bad = TABLE.bad
CASES = TABLE.cases


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
bad(P, "PositioningRun", "beyond any physical value", lambda: po.PositioningRun([0.0, 1e300], D25, D25), lambda: po.PositioningRun(T2, np.full((2, 5), 1e300), None))
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
bad(P, "plan_step_cycle", "period_m", lambda: po.plan_step_cycle(0.0, 0.0), lambda: po.plan_step_cycle(0.0, NAN))
bad(P, "plan_step_cycle", "steps_per_period", lambda: po.plan_step_cycle(0.0, 5e-3, steps_per_period=3))
bad(P, "plan_step_cycle", "periods", lambda: po.plan_step_cycle(0.0, 5e-3, periods=0))
bad(P, "plan_step_cycle", "overrun_m", lambda: po.plan_step_cycle(0.0, 5e-3, overrun_m=-1e-3))
bad(P, "plan_step_cycle", "at least 1 um", lambda: po.plan_step_cycle(0.0, 5e-6, steps_per_period=12))
bad(P, "gcode_program", "on_the_fly", lambda: po.gcode_program(PLAN, on_the_fly="yes"))
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



# ---------------------------------------------------------------- compensation
co = api("compensation")
C = "compensation"
STATS = po.target_statistics(RUN)
CURVE = co.error_curve(STATS)
LCNC = co.linuxcnc_table(CURVE)
SAG_X = np.linspace(0.0, 0.4, 5)
SAG_E = np.array([0.0, 1e-6, 2e-6, 1e-6, 0.0])
PROFILE = EXAMPLES / "straightness_profile.csv"

bad(C, "ErrorCurve", "positions", lambda: co.ErrorCurve(None, [0.0], [0.0]), lambda: co.ErrorCurve([], [], []), lambda: co.ErrorCurve([NAN, 0.1], [0.0, 0.0], [0.0, 0.0]),
    lambda: co.ErrorCurve("ab", [0.0, 0.0], [0.0, 0.0]), lambda: co.ErrorCurve(np.zeros((2, 2)), [0.0, 0.0], [0.0, 0.0]))
bad(C, "ErrorCurve", "strictly increasing", lambda: co.ErrorCurve([0.1, 0.0], [0.0, 0.0], [0.0, 0.0]))
bad(C, "ErrorCurve", "up", lambda: co.ErrorCurve(T2, [0.0, NAN], [0.0, 0.0]), lambda: co.ErrorCurve(T2, None, [0.0, 0.0]), lambda: co.ErrorCurve(T2, [0.0], [0.0, 0.0]))
bad(C, "ErrorCurve", "down", lambda: co.ErrorCurve(T2, [0.0, 0.0], [INF, 0.0]), lambda: co.ErrorCurve(T2, [0.0, 0.0], [0.0, 0.0, 0.0]))
bad(C, "ErrorCurve", "period", lambda: co.ErrorCurve(T2, [0.0, 0.0], [0.0, 0.0], period=0.0), lambda: co.ErrorCurve(T2, [0.0, 0.0], [0.0, 0.0], period=NAN),
    lambda: co.ErrorCurve(T2, [0.0, 0.0], [0.0, 0.0], period="turn"))
bad(C, "ErrorCurve", "unknown direction", lambda: CURVE.at(0.0, "up"), lambda: CURVE.at(0.0, None), lambda: CURVE.at(0.0, np.array([])))
bad(C, "ErrorCurve", "x", lambda: CURVE.at(NAN, "+"), lambda: CURVE.at("a", "+"), lambda: CURVE.at(None, "+"))
bad(C, "error_curve", "stats must be a TargetStatistics, not None", lambda: co.error_curve(None))
bad(C, "error_curve", "stats", lambda: co.error_curve(RUN), lambda: co.error_curve({"targets": T2}))
bad(C, "error_curve", "period", lambda: co.error_curve(STATS, period=-1.0), lambda: co.error_curve(STATS, period=INF))
bad(C, "residuals", "curve must be an ErrorCurve", lambda: co.residuals(LCNC, None, 0.0, "+"))
bad(C, "residuals", "table", lambda: co.residuals(None, CURVE, 0.0, "+"), lambda: co.residuals("table", CURVE, 0.0, "+"))
bad(C, "residuals", "x", lambda: co.residuals(LCNC, CURVE, [NAN], "+"), lambda: co.residuals(LCNC, CURVE, "a", "+"))
bad(C, "residuals", "direction", lambda: co.residuals(LCNC, CURVE, 0.0, "up"), lambda: co.residuals(LCNC, CURVE, 0.0, None))
bad(C, "residuals", "offset", lambda: co.residuals(LCNC, CURVE, 0.0, "+", offset=NAN), lambda: co.residuals(LCNC, CURVE, 0.0, "+", offset=None))
bad(C, "linuxcnc_table", "curve must be an ErrorCurve, not None", lambda: co.linuxcnc_table(None))
bad(C, "linuxcnc_table", "curve", lambda: co.linuxcnc_table(STATS), lambda: co.linuxcnc_table(np.array([])))
bad(C, "linuxcnc_table", "comp_type", lambda: co.linuxcnc_table(CURVE, comp_type=None), lambda: co.linuxcnc_table(CURVE, comp_type=0.5), lambda: co.linuxcnc_table(CURVE, comp_type=np.array([])))
bad(C, "read_compensation", "text", lambda: co.read_compensation(None, "linuxcnc"), lambda: co.read_compensation(b"0 0 0", "linuxcnc"))
bad(C, "read_compensation", "controller", lambda: co.read_compensation("0 0 0\n", "mach3"), lambda: co.read_compensation("0 0 0\n", None))
bad(C, "read_compensation", "unit_m", lambda: co.read_compensation("0 0 0\n", "linuxcnc", unit_m=0.0))
bad(C, "read_compensation", "comp_type", lambda: co.read_compensation("0 0 0\n", "linuxcnc", comp_type=2))
bad(C, "read_compensation", "reference_position_m", lambda: co.read_compensation("%\n%\n", "fanuc", reference_position_m=np.nan))
bad(C, "parse_fanuc_tape", "text", lambda: co.parse_fanuc_tape(None))
bad(C, "parse_fanuc_tape", "'%'", lambda: co.parse_fanuc_tape("N03620A1P1\n"))
bad(C, "parse_siemens", "text", lambda: co.parse_siemens(None))
bad(C, "parse_siemens", "%_N_AX_EEC_INI", lambda: co.parse_siemens("$AA_ENC_COMP[0,0,X1]=0.0\n"))
bad(C, "ControllerCompensation", "controller", lambda: co.ControllerCompensation("mach3", np.zeros(1), np.zeros(1), np.zeros(1)))
bad(C, "ControllerCompensation", "nodes_m", lambda: co.ControllerCompensation("linuxcnc", np.array([0.0, 0.0]), np.zeros(2), np.zeros(2)),
    lambda: co.ControllerCompensation("linuxcnc", np.array([]), np.zeros(0), np.zeros(0)))
bad(C, "ControllerCompensation", "minus_m", lambda: co.ControllerCompensation("linuxcnc", np.zeros(1), np.zeros(1), np.zeros(2)))
bad(C, "linuxcnc_table", "0 or 1", lambda: co.linuxcnc_table(CURVE, comp_type=2))
bad(C, "linuxcnc_table", "unit_m", lambda: co.linuxcnc_table(CURVE, unit_m=0.0), lambda: co.linuxcnc_table(CURVE, unit_m=NAN), lambda: co.linuxcnc_table(CURVE, unit_m="mm"))
bad(C, "linuxcnc_table", "decimals", lambda: co.linuxcnc_table(CURVE, decimals=-1), lambda: co.linuxcnc_table(CURVE, decimals=2.5), lambda: co.linuxcnc_table(CURVE, decimals=None))
bad(C, "LinuxcncTable", "x", lambda: LCNC.correction("a", "+"), lambda: LCNC.correction([NAN], "+"))
bad(C, "LinuxcncTable", "unknown direction", lambda: LCNC.correction(0.0, "mean"), lambda: LCNC.correction(0.0, None))
bad(C, "parse_linuxcnc", "text", lambda: co.parse_linuxcnc(None), lambda: co.parse_linuxcnc(5), lambda: co.parse_linuxcnc(np.array([])))
bad(C, "parse_linuxcnc", "line 1", lambda: co.parse_linuxcnc("a b c"))
bad(C, "fanuc_table", "curve must be an ErrorCurve", lambda: co.fanuc_table(None, interval_m=0.01))
bad(C, "fanuc_table", "interval", lambda: co.fanuc_table(CURVE, interval_m=None), lambda: co.fanuc_table(CURVE, interval_m=NAN), lambda: co.fanuc_table(CURVE, interval_m=-0.01),
    lambda: co.fanuc_table(CURVE, interval_m="10"), lambda: co.fanuc_table(CURVE, interval_m=np.array([])))
bad(C, "fanuc_table", "magnification", lambda: co.fanuc_table(CURVE, interval_m=0.01, magnification=0), lambda: co.fanuc_table(CURVE, interval_m=0.01, magnification=1.5),
    lambda: co.fanuc_table(CURVE, interval_m=0.01, magnification=None))
bad(C, "fanuc_table", "detection_unit_m", lambda: co.fanuc_table(CURVE, interval_m=0.01, detection_unit_m=NAN), lambda: co.fanuc_table(CURVE, interval_m=0.01, detection_unit_m=None))
bad(C, "fanuc_table", "reference_position_m", lambda: co.fanuc_table(CURVE, interval_m=0.01, reference_position_m=INF), lambda: co.fanuc_table(CURVE, interval_m=0.01, reference_position_m="0"))
bad(C, "fanuc_table", "reference_point", lambda: co.fanuc_table(CURVE, interval_m=0.01, reference_point=-1), lambda: co.fanuc_table(CURVE, interval_m=0.01, reference_point=2.5))
bad(C, "fanuc_table", "axis number", lambda: co.fanuc_table(CURVE, interval_m=0.01, axis_number=0))
bad(C, "fanuc_table", "axis_number", lambda: co.fanuc_table(CURVE, interval_m=0.01, axis_number="X"))
bad(C, "fanuc_table", "bidirectional", lambda: co.fanuc_table(CURVE, interval_m=0.01, bidirectional="no"))
bad(C, "fanuc_table", "rotary", lambda: co.fanuc_table(CURVE, interval_m=0.01, rotary=None))
bad(C, "fanuc_table", "travel per revolution", lambda: co.fanuc_table(CURVE, interval_m=0.01, rotary=True), lambda: co.fanuc_table(CURVE, interval_m=0.01, rotary=True, travel_per_revolution=-1.0))
bad(C, "fanuc_table", "value_limit", lambda: co.fanuc_table(CURVE, interval_m=0.01, value_limit=None))
bad(C, "fanuc_table", "max_point", lambda: co.fanuc_table(CURVE, interval_m=0.01, max_point="1023"))
bad(C, "fanuc_table", "input_increment_m", lambda: co.fanuc_table(CURVE, interval_m=0.01, input_increment_m=None))
bad(C, "fanuc_table", "far too small", lambda: co.fanuc_table(CURVE, interval_m=0.01, detection_unit_m=1e-300), lambda: co.fanuc_table(CURVE, interval_m=0.01, detection_unit_m=5e-324))
bad(C, "fanuc_table", "more compensation points", lambda: co.fanuc_table(CURVE, interval_m=5e-324))
bad(C, "fanuc_table", "interval_m must be between", lambda: co.fanuc_table(CURVE, interval_m=1e308))
bad(C, "FanucTable", "x", lambda: co.fanuc_table(CURVE, interval_m=0.01).correction("a", "+"))
bad(C, "FanucTable", "unknown direction", lambda: co.fanuc_table(CURVE, interval_m=0.01).correction(0.0, 5))
bad(C, "siemens_table", "curve must be an ErrorCurve", lambda: co.siemens_table(None, step_m=0.01))
bad(C, "siemens_table", "step_m", lambda: co.siemens_table(CURVE, step_m=None), lambda: co.siemens_table(CURVE, step_m=NAN), lambda: co.siemens_table(CURVE, step_m="1"))
bad(C, "siemens_table", "interval must be positive", lambda: co.siemens_table(CURVE, step_m=0.0))
bad(C, "siemens_table", "machine axis", lambda: co.siemens_table(CURVE, step_m=0.01, axis=None), lambda: co.siemens_table(CURVE, step_m=0.01, axis="X 1"))
bad(C, "siemens_table", "direction", lambda: co.siemens_table(CURVE, step_m=0.01, direction="up"), lambda: co.siemens_table(CURVE, step_m=0.01, direction=None))
bad(C, "siemens_table", "zero_at_m", lambda: co.siemens_table(CURVE, step_m=0.01, zero_at_m=NAN), lambda: co.siemens_table(CURVE, step_m=0.01, zero_at_m="0"))
bad(C, "siemens_table", "encoder", lambda: co.siemens_table(CURVE, step_m=0.01, encoder=0.5))
bad(C, "siemens_table", "decimals", lambda: co.siemens_table(CURVE, step_m=0.01, decimals=-2))
bad(C, "siemens_table", "max_points", lambda: co.siemens_table(CURVE, step_m=0.01, max_points=0), lambda: co.siemens_table(CURVE, step_m=0.01, max_points=None))
bad(C, "siemens_table", "MD38000", lambda: co.siemens_table(CURVE, step_m=1e-15))
bad(C, "siemens_table", "more than 10^9 points", lambda: co.siemens_table(CURVE, step_m=1e-12, max_points=10**12))
bad(C, "siemens_table", "unit_m", lambda: co.siemens_table(CURVE, step_m=0.01, unit_m=-1.0))
bad(C, "SiemensTable", "x", lambda: co.siemens_table(CURVE, step_m=0.01).correction(None, "+"))
bad(C, "heidenhain_table", "curve must be an ErrorCurve", lambda: co.heidenhain_table(None), lambda: co.heidenhain_table("curve"))
bad(C, "heidenhain_table", "axis", lambda: co.heidenhain_table(CURVE, axis=None), lambda: co.heidenhain_table(CURVE, axis="X1"))
bad(C, "heidenhain_table", "backlash", lambda: co.heidenhain_table(CURVE, backlash="yes"))
bad(C, "heidenhain_table", "decimals", lambda: co.heidenhain_table(CURVE, decimals=1.5), lambda: co.heidenhain_table(CURVE, decimals=-1))
bad(C, "heidenhain_table", "unit_m", lambda: co.heidenhain_table(CURVE, unit_m=NAN))
bad(C, "HeidenhainTable", "x", lambda: co.heidenhain_table(CURVE).correction("a", "+"))
bad(C, "compensation_table", "path", lambda: co.compensation_table(None, "linuxcnc"), lambda: co.compensation_table(5, "linuxcnc"))
bad(C, "compensation_table", "unknown compensation table format", lambda: co.compensation_table(RUN, "okuma"), lambda: co.compensation_table(RUN, None),
    lambda: co.compensation_table(RUN, np.array([])))
bad(C, "compensation_table", "comp_type", lambda: co.compensation_table(RUN, "linuxcnc", comp_type=0.5), lambda: co.compensation_table(RUN, "linuxcnc", comp_type="1"))
bad(C, "compensation_table", "interval_m", lambda: co.compensation_table(RUN, "fanuc", interval_m=NAN), lambda: co.compensation_table(RUN, "fanuc", interval_m="10"))
bad(C, "compensation_table", "magnification", lambda: co.compensation_table(RUN, "fanuc", magnification=2.5))
bad(C, "compensation_table", "bidirectional", lambda: co.compensation_table(RUN, "fanuc", bidirectional="yes"))
bad(C, "compensation_table", "backlash", lambda: co.compensation_table(RUN, "heidenhain", backlash=1))
bad(C, "compensation_table", "axis", lambda: co.compensation_table(RUN, "siemens", axis=5), lambda: co.compensation_table(RUN, "heidenhain", axis=["X"]))
bad(C, "compensation_table", "applies to format", lambda: co.compensation_table(RUN, "linuxcnc", magnification=2))
bad(C, "klipper_lengths", "squareness_rad", lambda: co.klipper_lengths(NAN, 0.1), lambda: co.klipper_lengths(None, 0.1), lambda: co.klipper_lengths("1", 0.1))
bad(C, "klipper_lengths", "square_m", lambda: co.klipper_lengths(1e-3, 0.0), lambda: co.klipper_lengths(1e-3, -0.1), lambda: co.klipper_lengths(1e-3, None))
bad(C, "skew_correction", "firmware", lambda: co.skew_correction("grbl", xy_rad=1e-3), lambda: co.skew_correction(None, xy_rad=1e-3), lambda: co.skew_correction(np.array([]), xy_rad=1e-3))
bad(C, "skew_correction", "convention", lambda: co.skew_correction("klipper", xy_rad=1e-3, convention="x"), lambda: co.skew_correction("klipper", xy_rad=1e-3, convention=None))
bad(C, "skew_correction", "xy_rad", lambda: co.skew_correction("klipper", xy_rad="1"), lambda: co.skew_correction("klipper", xy_rad=np.array([])))
bad(C, "skew_correction", "squareness", lambda: co.skew_correction("marlin", xz_rad=NAN), lambda: co.skew_correction("rrf", yz_rad=1.0), lambda: co.skew_correction("klipper"))
bad(C, "skew_correction", "square", lambda: co.skew_correction("klipper", xy_rad=1e-3, square_m=0.0), lambda: co.skew_correction("klipper", xy_rad=1e-3, square_m="0.1"),
    lambda: co.skew_correction("klipper", xy_rad=1e-3, square_m=NAN))
bad(C, "squareness_from_results", "paths", lambda: co.squareness_from_results(None), lambda: co.squareness_from_results("result.json"), lambda: co.squareness_from_results([None]),
    lambda: co.squareness_from_results(5))
bad(C, "squareness_from_results", "not a squareness result", lambda: co.squareness_from_results([EXAMPLES / "positioning_run.json"]))
bad(C, "reversal_backlash", "run must be a PositioningRun, not None", lambda: co.reversal_backlash(None))
bad(C, "reversal_backlash", "method", lambda: co.reversal_backlash(RUN, method="median"), lambda: co.reversal_backlash(RUN, method=None))
bad(C, "reversal_backlash", "target_m", lambda: co.reversal_backlash(RUN, method="target", target_m=NAN), lambda: co.reversal_backlash(RUN, method="target", target_m="0"))
bad(C, "reversal_backlash", "target position", lambda: co.reversal_backlash(RUN, method="target"))
bad(C, "backlash_setting", "controller", lambda: co.backlash_setting("okuma", 1e-6), lambda: co.backlash_setting(None, 1e-6), lambda: co.backlash_setting(np.array([]), 1e-6))
bad(C, "backlash_setting", "backlash_m", lambda: co.backlash_setting("fanuc", NAN), lambda: co.backlash_setting("fanuc", None), lambda: co.backlash_setting("fanuc", "5"),
    lambda: co.backlash_setting("fanuc", np.array([])))
bad(C, "backlash_setting", "axis", lambda: co.backlash_setting("fanuc", 1e-6, axis=None), lambda: co.backlash_setting("fanuc", 1e-6, axis="Q"))
bad(C, "backlash_setting", "axis_number", lambda: co.backlash_setting("siemens", 1e-6, axis_number=1.5), lambda: co.backlash_setting("siemens", 1e-6, axis_number="1"))
bad(C, "backlash_setting", "axis numbers start at 1", lambda: co.backlash_setting("siemens", 1e-6, axis_number=0))
bad(C, "backlash_from_run", "controller", lambda: co.backlash_from_run("okuma", RUN), lambda: co.backlash_from_run(None, RUN))
bad(C, "backlash_from_run", "run", lambda: co.backlash_from_run("fanuc", None), lambda: co.backlash_from_run("fanuc", 5))
bad(C, "backlash_from_run", "method", lambda: co.backlash_from_run("fanuc", RUN, method="x"))
bad(C, "mach4_screw_map", "curve must be an ErrorCurve, not None", lambda: co.mach4_screw_map(None))
bad(C, "mach4_screw_map", "axis", lambda: co.mach4_screw_map(CURVE, axis=None))
bad(C, "mach4_screw_map", "points", lambda: co.mach4_screw_map(CURVE, points=1), lambda: co.mach4_screw_map(CURVE, points=2.5), lambda: co.mach4_screw_map(CURVE, points="5"))
bad(C, "mach4_screw_map", "unit", lambda: co.mach4_screw_map(CURVE, unit="cm"), lambda: co.mach4_screw_map(CURVE, unit=None), lambda: co.mach4_screw_map(CURVE, unit=np.array([])))
bad(C, "mach4_screw_map", "decimals", lambda: co.mach4_screw_map(CURVE, decimals=7), lambda: co.mach4_screw_map(CURVE, decimals=1.5))
bad(C, "mach4_screw_map", "bidirectional", lambda: co.mach4_screw_map(CURVE, bidirectional="no"))
bad(C, "Mach4ScrewMap", "x", lambda: co.mach4_screw_map(CURVE).correction("a", "+"))
bad(C, "Mach4ScrewMap", "unknown direction", lambda: co.mach4_screw_map(CURVE).correction(0.0, np.array([])))
bad(C, "twincat_table", "curve must be an ErrorCurve", lambda: co.twincat_table(None))
bad(C, "twincat_table", "axis_number", lambda: co.twincat_table(CURVE, axis_number=None), lambda: co.twincat_table(CURVE, axis_number=1.5), lambda: co.twincat_table(CURVE, axis_number=np.array([])))
bad(C, "twincat_table", "axis numbers start at 1", lambda: co.twincat_table(CURVE, axis_number=0))
bad(C, "twincat_table", "interval", lambda: co.twincat_table(CURVE, interval_m=NAN), lambda: co.twincat_table(CURVE, interval_m="1"), lambda: co.twincat_table(CURVE, interval_m=-1e-3))
bad(C, "twincat_table", "max_points", lambda: co.twincat_table(CURVE, max_points=2.5))
bad(C, "twincat_table", "axis", lambda: co.twincat_table(CURVE, axis=None))
bad(C, "twincat_table", "bilateral", lambda: co.twincat_table(CURVE, bilateral=None))
bad(C, "TwincatTable", "x", lambda: co.twincat_table(CURVE).correction("a", "+"))
bad(C, "TwincatTable", "unknown direction", lambda: co.twincat_table(CURVE).correction(0.0, None))
bad(C, "screwmap_file", "controller", lambda: co.screwmap_file(EXAMPLES / "positioning_run.csv", controller="fanuc"),
    lambda: co.screwmap_file(EXAMPLES / "positioning_run.csv", controller=None), lambda: co.screwmap_file(EXAMPLES / "positioning_run.csv", controller=np.array([])))
bad(C, "screwmap_file", "path", lambda: co.screwmap_file(None, controller="mach4"), lambda: co.screwmap_file(5, controller="twincat"))
bad(C, "screwmap_file", "axis_number", lambda: co.screwmap_file(EXAMPLES / "positioning_run.csv", controller="twincat", axis_number="1"))
ISG_TEXT = "X EXX\n0 0.001\n10 0.002\n"
bad(C, "parse_isg_csv", "text", lambda: co.parse_isg_csv(None), lambda: co.parse_isg_csv(b"X EXX"))
bad(C, "check_distinct_axis_numbers", "numbers", lambda: co.check_distinct_axis_numbers(None), lambda: co.check_distinct_axis_numbers([1, 2]))
bad(C, "check_distinct_axis_numbers", "X and Y", lambda: co.check_distinct_axis_numbers({"X": 1, "Y": 1}))
bad(C, "parse_isg_csv", "not an ISG argument", lambda: co.parse_isg_csv("Q EXX\n0 1\n"), lambda: co.parse_isg_csv("X EQX\n0 1\n"))
bad(C, "parse_isg_csv", "2 columns", lambda: co.parse_isg_csv("X EXX\n0 1 2\n"))
bad(C, "parse_isg_csv", "finite", lambda: co.parse_isg_csv("X EXX\n0 nan\n"), lambda: co.parse_isg_csv("X EXX\n0 1e400\n"))
bad(C, "parse_isg_csv", "holds no record", lambda: co.parse_isg_csv("X EXX\n#\nY EYY\n0 1\n"))
bad(C, "parse_isg_csv", "no ISG CSV block", lambda: co.parse_isg_csv("// nothing\n"))
bad(C, "read_isg_csv", "path", lambda: co.read_isg_csv(None), lambda: co.read_isg_csv(5))
bad(C, "IsgTable", "not an ISO 230-1 error parameter", lambda: co.IsgTable(("X",), ("EQX",), np.zeros((1, 1)), np.zeros((1, 1))))
bad(C, "IsgTable", "finite", lambda: co.IsgTable(("X",), ("EXX",), np.zeros((1, 1)), np.full((1, 1), NAN)))
bad(C, "IsgTable", "one row per record", lambda: co.IsgTable(("X",), ("EXX",), np.zeros((2, 1)), np.zeros((1, 1))))
bad(C, "IsgTable", "not an ISG argument", lambda: co.IsgTable(("Q",), ("EXX",), np.zeros((1, 1)), np.zeros((1, 1))))
bad(C, "volcomp_list_text", "files", lambda: co.volcomp_list_text([]), lambda: co.volcomp_list_text(None),
    lambda: co.volcomp_list_text(["a b.csv"]))
bad(C, "volcomp_list_text", "axis_numbers", lambda: co.volcomp_list_text(["v.csv"], axis_numbers={"Q": 1}),
    lambda: co.volcomp_list_text(["v.csv"], axis_numbers={"X": 1.5}))
bad(C, "volcomp_list_text", "axis numbers start at 1", lambda: co.volcomp_list_text(["v.csv"], axis_numbers={"X": 0}))
bad(C, "volcomp_list_text", "workpiece_axes", lambda: co.volcomp_list_text(["v.csv"], workpiece_axes=-1),
    lambda: co.volcomp_list_text(["v.csv"], workpiece_axes=None))
bad(C, "volcomp_list_text", "interpolation", lambda: co.volcomp_list_text(["v.csv"], interpolation="LINEAR"))
bad(C, "grid_values", "table", lambda: co.grid_values(None))
bad(C, "grid_values", "nodes of a grid", lambda: co.grid_values(co.parse_isg_csv("X Y EXX\n0 0 1\n1 0 1\n0 1 1\n")[0]))
bad(C, "parse_twincat_table", "text", lambda: co.parse_twincat_table(None))
bad(C, "parse_twincat_table", "the list has no", lambda: co.parse_twincat_table("kopf.achs_nr 1\n"))
bad(C, "parse_twincat_table", "cannot read", lambda: co.parse_twincat_table("kopf.achs_nr 1\nspeed 5\n"))
bad(C, "parse_twincat_table", "whole number", lambda: co.parse_twincat_table("kw.ssfk.interval 0.5\n"))
bad(C, "screwmap_file", "twincat settings", lambda: co.screwmap_file(EXAMPLES / "positioning_run.csv", controller="mach4", interval_m=1e-3))
bad(C, "sinumerik_sag_table", "position_m", lambda: co.sinumerik_sag_table("x", SAG_E, input_axis="X", output_axis="Z", step_m=0.1),
    lambda: co.sinumerik_sag_table(None, SAG_E, input_axis="X", output_axis="Z", step_m=0.1))
bad(C, "sinumerik_sag_table", "deviation_m", lambda: co.sinumerik_sag_table(SAG_X, [None] * 5, input_axis="X", output_axis="Z", step_m=0.1))
bad(C, "sinumerik_sag_table", "two equal lists", lambda: co.sinumerik_sag_table(SAG_X, SAG_E[:3], input_axis="X", output_axis="Z", step_m=0.1),
    lambda: co.sinumerik_sag_table([], [], input_axis="X", output_axis="Z", step_m=0.1))
bad(C, "sinumerik_sag_table", "finite", lambda: co.sinumerik_sag_table(SAG_X, [NAN] * 5, input_axis="X", output_axis="Z", step_m=0.1))
bad(C, "sinumerik_sag_table", "step", lambda: co.sinumerik_sag_table(SAG_X, SAG_E, input_axis="X", output_axis="Z", step_m=None),
    lambda: co.sinumerik_sag_table(SAG_X, SAG_E, input_axis="X", output_axis="Z", step_m="0.1"), lambda: co.sinumerik_sag_table(SAG_X, SAG_E, input_axis="X", output_axis="Z", step_m=0.0))
bad(C, "sinumerik_sag_table", "compensation axis", lambda: co.sinumerik_sag_table(SAG_X, SAG_E, input_axis=None, output_axis="Z", step_m=0.1),
    lambda: co.sinumerik_sag_table(SAG_X, SAG_E, input_axis="X", output_axis="X", step_m=0.1))
bad(C, "sinumerik_sag_table", "reference", lambda: co.sinumerik_sag_table(SAG_X, SAG_E, input_axis="X", output_axis="Z", step_m=0.1, reference="best"),
    lambda: co.sinumerik_sag_table(SAG_X, SAG_E, input_axis="X", output_axis="Z", step_m=0.1, reference=None))
bad(C, "sinumerik_sag_table", "direction", lambda: co.sinumerik_sag_table(SAG_X, SAG_E, input_axis="X", output_axis="Z", step_m=0.1, direction=0.5),
    lambda: co.sinumerik_sag_table(SAG_X, SAG_E, input_axis="X", output_axis="Z", step_m=0.1, direction=np.array([])))
bad(C, "sinumerik_sag_table", "table", lambda: co.sinumerik_sag_table(SAG_X, SAG_E, input_axis="X", output_axis="Z", step_m=0.1, table=-1),
    lambda: co.sinumerik_sag_table(SAG_X, SAG_E, input_axis="X", output_axis="Z", step_m=0.1, table="0"))
bad(C, "sinumerik_sag_table", "max_points", lambda: co.sinumerik_sag_table(SAG_X, SAG_E, input_axis="X", output_axis="Z", step_m=0.1, max_points="5"))
bad(C, "SinumerikSagTable", "x", lambda: co.sinumerik_sag_table(SAG_X, SAG_E, input_axis="X", output_axis="Z", step_m=0.1).correction("a"))
bad(C, "heidenhain_sag_table", "position_m", lambda: co.heidenhain_sag_table("x", SAG_E, base_axis="X", compensation_axis="Z"))
bad(C, "heidenhain_sag_table", "axis", lambda: co.heidenhain_sag_table(SAG_X, SAG_E, base_axis=5, compensation_axis="Z"),
    lambda: co.heidenhain_sag_table(SAG_X, SAG_E, base_axis="X1", compensation_axis="Z"))
bad(C, "heidenhain_sag_table", "step", lambda: co.heidenhain_sag_table(SAG_X, SAG_E, base_axis="X", compensation_axis="Z", step_m=NAN))
bad(C, "heidenhain_sag_table", "file name", lambda: co.heidenhain_sag_table(SAG_X, SAG_E, base_axis="X", compensation_axis="Z", name="a b"),
    lambda: co.heidenhain_sag_table(SAG_X, SAG_E, base_axis="X", compensation_axis="Z", name=5))
bad(C, "heidenhain_sag_table", "decimals", lambda: co.heidenhain_sag_table(SAG_X, SAG_E, base_axis="X", compensation_axis="Z", decimals=7))
bad(C, "sag_table_file", "controller", lambda: co.sag_table_file(PROFILE, controller="fanuc", base_axis="X", compensation_axis="Z"),
    lambda: co.sag_table_file(PROFILE, controller=np.array([]), base_axis="X", compensation_axis="Z"))
bad(C, "sag_table_file", "path", lambda: co.sag_table_file(None, controller="heidenhain", base_axis="X", compensation_axis="Z"))
bad(C, "sag_table_file", "table", lambda: co.sag_table_file(PROFILE, controller="heidenhain", base_axis="X", compensation_axis="Z", table=np.array([])))
bad(C, "sag_table_file", "direction", lambda: co.sag_table_file(PROFILE, controller="siemens", base_axis="X", compensation_axis="Z", step_m=0.01, direction="up"))
bad(C, "sag_table_file", "step", lambda: co.sag_table_file(PROFILE, controller="siemens", base_axis="X", compensation_axis="Z"))



# ---------------------------------------------------------------- model
mo = api("model")
M = "model"
XZ = EXAMPLES / "xz_module"
MACHINE = mo.load_machine(XZ / "machine.toml")
TX = mo.ErrorTable.zeros("X", 0.0, 0.2)
TZ = mo.ErrorTable.zeros("Z", 0.0, 0.2)
TC = mo.ErrorTable.zeros("C")
LX = mo.ChainLink("X", TX, np.zeros(3), np.zeros(3))
LZ = mo.ChainLink("Z", TZ, np.zeros(3), np.zeros(3))
Q = {"X": np.array([0.0, 0.1]), "Z": np.array([0.0, 0.1])}
V6 = np.zeros((6, 2))
START, END = {"X": 0.0, "Z": 0.0}, {"X": 0.19, "Z": 0.19}
DIAG = mo.diagonal_check(MACHINE, START, END, 4)

bad(M, "ErrorTable", "letter", lambda: mo.ErrorTable(np.array([]), [0.0, 1.0], V6), lambda: mo.ErrorTable(None, [0.0, 1.0], V6), lambda: mo.ErrorTable("Q", [0.0, 1.0], V6))
bad(M, "ErrorTable", "positions", lambda: mo.ErrorTable("X", "ab", V6), lambda: mo.ErrorTable("X", None, V6))
bad(M, "ErrorTable", "shape", lambda: mo.ErrorTable("X", [0.0, 1.0], np.zeros((5, 2))), lambda: mo.ErrorTable("X", [0.0, 1.0], np.zeros(6)))
bad(M, "ErrorTable", "non-finite", lambda: mo.ErrorTable("X", [0.0, NAN], V6), lambda: mo.ErrorTable("X", [0.0, 1.0], np.full((6, 2), INF)))
bad(M, "ErrorTable", "interpolation", lambda: mo.ErrorTable("X", [0.0, 1.0], V6, interpolation="spline"), lambda: mo.ErrorTable("X", [0.0, 1.0], V6, interpolation=None),
    lambda: mo.ErrorTable("X", [0.0, 1.0], V6, interpolation=np.array([])))
bad(M, "ErrorTable", "hold_ends", lambda: mo.ErrorTable("X", [0.0, 1.0], V6, hold_ends="no"))
bad(M, "ErrorTable", "periodic", lambda: mo.ErrorTable("X", [0.0, 1.0], V6, periodic=True), lambda: mo.ErrorTable("C", [0.0, 1.0], V6, periodic="yes"))
bad(M, "ErrorTable", "positions of axis X", lambda: TX.evaluate("a"), lambda: TX.evaluate(None), lambda: TX.evaluate([[0.0, "a"]]))
bad(M, "ErrorTable", "outside the error table", lambda: TX.evaluate([NAN]), lambda: MACHINE.table("X").evaluate(0.5), lambda: MACHINE.table("X").check_range([0.0, INF]))
bad(M, "ErrorTable", "component", lambda: TX.component("EXY"), lambda: TX.component(None))
bad(M, "ErrorTable", "components", lambda: mo.ErrorTable.from_components("X", [0.0, 0.1], None), lambda: mo.ErrorTable.from_components("X", [0.0, 0.1], {"QQQ": [0, 0]}))
bad(M, "ErrorTable", "start_m", lambda: mo.ErrorTable.zeros("X", NAN, 1.0), lambda: mo.ErrorTable.zeros("X", "0", 1.0))
bad(M, "read_error_table", "path", lambda: mo.read_error_table(None, "X"), lambda: mo.read_error_table(5, "X"))
bad(M, "read_error_table", "letter", lambda: mo.read_error_table(XZ / "x_errors.csv", None), lambda: mo.read_error_table(XZ / "x_errors.csv", "Q"))
bad(M, "read_error_table", "interpolation", lambda: mo.read_error_table(XZ / "x_errors.csv", "X", interpolation="spline"))
bad(M, "read_error_table", "hold_ends", lambda: mo.read_error_table(XZ / "x_errors.csv", "X", hold_ends=None))
bad(M, "ChainLink", "letter", lambda: mo.ChainLink("C", TX, np.zeros(3), np.zeros(3)), lambda: mo.ChainLink(None, TX, np.zeros(3), np.zeros(3)))
bad(M, "ChainLink", "table", lambda: mo.ChainLink("X", None, np.zeros(3), np.zeros(3)), lambda: mo.ChainLink("X", TZ, np.zeros(3), np.zeros(3)))
bad(M, "ChainLink", "origin_m", lambda: mo.ChainLink("X", TX, np.zeros(2), np.zeros(3)), lambda: mo.ChainLink("X", TX, [NAN, 0, 0], np.zeros(3)), lambda: mo.ChainLink("X", TX, None, np.zeros(3)))
bad(M, "ChainLink", "squareness_rad", lambda: mo.ChainLink("X", TX, np.zeros(3), "abc"), lambda: mo.ChainLink("X", TX, np.zeros(3), [0, INF, 0]))
bad(M, "RotaryLink", "letter", lambda: mo.RotaryLink("X", TC, np.zeros(3), np.zeros(3), np.zeros(3)))
bad(M, "RotaryLink", "table", lambda: mo.RotaryLink("C", "table", np.zeros(3), np.zeros(3), np.zeros(3)))
bad(M, "RotaryLink", "offset_m", lambda: mo.RotaryLink("C", TC, np.zeros(3), np.zeros(4), np.zeros(3)))
bad(M, "RotaryLink", "tilt_rad", lambda: mo.RotaryLink("C", TC, np.zeros(3), np.zeros(3), [NAN, 0, 0]))
bad(M, "volumetric_error", "tool_links", lambda: mo.volumetric_error(None, [], np.zeros(3), np.zeros(3), Q), lambda: mo.volumetric_error(["X"], [], np.zeros(3), np.zeros(3), Q))
bad(M, "volumetric_error", "workpiece_links", lambda: mo.volumetric_error([LX], "Z", np.zeros(3), np.zeros(3), Q))
bad(M, "volumetric_error", "tool_m", lambda: mo.volumetric_error([LX, LZ], [], None, np.zeros(3), Q), lambda: mo.volumetric_error([LX, LZ], [], np.zeros(2), np.zeros(3), Q))
bad(M, "volumetric_error", "workpiece_m", lambda: mo.volumetric_error([LX, LZ], [], np.zeros(3), [NAN, 0, 0], Q))
bad(M, "volumetric_error", "positions_m", lambda: mo.volumetric_error([LX, LZ], [], np.zeros(3), np.zeros(3), None),
    lambda: mo.volumetric_error([LX, LZ], [], np.zeros(3), np.zeros(3), {"X": [0.0]}), lambda: mo.volumetric_error([LX, LZ], [], np.zeros(3), np.zeros(3), {"X": [NAN], "Z": [0.0]}),
    lambda: mo.volumetric_error([LX, LZ], [], np.zeros(3), np.zeros(3), {"X": [0.0, 0.1], "Z": [0.0]}), lambda: mo.volumetric_error([LX, LZ], [], np.zeros(3), np.zeros(3), {"X": "a", "Z": [0.0]}))
bad(M, "volumetric_error", "errors", lambda: mo.volumetric_error([LX, LZ], [], np.zeros(3), np.zeros(3), Q, {"X": V6}), lambda: mo.volumetric_error([LX, LZ], [], np.zeros(3), np.zeros(3), Q, {"X": V6, "Z": np.zeros((6, 3))}),
    lambda: mo.volumetric_error([LX, LZ], [], np.zeros(3), np.zeros(3), Q, {"X": V6, "Z": np.full((6, 2), NAN)}), lambda: mo.volumetric_error([LX, LZ], [], np.zeros(3), np.zeros(3), Q, 5))
bad(M, "pose_error", "tool_links", lambda: mo.pose_error(None, [], np.zeros(3), Q))
bad(M, "pose_error", "positions_m", lambda: mo.pose_error([LX, LZ], [], np.zeros(3), None), lambda: mo.pose_error([LX, LZ], [], np.zeros(3), {"X": [INF], "Z": [0.0]}))
bad(M, "pose_error", "tool_m", lambda: mo.pose_error([LX, LZ], [], "x", Q))
bad(M, "pose_error", "errors", lambda: mo.pose_error([LX, LZ], [], np.zeros(3), Q, {"X": V6}))
bad(M, "reference_volumetric_error", "tool_links", lambda: mo.reference_volumetric_error(None, [], np.zeros(3), np.zeros(3), Q),
    lambda: mo.reference_volumetric_error([mo.RotaryLink("C", TC, np.zeros(3), np.zeros(3), np.zeros(3))], [], np.zeros(3), np.zeros(3), {"C": [0.0]}))
bad(M, "reference_volumetric_error", "positions_m", lambda: mo.reference_volumetric_error([LX, LZ], [], np.zeros(3), np.zeros(3), {"X": [NAN], "Z": [0.0]}))
bad(M, "translation_matrix", "t_m", lambda: mo.translation_matrix(None), lambda: mo.translation_matrix([NAN, 0, 0]), lambda: mo.translation_matrix([0, 0]), lambda: mo.translation_matrix("abc"))
bad(M, "error_matrix", "tx_m", lambda: mo.error_matrix(None, 0, 0, 0, 0, 0), lambda: mo.error_matrix(NAN, 0, 0, 0, 0, 0))
bad(M, "error_matrix", "ec_rad", lambda: mo.error_matrix(0, 0, 0, 0, 0, "x"), lambda: mo.error_matrix(0, 0, 0, 0, 0, np.zeros(2)))
bad(M, "link_matrix", "link", lambda: mo.link_matrix(None, 0.0), lambda: mo.link_matrix("X", 0.0))
bad(M, "link_matrix", "q_m", lambda: mo.link_matrix(LX, NAN), lambda: mo.link_matrix(LX, None), lambda: mo.link_matrix(LX, "0"))
bad(M, "Axis", "letter", lambda: mo.Axis(None), lambda: mo.Axis("Q"), lambda: mo.Axis(np.array([])))
bad(M, "Axis", "table", lambda: mo.Axis("X", table="x_errors.csv"), lambda: mo.Axis("X", table=TZ))
bad(M, "Axis", "origin_m", lambda: mo.Axis("X", origin_m=(NAN, 0.0, 0.0)), lambda: mo.Axis("X", origin_m=(0.0, 0.0)), lambda: mo.Axis("X", origin_m=None))
bad(M, "parse_chain", "chain", lambda: mo.parse_chain(None), lambda: mo.parse_chain(5), lambda: mo.parse_chain("XQF"), lambda: mo.parse_chain(np.array([])))
bad(M, "Machine", "chain", lambda: mo.Machine(None, {"X": mo.Axis("X")}), lambda: mo.Machine("FQ", {}))
bad(M, "Machine", "axes", lambda: mo.Machine("FX", None))
bad(M, "Machine", "axis", lambda: mo.Machine("FX", {"X": "axis"}), lambda: mo.Machine("FX", {}), lambda: mo.Machine("FX", {"X": mo.Axis("Z")}))
bad(M, "Machine", "squareness", lambda: mo.Machine("FXZ", {"X": mo.Axis("X"), "Z": mo.Axis("Z")}, squareness_rad={"EB0Z": NAN}),
    lambda: mo.Machine("FXZ", {"X": mo.Axis("X"), "Z": mo.Axis("Z")}, squareness_rad={"EB0Z": "1"}), lambda: mo.Machine("FXZ", {"X": mo.Axis("X"), "Z": mo.Axis("Z")}, squareness_rad=None))
bad(M, "Machine", "tool_m", lambda: mo.Machine("FX", {"X": mo.Axis("X")}, tool_m=(0.0, NAN, 0.0)), lambda: mo.Machine("FX", {"X": mo.Axis("X")}, tool_m=None))
bad(M, "Machine", "workpiece_m", lambda: mo.Machine("FX", {"X": mo.Axis("X")}, workpiece_m="abc"))
bad(M, "Machine", "name", lambda: mo.Machine("FX", {"X": mo.Axis("X")}, name=None))
bad(M, "Machine", "placement", lambda: mo.Machine("FX", {"X": mo.Axis("X")}, squareness_placement="absolute"))
bad(M, "Machine", "positions", lambda: MACHINE.volumetric_error(None), lambda: MACHINE.volumetric_error({"X": [0.0]}), lambda: MACHINE.volumetric_error({"X": [NAN], "Z": [0.0]}))
bad(M, "Machine", "errors", lambda: MACHINE.volumetric_error(Q, errors={"X": V6, "Z": np.full((6, 2), NAN)}), lambda: MACHINE.volumetric_error(Q, errors=5))
bad(M, "Machine", "workers", lambda: MACHINE.volumetric_error(Q, workers=0), lambda: MACHINE.volumetric_error(Q, workers="2"))
bad(M, "Machine", "not in chain", lambda: MACHINE.table("Q"), lambda: MACHINE.travel_m(None), lambda: MACHINE.table(np.array([])))
bad(M, "machine_from_dict", "chain", lambda: mo.machine_from_dict({}), lambda: mo.machine_from_dict({"chain": 5}))
bad(M, "machine_from_dict", "machine description", lambda: mo.machine_from_dict(None), lambda: mo.machine_from_dict([("chain", "FX")]))
bad(M, "machine_from_dict", "base_dir", lambda: mo.machine_from_dict({"chain": "FX"}, base_dir=None))
bad(M, "machine_from_dict", "source", lambda: mo.machine_from_dict({"chain": "FX"}, source=None))
bad(M, "load_machine", "path", lambda: mo.load_machine(None), lambda: mo.load_machine(5))
bad(M, "load_machine", "tables_dir", lambda: mo.load_machine(XZ / "machine.toml", tables_dir=5))
bad(M, "as_machine", "machine", lambda: mo.as_machine(None), lambda: mo.as_machine(5), lambda: mo.as_machine({"chain": "FX"}))
bad(M, "axis_positions_from_grid", "grid", lambda: mo.axis_positions_from_grid(None), lambda: mo.axis_positions_from_grid(5), lambda: mo.axis_positions_from_grid("X=a"),
    lambda: mo.axis_positions_from_grid("X=0:nan:10"), lambda: mo.axis_positions_from_grid(""), lambda: mo.axis_positions_from_grid(np.array([])))
bad(M, "positions_from_points", "point", lambda: mo.positions_from_points(None), lambda: mo.positions_from_points([]), lambda: mo.positions_from_points([{"X": NAN}]),
    lambda: mo.positions_from_points([{"X": "a"}]), lambda: mo.positions_from_points([5]), lambda: mo.positions_from_points([{"X": 0.0}, {"Z": 0.0}]))
bad(M, "positions_from_points", "one number per point", lambda: mo.positions_from_points([{"X": [0.0, 1.0]}]))
bad(M, "read_points", "machine", lambda: mo.read_points(XZ / "diagonal_laser.csv", None))
bad(M, "read_points", "path", lambda: mo.read_points(None, MACHINE))
bad(M, "check_travel", "machine", lambda: mo.check_travel(None, Q))
bad(M, "check_travel", "positions", lambda: mo.check_travel(MACHINE, None), lambda: mo.check_travel(MACHINE, {"X": ["a"], "Z": [0.0]}), lambda: mo.check_travel(MACHINE, [0.0, 0.1]))
bad(M, "check_travel", "outside the error table", lambda: mo.check_travel(MACHINE, {"X": [NAN], "Z": [0.0]}), lambda: mo.check_travel(MACHINE, {"X": [0.0], "Z": [1.0]}))
bad(M, "check_travel", "lines", lambda: mo.check_travel(MACHINE, Q, lines=5), lambda: mo.check_travel(MACHINE, Q, lines=[1]))
bad(M, "parse_point", "point", lambda: mo.parse_point(None), lambda: mo.parse_point(5), lambda: mo.parse_point("X=a"), lambda: mo.parse_point("X=nan"), lambda: mo.parse_point(""))
bad(M, "parse_point", "option", lambda: mo.parse_point("X=0", option=None))
bad(M, "read_targets", "path", lambda: mo.read_targets(None), lambda: mo.read_targets(5))
bad(M, "read_interferometer", "path", lambda: mo.read_interferometer(None))
bad(M, "read_interferometer", "nominal_m", lambda: mo.read_interferometer(XZ / "diagonal_laser.csv", nominal_m="x"), lambda: mo.read_interferometer(XZ / "diagonal_laser.csv", nominal_m=[NAN]))
bad(M, "read_interferometer", "readings for a diagonal of 2 points", lambda: mo.read_interferometer(XZ / "diagonal_laser.csv", nominal_m=[0.0, 0.01]))
bad(M, "table_text", "columns", lambda: mo.table_text(None), lambda: mo.table_text({"a_mm": [1.0], "b_mm": [1.0, 2.0]}), lambda: mo.table_text([1, 2]))
bad(M, "table_text", "column", lambda: mo.table_text({"a_mm": "x"}), lambda: mo.table_text({"a_mm": [[1.0]]}), lambda: mo.table_text({5: [1.0]}))
bad(M, "table_text", "fmt", lambda: mo.table_text({"a_mm": [1.0]}, fmt=None), lambda: mo.table_text({"a_mm": [1.0]}, fmt="{:q}"))
bad(M, "write_table", "path", lambda: mo.write_table(None, {"a_mm": [1.0]}, kind="t"), lambda: mo.write_table(5, {"a_mm": [1.0]}, kind="t"))
bad(M, "write_table", "columns", lambda: mo.write_table(NEVER / "t.csv", None, kind="t"))
bad(M, "write_table", "kind", lambda: mo.write_table(NEVER / "t.csv", {"a_mm": [1.0]}, kind=None))
bad(M, "write_table", "sources", lambda: mo.write_table(NEVER / "t.csv", {"a_mm": [1.0]}, kind="t", sources=5))
bad(M, "render_template", "template", lambda: mo.render_template(None), lambda: mo.render_template("model/none.txt.j2"))
bad(M, "volumetric_map", "machine", lambda: mo.volumetric_map(None, grid="X=0,Z=0"), lambda: mo.volumetric_map(5, grid="X=0,Z=0"))
bad(M, "volumetric_map", "points", lambda: mo.volumetric_map(MACHINE), lambda: mo.volumetric_map(MACHINE, grid="X=0,Z=0", points=XZ / "p.csv"))
bad(M, "volumetric_map", "grid", lambda: mo.volumetric_map(MACHINE, grid=5), lambda: mo.volumetric_map(MACHINE, grid="X=nan,Z=0"))
bad(M, "volumetric_map", "positions", lambda: mo.volumetric_map(MACHINE, positions=5), lambda: mo.volumetric_map(MACHINE, positions={"X": "a", "Z": [0.0]}))
bad(M, "volumetric_map", "outside the error table", lambda: mo.volumetric_map(MACHINE, positions={"X": [NAN], "Z": [0.0]}))
bad(M, "diagonal_positions", "start and end", lambda: mo.diagonal_positions(None, END, 4), lambda: mo.diagonal_positions(START, None, 4), lambda: mo.diagonal_positions(START, {"X": 0.1}, 4))
bad(M, "diagonal_positions", "position of axis X must be a finite number of metres", lambda: mo.diagonal_positions({"X": NAN, "Z": 0.0}, END, 4),
    lambda: mo.diagonal_positions({"X": "0", "Z": 0.0}, END, 4), lambda: mo.diagonal_positions(START, {"X": np.array([]), "Z": 0.0}, 4))
bad(M, "diagonal_positions", "steps", lambda: mo.diagonal_positions(START, END, 0), lambda: mo.diagonal_positions(START, END, 2.5), lambda: mo.diagonal_positions(START, END, None))
bad(M, "diagonal_check", "machine", lambda: mo.diagonal_check(None, START, END, 4))
bad(M, "diagonal_check", "steps", lambda: mo.diagonal_check(MACHINE, START, END, 0))
bad(M, "diagonal_check", "readings for a diagonal", lambda: mo.diagonal_check(MACHINE, START, END, 4, measured_m=[0.0]))
bad(M, "diagonal_check", "measured_m", lambda: mo.diagonal_check(MACHINE, START, END, 4, measured_m=[NAN] * 5),
    lambda: mo.diagonal_check(MACHINE, START, END, 4, measured_m="x"))
bad(M, "diagonal_check", "measure", lambda: mo.diagonal_check(MACHINE, START, END, 4, measure="size"), lambda: mo.diagonal_check(MACHINE, START, END, 4, measure=None))
bad(M, "diagonal_test", "machine", lambda: mo.diagonal_test(None, "X=0,Z=0", "X=190,Z=190"))
bad(M, "diagonal_test", "start", lambda: mo.diagonal_test(MACHINE, None, "X=190,Z=190"), lambda: mo.diagonal_test(MACHINE, "X=a", "X=190,Z=190"))
bad(M, "diagonal_test", "end", lambda: mo.diagonal_test(MACHINE, START, 5))
bad(M, "diagonal_test", "steps", lambda: mo.diagonal_test(MACHINE, START, END, steps=-1), lambda: mo.diagonal_test(MACHINE, START, END, steps="5"))
bad(M, "diagonal_test", "readings", lambda: mo.diagonal_test(MACHINE, START, END, steps=4, readings=5))
bad(M, "diagonal_test", "measure", lambda: mo.diagonal_test(MACHINE, START, END, steps=4, measure="x"))
bad(M, "inverse_commands", "machine", lambda: mo.inverse_commands(None, [[0.0, 0.0, 0.0]]))
bad(M, "inverse_commands", "targets", lambda: mo.inverse_commands(MACHINE, None), lambda: mo.inverse_commands(MACHINE, [[NAN, 0.0, 0.0]]), lambda: mo.inverse_commands(MACHINE, np.zeros((0, 3))),
    lambda: mo.inverse_commands(MACHINE, [["a", 0.0, 0.0]]))
bad(M, "inverse_commands", "target points must have shape (N, 3)", lambda: mo.inverse_commands(MACHINE, [0.0, 0.0]), lambda: mo.inverse_commands(MACHINE, 5))
bad(M, "plot_error_tables", "machine", lambda: mo.plot_error_tables(None, NEVER / "t.png"), lambda: mo.plot_error_tables("machine.toml", NEVER / "t.png"))
bad(M, "plot_error_tables", "path", lambda: mo.plot_error_tables(MACHINE, None))
bad(M, "plot_volumetric", "positions_m", lambda: mo.plot_volumetric(None, np.zeros((2, 3)), NEVER / "v.png"), lambda: mo.plot_volumetric({"X": [NAN, 0.0]}, np.zeros((2, 3)), NEVER / "v.png"))
bad(M, "plot_volumetric", "error_m", lambda: mo.plot_volumetric(Q, None, NEVER / "v.png"), lambda: mo.plot_volumetric(Q, np.zeros((3, 3)), NEVER / "v.png"), lambda: mo.plot_volumetric(Q, np.zeros(2), NEVER / "v.png"))
bad(M, "plot_volumetric", "orientation_rad", lambda: mo.plot_volumetric(Q, np.zeros((2, 3)), NEVER / "v.png", orientation_rad=np.zeros((3, 2))))
bad(M, "plot_volumetric", "path", lambda: mo.plot_volumetric(Q, np.zeros((2, 3)), None))
bad(M, "plot_diagonal", "result", lambda: mo.plot_diagonal(None, NEVER / "d.png"), lambda: mo.plot_diagonal({"nominal_m": [0.0]}, NEVER / "d.png"))
bad(M, "plot_diagonal", "path", lambda: mo.plot_diagonal(DIAG, None))
bad(M, "plot_diagonal", "overlay", lambda: mo.plot_diagonal(DIAG, NEVER / "d.png", overlay=3),
    lambda: mo.plot_diagonal(DIAG, NEVER / "d.png", overlay={"nominal_mm": [0, 1], "E_BD_um": [0, 1, 2]}))
bad(M, "plot_diagonal_experiment", "result", lambda: mo.plot_diagonal_experiment(None, NEVER / "d.png"), lambda: mo.plot_diagonal_experiment(DIAG, NEVER / "d.png"))
bad(M, "plot_diagonal_experiment", "path", lambda: mo.plot_diagonal_experiment(
    SimpleNamespace(x_m=np.zeros(2), z_m=np.zeros(2), before_m=np.zeros(2), after_m=np.zeros(2), scales_only_m=np.zeros(2)), None))


# ---------------------------------------------------------------- the check
EXEMPT = {
    # result records: the library fills them with what a function computed (per-target statistics,
    # the ISO 230-2 and VDI 3441 figures, a run file's contents, a plan, an evaluation); a user
    # reads them and does not build them, so they take no user values to check
    "positioning": {"TargetStatistics", "Iso230Result", "Vdi3441Result", "RunFile", "PositioningTestPlan", "PositioningEvaluation",
                    # a function of no arguments: the table of paper 003
                    "paper003_table4_run"},
    # result records: the table formats and findings the library writes (their methods that take
    # user values, correction(x, direction), have cases under the class name)
    "compensation": {"CompensationResult", "SkewCorrection", "BacklashSetting"},
    # result records of volumetric_map, diagonal_check and inverse_commands, and the abstract base
    # they share (their write_csv takes a path, checked where it is written)
    "model": {"VolumetricMap", "DiagonalResult", "InverseResult", "TableResult"},
}






test_bad_arguments_raise_axiscal_error_naming_them, test_every_public_callable_has_a_bad_argument_case = TABLE.tests(EXEMPT)


def test_a_volumetric_map_without_error_plots_without_a_warning(tmp_path):
    """Zero error in a plane leaves no arrows to scale: the plot is drawn, no RuntimeWarning escapes."""
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        mo.plot_volumetric(Q, np.zeros((2, 3)), tmp_path / "v.png")
    assert (tmp_path / "v.png").stat().st_size > 0


# ---------------------------------------------------------------- properties: any numbers in, finite figures out or AxiscalError
_ANY_FLOAT = hs.one_of(hs.floats(allow_nan=True, allow_infinity=True, width=64),
                       hs.sampled_from([0.0, 5e-324, -5e-324, 1e-300, 1e300, -1e300, 1.7e308]))


_finite_or_refused = finite_or_refused


@settings(max_examples=150, deadline=None)
@given(hs.lists(_ANY_FLOAT, min_size=0, max_size=4), hs.lists(_ANY_FLOAT, min_size=0, max_size=12), hs.integers(1, 3))
def test_iso230_2_of_any_numbers_is_finite_or_refused(targets, deviations, runs):
    devs = np.resize(np.asarray(deviations, dtype=float), (len(targets), runs)) if deviations else np.zeros((len(targets), runs))
    result = _finite_or_refused(lambda: po.iso230_2(po.PositioningRun(targets, devs, devs[::-1].copy())))
    if result is not None:
        figures = [v for k, v in result.figures().items() if runs >= 2 or k not in ("A", "A_up", "A_down", "R", "R_up", "R_down", "S_up", "S_down")]
        assert all(np.isfinite(v) for v in figures)


@settings(max_examples=150, deadline=None)
@given(hs.lists(hs.tuples(_ANY_FLOAT, _ANY_FLOAT), min_size=0, max_size=8))
def test_volumetric_error_of_any_positions_is_finite_or_refused(points):
    q = {"X": [p[0] for p in points], "Z": [p[1] for p in points]}
    error = _finite_or_refused(lambda: MACHINE.volumetric_error(q))
    if error is not None:
        assert error.shape == (len(points), 3) and np.all(np.isfinite(error))


@settings(max_examples=100, deadline=None)
@given(_ANY_FLOAT, _ANY_FLOAT, _ANY_FLOAT, hs.sampled_from(["fanuc", "siemens"]))
def test_compensation_table_of_any_interval_is_finite_or_refused(interval, reference, unit, fmt):
    options = {"interval_m": interval, "reference_position_m": reference}
    if fmt == "fanuc":
        options["detection_unit_m"] = unit
    result = _finite_or_refused(lambda: co.compensation_table(RUN, fmt, **options))
    if result is not None:
        assert np.isfinite(result.largest_residual_m)
