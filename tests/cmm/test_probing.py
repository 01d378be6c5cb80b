"""ISO 10360-5 probing test: the least-squares sphere against reference data and a plain solver, and the figures."""

from __future__ import annotations

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st
from scipy.optimize import least_squares

from axiscal.cmm import SpherePoints, evaluate_probing, fit_sphere, fit_spread, probing_test, read_sphere_points
from axiscal.errors import AxiscalError

UM, MM = 1e-6, 1e-3
CENTRE = np.array([310.0, 220.0, -180.0]) * MM
RADIUS = 12.5 * MM


def pattern(pole=(0.0, 0.0, 1.0)) -> np.ndarray:
    """The 25 directions: one at the pole, 4 at 22.5 deg below it, 8 at 45 deg, 4 at 67.5 deg, 8 at the equator."""
    out = []
    for polar, count, turn in [(0.0, 1, 0.0), (22.5, 4, 0.0), (45.0, 8, 22.5), (67.5, 4, 22.5), (90.0, 8, 22.5)]:
        for k in range(count):
            a, t = np.radians(turn + 360.0 * k / count), np.radians(polar)
            out.append((np.sin(t) * np.cos(a), np.sin(t) * np.sin(a), np.cos(t)))
    v = np.array(out)
    pole = np.asarray(pole, dtype=float) / np.linalg.norm(pole)
    if np.allclose(pole, (0, 0, 1)):
        return v
    k = np.cross((0, 0, 1), pole)
    s, c = np.linalg.norm(k), pole[2]
    kx = np.array([[0, -k[2], k[1]], [k[2], 0, -k[0]], [-k[1], k[0], 0]]) / s
    return v @ (np.eye(3) + s * kx + (1 - c) * kx @ kx).T


def reference_data(directions, residual_range_m, seed):
    """Points whose least-squares sphere is known: CENTRE, RADIUS, and residuals of the given range.

    The way reference data sets for fitting software are made (ISO 10360-6; C. M. Shakarji,
    "Least-squares fitting algorithms of the NIST algorithm testing system", J. Res. NIST 103
    (1998) 633): the residuals are orthogonal to the columns of the Jacobian at the solution (the
    normals and the radius' column of ones), so the solution is a stationary point of the sum of
    squares, and the points are displaced along their normals by them.
    """
    rng = np.random.default_rng(seed)
    jacobian = np.column_stack([directions, np.ones(len(directions))])
    w = rng.normal(size=len(directions))
    delta = w - jacobian @ np.linalg.lstsq(jacobian, w, rcond=None)[0]
    delta *= residual_range_m / np.ptp(delta)
    return CENTRE + (RADIUS + delta)[:, None] * directions, delta


def test_six_points_by_hand():
    """±x, ±y, ±z at r = 10 mm; the x pair pushed out by a = 1 um, the y pair pulled in by a.

    Sum of residuals 0 and sum of residual x normal 0: the least-squares sphere is the nominal one,
    form = 2a = 2 um, diameter 20 mm exactly.
    """
    a, r = 1 * UM, 10 * MM
    points = np.array([[r + a, 0, 0], [-(r + a), 0, 0], [0, r - a, 0], [0, -(r - a), 0], [0, 0, r], [0, 0, -r]])
    fit = fit_sphere(points)
    assert fit.centre_m == pytest.approx([0, 0, 0], abs=1e-15)
    assert fit.radius_m == pytest.approx(r, abs=1e-15)
    assert fit.form_m == pytest.approx(2 * a, abs=1e-15)


@pytest.mark.parametrize("seed", [1, 2, 3])
def test_reference_data_with_a_known_solution(seed):
    directions = pattern()
    points, delta = reference_data(directions, 1.2 * UM, seed)
    fit = fit_sphere(points)
    assert np.abs(fit.centre_m - CENTRE).max() < 1e-12
    assert abs(fit.radius_m - RADIUS) < 1e-12
    assert fit.form_m == pytest.approx(1.2 * UM, abs=1e-12)
    assert fit.residual_m == pytest.approx(delta, abs=1e-12)


def test_agrees_with_a_plain_solver_on_noisy_points():
    """Against scipy's least_squares on the geometric residuals, from the nominal sphere."""
    rng = np.random.default_rng(7)
    directions = pattern()
    points = CENTRE + (RADIUS + rng.normal(0, 2 * UM, 25))[:, None] * directions
    plain = least_squares(lambda p: np.linalg.norm(points - p[:3], axis=1) - p[3], np.r_[CENTRE, RADIUS],
                          xtol=1e-15, ftol=1e-15, gtol=1e-15).x
    fit = fit_sphere(points)
    assert np.abs(fit.centre_m - plain[:3]).max() < 1e-11
    assert abs(fit.radius_m - plain[3]) < 1e-11


@settings(max_examples=40, deadline=None)
@given(st.lists(st.floats(-1, 1), min_size=3, max_size=3), st.floats(0, 2 * np.pi), st.integers(0, 1000))
def test_moving_the_points_moves_the_sphere_only(shift, angle, seed):
    """A rigid motion of the points moves the centre with them and leaves radius and form."""
    rng = np.random.default_rng(seed)
    points = CENTRE + (RADIUS + rng.normal(0, 1 * UM, 25))[:, None] * pattern()
    c, s = np.cos(angle), np.sin(angle)
    rotation = np.array([[c, -s, 0], [s, c, 0], [0, 0, 1]])
    moved = points @ rotation.T + np.array(shift)
    a, b = fit_sphere(points), fit_sphere(moved)
    assert b.centre_m == pytest.approx(rotation @ a.centre_m + np.array(shift), abs=1e-11)
    assert b.radius_m == pytest.approx(a.radius_m, abs=1e-11)
    assert b.form_m == pytest.approx(a.form_m, abs=1e-11)


def test_single_stylus_figures_by_construction():
    """Reference data of 1.2 um range on a sphere 0.4 um larger than calibrated: PForm 1.2, PSize 0.4 um."""
    points, _ = reference_data(pattern(), 1.2 * UM, 4)
    r = probing_test(SpherePoints(points, ("1",) * 25), calibrated_diameter_m=2 * RADIUS - 0.4 * UM,
                     mpe_m={"pform": 1.5 * UM, "psize": 0.5 * UM}, uncertainty_m=0.2 * UM)
    assert r.figures_m["pform"] / UM == pytest.approx(1.2, abs=1e-6)
    assert r.figures_m["psize"] / UM == pytest.approx(0.4, abs=1e-6)
    assert r.names == {"pform": "PForm.Sph.1x25::SS:Tact", "psize": "PSize.Sph.1x25::SS:Tact"}
    # 1.2 + 0.2 <= 1.5 passes; 0.4 is within 0.5 but not by U = 0.2: no decision
    assert r.verdicts == {"pform": "pass", "psize": "inconclusive"} and r.verdict == "inconclusive"


def test_five_styli_location_form_and_size():
    """Five styli, each on the sphere exactly but with its centre off by a known offset.

    PLoc = the largest range of the centres' X, Y, Z: X ranges 0.3 - (-0.2) = 0.5 um, Y 0.4 - (-0.3)
    = 0.7 um, Z 0.2 - (-0.3) = 0.5 um, so 0.7 um. Each stylus alone has no form error.
    """
    offsets = np.array([[0, 0, 0], [0.3, -0.1, 0.2], [-0.2, 0.2, -0.3], [0.1, 0.4, 0.1], [-0.1, -0.3, 0.0]]) * UM
    poles = [(0, 0, 1), (-1, 0, 0.2), (1, 0, 0.2), (0, -1, 0.2), (0, 1, 0.2)]
    points = np.vstack([CENTRE + o + RADIUS * pattern(p) for o, p in zip(offsets, poles)])
    styli = tuple(f"T{j + 1}" for j in range(5) for _ in range(25))
    r = probing_test(SpherePoints(points, styli), calibrated_diameter_m=2 * RADIUS, mpe_m={"ploc": 1.0 * UM})
    assert r.figures_m["ploc"] / UM == pytest.approx(0.7, abs=1e-6)
    assert r.figures_m["pform"] < 1e-12 and abs(r.figures_m["psize"]) < 1e-12
    assert 0 < r.figures_m["pform_ms"] < 1.5 * UM
    assert r.names["ploc"] == "PLoc.Sph.5x25::MS:Tact" and r.verdicts["ploc"] == "pass"
    assert set(r.payload()["styli"]) == {"T1", "T2", "T3", "T4", "T5"}


def test_the_example_files(examples):
    single = evaluate_probing(examples / "cmm" / "sphere_single.csv", calibrated_diameter_m=25.00018 * MM)
    assert set(single.figures_m) == {"pform", "psize"} and single.warnings == ()
    assert 0.5 * UM < single.figures_m["pform"] < 1.5 * UM
    multi = evaluate_probing(examples / "cmm" / "sphere_five_styli.csv", calibrated_diameter_m=25.00018 * MM)
    assert set(multi.figures_m) == {"pform", "psize", "pform_ms", "psize_ms", "ploc"}
    assert multi.figures_m["ploc"] < 1 * UM
    assert "PLoc.Sph.5x25::MS:Tact" in multi.report()


def test_degenerate_points_and_bad_files(tmp_path):
    with pytest.raises(AxiscalError, match="one plane"):
        fit_sphere([[0, 0, 0], [1, 0, 0], [0, 1, 0], [1, 1, 0], [2, 3, 0]])
    path = tmp_path / "s.csv"
    path.write_text("stylus,x_mm,y_mm,z_mm\nA,1,0,0\nA,0,1,0\nA,0,0,1\nA,-1,0,0\nB,1,0,0\nB,0,1,0\n")
    with pytest.raises(AxiscalError, match="stylus B has 2 points") as caught:
        read_sphere_points(path)
    assert caught.value.line == 7
    path.write_text("x_mm,y_mm,z_mm\n1,0,0\n0,1,0\n0,0,1\n-1,0,0\n0,-1,0\n")
    with pytest.raises(AxiscalError, match="several styli"):
        evaluate_probing(path, calibrated_diameter_m=2 * MM, mpe_m={"ploc": 1 * UM})


def test_the_simulated_styli_are_recovered_from_the_example(examples):
    """examples/make_cmm_examples.py offsets each stylus's centre by a few tenths of a um; the fits find them."""
    from importlib import util

    spec = util.spec_from_file_location("make_cmm", examples / "make_cmm_examples.py")
    module = util.module_from_spec(spec)
    spec.loader.exec_module(module)
    r = evaluate_probing(examples / "cmm" / "sphere_five_styli.csv", calibrated_diameter_m=module.SPHERE_MM * MM)
    first = r.fits["T1"].centre_m
    for name, (_, offset_mm) in module.STYLI.items():
        found = (r.fits[name].centre_m - first) / MM
        # the noise (0.15 um), the rounding (0.1 um) and the probe's lobing seen over half a sphere
        # move a centre by up to 0.17 um
        assert np.abs(found - np.array(offset_mm)).max() < 0.2e-3, name
    # the simulated probe reads 0.2 um large in radius: the size error is near +0.4 um
    assert r.figures_m["psize"] / UM == pytest.approx(0.4, abs=0.15)


def _on_sphere(directions, seed=0, noise_m=0.3 * UM):
    rng = np.random.default_rng(seed)
    return CENTRE + RADIUS * np.asarray(directions) + rng.normal(0, noise_m, np.shape(directions))


def _cap(half_angle_deg):
    """25 points on a cap about the pole: the pole, 8 at half the angle, 16 at the angle."""
    out = [(0.0, 0.0, 1.0)]
    for polar, count in ((half_angle_deg / 2, 8), (half_angle_deg, 16)):
        for k in range(count):
            a, t = 2 * np.pi * k / count, np.radians(polar)
            out.append((np.sin(t) * np.cos(a), np.sin(t) * np.sin(a), np.cos(t)))
    return np.array(out)


def _circle(elevation_deg):
    a, e = np.linspace(0, 2 * np.pi, 25, endpoint=False), np.radians(elevation_deg)
    return np.column_stack([np.cos(e) * np.cos(a), np.cos(e) * np.sin(a), np.full(25, np.sin(e))])


def test_the_spread_of_the_standards_pattern_and_of_a_whole_sphere():
    """sqrt of the largest diagonal term of (J^T J)^-1: the pattern of ISO 10360-5 0.546, the six poles 1/sqrt(2)."""
    points = _on_sphere(pattern(), noise_m=0.0)
    assert fit_spread(points, fit_sphere(points)) == pytest.approx(0.5462, abs=1e-4)
    six = np.vstack([np.eye(3), -np.eye(3)])
    assert fit_spread(six, fit_sphere(six)) == pytest.approx(np.sqrt(0.5), abs=1e-12)
    # it depends on the directions only: not on the size, the place or the noise of the points
    moved = 3.0 * _on_sphere(pattern(), seed=5) + 0.1
    assert fit_spread(moved, fit_sphere(moved)) == pytest.approx(0.5462, abs=1e-3)


@pytest.mark.parametrize(("directions", "refused"), [
    (_circle(0.0), True), (_circle(20.0), True), (_cap(10.0), True), (_cap(30.0), True),
    (_cap(45.0), False), (_cap(90.0), False), (pattern((1.0, 1.0, 0.0)), False),
])
def test_points_on_too_little_of_the_sphere_are_refused(directions, refused):
    """A great circle with 0.3 um of noise gave PSize 1703 um and a 10-degree cap -14 um, printed as figures."""
    points = SpherePoints(_on_sphere(directions), ("1",) * len(directions))
    if refused:
        with pytest.raises(AxiscalError, match="stylus 1: the points cover too little of the sphere"):
            probing_test(points, calibrated_diameter_m=2 * RADIUS)
    else:
        r = probing_test(points, calibrated_diameter_m=2 * RADIUS)
        assert abs(r.figures_m["psize"]) < 3 * UM


def test_one_stylus_on_a_circle_is_named_in_the_multi_stylus_test(tmp_path):
    good = _on_sphere(pattern(), seed=1)
    bad = _on_sphere(_circle(0.0), seed=2)
    path = tmp_path / "s.csv"
    rows = [f"{s},{x / MM},{y / MM},{z / MM}" for s, block in (("A", good), ("B", bad)) for x, y, z in block]
    path.write_text("stylus,x_mm,y_mm,z_mm\n" + "\n".join(rows) + "\n")
    with pytest.raises(AxiscalError, match="stylus B: the points cover too little") as caught:
        evaluate_probing(path, calibrated_diameter_m=2 * RADIUS)
    assert caught.value.path == str(path)


@pytest.mark.parametrize("diameter_mm", [2500.0, 2.5, 25.0 * 1.12, 25.0 * 0.88])
def test_points_that_cannot_lie_on_the_calibrated_sphere_are_refused(examples, diameter_mm):
    """--diameter-mm 2500 for a 25 mm sphere gave 'PSize -2474999 um, verdict: pass'."""
    with pytest.raises(AxiscalError, match=r"the points lie on a sphere 25\.\d+ mm across, not on the calibrated one"):
        evaluate_probing(examples / "cmm" / "sphere_single.csv", calibrated_diameter_m=diameter_mm * MM)
    near = evaluate_probing(examples / "cmm" / "sphere_single.csv", calibrated_diameter_m=25.0 * 1.09 * MM)
    assert near.figures_m["psize"] == pytest.approx(-0.09 * 25 * MM, abs=5 * UM)


@pytest.mark.parametrize(("options", "words"), [
    (dict(mpe_m={"pform": 1e300}), r"mpe_m\['pform'\] must be at most 0.01"),
    (dict(uncertainty_m=1e300), "uncertainty_m must be at most 0.01"),
])
def test_limits_beyond_ten_millimetres_are_refused(examples, options, words):
    with pytest.raises(AxiscalError, match=words):
        evaluate_probing(examples / "cmm" / "sphere_single.csv", calibrated_diameter_m=25 * MM, **options)
