"""Every public callable of the cmm room refuses bad arguments with AxiscalError naming the argument
(the harness is api_cases.py; the coverage test fails when a public callable of the room has no case)."""

from __future__ import annotations

import numpy as np

from api_cases import EXAMPLES, CaseTable, api

ROOMS = ("cmm",)
NAN, INF = float("nan"), float("inf")

TABLE = CaseTable(ROOMS)
bad = TABLE.bad

cm = api("cmm")
C = "cmm"
E0 = EXAMPLES / "cmm" / "e0_gauge_blocks.csv"
SPHERE = EXAMPLES / "cmm" / "sphere_single.csv"
MPE = cm.Mpe(1.5e-6, k=333.0)
SIX = np.array([[1, 0, 0], [-1, 0, 0], [0, 1, 0], [0, -1, 0], [0, 0, 1], [0, 0, -1]]) * 0.01


def _m(**changes):
    args = dict(position=("1", "1"), length=("L", "L"), nominal_m=[0.1, 0.1], measured_m=[0.1, 0.1],
                repeat=[1, 2], ram_offset_m=[0.0, 0.0])
    args.update(changes)
    return cm.LengthMeasurements(**args)


def _points():
    return cm.SpherePoints(SIX, ("1",) * 6)


bad(C, "Mpe", "a_m", lambda: cm.Mpe(NAN), lambda: cm.Mpe(-1e-6), lambda: cm.Mpe("1"))
bad(C, "Mpe", "k", lambda: cm.Mpe(1e-6, k=0.0), lambda: cm.Mpe(1e-6, k=INF), lambda: cm.Mpe(1e-6, k=0.5))
bad(C, "Mpe", "at most 0.01", lambda: cm.Mpe(1e300), lambda: cm.Mpe(1e-6, b_m=1.0))
bad(C, "Mpe", "b_m", lambda: cm.Mpe(2e-6, b_m=1e-6), lambda: cm.Mpe(1e-6, b_m=NAN))
bad(C, "Mpe.at", "length_m", lambda: MPE.at([NAN]), lambda: MPE.at("abc"))
bad(C, "LengthMeasurements", "position", lambda: _m(position="12"), lambda: _m(position=("1", "")))
bad(C, "LengthMeasurements", "nominal_m", lambda: _m(nominal_m=[0.1, -0.1]), lambda: _m(nominal_m=[0.1, NAN]))
bad(C, "LengthMeasurements", "measured_m", lambda: _m(measured_m=[0.1]), lambda: _m(measured_m=None))
bad(C, "LengthMeasurements", "repeat", lambda: _m(repeat=[1, 1.5]), lambda: _m(repeat=[0, 1]))
bad(C, "LengthMeasurements", "times the nominal", lambda: _m(measured_m=[0.1, 100.0]), lambda: _m(nominal_m=[0.1, 1e-4]))
bad(C, "length_acceptance", "hold no E150 value", lambda: cm.length_acceptance(_m(), mpe_150=MPE))
bad(C, "LengthMeasurements", "ram_offset_m", lambda: _m(ram_offset_m=[0.0, -0.15]))
bad(C, "LengthMeasurements", "at least one", lambda: _m(position=(), length=(), nominal_m=[], measured_m=[], repeat=[],
                                                       ram_offset_m=[]))
bad(C, "read_length_measurements", "path", lambda: cm.read_length_measurements(None))
bad(C, "read_length_measurements", "not found", lambda: cm.read_length_measurements(EXAMPLES / "no_such_e0.csv"))
bad(C, "LengthSet", "test", lambda: cm.LengthSet("E1", "1", "L", 0.1, (0,), 0.0, 0))
bad(C, "LengthSet", "range_m", lambda: cm.LengthSet("E0", "1", "L", 0.1, (0,), -1.0, 0))
bad(C, "combined_verdict", "verdict", lambda: cm.combined_verdict(["pass", "maybe"]), lambda: cm.combined_verdict("pass"))
bad(C, "AcceptanceResult", "measurements", lambda: cm.AcceptanceResult(None, (), [], [], (), (), None, None, None,
                                                                        "simple", 0.0, 0.0))
bad(C, "length_acceptance", "measurements", lambda: cm.length_acceptance(None))
bad(C, "length_acceptance", "mpe", lambda: cm.length_acceptance(_m(), mpe=1.5e-6), lambda: cm.length_acceptance(_m(), mpe_150="x"))
bad(C, "length_acceptance", "r0_mpl_m", lambda: cm.length_acceptance(_m(), r0_mpl_m=0.0))
bad(C, "length_acceptance", "uncertainty", lambda: cm.length_acceptance(_m(), uncertainty_m=-1e-6),
    lambda: cm.length_acceptance(_m(), uncertainty_per_m=NAN))
bad(C, "length_acceptance", "decision rule", lambda: cm.length_acceptance(_m(), rule="lenient"))
bad(C, "evaluate_acceptance", "path", lambda: cm.evaluate_acceptance(None))
bad(C, "evaluate_acceptance", "uncertainty_m", lambda: cm.evaluate_acceptance(E0, uncertainty_m=INF))
bad(C, "SphereFit", "radius_m", lambda: cm.SphereFit([0, 0, 0], -1.0, [0.0]))
bad(C, "SphereFit", "centre_m", lambda: cm.SphereFit([0, 0], 1.0, [0.0]))
bad(C, "fit_sphere", "points_m", lambda: cm.fit_sphere(SIX[:3]), lambda: cm.fit_sphere(SIX[:, :2]),
    lambda: cm.fit_sphere([[NAN, 0, 0]] * 5), lambda: cm.fit_sphere("points"), lambda: cm.fit_sphere(SIX * 1e6))
bad(C, "fit_sphere", "one plane", lambda: cm.fit_sphere(SIX[:4]))
bad(C, "fit_sphere", "same point", lambda: cm.fit_sphere(np.zeros((5, 3))))
bad(C, "fit_spread", "points_m", lambda: cm.fit_spread(SIX[:3], cm.fit_sphere(SIX)), lambda: cm.fit_spread([[NAN, 0, 0]] * 6,
    cm.fit_sphere(SIX)))
bad(C, "fit_spread", "fit", lambda: cm.fit_spread(SIX, None), lambda: cm.fit_spread(SIX, 0.01))
bad(C, "SpherePoints", "stylus", lambda: cm.SpherePoints(SIX, ("1",) * 5), lambda: cm.SpherePoints(SIX, "111111"))
bad(C, "SpherePoints", "points_m", lambda: cm.SpherePoints(SIX[:2], ("1",) * 2))
bad(C, "read_sphere_points", "path", lambda: cm.read_sphere_points(3.5))
bad(C, "read_sphere_points", "not found", lambda: cm.read_sphere_points(EXAMPLES / "no_such_sphere.csv"))
bad(C, "ProbingResult", "points", lambda: cm.ProbingResult(None, 0.02, {}, None, {}, {}, {}, 0.0, "simple"))
bad(C, "probing_test", "points", lambda: cm.probing_test(SIX, calibrated_diameter_m=0.02))
bad(C, "probing_test", "calibrated_diameter_m", lambda: cm.probing_test(_points(), calibrated_diameter_m=0.0),
    lambda: cm.probing_test(_points(), calibrated_diameter_m=NAN))
bad(C, "probing_test", "mpe_m", lambda: cm.probing_test(_points(), calibrated_diameter_m=0.02, mpe_m={"pform": -1e-6}),
    lambda: cm.probing_test(_points(), calibrated_diameter_m=0.02, mpe_m=[1e-6]))
bad(C, "probing_test", "figure", lambda: cm.probing_test(_points(), calibrated_diameter_m=0.02, mpe_m={"pround": 1e-6}))
bad(C, "probing_test", "several styli", lambda: cm.probing_test(_points(), calibrated_diameter_m=0.02, mpe_m={"ploc": 1e-6}))
bad(C, "probing_test", "uncertainty_m", lambda: cm.probing_test(_points(), calibrated_diameter_m=0.02, uncertainty_m=-1.0),
    lambda: cm.probing_test(_points(), calibrated_diameter_m=0.02, uncertainty_m=1e300))
bad(C, "probing_test", "cover too little", lambda: cm.probing_test(
    cm.SpherePoints(0.01 * np.c_[np.cos(np.arange(8.0)), np.sin(np.arange(8.0)), 1e-4 * np.cos(3 * np.arange(8.0))], ("1",) * 8),
    calibrated_diameter_m=0.02))
bad(C, "probing_test", "calibrated one", lambda: cm.probing_test(_points(), calibrated_diameter_m=2.0))
bad(C, "probing_test", "decision rule", lambda: cm.probing_test(_points(), calibrated_diameter_m=0.02, rule=None))
bad(C, "evaluate_probing", "calibrated_diameter_m", lambda: cm.evaluate_probing(SPHERE, calibrated_diameter_m="25"))
bad(C, "evaluate_probing", "path", lambda: cm.evaluate_probing(None, calibrated_diameter_m=0.025))
bad(C, "plot_acceptance", "result", lambda: cm.plot_acceptance("x.png", None))
bad(C, "plot_acceptance", "figure format", lambda: cm.plot_acceptance("x.nope", cm.length_acceptance(_m())))
bad(C, "plot_probing", "result", lambda: cm.plot_probing("x.png", cm.length_acceptance(_m())))
bad(C, "plot_probing", "figure format",
    lambda: cm.plot_probing("x.nope", cm.probing_test(_points(), calibrated_diameter_m=0.02)))

test_bad_arguments, test_every_public_callable_has_a_case = TABLE.tests({})
