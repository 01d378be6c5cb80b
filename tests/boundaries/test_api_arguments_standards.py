"""Every public callable of the levels, flatness and thermal rooms refuses bad arguments with
AxiscalError naming the argument (the harness is api_cases.py; the coverage test fails when a
public callable of these rooms has no case)."""

from __future__ import annotations

import numpy as np

from api_cases import EXAMPLES, CaseTable, api

ROOMS = ("levels",)
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

test_bad_arguments, test_every_public_callable_has_a_case = TABLE.tests({})
