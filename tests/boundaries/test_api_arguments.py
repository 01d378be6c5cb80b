"""Every public callable of the instruments, straightness, squareness, circular and measurement rooms
refuses bad arguments with AxiscalError naming the argument: never an IndexError, a TypeError from
deep inside, a NumPy broadcast error, a division by zero, a stray RuntimeWarning or a silent NaN.

The table lists, per public name, calls with the kinds of bad values a user passes: NaN and inf,
empty and mismatched arrays, wrong shapes, a string, None or a bool for a number, zero or negative
counts and sizes, unknown option strings, values out of physical range. A coverage check fails when
a public callable of these rooms has no case (or an explicit exemption below).
"""

from __future__ import annotations

from pathlib import Path

import numpy as np
from hypothesis import given, settings
from hypothesis import strategies as hs

from api_cases import EXAMPLES, CaseTable, api, finite_or_refused

from axiscal.io import parse_csv


ROOMS = ("instruments", "straightness", "squareness", "circular", "measurement")
NAN, INF = float("nan"), float("inf")

TABLE = CaseTable(ROOMS)
bad = TABLE.bad
CASES = TABLE.cases


# ---------------------------------------------------------------- instruments
ins = api("instruments")
I = "instruments"
P3 = np.zeros(3)

bad(I, "transfer_point", "delta_m", lambda: ins.transfer_point([NAN, 0, 0], P3, P3), lambda: ins.transfer_point("a", P3, P3))
bad(I, "transfer_point", "eps_rad", lambda: ins.transfer_point(P3, np.zeros(2), P3), lambda: ins.transfer_point(P3, None, P3))
bad(I, "transfer_point", "offset_m", lambda: ins.transfer_point(P3, P3, [0, INF, 0]))
bad(I, "transfer_point", "do not match", lambda: ins.transfer_point(np.zeros((4, 3)), np.zeros((5, 3)), P3))
bad(I, "transfer_components", "offsets_m", lambda: ins.transfer_components(P3, P3, np.zeros((3, 2))), lambda: ins.transfer_components(P3, P3, np.full((3, 3), NAN)))
bad(I, "transfer_components", "eps_rad", lambda: ins.transfer_components(P3, [NAN, 0, 0], np.zeros((3, 3))))
bad(I, "transfer_components", "delta_m", lambda: ins.transfer_components("x", P3, np.zeros((3, 3))))
bad(I, "saturation_vapour_pressure", "temperature_c", lambda: ins.saturation_vapour_pressure(NAN), lambda: ins.saturation_vapour_pressure("20"),
    lambda: ins.saturation_vapour_pressure(-300.0), lambda: ins.saturation_vapour_pressure(None))
bad(I, "saturation_vapour_pressure", "phase", lambda: ins.saturation_vapour_pressure(20.0, over="steam"))
bad(I, "water_vapour_mole_fraction", "temperature_c", lambda: ins.water_vapour_mole_fraction(NAN, 101325.0, 50.0), lambda: ins.water_vapour_mole_fraction(-274.0, 101325.0, 50.0))
bad(I, "water_vapour_mole_fraction", "pressure_pa", lambda: ins.water_vapour_mole_fraction(20.0, 0.0, 50.0), lambda: ins.water_vapour_mole_fraction(20.0, -1.0, 50.0), lambda: ins.water_vapour_mole_fraction(20.0, INF, 50.0))
bad(I, "water_vapour_mole_fraction", "humidity_pct", lambda: ins.water_vapour_mole_fraction(20.0, 101325.0, 101.0), lambda: ins.water_vapour_mole_fraction(20.0, 101325.0, True))
bad(I, "water_vapour_mole_fraction", "do not match", lambda: ins.water_vapour_mole_fraction([20.0, 21.0], [101325.0] * 3, 50.0))
bad(I, "refractive_index", "temperature", lambda: ins.refractive_index(NAN, 101325.0, 50.0, 633.0), lambda: ins.refractive_index(-300.0, 101325.0, 50.0, 633.0))
bad(I, "refractive_index", "pressure", lambda: ins.refractive_index(20.0, 0.0, 50.0, 633.0), lambda: ins.refractive_index(20.0, -5.0, 50.0, 633.0))
bad(I, "refractive_index", "humidity", lambda: ins.refractive_index(20.0, 101325.0, -1.0, 633.0), lambda: ins.refractive_index(20.0, 101325.0, 100.5, 633.0))
bad(I, "refractive_index", "wavelength", lambda: ins.refractive_index(20.0, 101325.0, 50.0, 0.0), lambda: ins.refractive_index(20.0, 101325.0, 50.0, -633.0))
bad(I, "refractive_index", "method", lambda: ins.refractive_index(20.0, 101325.0, 50.0, 633.0, method="magic"), lambda: ins.refractive_index(20.0, 101325.0, 50.0, 633.0, method=None))
bad(I, "refractive_index", "numbers", lambda: ins.refractive_index("warm", 101325.0, 50.0, 633.0), lambda: ins.refractive_index(None, 101325.0, 50.0, 633.0))
bad(I, "refractive_index", "do not match", lambda: ins.refractive_index([20.0, 21.0], [101325.0] * 3, 50.0, 633.0))
bad(I, "air_report", "temperature", lambda: ins.air_report(NAN, 101325.0, 50.0), lambda: ins.air_report(True, 101325.0, 50.0))
bad(I, "air_report", "pressure", lambda: ins.air_report(20.0, 0.0, 50.0))
bad(I, "air_report", "method", lambda: ins.air_report(20.0, 101325.0, 50.0, method="x"))
bad(I, "air_inputs", "method", lambda: ins.air_inputs(20.0, 101325.0, 50.0, 633.0, 450.0, "magic"))
bad(I, "air_inputs", "temperature_c", lambda: ins.air_inputs(NAN, 101325.0, 50.0, 633.0, 450.0, "ciddor"))
bad(I, "air_text", "report", lambda: ins.air_text({}), lambda: ins.air_text(None))
bad(I, "ChannelCalibration", "gain", lambda: ins.ChannelCalibration("u", 0.0, 0.0), lambda: ins.ChannelCalibration("u", NAN, 0.0), lambda: ins.ChannelCalibration("u", "1", 0.0))
bad(I, "ChannelCalibration", "offset", lambda: ins.ChannelCalibration("u", 1.0, INF), lambda: ins.ChannelCalibration("u", 1.0, None))
bad(I, "ChannelCalibration", "channel", lambda: ins.ChannelCalibration(5, 1.0, 0.0))
bad(I, "ChannelCalibration", "raw", lambda: ins.ChannelCalibration("u", 1.0, 0.0).apply("x"))
bad(I, "fit_sensitivity", "same length", lambda: ins.fit_sensitivity("u", [1, 2, 3], [1, 2]))
bad(I, "fit_sensitivity", "at least 3", lambda: ins.fit_sensitivity("u", [1, 2], [1, 2]), lambda: ins.fit_sensitivity("u", [], []))
bad(I, "fit_sensitivity", "non-finite", lambda: ins.fit_sensitivity("u", [1, NAN, 3], [1, 2, 3]))
bad(I, "fit_sensitivity", "raw", lambda: ins.fit_sensitivity("u", "abc", [1, 2, 3]), lambda: ins.fit_sensitivity("u", None, [1, 2, 3]))
bad(I, "fit_sensitivity", "do not vary", lambda: ins.fit_sensitivity("u", [1, 1, 1], [1, 2, 3]))
bad(I, "transfer_reference", "eps_rad", lambda: ins.transfer_reference([0.0], np.zeros((1, 2)), P3, 0), lambda: ins.transfer_reference([0.0], [[NAN, 0, 0]], P3, 0))
bad(I, "transfer_reference", "component", lambda: ins.transfer_reference([0.0], np.zeros((1, 3)), P3, 3), lambda: ins.transfer_reference([0.0], np.zeros((1, 3)), P3, "x"))
bad(I, "transfer_reference", "reference_m", lambda: ins.transfer_reference([0.0, 1.0], np.zeros((1, 3)), P3, 0), lambda: ins.transfer_reference([NAN], np.zeros((1, 3)), P3, 0))
bad(I, "MirrorCorrection", "end_m", lambda: ins.MirrorCorrection("X", 0.5, 0.5, (0.0,)), lambda: ins.MirrorCorrection("X", 0.0, NAN, (0.0,)))
bad(I, "MirrorCorrection", "coefficients_rad", lambda: ins.MirrorCorrection("X", 0.0, 1.0, ()), lambda: ins.MirrorCorrection("X", 0.0, 1.0, (NAN,)))
bad(I, "MirrorCorrection", "q_m", lambda: ins.MirrorCorrection("X", 0.0, 1.0, (0.0,)).evaluate([NAN]), lambda: ins.MirrorCorrection("X", 0.0, 1.0, (0.0,)).evaluate("a"))
bad(I, "fit_mirror", "same length", lambda: ins.fit_mirror("X", np.linspace(0, 1, 6), np.zeros(6), np.zeros(5)))
bad(I, "fit_mirror", "non-finite", lambda: ins.fit_mirror("X", np.linspace(0, 1, 6), np.full(6, NAN), np.zeros(6)))
bad(I, "fit_mirror", "at least 4", lambda: ins.fit_mirror("X", [0.0, 0.1], [0.0, 0.0], [0.0, 0.0]))
bad(I, "fit_mirror", "max_order", lambda: ins.fit_mirror("X", np.linspace(0, 1, 6), np.zeros(6), np.zeros(6), max_order=-1),
    lambda: ins.fit_mirror("X", np.linspace(0, 1, 6), np.zeros(6), np.zeros(6), max_order=2.5))
bad(I, "fit_mirror", "position_m", lambda: ins.fit_mirror("X", "abc", np.zeros(6), np.zeros(6)))
bad(I, "Calibration", "channels", lambda: ins.Calibration(channels={"u": 5}), lambda: ins.Calibration(channels=5))
bad(I, "Calibration", "mirrors", lambda: ins.Calibration(mirrors={"X": "m"}))
bad(I, "save_calibration", "calibration", lambda: ins.save_calibration({"u": 1}, "/tmp/never-written.json"))
bad(I, "calibration_from_dict", "not a sensor calibration", lambda: ins.calibration_from_dict({}), lambda: ins.calibration_from_dict([]))
bad(I, "load_calibration", "path", lambda: ins.load_calibration(None), lambda: ins.load_calibration(5))
bad(I, "fringe_report", "optical_fold", lambda: ins.fringe_report(1000, optical_fold=0, temperature_c=20, pressure_pa=101325, humidity_pct=50))
bad(I, "fringe_report", "counts", lambda: ins.fringe_report(NAN, temperature_c=20, pressure_pa=101325, humidity_pct=50), lambda: ins.fringe_report("10", temperature_c=20, pressure_pa=101325, humidity_pct=50))
bad(I, "fringe_report", "pressure", lambda: ins.fringe_report(1000, temperature_c=20, pressure_pa=-1, humidity_pct=50))
bad(I, "fringe_report", "material_temperature_c", lambda: ins.fringe_report(1000, temperature_c=20, pressure_pa=101325, humidity_pct=50, material_temperature_c=[NAN]),
    lambda: ins.fringe_report(1000, temperature_c=20, pressure_pa=101325, humidity_pct=50, material_temperature_c=5.0))
bad(I, "fringe_text", "report", lambda: ins.fringe_text({}), lambda: ins.fringe_text(None))
bad(I, "length_from_fringes", "counts", lambda: ins.length_from_fringes(NAN), lambda: ins.length_from_fringes("a"), lambda: ins.length_from_fringes(None))
bad(I, "length_from_fringes", "optical_fold", lambda: ins.length_from_fringes(1.0, optical_fold=0), lambda: ins.length_from_fringes(1.0, optical_fold=True), lambda: ins.length_from_fringes(1.0, optical_fold=1.5))
bad(I, "length_from_fringes", "interpolation", lambda: ins.length_from_fringes(1.0, interpolation=-4))
bad(I, "length_from_fringes", "wavelength_nm", lambda: ins.length_from_fringes(1.0, wavelength_nm=0.0), lambda: ins.length_from_fringes(1.0, wavelength_nm=-633.0))
bad(I, "length_from_fringes", "index_of_air", lambda: ins.length_from_fringes(1.0, index_of_air=0.5), lambda: ins.length_from_fringes(1.0, index_of_air=NAN))
bad(I, "length_from_fringes", "do not match", lambda: ins.length_from_fringes([1.0, 2.0], wavelength_nm=[633.0] * 3))
bad(I, "fringes_from_length", "length_m", lambda: ins.fringes_from_length(INF), lambda: ins.fringes_from_length("a"))
bad(I, "fringes_from_length", "wavelength_nm", lambda: ins.fringes_from_length(1.0, wavelength_nm=0.0))
bad(I, "fringes_from_length", "optical_fold", lambda: ins.fringes_from_length(1.0, optical_fold=0))
bad(I, "normalise_to_20c", "length_m", lambda: ins.normalise_to_20c(NAN, 20.0))
bad(I, "normalise_to_20c", "material_temperature_c", lambda: ins.normalise_to_20c(1.0, NAN), lambda: ins.normalise_to_20c(1.0, -300.0), lambda: ins.normalise_to_20c(1.0, []))
bad(I, "normalise_to_20c", "expansion_per_k", lambda: ins.normalise_to_20c(1.0, 21.0, expansion_per_k=NAN), lambda: ins.normalise_to_20c(1.0, 21.0, expansion_per_k="steel"))
bad(I, "normalise_to_20c", "do not match", lambda: ins.normalise_to_20c([1.0, 2.0], [20.0, 21.0, 22.0]))
bad(I, "compensated_length", "reading_m", lambda: ins.compensated_length(NAN, air_temperature_c=20, pressure_pa=101325, humidity_pct=50), lambda: ins.compensated_length(None, air_temperature_c=20, pressure_pa=101325, humidity_pct=50))
bad(I, "compensated_length", "pressure", lambda: ins.compensated_length(1.0, air_temperature_c=20, pressure_pa=0, humidity_pct=50))
bad(I, "compensated_length", "humidity", lambda: ins.compensated_length(1.0, air_temperature_c=20, pressure_pa=101325, humidity_pct=150))
bad(I, "compensated_length", "do not match", lambda: ins.compensated_length([1.0, 2.0], air_temperature_c=[20, 21, 22], pressure_pa=101325, humidity_pct=50))
bad(I, "compensated_length", "material", lambda: ins.compensated_length(1.0, air_temperature_c=20, pressure_pa=101325, humidity_pct=50, material_temperature_c=NAN))
bad(I, "dead_path_error", "dead_path_m", lambda: ins.dead_path_error(NAN, index_at_datum=1.0003, index_now=1.0002))
bad(I, "dead_path_error", "index_now", lambda: ins.dead_path_error(0.1, index_at_datum=1.0003, index_now=0.0), lambda: ins.dead_path_error(0.1, index_at_datum=1.0003, index_now=0.5))
bad(I, "dead_path_error", "index_at_datum", lambda: ins.dead_path_error(0.1, index_at_datum="n", index_now=1.0))
bad(I, "dead_path_error", "do not match", lambda: ins.dead_path_error([0.1, 0.2], index_at_datum=[1.0, 1.0, 1.0], index_now=1.0))
bad(I, "cosine_error", "length_m", lambda: ins.cosine_error(NAN, 0.001), lambda: ins.cosine_error("1", 0.001))
bad(I, "cosine_error", "misalignment_rad", lambda: ins.cosine_error(1.0, INF))
bad(I, "cosine_error", "do not match", lambda: ins.cosine_error([1.0, 2.0], [0.1, 0.2, 0.3]))
bad(I, "misalignment_for_cosine_error", "relative", lambda: ins.misalignment_for_cosine_error(NAN), lambda: ins.misalignment_for_cosine_error(-0.1), lambda: ins.misalignment_for_cosine_error(3.0))
bad(I, "abbe_error", "arm_m", lambda: ins.abbe_error(NAN, 0.001), lambda: ins.abbe_error(None, 0.001))
bad(I, "abbe_error", "angle_rad", lambda: ins.abbe_error(0.1, INF))
bad(I, "abbe_error", "do not match", lambda: ins.abbe_error([0.1, 0.2], [0.1, 0.2, 0.3]))
for _rot in ("rotation_x", "rotation_y", "rotation_z"):
    bad(I, _rot, "angle_rad", lambda _f=getattr(ins, _rot): _f(NAN), lambda _f=getattr(ins, _rot): _f("a"), lambda _f=getattr(ins, _rot): _f(None))
bad(I, "rotation_xyz", "rx_rad", lambda: ins.rotation_xyz(NAN, 0.0, 0.0))
bad(I, "rotation_xyz", "rz_rad", lambda: ins.rotation_xyz(0.0, 0.0, "a"))
bad(I, "rotation_xyz", "do not match", lambda: ins.rotation_xyz([0.0, 0.1], [0.0, 0.1, 0.2], 0.0))
bad(I, "reflection_matrix", "normal", lambda: ins.reflection_matrix([0, 0, 0]), lambda: ins.reflection_matrix([NAN, 0, 1]), lambda: ins.reflection_matrix([0, 1]), lambda: ins.reflection_matrix("z"))
bad(I, "reflect", "directions", lambda: ins.reflect([[1, 0]], [0, 0, 1]), lambda: ins.reflect([NAN, 0, 1], [0, 0, 1]), lambda: ins.reflect("x", [0, 0, 1]))
bad(I, "reflect", "normal", lambda: ins.reflect([1, 0, 0], [0, 0, 0]))
bad(I, "refract", "index_ratio", lambda: ins.refract([1, 0, 0], [1, 0, 0], 0.0), lambda: ins.refract([1, 0, 0], [1, 0, 0], NAN), lambda: ins.refract([1, 0, 0], [1, 0, 0], "glass"))
bad(I, "refract", "directions", lambda: ins.refract([1, 0], [1, 0, 0], 1.5))
bad(I, "refract", "normal", lambda: ins.refract([1, 0, 0], [0, 0, 0], 1.5))
bad(I, "Face", "face kind", lambda: ins.Face([0, 0, 1], P3, "absorb"))
bad(I, "Face", "normal", lambda: ins.Face([0, 0], P3, "reflect"), lambda: ins.Face([0, 0, 0], P3, "reflect"))
bad(I, "Face", "point_m", lambda: ins.Face([0, 0, 1], [0, 0], "reflect"), lambda: ins.Face([0, 0, 1], [NAN, 0, 0], "reflect"))
_face = ins.Face([0, 0, 1], P3, "reflect")
bad(I, "Prism", "index", lambda: ins.Prism((_face,), 0.5), lambda: ins.Prism((_face,), "glass"), lambda: ins.Prism((_face,), NAN))
bad(I, "Prism", "face", lambda: ins.Prism((), 1.5), lambda: ins.Prism(("a",), 1.5))
bad(I, "Prism", "pivot_m", lambda: ins.Prism((_face,), 1.5, pivot_m=[0, 0]), lambda: ins.Prism((_face,), 1.5, pivot_m=[NAN, 0, 0]))
bad(I, "Prism", "rotation", lambda: ins.Prism((_face,), 1.5).rotated(np.eye(2)))
bad(I, "Prism", "offset_m", lambda: ins.Prism((_face,), 1.5).translated([NAN, 0, 0]))
bad(I, "trace", "prism", lambda: ins.trace("prism", P3, [0, 0, 1]))
bad(I, "trace", "origins_m", lambda: ins.trace(ins.pentaprism(), [NAN, 0, 0], [0, 0, 1]), lambda: ins.trace(ins.pentaprism(), [0, 0], [0, 0, 1]))
bad(I, "trace", "directions", lambda: ins.trace(ins.pentaprism(), P3, [0, 0, 0]))
bad(I, "trace", "ambient_index", lambda: ins.trace(ins.pentaprism(), P3, [1, 0, 0], ambient_index=0.0), lambda: ins.trace(ins.pentaprism(), P3, [1, 0, 0], ambient_index=NAN))
bad(I, "angle_between", "a", lambda: ins.angle_between([0, 0], [0, 0, 1]), lambda: ins.angle_between([0, 0, 0], [0, 0, 1]), lambda: ins.angle_between([NAN, 0, 1], [0, 0, 1]))
bad(I, "angle_between", "b", lambda: ins.angle_between([0, 0, 1], "b"))
bad(I, "pentaprism", "index", lambda: ins.pentaprism(index=0.9), lambda: ins.pentaprism(index=NAN), lambda: ins.pentaprism(index="bk7"))
bad(I, "pentaprism", "size_m", lambda: ins.pentaprism(size_m=0.0), lambda: ins.pentaprism(size_m=NAN), lambda: ins.pentaprism(size_m=None))
bad(I, "pentaprism", "mirror_angle_error_rad", lambda: ins.pentaprism(mirror_angle_error_rad=NAN), lambda: ins.pentaprism(mirror_angle_error_rad="small"))
bad(I, "mirror_angle_error_for_deviation", "deviation_error_rad", lambda: ins.mirror_angle_error_for_deviation(NAN), lambda: ins.mirror_angle_error_for_deviation("a"))
bad(I, "mirror_angle_error_for_deviation", "index", lambda: ins.mirror_angle_error_for_deviation(0.0, index=0.5))
bad(I, "pentaprism_deviation", "rx_rad", lambda: ins.pentaprism_deviation(NAN, 0.0, 0.0), lambda: ins.pentaprism_deviation("a", 0.0, 0.0))
bad(I, "pentaprism_deviation", "index", lambda: ins.pentaprism_deviation(0.0, 0.0, 0.0, index=0.0))
bad(I, "pentaprism_deviation", "translation_m", lambda: ins.pentaprism_deviation(0.0, 0.0, 0.0, translation_m=[0.0, 0.0]), lambda: ins.pentaprism_deviation(0.0, 0.0, 0.0, translation_m=[NAN, 0, 0]))
bad(I, "pentaprism_deviation", "deviation_error_rad", lambda: ins.pentaprism_deviation(0.0, 0.0, 0.0, deviation_error_rad=NAN))
bad(I, "pentaprism_deviation", "do not match", lambda: ins.pentaprism_deviation([0.0, 0.1], [0.0, 0.1, 0.2], 0.0))
bad(I, "pentaprism_sensitivity", "rotation_rad", lambda: ins.pentaprism_sensitivity([]), lambda: ins.pentaprism_sensitivity([NAN, 0.0]), lambda: ins.pentaprism_sensitivity([[0.0, 0.1]]))
bad(I, "pentaprism_sensitivity", "translation_m", lambda: ins.pentaprism_sensitivity([0.0, 0.001], []), lambda: ins.pentaprism_sensitivity([0.0, 0.001], [INF]))
bad(I, "pentaprism_sensitivity", "index", lambda: ins.pentaprism_sensitivity([0.0, 0.001], index=0.0))
bad(I, "render_report", "template", lambda: ins.render_report("instruments/none.txt.j2"), lambda: ins.render_report(None))
bad(I, "straightness_from_psd", "shift_m", lambda: ins.straightness_from_psd([NAN]), lambda: ins.straightness_from_psd("a"), lambda: ins.straightness_from_psd(None))
for _fn, _arg in (("angle_from_quadrant", "shift_m"), ("roll_from_autocollimation", "shift_m"), ("quadrant_shift", "angle_rad"), ("autocollimation_shift", "roll_rad")):
    _f = getattr(ins, _fn)
    bad(I, _fn, "focal_m", lambda _f=_f: _f([0.001], 0.0), lambda _f=_f: _f([0.001], -0.1), lambda _f=_f: _f([0.001], NAN), lambda _f=_f: _f([0.001], "f"))
    bad(I, _fn, _arg, lambda _f=_f: _f([NAN], 0.1), lambda _f=_f: _f("x", 0.1))
bad(I, "SignedComponent", "index", lambda: ins.SignedComponent(7, 1.0), lambda: ins.SignedComponent(-1, 1.0))
bad(I, "SignedComponent", "sign", lambda: ins.SignedComponent(0, 0.5))
bad(I, "parse_signed_component", "expected one of", lambda: ins.parse_signed_component("EQX", "X", what="qd_u"), lambda: ins.parse_signed_component(5, "X", what="qd_u"))
bad(I, "parse_signed_component", "letter", lambda: ins.parse_signed_component("EAX", "Q", what="qd_u"))
_sc = ins.SignedComponent(3, 1.0)
bad(I, "SensorHead", "qd_focal_m", lambda: ins.SensorHead("X", "x", (0, 0, 0), (0, 0, 0), 0.0, 0.1, ins.SignedComponent(4, 1.0), ins.SignedComponent(5, 1.0), _sc))
bad(I, "SensorHead", "psd_point_m", lambda: ins.SensorHead("X", "x", (0, 0, 0), (0, NAN), 0.1, 0.1, ins.SignedComponent(4, 1.0), ins.SignedComponent(5, 1.0), _sc))
bad(I, "sensor_head_from_dict", "must be a table", lambda: ins.sensor_head_from_dict("X", 5))
bad(I, "sensor_head_from_dict", "letter", lambda: ins.sensor_head_from_dict("Q", {}))
bad(I, "sensor_head_from_dict", "qd_focal", lambda: ins.sensor_head_from_dict("X", {"qd_focal_mm": -1.0}), lambda: ins.sensor_head_from_dict("X", {"qd_focal_mm": NAN}))


# ---------------------------------------------------------------- straightness
st_ = api("straightness")
S = "straightness"
X = np.arange(12) * 1e-3
Z12 = np.zeros(12)
RD = st_.ProbeReadings(X, Z12, Z12, Z12, 3e-3, 3e-3)
LINE = st_.reference_line([0.0, 0.1], [0.0, 1e-6])
FLAT = lambda p: 0.0 * p  # noqa: E731


bad(S, "reference_line", "position_m", lambda: st_.reference_line([0.0, NAN], [0.0, 0.0]), lambda: st_.reference_line("ab", [0.0, 0.0]),
    lambda: st_.reference_line([[0.0, 1.0]], [[0.0, 1.0]]), lambda: st_.reference_line([0.0, 1e300], [0.0, 0.0]),
    lambda: st_.reference_line([0.0, 1e-320], [0.0, 1.0]))
bad(S, "reference_line", "same length", lambda: st_.reference_line([0.0, 1.0, 2.0], [0.0, 1.0]))
bad(S, "reference_line", "at least 2", lambda: st_.reference_line([], []), lambda: st_.reference_line([0.0], [0.0]))
bad(S, "reference_line", "distinct positions", lambda: st_.reference_line([1.0, 1.0], [0.0, 1.0]))
bad(S, "reference_line", "deviation_m", lambda: st_.reference_line([0.0, 1.0], [None, 1.0]), lambda: st_.reference_line([0.0, 1.0], [INF, 1.0]))
bad(S, "reference_line", "unknown reference", lambda: st_.reference_line([0.0, 1.0], [0.0, 1.0], reference="best"),
    lambda: st_.reference_line([0.0, 1.0], [0.0, 1.0], reference=None))
bad(S, "ReferenceLine", "slope", lambda: st_.ReferenceLine(NAN, 0.0, 0.0, "least-squares"), lambda: st_.ReferenceLine("1", 0.0, 0.0, "least-squares"))
bad(S, "ReferenceLine", "reference", lambda: st_.ReferenceLine(0.0, 0.0, 0.0, "best"))
bad(S, "ReferenceLine", "position_m", lambda: LINE.residuals([NAN], [0.0]))
bad(S, "ReferenceLine", "same length", lambda: LINE.residuals([0.0, 1.0], [0.0]))
bad(S, "ProbeReadings", "position_m", lambda: st_.ProbeReadings([NAN] * 12, Z12, Z12, None, 3e-3), lambda: st_.ProbeReadings("x", Z12, Z12, None, 3e-3),
    lambda: st_.ProbeReadings(np.zeros((2, 6)), Z12, Z12, None, 3e-3))
bad(S, "ProbeReadings", "same length", lambda: st_.ProbeReadings(X, Z12, Z12[:5], None, 3e-3), lambda: st_.ProbeReadings(X, Z12, Z12, Z12[:3], 3e-3, 3e-3))
bad(S, "ProbeReadings", "b_m", lambda: st_.ProbeReadings(X, Z12, [NAN] * 12, None, 3e-3), lambda: st_.ProbeReadings(X, Z12, None, None, 3e-3))
bad(S, "ProbeReadings", "spacing_ab_m", lambda: st_.ProbeReadings(X, Z12, Z12, None, 0.0), lambda: st_.ProbeReadings(X, Z12, Z12, None, NAN),
    lambda: st_.ProbeReadings(X, Z12, Z12, None, "3"), lambda: st_.ProbeReadings(X, Z12, Z12, None, True))
bad(S, "ProbeReadings", "spacing_bc_m", lambda: st_.ProbeReadings(X, Z12, Z12, Z12, 3e-3, "3"))
bad(S, "simulate_readings", "position_m", lambda: st_.simulate_readings([], FLAT, FLAT, spacing_ab_m=1e-3), lambda: st_.simulate_readings([NAN], FLAT, FLAT, spacing_ab_m=1e-3))
bad(S, "simulate_readings", "spacing_ab_m", lambda: st_.simulate_readings(X, FLAT, FLAT, spacing_ab_m=-1e-3), lambda: st_.simulate_readings(X, FLAT, FLAT, spacing_ab_m=None))
bad(S, "simulate_readings", "spacing_bc_m", lambda: st_.simulate_readings(X, FLAT, FLAT, spacing_ab_m=1e-3, spacing_bc_m=0.0))
bad(S, "simulate_readings", "noise_m", lambda: st_.simulate_readings(X, FLAT, FLAT, spacing_ab_m=1e-3, noise_m=-1.0), lambda: st_.simulate_readings(X, FLAT, FLAT, spacing_ab_m=1e-3, noise_m=NAN))
bad(S, "simulate_readings", "offsets_m", lambda: st_.simulate_readings(X, FLAT, FLAT, spacing_ab_m=1e-3, offsets_m=(0.0, 0.0)))
bad(S, "simulate_readings", "profile", lambda: st_.simulate_readings(X, "flat", FLAT, spacing_ab_m=1e-3), lambda: st_.simulate_readings(X, lambda p: p[:2], FLAT, spacing_ab_m=1e-3),
    lambda: st_.simulate_readings(X, lambda p: p * NAN, FLAT, spacing_ab_m=1e-3))
bad(S, "simulate_readings", "motion", lambda: st_.simulate_readings(X, FLAT, None, spacing_ab_m=1e-3))
bad(S, "simulate_readings", "rng", lambda: st_.simulate_readings(X, FLAT, FLAT, spacing_ab_m=1e-3, noise_m=1e-9, rng=5))
bad(S, "uneven_step", "position_m", lambda: st_.uneven_step([0.0]), lambda: st_.uneven_step([]), lambda: st_.uneven_step([0.0, NAN]), lambda: st_.uneven_step("ab"))
bad(S, "reversal", "same positions", lambda: st_.reversal([0.0, 1.0], [0.0, 1.0], [0.0]))
bad(S, "reversal", "position_m", lambda: st_.reversal([], [], []), lambda: st_.reversal([NAN], [0.0], [0.0]))
bad(S, "reversal", "normal_m", lambda: st_.reversal([0.0], [INF], [0.0]), lambda: st_.reversal([0.0], "a", [0.0]))
for _fn in ("sequential_two_point", "sequential_three_point", "fine_sequential_three_point", "generalized_two_point", "frequency_domain", "combined"):
    bad(S, _fn, "readings", lambda _f=getattr(st_, _fn): _f({"position_m": X}), lambda _f=getattr(st_, _fn): _f(None))
bad(S, "sequential_two_point", "yaw_rad", lambda: st_.sequential_two_point(RD, yaw_rad=[NAN] * 12), lambda: st_.sequential_two_point(RD, yaw_rad=[0.0] * 3))
bad(S, "sequential_two_point", "at least 2", lambda: st_.sequential_two_point(st_.ProbeReadings([0.0], [0.0], [0.0], None, 1e-3)))
bad(S, "sequential_three_point", "equal spacings", lambda: st_.sequential_three_point(st_.ProbeReadings(X, Z12, Z12, Z12, 3e-3, NAN)))
bad(S, "fine_sequential_three_point", "positive, finite", lambda: st_.fine_sequential_three_point(st_.ProbeReadings(X, Z12, Z12, Z12, 2e-3, -1e-3)))
bad(S, "frequency_domain", "min_gain", lambda: st_.frequency_domain(RD, min_gain=NAN), lambda: st_.frequency_domain(RD, min_gain="0.1"), lambda: st_.frequency_domain(RD, min_gain=1.0))
bad(S, "frequency_domain", "probes", lambda: st_.frequency_domain(RD, probes=4), lambda: st_.frequency_domain(RD, probes="3"))
bad(S, "frequency_domain", "parabola", lambda: st_.frequency_domain(RD, parabola="no"))
bad(S, "combined", "calibration_m", lambda: st_.combined(RD, calibration_m=(1.0,)), lambda: st_.combined(RD, calibration_m=(NAN, 1.0)), lambda: st_.combined(RD, calibration_m=(0.01, 0.0)))
bad(S, "separate", "unknown separation method", lambda: st_.separate(RD, method="magic"), lambda: st_.separate(RD, method=None))
bad(S, "separate", "readings", lambda: st_.separate("readings.csv", method="stp"))
bad(S, "separate", "probes", lambda: st_.separate(RD, method="frequency", probes=0))
bad(S, "gtp_amplitude_response", "wavelength_m", lambda: st_.gtp_amplitude_response(0.0, spacing_m=1e-3, step_m=1e-4), lambda: st_.gtp_amplitude_response([NAN], spacing_m=1e-3, step_m=1e-4))
bad(S, "gtp_amplitude_response", "spacing_m", lambda: st_.gtp_amplitude_response(0.1, spacing_m=NAN, step_m=1e-4), lambda: st_.gtp_amplitude_response(0.1, spacing_m=0.0, step_m=1e-4))
bad(S, "gtp_amplitude_response", "step_m", lambda: st_.gtp_amplitude_response(0.1, spacing_m=1e-3, step_m=-1.0), lambda: st_.gtp_amplitude_response(0.1, spacing_m=1e-3, step_m=0.1))
bad(S, "stp_offset_error", "n (chain", lambda: st_.stp_offset_error([NAN], 1e-6), lambda: st_.stp_offset_error([-1], 1e-6), lambda: st_.stp_offset_error("n", 1e-6))
bad(S, "stp_offset_error", "delta1_m", lambda: st_.stp_offset_error([1], NAN), lambda: st_.stp_offset_error([1], None))
bad(S, "strp_offset_error", "delta2_m", lambda: st_.strp_offset_error([1], 0.0, INF))
bad(S, "strp_offset_error", "n (chain", lambda: st_.strp_offset_error([NAN], 0.0, 0.0))
bad(S, "strp_yaw_offset_error", "spacing_m", lambda: st_.strp_yaw_offset_error([1], 0.0, 0.0, spacing_m=0.0), lambda: st_.strp_yaw_offset_error([1], 0.0, 0.0, spacing_m=NAN))
bad(S, "strp_yaw_offset_error", "delta1_m", lambda: st_.strp_yaw_offset_error([1], "x", 0.0, spacing_m=1e-3))
bad(S, "stp_yaw_neglect_error", "yaw_rad", lambda: st_.stp_yaw_neglect_error([NAN], spacing_m=1e-3), lambda: st_.stp_yaw_neglect_error([[0.0]], spacing_m=1e-3))
bad(S, "stp_yaw_neglect_error", "spacing_m", lambda: st_.stp_yaw_neglect_error([0.0], spacing_m=-1e-3))
bad(S, "stp_residual_yaw_error", "mean_rad", lambda: st_.stp_residual_yaw_error([1], spacing_m=1e-3, mean_rad=NAN, slope_rad_per_step=0.0))
bad(S, "stp_residual_yaw_error", "slope_rad_per_step", lambda: st_.stp_residual_yaw_error([1], spacing_m=1e-3, mean_rad=0.0, slope_rad_per_step="0"))
bad(S, "stp_residual_yaw_error", "spacing_m", lambda: st_.stp_residual_yaw_error([1], spacing_m=0.0, mean_rad=0.0, slope_rad_per_step=0.0))
for _fn in ("stp_noise_std", "strp_noise_std"):
    bad(S, _fn, "noise_m", lambda _f=getattr(st_, _fn): _f([1], -1e-9), lambda _f=getattr(st_, _fn): _f([1], NAN))
    bad(S, _fn, "n (chain", lambda _f=getattr(st_, _fn): _f([-2], 1e-9), lambda _f=getattr(st_, _fn): _f([INF], 1e-9))
bad(S, "gtp_noise_std", "steps_per_spacing", lambda: st_.gtp_noise_std([1], 1e-9, steps_per_spacing=0), lambda: st_.gtp_noise_std([1], 1e-9, steps_per_spacing=2.5))
bad(S, "gtp_noise_std", "noise_m", lambda: st_.gtp_noise_std([1], NAN, steps_per_spacing=3))
bad(S, "noise_propagation", "method", lambda: st_.noise_propagation(RD, method="magic", noise_m=1e-9))
bad(S, "noise_propagation", "noise_m", lambda: st_.noise_propagation(RD, method="stp", noise_m=0.0), lambda: st_.noise_propagation(RD, method="stp", noise_m=NAN))
bad(S, "noise_propagation", "trials", lambda: st_.noise_propagation(RD, method="stp", noise_m=1e-9, trials=0), lambda: st_.noise_propagation(RD, method="stp", noise_m=1e-9, trials=1.5))
bad(S, "noise_propagation", "rng", lambda: st_.noise_propagation(RD, method="stp", noise_m=1e-9, trials=3, rng=1))
bad(S, "noise_propagation", "readings", lambda: st_.noise_propagation(None, method="stp", noise_m=1e-9))
bad(S, "Profile", "position_m", lambda: st_.Profile([NAN, 0.0], [0.0, 0.0], None, "p.csv", (2, 3)), lambda: st_.Profile([0.0, 1.0], [0.0], None, "p.csv", (2, 3)))
bad(S, "Profile", "yaw_rad", lambda: st_.Profile([0.0, 1.0], [0.0, 0.0], "yaw", "p.csv", (2, 3)), lambda: st_.Profile([0.0, 1.0], [0.0, 0.0], [0.0], "p.csv", (2, 3)))
bad(S, "read_profile", "path", lambda: st_.read_profile(None), lambda: st_.read_profile(3))
bad(S, "read_profile", "increasing", lambda: st_.read_profile(EXAMPLES / "straightness_profile.csv", increasing="yes"))
bad(S, "read_probe_readings", "path", lambda: st_.read_probe_readings(None, spacing_ab_m=1e-3))
bad(S, "read_probe_readings", "spacing_ab_m", lambda: st_.read_probe_readings(EXAMPLES / "probe_readings.csv", spacing_ab_m=NAN),
    lambda: st_.read_probe_readings(EXAMPLES / "probe_readings.csv", spacing_ab_m="5"))
bad(S, "read_reversal_runs", "path", lambda: st_.read_reversal_runs(None, EXAMPLES / "straightness_profile.csv"))
bad(S, "StraightnessEvaluation", "profile", lambda: st_.StraightnessEvaluation("p.csv", LINE))
bad(S, "StraightnessEvaluation", "line", lambda: st_.StraightnessEvaluation(st_.read_profile(EXAMPLES / "straightness_profile.csv"), None))
bad(S, "evaluate_straightness_file", "unknown reference", lambda: st_.evaluate_straightness_file(EXAMPLES / "straightness_profile.csv", reference="best"))
bad(S, "evaluate_straightness_file", "path", lambda: st_.evaluate_straightness_file(None))
bad(S, "separation_columns", "result", lambda: st_.separation_columns(None), lambda: st_.separation_columns(RD))
bad(S, "SeparationRun", "separation", lambda: st_.SeparationRun(None, "", {}))
bad(S, "separate_file", "unknown separation method", lambda: st_.separate_file(EXAMPLES / "probe_readings.csv", method="magic"))
bad(S, "separate_file", "spacing_ab_m", lambda: st_.separate_file(EXAMPLES / "probe_readings.csv", spacing_ab_m=-1.0))
bad(S, "separate_file", "readings_path", lambda: st_.separate_file(None))
bad(S, "SimulatedReadings", "readings", lambda: st_.SimulatedReadings(None, "", {}))
bad(S, "simulate_probe_readings", "spacing_ab_m", lambda: st_.simulate_probe_readings(EXAMPLES / "separation_profile.csv", EXAMPLES / "separation_motion.csv", spacing_ab_m=NAN, step_m=1e-3))
bad(S, "simulate_probe_readings", "step_m", lambda: st_.simulate_probe_readings(EXAMPLES / "separation_profile.csv", EXAMPLES / "separation_motion.csv", spacing_ab_m=5e-3, step_m=0.0))
bad(S, "simulate_probe_readings", "probes", lambda: st_.simulate_probe_readings(EXAMPLES / "separation_profile.csv", EXAMPLES / "separation_motion.csv", spacing_ab_m=5e-3, step_m=1e-3, probes=5))
bad(S, "simulate_probe_readings", "noise_m", lambda: st_.simulate_probe_readings(EXAMPLES / "separation_profile.csv", EXAMPLES / "separation_motion.csv", spacing_ab_m=5e-3, step_m=1e-3, noise_m=-1.0))
bad(S, "simulate_probe_readings", "seed", lambda: st_.simulate_probe_readings(EXAMPLES / "separation_profile.csv", EXAMPLES / "separation_motion.csv", spacing_ab_m=5e-3, step_m=1e-3, seed="a"))
bad(S, "simulate_probe_readings", "profile_path", lambda: st_.simulate_probe_readings(None, EXAMPLES / "separation_motion.csv", spacing_ab_m=5e-3, step_m=1e-3))
bad(S, "plot_straightness", "position_m", lambda: st_.plot_straightness("/tmp/never.png", [NAN, 0.0], [0.0, 0.0], LINE))
bad(S, "plot_straightness", "same length", lambda: st_.plot_straightness("/tmp/never.png", [0.0, 1.0], [0.0], LINE))
bad(S, "plot_straightness", "line", lambda: st_.plot_straightness("/tmp/never.png", [0.0, 1.0], [0.0, 0.0], None))
bad(S, "plot_straightness", "path", lambda: st_.plot_straightness(None, [0.0, 1.0], [0.0, 0.0], LINE))
bad(S, "plot_separation", "result", lambda: st_.plot_separation("/tmp/never.png", None))
bad(S, "plot_separation", "path", lambda: st_.plot_separation(None, st_.reversal([0.0, 1.0], [0.0, 0.0], [0.0, 0.0])))
bad(S, "plot_separation", "reference", lambda: st_.plot_separation("/tmp/never.png", st_.reversal([0.0, 1.0], [0.0, 0.0], [0.0, 0.0]),
                                                                 reference="best"))
bad(S, "plot_straightness", "overlay", lambda: st_.plot_straightness("/tmp/never.png", [0.0, 1.0], [0.0, 0.0], LINE, overlay=5),
    lambda: st_.plot_straightness("/tmp/never.png", [0.0, 1.0], [0.0, 0.0], LINE, overlay={"position_mm": "0,1"}),
    lambda: st_.plot_straightness("/tmp/never.png", [0.0, 1.0], [0.0, 0.0], LINE, overlay={"position_mm": [0, 1], "deviation_um": [1.0]}))
bad(S, "plot_separation", "overlay", lambda: st_.plot_separation("/tmp/never.png", st_.reversal([0.0, 1.0], [0.0, 0.0], [0.0, 0.0]), overlay=[1]),
    lambda: st_.plot_separation("/tmp/never.png", st_.reversal([0.0, 1.0], [0.0, 0.0], [0.0, 0.0]),
                                overlay={"position_mm": [0, 1], "profile_um": [0, 1], "motion_um": [True, False]}))
bad(S, "render_report", "template", lambda: st_.render_report("none.txt.j2"), lambda: st_.render_report(None), lambda: st_.render_report("straightness.txt.j2"))


# ---------------------------------------------------------------- squareness
sq = api("squareness")
Q = "squareness"
XS = [0.0, 0.1, 0.2]
YS = [0.0, 1e-6, 0.0]
CMM = sq.CmmSquareness(1e-4, 2e-4, -1e-4)
PTS = np.zeros((2, 3))
FIT = sq.squareness(XS, YS, XS, YS)

bad(Q, "iso_term", "unknown plane", lambda: sq.iso_term("XW"), lambda: sq.iso_term(None), lambda: sq.iso_term(5))
bad(Q, "squareness_name", "unknown plane", lambda: sq.squareness_name("XW", "iso"), lambda: sq.squareness_name(None, "iso"))
bad(Q, "squareness_name", "convention", lambda: sq.squareness_name("XY", "included"), lambda: sq.squareness_name("XY", None))
bad(Q, "iso_from_included_angle", "squareness_rad", lambda: sq.iso_from_included_angle(NAN, plane="XY"), lambda: sq.iso_from_included_angle("1", plane="XY"))
bad(Q, "iso_from_included_angle", "unknown plane", lambda: sq.iso_from_included_angle(0.0, plane="AB"))
bad(Q, "included_angle_from_iso", "iso_value_rad", lambda: sq.included_angle_from_iso(INF, plane="XY"), lambda: sq.included_angle_from_iso(None, plane="XY"))
bad(Q, "included_angle_from_iso", "unknown plane", lambda: sq.included_angle_from_iso(0.0, plane=""))
bad(Q, "squareness_from_slopes", "slope_first", lambda: sq.squareness_from_slopes(NAN, 0.0), lambda: sq.squareness_from_slopes("0", 0.0), lambda: sq.squareness_from_slopes(True, 0.0))
bad(Q, "squareness_from_slopes", "slope_second", lambda: sq.squareness_from_slopes(0.0, INF))
bad(Q, "squareness_from_slopes", "prism_deviation_rad", lambda: sq.squareness_from_slopes(0.0, 0.0, prism_deviation_rad=NAN))
bad(Q, "squareness_from_slopes", "not a pentaprism", lambda: sq.squareness_from_slopes(0.0, 0.0, prism_deviation_rad=0.1))
bad(Q, "squareness_from_slopes", "parallel", lambda: sq.squareness_from_slopes(1e6, 1e6))
bad(Q, "squareness_from_slopes", "convention", lambda: sq.squareness_from_slopes(0.0, 0.0, convention="left"), lambda: sq.squareness_from_slopes(0.0, 0.0, convention=None))
bad(Q, "squareness_from_slopes", "unknown plane", lambda: sq.squareness_from_slopes(0.0, 0.0, plane="QQ"))
bad(Q, "squareness", "first_position_m", lambda: sq.squareness([0.0], [0.0], XS, YS), lambda: sq.squareness([0.0, NAN], [0.0, 0.0], XS, YS), lambda: sq.squareness(None, YS, XS, YS))
bad(Q, "squareness", "second_deviation_m", lambda: sq.squareness(XS, YS, XS, [0.0, "a", 0.0]))
bad(Q, "squareness", "same length", lambda: sq.squareness(XS, YS, XS, YS[:2]))
bad(Q, "squareness", "unknown reference", lambda: sq.squareness(XS, YS, XS, YS, reference="best"))
bad(Q, "squareness", "unknown plane", lambda: sq.squareness(XS, YS, XS, YS, plane="AB"))
bad(Q, "prism_reversal", "alpha1_rad", lambda: sq.prism_reversal(NAN, 0.0), lambda: sq.prism_reversal("a", 0.0))
bad(Q, "prism_reversal", "alpha2_rad", lambda: sq.prism_reversal(0.0, None))
bad(Q, "prism_deviation_from_wedge", "alpha1_rad", lambda: sq.prism_deviation_from_wedge(INF, 0.0))
bad(Q, "prism_deviation_from_wedge", "alpha2_rad", lambda: sq.prism_deviation_from_wedge(0.0, [1.0]))
bad(Q, "psd_angular_resolution", "linear_resolution_m", lambda: sq.psd_angular_resolution(0.0, 1.0), lambda: sq.psd_angular_resolution(NAN, 1.0))
bad(Q, "psd_angular_resolution", "travel_m", lambda: sq.psd_angular_resolution(1e-6, -1.0), lambda: sq.psd_angular_resolution(1e-6, "1"))
bad(Q, "SquarenessEvaluation", "result", lambda: sq.SquarenessEvaluation(None, None, None))
bad(Q, "SquarenessEvaluation", "first", lambda: sq.SquarenessEvaluation(FIT, "x.csv", "y.csv"))
bad(Q, "squareness_from_files", "least-squares or end-points", lambda: sq.squareness_from_files(EXAMPLES / "squareness_x.csv", EXAMPLES / "squareness_y.csv", reference="minimum-zone"))
bad(Q, "squareness_from_files", "first_path", lambda: sq.squareness_from_files(None, EXAMPLES / "squareness_y.csv"))
bad(Q, "squareness_from_files", "unknown plane", lambda: sq.squareness_from_files(EXAMPLES / "squareness_x.csv", EXAMPLES / "squareness_y.csv", plane="XW"))
bad(Q, "squareness_from_files", "prism_deviation_rad", lambda: sq.squareness_from_files(EXAMPLES / "squareness_x.csv", EXAMPLES / "squareness_y.csv", prism_deviation_rad=NAN))
bad(Q, "PentaprismStudy", "table", lambda: sq.PentaprismStudy(None))
bad(Q, "pentaprism_study", "range_rad", lambda: sq.pentaprism_study(range_rad=0.0), lambda: sq.pentaprism_study(range_rad=NAN), lambda: sq.pentaprism_study(range_rad="1"))
bad(Q, "pentaprism_study", "steps", lambda: sq.pentaprism_study(steps=1), lambda: sq.pentaprism_study(steps=2.5), lambda: sq.pentaprism_study(steps=True))
bad(Q, "pentaprism_study", "index", lambda: sq.pentaprism_study(index=0.5), lambda: sq.pentaprism_study(index=NAN))
bad(Q, "CmmSquareness", "xy_rad", lambda: sq.CmmSquareness(NAN, 0.0, 0.0), lambda: sq.CmmSquareness("1", 0.0, 0.0))
bad(Q, "CmmSquareness", "yz_rad", lambda: sq.CmmSquareness(0.0, 0.0, None))
bad(Q, "CmmSquareness", "arc minutes", lambda: sq.CmmSquareness.checked(0.0, 0.1, 0.0))
bad(Q, "CmmSquareness", "unknown squareness term", lambda: sq.CmmSquareness.from_iso({"EC0X": 1e-5}))
bad(Q, "CmmSquareness", "EC0Y", lambda: sq.CmmSquareness.from_iso({"EC0Y": "1"}), lambda: sq.CmmSquareness.from_iso({"EC0Y": NAN}))
bad(Q, "CmmSquareness", "terms", lambda: sq.CmmSquareness.from_iso(None))
bad(Q, "compensate", "points_m", lambda: sq.compensate(np.zeros((2, 2)), CMM), lambda: sq.compensate([[NAN, 0, 0]], CMM), lambda: sq.compensate("a", CMM))
bad(Q, "compensate", "squareness", lambda: sq.compensate(PTS, (0.0, 0.0, 0.0)))
bad(Q, "readings_for", "points_m", lambda: sq.readings_for(np.zeros((2, 4)), CMM), lambda: sq.readings_for([[INF, 0, 0]], CMM))
bad(Q, "readings_for", "squareness", lambda: sq.readings_for(PTS, None))
bad(Q, "psd_squareness", "position_m", lambda: sq.psd_squareness([0.0], [0.0]), lambda: sq.psd_squareness([0.0, NAN], [0.0, 0.0]), lambda: sq.psd_squareness(None, [0.0]))
bad(Q, "psd_squareness", "reading_m", lambda: sq.psd_squareness([0.0, 1.0], [INF, 0.0]))
bad(Q, "psd_squareness", "prism_deviation_rad", lambda: sq.psd_squareness([0.0, 1.0], [0.0, 0.0], prism_deviation_rad=NAN))
bad(Q, "psd_squareness", "unknown reference", lambda: sq.psd_squareness([0.0, 1.0], [0.0, 0.0], reference="best"))
bad(Q, "squareness_from_psd_runs", "XY, XZ and YZ", lambda: sq.squareness_from_psd_runs({"XY": (XS, YS)}))
bad(Q, "squareness_from_psd_runs", "runs", lambda: sq.squareness_from_psd_runs(None), lambda: sq.squareness_from_psd_runs({"XY": (XS, YS), "XZ": XS, "YZ": (XS, YS)}))
bad(Q, "least_squares_plane", "at least 3", lambda: sq.least_squares_plane(PTS))
bad(Q, "least_squares_plane", "points_m", lambda: sq.least_squares_plane([[0, 0, NAN]] * 3), lambda: sq.least_squares_plane(None), lambda: sq.least_squares_plane(np.zeros((3, 2))))
bad(Q, "least_squares_plane", "one line", lambda: sq.least_squares_plane([[0, 0, 0], [1, 0, 0], [2, 0, 0]]))
bad(Q, "gauge_block_length", "points_m", lambda: sq.gauge_block_length([[0, 0, 0], [1, 0, 0], [0, 1, 0]], [NAN, 0, 0], [0, 0, 1]), lambda: sq.gauge_block_length([[0, 0, 0], [1, 0, 0], [0, 1, 0]], [0, 0], [0, 0, 1]))
bad(Q, "simulate_gauge_block", "nominal_m", lambda: sq.simulate_gauge_block(CMM, 0.0, (1, 0, 0)), lambda: sq.simulate_gauge_block(CMM, NAN, (1, 0, 0)))
bad(Q, "simulate_gauge_block", "axis", lambda: sq.simulate_gauge_block(CMM, 1e-3, (0, 0, 0)), lambda: sq.simulate_gauge_block(CMM, 1e-3, (1, 0)), lambda: sq.simulate_gauge_block(CMM, 1e-3, "x"))
bad(Q, "simulate_gauge_block", "centre_m", lambda: sq.simulate_gauge_block(CMM, 1e-3, (1, 0, 0), centre_m=(NAN, 0, 0)))
bad(Q, "simulate_gauge_block", "end_offset_m", lambda: sq.simulate_gauge_block(CMM, 1e-3, (1, 0, 0), end_offset_m=(0, 0)))
bad(Q, "simulate_gauge_block", "probe_rectangle_m", lambda: sq.simulate_gauge_block(CMM, 1e-3, (1, 0, 0), probe_rectangle_m=(0.02,)), lambda: sq.simulate_gauge_block(CMM, 1e-3, (1, 0, 0), probe_rectangle_m=(0.0, 0.01)))
bad(Q, "simulate_gauge_block", "squareness", lambda: sq.simulate_gauge_block(None, 1e-3, (1, 0, 0)))
bad(Q, "simulate_gauge_block", "compensation", lambda: sq.simulate_gauge_block(CMM, 1e-3, (1, 0, 0), compensation=5))
bad(Q, "compensate_file", "points_path", lambda: sq.compensate_file(None, CMM))
bad(Q, "compensate_file", "squareness", lambda: sq.compensate_file(EXAMPLES / "cmm_points.csv", None))
bad(Q, "compensate_file", "inverse", lambda: sq.compensate_file(EXAMPLES / "cmm_points.csv", CMM, inverse="no"))
bad(Q, "gauge_block_study", "end_offset_m", lambda: sq.gauge_block_study(CMM, end_offset_m=NAN), lambda: sq.gauge_block_study(CMM, end_offset_m="1"))
bad(Q, "gauge_block_study", "squareness", lambda: sq.gauge_block_study(None))
bad(Q, "plot_squareness", "result", lambda: sq.plot_squareness("/tmp/never.png", sq.squareness_from_slopes(0.0, 0.0), ((XS, YS), (XS, YS))), lambda: sq.plot_squareness("/tmp/never.png", None, ()))
bad(Q, "plot_squareness", "runs", lambda: sq.plot_squareness("/tmp/never.png", FIT, (XS, YS)), lambda: sq.plot_squareness("/tmp/never.png", FIT, (([NAN], [0.0]), (XS, YS))))
bad(Q, "plot_squareness", "path", lambda: sq.plot_squareness(None, FIT, ((XS, YS), (XS, YS))))
bad(Q, "plot_squareness", "overlay", lambda: sq.plot_squareness("/tmp/never.png", FIT, ((XS, YS), (XS, YS)), overlay=(1, 2)),
    lambda: sq.plot_squareness("/tmp/never.png", FIT, ((XS, YS), (XS, YS)), overlay={"first": [1, 2]}),
    lambda: sq.plot_squareness("/tmp/never.png", FIT, ((XS, YS), (XS, YS)), overlay={"second": {"position_mm": [0], "deviation_um": "1"}}))
bad(Q, "plot_pentaprism", "table", lambda: sq.plot_pentaprism("/tmp/never.png", None))
bad(Q, "plot_pentaprism", "path", lambda: sq.plot_pentaprism(5, ins.pentaprism_sensitivity([0.0, 1e-3])))


# ---------------------------------------------------------------- circular
ci = api("circular")
C = "circular"
A72 = np.radians(np.arange(0.0, 360.0, 5.0))
TRACE = ci.BallbarTrace(A72, ("ccw",) * 72, np.zeros(72), radius=0.1)
RESULT = ci.evaluate_ballbar(TRACE)
BALLBAR = EXAMPLES / "ballbar" / "ballbar_run.csv"

bad(C, "plane_axes", "unknown plane", lambda: ci.plane_axes("XX"), lambda: ci.plane_axes(None), lambda: ci.plane_axes(5))
bad(C, "coverage_gap", "angles", lambda: ci.coverage_gap([NAN, 0.0]), lambda: ci.coverage_gap("a"), lambda: ci.coverage_gap(np.zeros((2, 2))))
bad(C, "check_direction", "angles", lambda: ci.check_direction([INF] * 40, "ccw"), lambda: ci.check_direction(None, "ccw"))
bad(C, "check_direction", "direction", lambda: ci.check_direction(A72, "up"), lambda: ci.check_direction(A72, None))
bad(C, "BallbarTrace", "radius", lambda: ci.BallbarTrace(A72, ("ccw",) * 72, np.zeros(72), radius=0.0), lambda: ci.BallbarTrace(A72, ("ccw",) * 72, np.zeros(72), radius=NAN),
    lambda: ci.BallbarTrace(A72, ("ccw",) * 72, np.zeros(72), radius="0.1"), lambda: ci.BallbarTrace(A72, ("ccw",) * 72, np.zeros(72), radius=True))
bad(C, "BallbarTrace", "length", lambda: ci.BallbarTrace(A72, ("ccw",) * 71, np.zeros(72), radius=0.1), lambda: ci.BallbarTrace(A72, ("ccw",) * 72, np.zeros(70), radius=0.1))
bad(C, "BallbarTrace", "finite", lambda: ci.BallbarTrace(A72, ("ccw",) * 72, np.full(72, NAN), radius=0.1))
bad(C, "BallbarTrace", "angles", lambda: ci.BallbarTrace("a", ("ccw",), [0.0], radius=0.1), lambda: ci.BallbarTrace(None, ("ccw",), [0.0], radius=0.1))
bad(C, "BallbarTrace", "direction", lambda: ci.BallbarTrace(A72, ("up",) * 72, np.zeros(72), radius=0.1), lambda: ci.BallbarTrace(A72, "ccw", np.zeros(72), radius=0.1))
bad(C, "BallbarTrace", "at least 36", lambda: ci.BallbarTrace(A72[:10], ("ccw",) * 10, np.zeros(10), radius=0.1))
bad(C, "BallbarTrace", "no points", lambda: ci.BallbarTrace([], (), [], radius=0.1))
bad(C, "BallbarTrace", "unknown plane", lambda: ci.BallbarTrace(A72, ("ccw",) * 72, np.zeros(72), radius=0.1, plane="XQ"))
bad(C, "BallbarTrace", "source", lambda: ci.BallbarTrace(A72, ("ccw",) * 72, np.zeros(72), radius=0.1, source=None))
bad(C, "lsq_circle", "at least 3", lambda: ci.lsq_circle([0.0, 1.0], [0.0, 0.0], 0.1))
bad(C, "lsq_circle", "angles", lambda: ci.lsq_circle([NAN, 1.0, 2.0], [0.0] * 3, 0.1), lambda: ci.lsq_circle([[0.0, 1.0, 2.0]], [[0.0] * 3], 0.1))
bad(C, "lsq_circle", "deviations", lambda: ci.lsq_circle([0.0, 1.0, 2.0], [0.0, INF, 0.0], 0.1))
bad(C, "lsq_circle", "same length", lambda: ci.lsq_circle([0.0, 1.0, 2.0], [0.0] * 4, 0.1))
bad(C, "lsq_circle", "radius", lambda: ci.lsq_circle([0.0, 1.0, 2.0], [0.0] * 3, 0.0), lambda: ci.lsq_circle([0.0, 1.0, 2.0], [0.0] * 3, NAN))
bad(C, "radial_deviations", "centre", lambda: ci.radial_deviations([0.0], [0.0], 0.1, (0.0,)), lambda: ci.radial_deviations([0.0], [0.0], 0.1, (NAN, 0.0)),
    lambda: ci.radial_deviations([0.0, 1.6], [0.0, 0.0], 0.1, (0.0, 0.5)))
bad(C, "radial_deviations", "radius", lambda: ci.radial_deviations([0.0], [0.0], -0.1, (0.0, 0.0)))
bad(C, "radial_deviations", "same length", lambda: ci.radial_deviations([0.0, 1.0], [0.0], 0.1, (0.0, 0.0)))
bad(C, "radial_deviations", "deviations", lambda: ci.radial_deviations([0.0], [NAN], 0.1, (0.0, 0.0)))
bad(C, "iso230_4", "trace", lambda: ci.iso230_4(None), lambda: ci.iso230_4(A72))
bad(C, "reversal_angles", "axis", lambda: ci.reversal_angles(2), lambda: ci.reversal_angles("x"), lambda: ci.reversal_angles(-1))
bad(C, "backlash_signature", "axis", lambda: ci.backlash_signature(A72, np.ones(72), 2))
bad(C, "backlash_signature", "signs", lambda: ci.backlash_signature(A72, np.zeros(72), 0), lambda: ci.backlash_signature(A72, np.ones(3), 0))
bad(C, "backlash_signature", "angles", lambda: ci.backlash_signature([NAN], [1.0], 0))
bad(C, "diagnose", "trace", lambda: ci.diagnose(None))
bad(C, "diagnose", "feed", lambda: ci.diagnose(TRACE, feed=0.0), lambda: ci.diagnose(TRACE, feed=NAN), lambda: ci.diagnose(TRACE, feed="fast"))
bad(C, "diagnose", "window", lambda: ci.diagnose(TRACE, spike_window=0.0), lambda: ci.diagnose(TRACE, spike_window=NAN), lambda: ci.diagnose(TRACE, spike_window=None))
bad(C, "read_ballbar", "radius", lambda: ci.read_ballbar(BALLBAR, radius=0.0), lambda: ci.read_ballbar(BALLBAR, radius="0.1"), lambda: ci.read_ballbar(BALLBAR, radius=NAN))
bad(C, "read_ballbar", "plane", lambda: ci.read_ballbar(BALLBAR, radius=0.1, plane="AB"))
bad(C, "read_ballbar", "path", lambda: ci.read_ballbar(None, radius=0.1))
bad(C, "iso_squareness", "unknown plane", lambda: ci.iso_squareness("XW", 0.0), lambda: ci.iso_squareness(None, 0.0))
bad(C, "iso_squareness", "squareness", lambda: ci.iso_squareness("XY", NAN), lambda: ci.iso_squareness("XY", "1"))
bad(C, "BallbarResult", "trace", lambda: ci.BallbarResult(None, RESULT.figures, RESULT.diagnostics))
bad(C, "BallbarResult", "feed", lambda: ci.BallbarResult(TRACE, RESULT.figures, RESULT.diagnostics, feed=-1.0))
bad(C, "evaluate_ballbar", "trace", lambda: ci.evaluate_ballbar(None))
bad(C, "evaluate_ballbar", "feed", lambda: ci.evaluate_ballbar(TRACE, feed=-1.0))
bad(C, "evaluate_ballbar_file", "radius", lambda: ci.evaluate_ballbar_file(BALLBAR, radius=-1.0))
bad(C, "evaluate_ballbar_file", "feed", lambda: ci.evaluate_ballbar_file(BALLBAR, radius=0.15, feed=NAN))
bad(C, "evaluate_ballbar_file", "path", lambda: ci.evaluate_ballbar_file(5, radius=0.1))
bad(C, "ballbar_payload", "result", lambda: ci.ballbar_payload(None), lambda: ci.ballbar_payload(TRACE))
bad(C, "format_number", "value", lambda: ci.format_number("1.5"))
bad(C, "format_number", "fmt", lambda: ci.format_number(1.5, None), lambda: ci.format_number(1.5, "{0} {1}"))
bad(C, "render_report", "result", lambda: ci.render_report(None))
bad(C, "simulate_ballbar", "radius", lambda: ci.simulate_ballbar(radius=0.0), lambda: ci.simulate_ballbar(radius="1"))
bad(C, "simulate_ballbar", "feed", lambda: ci.simulate_ballbar(feed=NAN))
bad(C, "simulate_ballbar", "step", lambda: ci.simulate_ballbar(step=0.0), lambda: ci.simulate_ballbar(step=1.0))
bad(C, "simulate_ballbar", "noise", lambda: ci.simulate_ballbar(noise=-1.0), lambda: ci.simulate_ballbar(noise=None))
bad(C, "simulate_ballbar", "squareness", lambda: ci.simulate_ballbar(squareness=NAN), lambda: ci.simulate_ballbar(squareness="1"))
bad(C, "simulate_ballbar", "scale", lambda: ci.simulate_ballbar(scale={"Z": 1e-5}), lambda: ci.simulate_ballbar(scale={"X": NAN}), lambda: ci.simulate_ballbar(scale=5),
    lambda: ci.simulate_ballbar(scale={"X": "1"}))
bad(C, "simulate_ballbar", "pitch", lambda: ci.simulate_ballbar(cyclic_error={"X": 1e-6}))
bad(C, "simulate_ballbar", "directions", lambda: ci.simulate_ballbar(directions=()), lambda: ci.simulate_ballbar(directions=("up",)))
bad(C, "simulate_ballbar", "seed", lambda: ci.simulate_ballbar(seed=-1), lambda: ci.simulate_ballbar(seed="a"))
bad(C, "simulate_ballbar", "unknown plane", lambda: ci.simulate_ballbar(plane="AA"))
bad(C, "trace_csv", "trace", lambda: ci.trace_csv(None))
bad(C, "write_trace", "trace", lambda: ci.write_trace("/tmp/never-written.csv", None))
bad(C, "write_trace", "path", lambda: ci.write_trace(None, TRACE))
bad(C, "plot_ballbar", "result", lambda: ci.plot_ballbar(None, "/tmp/never.png"))
bad(C, "plot_ballbar", "figure format", lambda: ci.plot_ballbar(RESULT, "/tmp/never.xyz"))
bad(C, "plot_ballbar", "path", lambda: ci.plot_ballbar(RESULT, None))
bad(C, "plot_ballbar", "title", lambda: ci.plot_ballbar(RESULT, "/tmp/never.png", title=5))
bad(C, "plot_ballbar", "overlay", lambda: ci.plot_ballbar(RESULT, "/tmp/never.png", overlay="before"),
    lambda: ci.plot_ballbar(RESULT, "/tmp/never.png", overlay={"ccw": [1, 2]}),
    lambda: ci.plot_ballbar(RESULT, "/tmp/never.png", overlay={"cw": {"angle_deg": [0, 1], "deviation_um": [0]}}))
bad(C, "circle_deviations", "result", lambda: ci.circle_deviations(None), lambda: ci.circle_deviations(TRACE))
bad(C, "trace_payload", "result", lambda: ci.trace_payload(None))
bad(C, "trace_payload", "max_points", lambda: ci.trace_payload(RESULT, max_points=1), lambda: ci.trace_payload(RESULT, max_points=NAN))


# ---------------------------------------------------------------- measurement
me = api("measurement")
M = "measurement"
XZ = Path(__file__).resolve().parents[2] / "src" / "axiscal" / "data" / "xz_module"
MODULE = me.VirtualModule(seed=0)
SYSTEM = MODULE.measurement_system()
CSV_TABLE = parse_csv(["a_mm,b_um", "1,2"], path="t.csv")
E3 = np.zeros((2, 3))

bad(M, "display_name", "name", lambda: me.display_name(None), lambda: me.display_name(5))
bad(M, "display_factor", "name", lambda: me.display_factor(None))
bad(M, "to_display", "results", lambda: me.to_display(None), lambda: me.to_display({"ex_m": "a"}))
bad(M, "to_display", "name", lambda: me.to_display({5: [1.0]}))
bad(M, "fault_text", "fault", lambda: me.fault_text("x"), lambda: me.fault_text(-1), lambda: me.fault_text(1.5), lambda: me.fault_text(None))
bad(M, "mark_malformed", "malformed", lambda: me.mark_malformed({"fault": np.zeros(2, dtype=int), "e_m": np.zeros(2)}, [True]),
    lambda: me.mark_malformed({"fault": np.zeros(2, dtype=int)}, "yes"))
bad(M, "mark_malformed", "fault", lambda: me.mark_malformed({"e_m": np.zeros(2)}, [True, False]), lambda: me.mark_malformed(None, [True]))
bad(M, "mark_malformed", "same length", lambda: me.mark_malformed({"fault": np.zeros(2, dtype=int), "e_m": np.zeros(3)}, [True, False]))
bad(M, "load_system", "seed", lambda: me.load_system(seed=-1), lambda: me.load_system(seed="a"))
bad(M, "load_system", "load_kg", lambda: me.load_system(load_kg=NAN), lambda: me.load_system(load_kg=-5.0), lambda: me.load_system(load_kg="heavy"))
bad(M, "load_system", "machine", lambda: me.load_system(5))
bad(M, "is_live_record", "path", lambda: me.is_live_record(None))
bad(M, "is_live_record", "header", lambda: me.is_live_record("x.csv", header=5), lambda: me.is_live_record("x.csv", header="t_s"))
bad(M, "drop_cut_line", "text", lambda: me.drop_cut_line(None), lambda: me.drop_cut_line(b"a,b\n"))
bad(M, "numeric_columns", "table", lambda: me.numeric_columns(None, ["a_mm"]))
bad(M, "numeric_columns", "names", lambda: me.numeric_columns(CSV_TABLE, "a_mm"), lambda: me.numeric_columns(CSV_TABLE, [5]))
bad(M, "read_frames_table", "path", lambda: me.read_frames_table(None))
bad(M, "read_frames_table", "min_rows", lambda: me.read_frames_table(XZ / "sensors_frames.csv", min_rows=-1), lambda: me.read_frames_table(XZ / "sensors_frames.csv", min_rows="1"))
bad(M, "read_frames", "path", lambda: me.read_frames(None, ["t_s"]))
bad(M, "read_frames", "channels", lambda: me.read_frames(XZ / "sensors_frames.csv", "x_cmd_mm"), lambda: me.read_frames(XZ / "sensors_frames.csv", None))
bad(M, "columns_csv", "columns", lambda: me.columns_csv(None), lambda: me.columns_csv({"a_mm": "x"}))
bad(M, "columns_csv", "same length", lambda: me.columns_csv({"a_mm": [1.0], "b_um": [1.0, 2.0]}))
bad(M, "write_data_csv", "path", lambda: me.write_data_csv(None, {"a_mm": [1.0]}, kind="test"))
bad(M, "write_data_csv", "same length", lambda: me.write_data_csv("/tmp/never-written.csv", {"a_mm": [1.0], "b_um": [1.0, 2.0]}, kind="test"))
bad(M, "write_data_csv", "kind", lambda: me.write_data_csv("/tmp/never-written.csv", {"a_mm": [1.0]}, kind=None))
bad(M, "CsvOutput", "text", lambda: me.CsvOutput(None, 0))
bad(M, "CsvOutput", "rows", lambda: me.CsvOutput("a\n", -1), lambda: me.CsvOutput("a\n", "1"))
bad(M, "MeasureResult", "source", lambda: me.MeasureResult(None, {}))
bad(M, "MeasureResult", "results", lambda: me.MeasureResult("x.csv", None), lambda: me.MeasureResult("x.csv", {"t_s": np.zeros(2)}))
bad(M, "measure_file", "frames_path", lambda: me.measure_file(None))
bad(M, "measure_file", "machine", lambda: me.measure_file(XZ / "sensors_frames.csv", machine=5))
bad(M, "calibrate_sensitivity", "run_path", lambda: me.calibrate_sensitivity(None, "x_scale_mm"))
bad(M, "calibrate_sensitivity", "channel", lambda: me.calibrate_sensitivity(XZ / "sensors_scale_run.csv", "nope"), lambda: me.calibrate_sensitivity(XZ / "sensors_scale_run.csv", None))
bad(M, "calibrate_sensitivity", "reference_offset_m", lambda: me.calibrate_sensitivity(XZ / "sensors_scale_run.csv", "x_scale_mm", reference_offset_m=(0.0, NAN, 0.0)),
    lambda: me.calibrate_sensitivity(XZ / "sensors_scale_run.csv", "x_scale_mm", reference_offset_m=(0.0, 0.0)))
bad(M, "calibrate_mirror", "run_path", lambda: me.calibrate_mirror(None, "X"))
bad(M, "calibrate_mirror", "letter", lambda: me.calibrate_mirror(XZ / "sensors_mirror_run.csv", "Q"), lambda: me.calibrate_mirror(XZ / "sensors_mirror_run.csv", None))
bad(M, "calibrate_mirror", "max_order", lambda: me.calibrate_mirror(XZ / "sensors_mirror_run.csv", "X", max_order=-1), lambda: me.calibrate_mirror(XZ / "sensors_mirror_run.csv", "X", max_order=2.5))
bad(M, "calibration_text", "report", lambda: me.calibration_text(None), lambda: me.calibration_text({}))
bad(M, "simulate_frames", "path", lambda: me.simulate_frames(path="circle"), lambda: me.simulate_frames(path=None))
bad(M, "simulate_frames", "rate_hz", lambda: me.simulate_frames(rate_hz=0.0), lambda: me.simulate_frames(rate_hz=NAN), lambda: me.simulate_frames(rate_hz="fast"))
bad(M, "simulate_frames", "duration_s", lambda: me.simulate_frames(duration_s=-1.0), lambda: me.simulate_frames(duration_s=INF))
bad(M, "simulate_frames", "load_kg", lambda: me.simulate_frames(load_kg=NAN))
bad(M, "simulate_frames", "seed", lambda: me.simulate_frames(seed=-3))
bad(M, "simulate_frames", "truth", lambda: me.simulate_frames(truth="yes"))
bad(M, "simulate_laser", "steps", lambda: me.simulate_laser(steps=0), lambda: me.simulate_laser(steps=2.5))
bad(M, "simulate_laser", "step_m", lambda: me.simulate_laser(step_m=0.0), lambda: me.simulate_laser(step_m=NAN), lambda: me.simulate_laser(step_m=1.0))
bad(M, "simulate_laser", "load_kg", lambda: me.simulate_laser(load_kg=-1.0))
bad(M, "DiagonalReport", "experiment", lambda: me.DiagonalReport(None))
bad(M, "run_diagonal_experiment", "load_kg", lambda: me.run_diagonal_experiment(load_kg=NAN), lambda: me.run_diagonal_experiment(load_kg=-1.0))
bad(M, "run_diagonal_experiment", "samples", lambda: me.run_diagonal_experiment(samples=0), lambda: me.run_diagonal_experiment(samples="2"))
bad(M, "run_diagonal_experiment", "seed", lambda: me.run_diagonal_experiment(seed=1.5))
bad(M, "run_diagonal_experiment", "squareness_error_rad", lambda: me.run_diagonal_experiment(squareness_error_rad=NAN))
bad(M, "MeasurementSystem", "machine", lambda: me.MeasurementSystem(None, SYSTEM.heads), lambda: me.MeasurementSystem("machine.toml", SYSTEM.heads))
bad(M, "MeasurementSystem", "heads", lambda: me.MeasurementSystem(SYSTEM.machine, None), lambda: me.MeasurementSystem(SYSTEM.machine, {"X": 5, "Z": 5}))
bad(M, "MeasurementSystem", "calibration", lambda: me.MeasurementSystem(SYSTEM.machine, SYSTEM.heads, calibration={}))
bad(M, "MeasurementSystem", "frames", lambda: SYSTEM.process(None), lambda: SYSTEM.process({"x_cmd_mm": [1.0, 2.0], "z_cmd_mm": [1.0]}), lambda: SYSTEM.process({"x_cmd_mm": "a"}))
bad(M, "MeasurementSystem", "frames", lambda: SYSTEM.channel_faults(None))
bad(M, "MeasurementSystem", "fault", lambda: SYSTEM.fault_text("bad"))
bad(M, "MeasurementSystem", "calibration", lambda: SYSTEM.with_calibration(None))
bad(M, "MeasurementSystem", "path", lambda: me.MeasurementSystem.from_toml(None))
bad(M, "spatial_error", "machine", lambda: me.spatial_error(None, {"X": [0.1]}, {"X": np.zeros((6, 1))}))
bad(M, "spatial_error", "errors", lambda: me.spatial_error(SYSTEM.machine, {"X": [0.1], "Z": [-0.1]}, None),
    lambda: me.spatial_error(SYSTEM.machine, {"X": [0.1], "Z": [-0.1]}, {"X": np.zeros((5, 1)), "Z": np.zeros((6, 1))}))
bad(M, "spatial_error", "positions", lambda: me.spatial_error(SYSTEM.machine, None, {"X": np.zeros((6, 1)), "Z": np.zeros((6, 1))}))
bad(M, "diagonal_errors", "x_m", lambda: me.diagonal_errors([NAN, 0.1], [0.1, 0.1], E3, [0.1, 0.2]), lambda: me.diagonal_errors("x", [0.1], E3[:1], [0.1]))
bad(M, "diagonal_errors", "error_m", lambda: me.diagonal_errors([0.1, 0.1], [0.1, 0.1], np.zeros((2, 2)), [0.1, 0.2]), lambda: me.diagonal_errors([0.1, 0.1], [0.1, 0.1], np.full((2, 3), NAN), [0.1, 0.2]))
bad(M, "diagonal_errors", "same length", lambda: me.diagonal_errors([0.1, 0.1], [0.1], E3, [0.1, 0.2]))
bad(M, "diagonal_errors", "laser_m", lambda: me.diagonal_errors([0.1, 0.1], [0.1, 0.1], E3, [INF, 0.2]))
bad(M, "Truth", "gain", lambda: me.Truth(0.0, 0.0, 0.0), lambda: me.Truth(NAN, 0.0, 0.0))
bad(M, "Truth", "noise", lambda: me.Truth(1.0, 0.0, -1.0))
bad(M, "calibrate_sensor_runs", "path", lambda: me.calibrate_sensor_runs(None))
bad(M, "calibrate_sensor_runs", "machine", lambda: me.calibrate_sensor_runs(EXAMPLES / "campaign" / "sensor_calibration_runs.csv", machine=5))
bad(M, "sensor_diagonal", "readings_path", lambda: me.sensor_diagonal(None, "f.csv", start={"X": 0.0}, end={"X": 0.1}))
bad(M, "sensor_diagonal", "frames_path", lambda: me.sensor_diagonal("r.csv", None, start={"X": 0.0}, end={"X": 0.1}))
bad(M, "sensor_diagonal", "start", lambda: me.sensor_diagonal("r.csv", "f.csv", start="X=0", end={"X": 0.1}),
    lambda: me.sensor_diagonal("r.csv", "f.csv", start={"Y": 0.0}, end={"X": 0.1}))
bad(M, "sensor_diagonal", "end", lambda: me.sensor_diagonal("r.csv", "f.csv", start={"X": 0.0}, end={"X": NAN}))
bad(M, "VirtualModule", "seed", lambda: me.VirtualModule(seed=-1), lambda: me.VirtualModule(seed="a"))
bad(M, "VirtualModule", "load_kg", lambda: me.VirtualModule(load_kg=NAN), lambda: me.VirtualModule(load_kg=-2.0), lambda: me.VirtualModule(load_kg=None))
bad(M, "VirtualModule", "noise", lambda: me.VirtualModule(noise="no"))
bad(M, "VirtualModule", "speed_mm_s", lambda: me.VirtualModule(speed_mm_s=0.0), lambda: me.VirtualModule(speed_mm_s=NAN))
bad(M, "VirtualModule", "letter", lambda: MODULE.true_errors("Y", [0.1]), lambda: MODULE.mirror_error(None, [0.1]))
bad(M, "VirtualModule", "q_m", lambda: MODULE.true_errors("X", [NAN]), lambda: MODULE.true_errors("X", "a"), lambda: MODULE.mirror_error("X", [INF]))
bad(M, "VirtualModule", "t_s", lambda: MODULE.positions([NAN]), lambda: MODULE.frames("a"))
bad(M, "VirtualModule", "path", lambda: MODULE.positions([0.0], path="circle"), lambda: MODULE.frames([0.0], path=None))
bad(M, "VirtualModule", "positions_m", lambda: MODULE.true_point(None), lambda: MODULE.true_point({"X": [NAN], "Z": [0.0]}), lambda: MODULE.laser_diagonal({"X": [0.1]}),
    lambda: MODULE.frames_at({"X": [0.1, 0.2], "Z": [0.1]}))
bad(M, "VirtualModule", "rng", lambda: MODULE.raw({}, None))
bad(M, "VirtualModule", "errors", lambda: MODULE.sensor_values("X", [0.1], np.zeros((5, 1))))
bad(M, "diagonal_experiment", "module", lambda: me.diagonal_experiment(None))
bad(M, "diagonal_experiment", "points", lambda: me.diagonal_experiment(MODULE, points=0), lambda: me.diagonal_experiment(MODULE, points=2.5))
bad(M, "diagonal_experiment", "step_m", lambda: me.diagonal_experiment(MODULE, step_m=0.0), lambda: me.diagonal_experiment(MODULE, step_m=NAN))
bad(M, "diagonal_experiment", "samples", lambda: me.diagonal_experiment(MODULE, samples=0))
bad(M, "diagonal_experiment", "squareness_error_rad", lambda: me.diagonal_experiment(MODULE, squareness_error_rad=INF))
bad(M, "diagonal_readings", "module", lambda: me.diagonal_readings(None))
bad(M, "laser_run", "module", lambda: me.laser_run(None, "X"))
bad(M, "laser_run", "letter", lambda: me.laser_run(MODULE, "Y"), lambda: me.laser_run(MODULE, None))
bad(M, "laser_run", "runs", lambda: me.laser_run(MODULE, "X", runs=0), lambda: me.laser_run(MODULE, "X", runs="5"))
bad(M, "laser_run", "targets", lambda: me.laser_run(MODULE, "X", targets=1))
bad(M, "laser_run", "seed", lambda: me.laser_run(MODULE, "X", seed=-1))
bad(M, "probe_readings", "module", lambda: me.probe_readings(None))
bad(M, "probe_readings", "seed", lambda: me.probe_readings(MODULE, seed="a"))
bad(M, "squareness_runs", "module", lambda: me.squareness_runs(None))
bad(M, "squareness_runs", "points", lambda: me.squareness_runs(MODULE, points=1), lambda: me.squareness_runs(MODULE, points=None))
bad(M, "squareness_runs", "seed", lambda: me.squareness_runs(MODULE, seed=-2))
bad(M, "write_campaign", "folder", lambda: me.write_campaign(None))
bad(M, "write_campaign", "seed", lambda: me.write_campaign("/tmp/never-written", seed=-1), lambda: me.write_campaign("/tmp/never-written", seed=1.5))
bad(M, "campaign_toml", "seed", lambda: me.campaign_toml(-1), lambda: me.campaign_toml(1.5))
bad(M, "SimulatedCampaign", "folder", lambda: me.SimulatedCampaign(None, 0, ()))
bad(M, "SimulatedCampaign", "files", lambda: me.SimulatedCampaign(Path("/tmp"), 0, "a.csv"))


# ---------------------------------------------------------------- the check
EXEMPT = {
    # result records: the library fills them with what a function computed; a user reads them and
    # does not build them, so they take no user values to check
    "instruments": {"RayTrace", "PentaprismSensitivity"},
    "straightness": {"Separation", "NoisePropagation"},
    "circular": {"CircularFigures", "BallbarDiagnostics"},
    # an IntFlag of fault bits, result records of diagonal_experiment, calibrate_sensor_runs and
    # sensor_diagonal, and a function of no arguments
    "measurement": {"Fault", "DiagonalExperiment", "SensorRuns", "SensorDiagonal", "fault_legend"},
    "squareness": {"SquarenessResult", "ReversalResult", "Plane", "GaugeBlockCheck", "CmmCompensation", "GaugeBlockStudy"},
}






test_bad_arguments_raise_axiscal_error_naming_them, test_every_public_callable_has_a_bad_argument_case = TABLE.tests(EXEMPT)


# ---------------------------------------------------------------- properties: finite in, finite out or AxiscalError
_ANY_FLOAT = hs.floats(allow_nan=True, allow_infinity=True, width=64)
_FINITE = hs.floats(allow_nan=False, allow_infinity=False, width=64)


_finite_or_refused = finite_or_refused


@settings(max_examples=150, deadline=None)
@given(hs.lists(hs.tuples(_FINITE, _FINITE), min_size=0, max_size=12), hs.sampled_from(st_.REFERENCES))
def test_reference_line_of_any_finite_profile_is_finite_or_refused(points, reference):
    x = [p[0] for p in points]
    y = [p[1] for p in points]
    line = _finite_or_refused(lambda: st_.reference_line(x, y, reference=reference))
    if line is not None:
        assert all(np.isfinite(v) for v in (line.slope, line.intercept_m, line.straightness_m))
        assert line.straightness_m >= 0.0


@settings(max_examples=150, deadline=None)
@given(hs.lists(_ANY_FLOAT, min_size=0, max_size=12), hs.lists(_ANY_FLOAT, min_size=0, max_size=12), hs.sampled_from(st_.REFERENCES))
def test_reference_line_refuses_what_is_not_finite(x, y, reference):
    line = _finite_or_refused(lambda: st_.reference_line(x, y, reference=reference))
    if line is not None:
        assert np.all(np.isfinite(x)) and np.all(np.isfinite(y)) and len(x) == len(y)


@settings(max_examples=100, deadline=None)
@given(_ANY_FLOAT, _ANY_FLOAT, _ANY_FLOAT, _ANY_FLOAT)
def test_refractive_index_of_any_numbers_is_finite_or_refused(t, p, h, wavelength):
    n = _finite_or_refused(lambda: ins.refractive_index(t, p, h, wavelength))
    if n is not None:
        assert np.isfinite(n) and n > 1.0


@settings(max_examples=100, deadline=None)
@given(_ANY_FLOAT, _ANY_FLOAT, _ANY_FLOAT)
def test_squareness_from_any_slopes_is_finite_or_refused(first, second, prism):
    result = _finite_or_refused(lambda: sq.squareness_from_slopes(first, second, prism_deviation_rad=prism))
    if result is not None:
        assert np.isfinite(result.squareness_rad) and np.isfinite(result.iso_value_rad)


@settings(max_examples=60, deadline=None)
@given(hs.lists(_ANY_FLOAT, min_size=0, max_size=8), _ANY_FLOAT)
def test_lsq_circle_of_any_numbers_is_finite_or_refused(deviations, radius):
    angles = np.linspace(0.0, 2.0 * np.pi, len(deviations), endpoint=False)
    fit = _finite_or_refused(lambda: ci.lsq_circle(angles, deviations, radius))
    if fit is not None:
        assert np.all(np.isfinite(fit))
