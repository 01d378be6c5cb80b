"""Every public callable of the levels, flatness and thermal rooms refuses bad arguments with
AxiscalError naming the argument (the harness is api_cases.py; the coverage test fails when a
public callable of these rooms has no case)."""

from __future__ import annotations

import numpy as np

from api_cases import EXAMPLES, CaseTable, api

ROOMS = ("levels", "flatness", "thermal")
NAN, INF = float("nan"), float("inf")

TABLE = CaseTable(ROOMS)
bad = TABLE.bad

# ---------------------------------------------------------------- levels
lv = api("levels")
L = "levels"
RUN = EXAMPLES / "levels" / "levels_run.csv"
X3 = np.array([0.0, 0.1, 0.2])


def _evaluation():
    return lv.evaluate_levels(RUN, foot_m=0.1)


bad(L, "level_profile", "foot_m", lambda: lv.level_profile(X3, np.zeros(3), foot_m=NAN),
    lambda: lv.level_profile(X3, np.zeros(3), foot_m=0.0), lambda: lv.level_profile(X3, np.zeros(3), foot_m="0.1"))
bad(L, "level_profile", "angle_rad", lambda: lv.level_profile(X3, [0, NAN, 0], foot_m=0.1),
    lambda: lv.level_profile(X3, "abc", foot_m=0.1), lambda: lv.level_profile(X3, [0, 2.0, 0], foot_m=0.1))
bad(L, "level_profile", "position_m", lambda: lv.level_profile([0.0, INF, 1.0], np.zeros(3), foot_m=0.1),
    lambda: lv.level_profile([0.2, 0.1, 0.0], np.zeros(3), foot_m=0.1), lambda: lv.level_profile([], [], foot_m=0.1))
bad(L, "level_profile", "reference_rad", lambda: lv.level_profile(X3, np.zeros(3), foot_m=0.1, reference_rad=[0, 0]),
    lambda: lv.level_profile(X3, np.zeros(3), foot_m=0.1, reference_rad=[NAN, 0, 0]))
bad(L, "LevelProfile", "foot_m", lambda: lv.LevelProfile(X3, X3, X3, X3, -1.0, "foot-chain"))
bad(L, "LevelProfile", "integration", lambda: lv.LevelProfile(X3, X3, X3, X3, 0.1, "simpson"))
bad(L, "LevelProfile", "deviation_m", lambda: lv.LevelProfile(X3, [0, NAN, 0], X3, X3, 0.1, "midpoint"))
bad(L, "LevelRun", "path", lambda: lv.LevelRun(X3, X3, None, "urad", None))
bad(L, "LevelRun", "angle_rad", lambda: lv.LevelRun(X3, X3[:2], None, "urad", "a.csv"))
bad(L, "read_level_run", "path", lambda: lv.read_level_run(None), lambda: lv.read_level_run(3))
bad(L, "read_level_run", "not found", lambda: lv.read_level_run(EXAMPLES / "no_such_levels.csv"))
bad(L, "LevelEvaluation", "run", lambda: lv.LevelEvaluation(None, _evaluation().profile, _evaluation().line))
bad(L, "LevelEvaluation", "line", lambda: lv.LevelEvaluation(_evaluation().run, _evaluation().profile, "line"))
bad(L, "evaluate_levels", "foot_m", lambda: lv.evaluate_levels(RUN, foot_m=NAN), lambda: lv.evaluate_levels(RUN, foot_m=True))
bad(L, "evaluate_levels", "reference", lambda: lv.evaluate_levels(RUN, foot_m=0.1, reference="best"))
bad(L, "evaluate_levels", "output", lambda: lv.evaluate_levels(RUN, foot_m=0.1, output=5))
bad(L, "plot_levels", "evaluation", lambda: lv.plot_levels("x.png", None))
bad(L, "plot_levels", "figure format", lambda: lv.plot_levels("x.nope", _evaluation()))


# ---------------------------------------------------------------- flatness
fl = api("flatness")
F = "flatness"
JACK = EXAMPLES / "flatness" / "union_jack_levels.toml"
LINE = fl.FlatnessLine("a", [0, 0], [1, 0], [0, 0.5, 1], [0, 0, 0])


def _surface():
    return fl.evaluate_flatness(JACK).surface


bad(F, "FlatnessLine", "name", lambda: fl.FlatnessLine("", [0, 0], [1, 0], [0, 1], [0, 0]),
    lambda: fl.FlatnessLine(None, [0, 0], [1, 0], [0, 1], [0, 0]))
bad(F, "FlatnessLine", "start_m", lambda: fl.FlatnessLine("a", [0, NAN], [1, 0], [0, 1], [0, 0]),
    lambda: fl.FlatnessLine("a", [0, 0, 0], [1, 0], [0, 1], [0, 0]))
bad(F, "FlatnessLine", "height_m", lambda: fl.FlatnessLine("a", [0, 0], [1, 0], [0, 1], [0, INF]),
    lambda: fl.FlatnessLine("a", [0, 0], [1, 0], [0, 1], [0]))
bad(F, "FlatnessLine", "distances", lambda: fl.FlatnessLine("a", [0, 0], [1, 0], [0.5, 0.2], [0, 0]),
    lambda: fl.FlatnessLine("a", [0, 0], [1, 0], [-1, 0.5], [0, 0]))
bad(F, "FlatnessLine", "same point", lambda: fl.FlatnessLine("a", [1, 1], [1, 1], [0, 1], [0, 0]))
bad(F, "FlatnessLine", "gravity", lambda: fl.FlatnessLine("a", [0, 0], [1, 0], [0, 1], [0, 0], "yes"),
    lambda: fl.line_from_angles("a", [0, 0], [1, 0], [0, 0], foot_m=0.1, gravity=None))
bad(F, "line_from_angles", "foot_m", lambda: fl.line_from_angles("a", [0, 0], [1, 0], [0, 0], foot_m=0.0),
    lambda: fl.line_from_angles("a", [0, 0], [1, 0], [0, 0], foot_m=None))
bad(F, "line_from_angles", "angle_rad", lambda: fl.line_from_angles("a", [0, 0], [1, 0], [0, NAN], foot_m=0.1),
    lambda: fl.line_from_angles("a", [0, 0], [1, 0], [0.0], foot_m=0.1))
bad(F, "line_from_angles", "end_m", lambda: fl.line_from_angles("a", [0, 0], "x", [0, 0], foot_m=0.1))
bad(F, "Closure", "value_m", lambda: fl.Closure(0.0, 0.0, ("a",), NAN))
bad(F, "Closure", "lines", lambda: fl.Closure(0.0, 0.0, (), 0.0), lambda: fl.Closure(0.0, 0.0, "ab", 0.0))
bad(F, "FlatnessZone", "minimum_zone_m", lambda: fl.FlatnessZone(1.0, -1.0, (0, 0, 0), (0, 0, 0)))
bad(F, "FlatnessZone", "least_squares_plane", lambda: fl.FlatnessZone(1.0, 1.0, (0, 0), (0, 0, 0)))
bad(F, "flatness_zone", "z_m", lambda: fl.flatness_zone([0, 1, 0], [0, 0, 1], [0, NAN, 0]),
    lambda: fl.flatness_zone([0, 1, 0], [0, 0, 1], [0, 0]))
bad(F, "flatness_zone", "one line", lambda: fl.flatness_zone([0, 1, 2], [0, 1, 2], [0, 0, 0]))
bad(F, "flatness_zone", "x_m", lambda: fl.flatness_zone("abc", [0, 0, 1], [0, 0, 0]), lambda: fl.flatness_zone([0, 1], [0, 1], [0, 0]))
bad(F, "FlatnessSurface", "lines", lambda: fl.FlatnessSurface(("a",), (), X3, X3, X3, (), _surface().zone, "moody"))
bad(F, "FlatnessSurface", "evaluation", lambda: fl.FlatnessSurface((LINE,), (), X3, X3, X3, (), _surface().zone, "best"))
bad(F, "FlatnessSurface", "zone", lambda: fl.FlatnessSurface((LINE,), (), X3, X3, X3, (), None, "moody"))
bad(F, "surface_from_lines", "lines", lambda: fl.surface_from_lines(None), lambda: fl.surface_from_lines([LINE, "b"]),
    lambda: fl.surface_from_lines("ab"))
bad(F, "surface_from_lines", "at least 2", lambda: fl.surface_from_lines([LINE]))
bad(F, "surface_from_lines", "two lines are named", lambda: fl.surface_from_lines([LINE, LINE]))
bad(F, "moody_union_jack", "8 lines", lambda: fl.moody_union_jack([LINE, fl.FlatnessLine("b", [0, 0], [0, 1], [0, 1], [0, 0])]))
bad(F, "moody_union_jack", "lines", lambda: fl.moody_union_jack(None))
bad(F, "FlatnessLines", "lines", lambda: fl.FlatnessLines([LINE], "", "a.toml"))
bad(F, "FlatnessLines", "path", lambda: fl.FlatnessLines((LINE,), "", None))
bad(F, "read_flatness_lines", "path", lambda: fl.read_flatness_lines(None))
bad(F, "read_flatness_lines", "not found", lambda: fl.read_flatness_lines(EXAMPLES / "no_such_lines.toml"))
bad(F, "FlatnessEvaluation", "source", lambda: fl.FlatnessEvaluation(None, _surface()))
bad(F, "FlatnessEvaluation", "surface", lambda: fl.FlatnessEvaluation(fl.read_flatness_lines(JACK), "surface"))
bad(F, "evaluate_flatness", "evaluation", lambda: fl.evaluate_flatness(JACK, evaluation="magic"),
    lambda: fl.evaluate_flatness(JACK, evaluation=None))
bad(F, "evaluate_flatness", "output", lambda: fl.evaluate_flatness(JACK, output=3.5))
bad(F, "plot_flatness", "surface", lambda: fl.plot_flatness("x.png", None))
bad(F, "plot_flatness", "title", lambda: fl.plot_flatness("x.png", _surface(), title=3))
bad(F, "plot_flatness", "figure format", lambda: fl.plot_flatness("x.nope", _surface()))

# ---------------------------------------------------------------- thermal
th = api("thermal")
T = "thermal"
ETVE = EXAMPLES / "thermal" / "etve_run.csv"
DRIFT = EXAMPLES / "thermal" / "drift_run.csv"
T5 = np.arange(5) * 60.0
Z5 = {"Z": np.zeros(5)}
AIR5 = {"air": np.linspace(20, 21, 5)}

bad(T, "Correlation", "lag_s", lambda: th.Correlation("X", "air", 0.5, NAN, 0.5, 1e-6))
bad(T, "Correlation", "direction", lambda: th.Correlation(None, "air", 0.5, 0.0, 0.5, 1e-6))
bad(T, "Correlation", "sensitivity", lambda: th.Correlation("X", "air", 0.5, 0.0, 0.5, "1"))
bad(T, "correlate", "time_s", lambda: th.correlate([0, 1], [0, 1], [0, 1]), lambda: th.correlate([0, 2, 1], [0, 1, 2], [0, 1, 2]))
bad(T, "correlate", "displacement", lambda: th.correlate(T5, [0, NAN, 0, 0, 0], AIR5["air"]), lambda: th.correlate(T5, None, AIR5["air"]))
bad(T, "correlate", "temperature_c", lambda: th.correlate(T5, np.zeros(5), np.zeros(4)))
bad(T, "correlate", "max_lag_s", lambda: th.correlate(T5, np.zeros(5), AIR5["air"], max_lag_s=-1.0),
    lambda: th.correlate(T5, np.zeros(5), AIR5["air"], max_lag_s=INF))
bad(T, "correlate", "sensor", lambda: th.correlate(T5, np.zeros(5), AIR5["air"], sensor=3))
bad(T, "fit_time_constant", "at least 4", lambda: th.fit_time_constant([0, 1, 2], [0, 1, 2]))
bad(T, "fit_time_constant", "values", lambda: th.fit_time_constant(T5, [0, 1, INF, 3, 4]), lambda: th.fit_time_constant(T5, "abc"))
bad(T, "EtveResult", "correlations", lambda: th.EtveResult({}, {}, [None], 1.0))
bad(T, "EtveResult", "duration_s", lambda: th.EtveResult({}, {}, (), -1.0))
bad(T, "EtveResult", "etve", lambda: th.EtveResult(None, {}, (), 1.0))
bad(T, "etve", "one temperature", lambda: th.etve(T5, Z5, {}))
bad(T, "etve", "unknown direction", lambda: th.etve(T5, {"Q": np.zeros(5)}, AIR5))
bad(T, "etve", "displacements", lambda: th.etve(T5, {"Z": np.zeros(3)}, AIR5), lambda: th.etve(T5, None, AIR5),
    lambda: th.etve(T5, {}, AIR5))
bad(T, "etve", "temperatures_c", lambda: th.etve(T5, Z5, {"air": [20, NAN, 20, 20, 20]}), lambda: th.etve(T5, Z5, [1, 2]))
bad(T, "etve", "max_lag_s", lambda: th.etve(T5, Z5, AIR5, max_lag_s=NAN))
bad(T, "DriftResult", "heating_phases", lambda: th.DriftResult({}, {}, {}, {}, {}, {}, -1, 1.0))
bad(T, "DriftResult", "drift_max", lambda: th.DriftResult(None, {}, {}, {}, {}, {}, 0, 1.0))
bad(T, "thermal_drift", "running", lambda: th.thermal_drift(T5, Z5, running=[0, 1, 2, 0, 0]),
    lambda: th.thermal_drift(T5, Z5, running=[0, 1]))
bad(T, "thermal_drift", "time_s", lambda: th.thermal_drift([0, 0, 0, 0, 0], Z5), lambda: th.thermal_drift("t", Z5))
bad(T, "thermal_drift", "displacements", lambda: th.thermal_drift(T5, {"Z": [0, 0]}))
bad(T, "ThermalRun", "time_s", lambda: th.ThermalRun([NAN], {}, {}, None, "a.csv"))
bad(T, "ThermalRun", "displacements", lambda: th.ThermalRun(T5, None, {}, None, "a.csv"))
bad(T, "ThermalRun", "path", lambda: th.ThermalRun(T5, {}, {}, None, 5))
bad(T, "read_thermal_run", "path", lambda: th.read_thermal_run(None))
bad(T, "read_thermal_run", "not found", lambda: th.read_thermal_run(EXAMPLES / "no_such_thermal.csv"))
bad(T, "EtveEvaluation", "run", lambda: th.EtveEvaluation(None, th.evaluate_etve(ETVE).result))
bad(T, "EtveEvaluation", "result", lambda: th.EtveEvaluation(th.read_thermal_run(ETVE), None))
bad(T, "evaluate_etve", "max_lag_s", lambda: th.evaluate_etve(ETVE, max_lag_s=-1.0), lambda: th.evaluate_etve(ETVE, max_lag_s="1"))
bad(T, "evaluate_etve", "path", lambda: th.evaluate_etve(None))
bad(T, "DriftEvaluation", "result", lambda: th.DriftEvaluation(th.read_thermal_run(DRIFT), th.evaluate_etve(ETVE).result))
bad(T, "DriftEvaluation", "run", lambda: th.DriftEvaluation("run", th.evaluate_drift(DRIFT).result))
bad(T, "evaluate_drift", "path", lambda: th.evaluate_drift(3), lambda: th.evaluate_drift(None))
bad(T, "plot_thermal", "run", lambda: th.plot_thermal("x.png", None))
bad(T, "plot_thermal", "title", lambda: th.plot_thermal("x.png", th.read_thermal_run(DRIFT), title=None))
bad(T, "plot_thermal", "figure format", lambda: th.plot_thermal("x.nope", th.read_thermal_run(DRIFT)))
bad(T, "plot_etve", "evaluation", lambda: th.plot_etve("x.png", None), lambda: th.plot_etve("x.png", th.read_thermal_run(DRIFT)))
bad(T, "plot_drift", "evaluation", lambda: th.plot_drift("x.png", None), lambda: th.plot_drift("x.png", th.read_thermal_run(DRIFT)))

test_bad_arguments, test_every_public_callable_has_a_case = TABLE.tests({})
