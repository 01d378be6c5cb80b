"""Error separation methods of paper 001: loop references, exactness, error analysis by simulation."""

from __future__ import annotations

import cmath
import math

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from axiscal.errors import AxiscalError
from axiscal.straightness.reference import reference_line
from axiscal.straightness.separation import (
    ProbeReadings,
    combined,
    fine_sequential_three_point,
    frequency_domain,
    generalized_two_point,
    gtp_amplitude_response,
    gtp_noise_std,
    noise_propagation,
    reversal,
    separate,
    sequential_three_point,
    sequential_two_point,
    simulate_readings,
    stp_noise_std,
    stp_offset_error,
    stp_residual_yaw_error,
    stp_yaw_neglect_error,
    strp_noise_std,
    strp_offset_error,
    strp_yaw_offset_error,
)
from axiscal.units import ARCSEC, MM, UM

STEP = 1 * MM
SPACING = 15 * MM
N_PAPER = 300


def paper_profile(x):
    """R(n) under paper 001 Fig. 4, n = x / step, in micrometres."""
    n = x / STEP
    return UM * (np.sin(np.pi * n / (2.5 * N_PAPER)) + 0.02 * np.sin(2 * np.pi * n / 54) + 0.02 * np.sin(2 * np.pi * n / 34))


def paper_motion(x):
    """S(n) under Fig. 4 with the step G on N/2.7 <= n <= N/1.5 (the printed range is empty)."""
    n = x / STEP
    return UM * (np.sin(0.75 * np.pi * n / (2.5 * N_PAPER)) + 0.4 * ((n >= N_PAPER / 2.7) & (n <= N_PAPER / 1.5)))


def detrended(position, values):
    return reference_line(position, values).residuals(position, values)


def separation_error(sep, truth=paper_profile):
    return np.ptp(detrended(sep.position_m, sep.profile_m - truth(sep.position_m)))


def random_readings(rng, n, spacing_ab, spacing_bc, step=STEP):
    x = 0.1 + step * np.arange(n)
    return ProbeReadings(x, *(1e-6 * rng.normal(size=(3, n))), spacing_ab, spacing_bc)


# --- plain loop references, written as the paper prints the recurrences ------------------------


def loop_stp(a, b, d, yaw=None):
    r = [0.0]
    for k in range(len(a)):
        r.append(r[-1] - a[k] + b[k] + (0.0 if yaw is None else d * yaw[k]))  # eq (4) / (13)
    return np.array(r)


def loop_strp(a, b, c, d):
    r = [0.0, 0.0]
    gamma = []
    for k in range(len(a)):
        r.append(c[k] - 2 * b[k] + a[k] + 2 * r[k + 1] - r[k])  # eq (2)
        s = r[k] - a[k]
        gamma.append((-b[k] + r[k + 1] - s) / d)
    return np.array(r), np.array(gamma)


def loop_gtp(a, b, d, s):
    z = [0.0]
    for k in range(len(a)):
        z.append(z[-1] + (b[k] - a[k]) / d * s)  # eq (7)
    return np.array(z)


def loop_chains(diff, m):
    r = np.zeros(len(diff) + m)
    for k in range(len(diff)):
        r[k + m] = r[k] + diff[k]
    return r


def loop_fstrp(a, b, c, p, q):
    first, second = loop_chains(b - a, p), loop_chains(c - a, q)
    rows, rhs = [], []
    for n in range(len(first)):
        row = np.zeros(p + q)
        row[n % p] = 1.0
        if n % q:
            row[p + n % q - 1] = -1.0
        row[p + q - 1] = n / len(first)
        rows.append(row)
        rhs.append(second[n] - first[n])
    sol = np.linalg.lstsq(np.array(rows), np.array(rhs), rcond=None)[0]
    out = second.copy()
    for n in range(len(second)):
        if n % q:
            out[n] += sol[p + n % q - 1]
    for n in range(len(first)):
        out[n] = 0.5 * (out[n] + first[n] + sol[n % p] + sol[p + q - 1] * n / len(first))
    return out


def loop_combined(a, b, c, d, s):
    k = round(d / s)
    z = loop_gtp(a, b, d, s)
    groups = len(a) // k
    profile = np.zeros((groups + 1) * k)
    for i in range(k):
        idx = [i + j * k for j in range(groups)]
        _, gamma = loop_strp(a[idx], b[idx], c[idx], d)
        j = np.arange(groups)
        slope, mean = np.polyfit(j, gamma, 1)
        flat = gamma - (slope * j + mean)
        p = loop_stp(a[idx], b[idx], d, flat)
        pts = [i + j * k for j in range(groups + 1)]
        z_centre = (k - 1) / 2 + np.arange(len(z))  # z(n) averages R over n..n + k - 1
        known = [(jj, n) for jj, n in enumerate(pts) if z_centre[0] <= n <= z_centre[-1]]
        lift = np.mean([np.interp(n, z_centre, z) - p[jj] for jj, n in known])  # eq (19)
        for jj, n in enumerate(pts):
            profile[n] = p[jj] + lift
    return profile


@pytest.mark.parametrize("seed", range(5))
def test_cumulative_sums_match_the_loops(seed):
    rng = np.random.default_rng(seed)
    n = int(rng.integers(40, 120))
    m = int(rng.integers(1, 5))
    rd = random_readings(rng, n, m * STEP, m * STEP)
    yaw = 1e-5 * rng.normal(size=n)

    stp = sequential_two_point(rd)
    np.testing.assert_allclose(stp.profile_m, loop_stp(rd.a_m[::m], rd.b_m[::m], rd.spacing_ab_m), atol=1e-18, rtol=1e-12)
    stp_yaw = sequential_two_point(rd, yaw_rad=yaw)
    np.testing.assert_allclose(stp_yaw.profile_m, loop_stp(rd.a_m[::m], rd.b_m[::m], rd.spacing_ab_m, yaw[::m]), rtol=1e-12)

    strp = sequential_three_point(rd)
    ref, gamma = loop_strp(rd.a_m[::m], rd.b_m[::m], rd.c_m[::m], rd.spacing_ab_m)
    np.testing.assert_allclose(strp.profile_m, ref, rtol=1e-10, atol=1e-15)
    np.testing.assert_allclose(strp.yaw_rad[: gamma.size], gamma, rtol=1e-10, atol=1e-12)
    np.testing.assert_allclose(strp.motion_m[: gamma.size], ref[: gamma.size] - rd.a_m[::m], rtol=1e-10, atol=1e-15)

    gtp = generalized_two_point(rd)
    np.testing.assert_allclose(gtp.profile_m, loop_gtp(rd.a_m, rd.b_m, rd.spacing_ab_m, STEP), rtol=1e-12, atol=1e-18)

    comb_rd = random_readings(rng, n, (m + 1) * STEP, (m + 1) * STEP)
    comb = combined(comb_rd)
    expected = loop_combined(comb_rd.a_m, comb_rd.b_m, comb_rd.c_m, comb_rd.spacing_ab_m, STEP)
    np.testing.assert_allclose(comb.profile_m, expected, rtol=1e-9, atol=1e-15)


@pytest.mark.parametrize(("p", "q"), [(2, 3), (3, 5), (7, 11), (1, 4)])
def test_fstrp_merge_matches_a_dense_least_squares(p, q):
    rng = np.random.default_rng(p * q)
    rd = random_readings(rng, 60, p * STEP, (q - p) * STEP)
    sep = fine_sequential_three_point(rd)
    np.testing.assert_allclose(sep.profile_m, loop_fstrp(rd.a_m, rd.b_m, rd.c_m, p, q), rtol=1e-9, atol=1e-15)
    assert sep.position_m.size == 60 + q


# --- exactness ---------------------------------------------------------------------------------


def paper_readings(**kw):
    x = np.arange(0.0, N_PAPER * STEP - 2 * SPACING + 1e-12, STEP)
    return simulate_readings(x, paper_profile, paper_motion, spacing_ab_m=SPACING, spacing_bc_m=SPACING, **kw)


def test_stp_and_strp_recover_the_paper_profile_exactly_up_to_a_line():
    rd = paper_readings()
    for sep in (sequential_two_point(rd), sequential_three_point(rd)):
        assert separation_error(sep) < 1e-9 * UM  # the profile's amplitude is about 1 um
        motion = sep.motion_m[np.isfinite(sep.motion_m)]
        pos = sep.position_m[np.isfinite(sep.motion_m)]
        assert np.ptp(detrended(pos, motion - paper_motion(pos))) < 1e-9 * UM  # the step G included


def test_fstrp_is_exact_without_yaw_and_resolves_every_step():
    x = np.arange(0.0, 0.25, STEP)
    rd = simulate_readings(x, paper_profile, paper_motion, spacing_ab_m=7 * STEP, spacing_bc_m=4 * STEP)
    sep = fine_sequential_three_point(rd)
    assert np.allclose(np.diff(sep.position_m), STEP)
    assert separation_error(sep) < 1e-9 * UM


def test_reversal_is_exact():
    x = np.linspace(0.0, 0.3, 31)
    r, s = paper_profile(x), paper_motion(x)
    sep = reversal(x, r - s, r + s)
    np.testing.assert_allclose(sep.profile_m, r, atol=1e-21)
    np.testing.assert_allclose(sep.motion_m, s, atol=1e-21)


@st.composite
def motions(draw):
    n = draw(st.integers(32, 64))
    return np.array(draw(st.lists(st.floats(-1e-5, 1e-5), min_size=n, max_size=n)))


@settings(max_examples=25, deadline=None)
@given(motions())
def test_any_slide_motion_cancels_in_every_method(motion):
    # S(x) enters all probes alike: adding any motion leaves every separated profile unchanged
    rng = np.random.default_rng(1)
    n = motion.size
    rd = random_readings(rng, n, 3 * STEP, 3 * STEP)
    moved = ProbeReadings(rd.position_m, rd.a_m + motion, rd.b_m + motion, rd.c_m + motion, rd.spacing_ab_m, rd.spacing_bc_m)
    rd_f = random_readings(rng, n, 2 * STEP, 3 * STEP)
    moved_f = ProbeReadings(rd_f.position_m, rd_f.a_m + motion, rd_f.b_m + motion, rd_f.c_m + motion, 2 * STEP, 3 * STEP)
    for method in ("stp", "strp", "gtp", "combined", "frequency"):
        np.testing.assert_allclose(separate(moved, method=method).profile_m, separate(rd, method=method).profile_m, atol=1e-15)
    np.testing.assert_allclose(
        separate(moved_f, method="fstrp").profile_m, separate(rd_f, method="fstrp").profile_m, atol=1e-15
    )


# --- zero offsets (eq 8-11) ---------------------------------------------------------------------


def offset_error(method, offsets):
    clean = method(paper_readings())
    shifted = method(paper_readings(offsets_m=offsets))
    return clean, shifted


def test_stp_offset_accumulates_linearly():
    # paper 001 eq (9): linear in n, so the straightness is untouched
    clean, shifted = offset_error(sequential_two_point, (0.0, 0.05 * UM, 0.0))
    n = np.arange(clean.profile_m.size)
    np.testing.assert_allclose(shifted.profile_m - clean.profile_m, stp_offset_error(n, 0.05 * UM), atol=1e-18)
    ls = reference_line(shifted.position_m, shifted.profile_m)
    assert ls.straightness_m == pytest.approx(reference_line(clean.position_m, clean.profile_m).straightness_m, rel=1e-9)


def test_strp_offset_accumulates_quadratically_and_the_printed_eq10_slips():
    d1, d2 = 0.03 * UM, 0.05 * UM  # Delta1 = xi_b - xi_a, Delta2 = xi_c - xi_a
    clean, shifted = offset_error(sequential_three_point, (0.0, d1, d2))
    n = np.arange(clean.profile_m.size)
    np.testing.assert_allclose(shifted.profile_m - clean.profile_m, strp_offset_error(n, d1, d2), atol=1e-18)
    yaw_err = (shifted.yaw_rad - clean.yaw_rad)[np.isfinite(clean.yaw_rad)]
    k = np.arange(yaw_err.size)
    np.testing.assert_allclose(yaw_err, strp_yaw_offset_error(k, d1, d2, spacing_m=SPACING), rtol=1e-9, atol=1e-15)
    # paper 001 eq (10) as printed: R'(n+2) - R(n+2) = -(n^2 - 1) D1 + n (n + 1) / 2 D2 -- not what the recurrence gives
    nn = n[2:] - 2
    printed = -(nn**2 - 1) * d1 + nn * (nn + 1) / 2 * d2
    assert not np.allclose(printed, (shifted.profile_m - clean.profile_m)[2:], atol=1e-3 * UM)
    # eq (11) as printed: (n - 1) D2 + (2n - 3) D1 (no 1 / d, and the D2 sign) -- also off
    printed_yaw = (k - 1) * d2 + (2 * k - 3) * d1
    assert not np.allclose(printed_yaw, yaw_err, rtol=0.1)


def test_printed_eq10_eq11_hold_for_delta2_and_slip_for_delta1():
    # paper 001 eq (10)-(11) number the points from 1 (R(1) = R(2) = 0) and carry the signs of offsets
    # ADDED to the readings (eq 8 subtracts them, as eq 9's +n Delta1 also shows). Read that way their
    # Delta2 terms are exact; their Delta1 terms are not: -n (n + 1) Delta1 in eq (10) (printed
    # -(n^2 - 1) Delta1) and -(2n - 1) Delta1 / dL in eq (11) (printed +(2n - 3) Delta1, and no 1 / dL).
    def printed_eq10(n, d1, d2):
        return -(n**2 - 1) * d1 + n * (n + 1) / 2 * d2

    def printed_eq11(n, d1, d2):
        return (n - 1) * d2 + (2 * n - 3) * d1

    delta = 0.04 * UM
    for d1, d2 in ((0.0, delta), (delta, 0.0)):
        clean, shifted = offset_error(sequential_three_point, (0.0, d1, d2))
        profile_err = -(shifted.profile_m - clean.profile_m)  # sign of offsets added, as the paper
        n = np.arange(profile_err.size - 2) + 1.0  # profile_err[j] is the paper's R(n + 2) with n = j - 1
        yaw_err = -(shifted.yaw_rad - clean.yaw_rad)[np.isfinite(clean.yaw_rad)] * SPACING
        m = np.arange(yaw_err.size) + 1.0  # paper's gamma(n) with n = k + 1, times dL
        if d1 == 0.0:
            np.testing.assert_allclose(profile_err[2:], printed_eq10(n, d1, d2), rtol=1e-9, atol=1e-20)
            np.testing.assert_allclose(yaw_err, printed_eq11(m, d1, d2), rtol=1e-9, atol=1e-20)
        else:
            np.testing.assert_allclose(profile_err[2:], -n * (n + 1) * d1, rtol=1e-9, atol=1e-20)
            np.testing.assert_allclose(yaw_err, -(2 * m - 1) * d1, rtol=1e-9, atol=1e-20)
            assert not np.allclose(profile_err[2:], printed_eq10(n, d1, d2), rtol=0.05)
            assert not np.allclose(yaw_err, printed_eq11(m, d1, d2), rtol=0.05)


# --- neglected yaw (eq 12-17) --------------------------------------------------------------------


def test_one_arcsecond_of_yaw_over_15_mm_is_0_0727_um():
    # paper 001 section 3.2: "when dL = 15 mm, 1 arc second corresponds to 0.0727 um"
    assert stp_yaw_neglect_error([ARCSEC], spacing_m=15 * MM)[-1] / UM == pytest.approx(-0.0727, abs=5e-5)


def test_neglected_yaw_error_matches_simulation():
    rng = np.random.default_rng(0)
    yaw_values = 2 * ARCSEC + ARCSEC * rng.normal(size=N_PAPER)
    grid = np.arange(N_PAPER) * STEP

    def yaw(x):
        return np.interp(x, grid, yaw_values)

    x = np.arange(0.0, N_PAPER * STEP - 2 * SPACING + 1e-12, STEP)
    with_yaw = simulate_readings(x, paper_profile, paper_motion, yaw, spacing_ab_m=SPACING, spacing_bc_m=SPACING)
    sep = sequential_two_point(with_yaw)
    error = sep.profile_m - (paper_profile(sep.position_m) - paper_profile(sep.position_m[0]))
    expected = stp_yaw_neglect_error(yaw(sep.position_m[:-1]), spacing_m=SPACING)  # eq (14)
    np.testing.assert_allclose(error, expected, atol=1e-15)
    # STRP separates the yaw (up to the constant that goes with R's undetermined line)
    strp = sequential_three_point(with_yaw)
    known = np.isfinite(strp.yaw_rad)
    yaw_err = strp.yaw_rad[known] - yaw(strp.position_m[known])
    assert np.ptp(yaw_err) < 1e-12


def test_residual_yaw_error_eq17_by_simulation():
    mu, eta = 1.5 * ARCSEC, 0.02 * ARCSEC  # mean and slope per step of the true yaw
    x = np.arange(0.0, 0.3, SPACING)

    def yaw(pos):
        return mu + eta * np.round((pos - x[0]) / SPACING)

    rd = simulate_readings(x, paper_profile, paper_motion, yaw, spacing_ab_m=SPACING)
    sep = sequential_two_point(rd, yaw_rad=yaw(x) - mu - eta * np.arange(x.size))  # eq (15)-(16)
    error = sep.profile_m - (paper_profile(sep.position_m) - paper_profile(x[0]))
    n = np.arange(error.size)
    expected = stp_residual_yaw_error(n, spacing_m=SPACING, mean_rad=mu, slope_rad_per_step=eta)
    np.testing.assert_allclose(error, expected, atol=1e-15)


def test_eq17_worked_number_and_its_slip():
    # paper 001 after eq (17): dL = 15, L = 300, yaw slope 1"/300 mm -> "maximum 0.0461 um".
    # Reproduced only with the slope taken per STEP as 1"/300 over n = 20 steps:
    n = 300 / 15
    printed = stp_residual_yaw_error(n, spacing_m=15 * MM, mean_rad=0.0, slope_rad_per_step=ARCSEC / 300)
    assert -printed / UM == pytest.approx(0.0461, abs=5e-5)
    # with 1"/300 mm read as it is written, the slope per 15 mm step is 1"/20: 15 times more
    physical = stp_residual_yaw_error(n, spacing_m=15 * MM, mean_rad=0.0, slope_rad_per_step=ARCSEC / 20)
    assert -physical / UM == pytest.approx(0.691, abs=5e-4)


# --- GTP -------------------------------------------------------------------------------------------


def test_gtp_method_error_at_75_mm_is_6_5_percent():
    # paper 001 after eq (7): m = 15 mm, s = 1 mm, 75 mm wavelength -> 6.5 % method error
    # is the chord-slope error alone (integration exact, step -> 0): 1 - sinc(15/75) = 0.0645
    chord_only = gtp_amplitude_response(75 * MM, spacing_m=15 * MM, step_m=0.0)
    assert 1 - chord_only == pytest.approx(0.065, abs=5e-4)
    # the rectangle-rule sum over s = 1 mm gives back 0.03 %: 6.4 % for the discrete method
    gain = gtp_amplitude_response(75 * MM, spacing_m=15 * MM, step_m=1 * MM)
    assert 1 - gain == pytest.approx(0.064, abs=5e-4)


def test_gtp_response_by_simulation():
    lam = 75 * MM
    x = np.arange(0.0, 0.6, STEP)
    rd = simulate_readings(x, lambda p: UM * np.sin(2 * np.pi * p / lam), lambda p: 0 * p, spacing_ab_m=SPACING)
    sep = generalized_two_point(rd)
    pos = sep.position_m
    design = np.column_stack([np.sin(2 * np.pi * pos / lam), np.cos(2 * np.pi * pos / lam), np.ones_like(pos), pos])
    coef = np.linalg.lstsq(design, sep.profile_m, rcond=None)[0]
    # placed at the window's centre, the GTP profile is in phase: all of it in the sine term
    assert coef[0] / UM == pytest.approx(gtp_amplitude_response(lam, spacing_m=SPACING, step_m=STEP), rel=1e-3)
    assert abs(coef[1]) < 1e-3 * UM


# --- noise propagation ---------------------------------------------------------------------------


def monte_carlo_std(method, n, trials, spacing_steps=1, sigma=1.0):
    rng = np.random.default_rng(0)
    x = STEP * np.arange(n)
    runs = []
    for _ in range(trials):
        a, b, c = sigma * rng.normal(size=(3, n))
        runs.append(method(ProbeReadings(x, a, b, c, spacing_steps * STEP, spacing_steps * STEP)).profile_m)
    return np.std(np.array(runs), axis=0)


def test_noise_propagation_matches_the_closed_forms():
    n = 30
    stp = monte_carlo_std(sequential_two_point, n, 3000)
    np.testing.assert_allclose(stp, stp_noise_std(np.arange(n + 1), 1.0), rtol=0.08, atol=1e-12)
    strp = monte_carlo_std(sequential_three_point, n, 3000)
    np.testing.assert_allclose(strp[2:], strp_noise_std(np.arange(2, n + 2), 1.0), rtol=0.08)
    gtp = monte_carlo_std(generalized_two_point, n, 3000, spacing_steps=5)
    np.testing.assert_allclose(gtp[1:], gtp_noise_std(np.arange(1, n + 1), 1.0, steps_per_spacing=5), rtol=0.08)


def test_noise_propagation_per_method():
    x = STEP * np.arange(60)
    template = ProbeReadings(x, x, x, x, 3 * STEP, 3 * STEP)
    # reversal halves the variance: sigma / sqrt(2) at every point (before the line, which the
    # Monte Carlo removes: its residual std is a little lower)
    rev = noise_propagation(template, method="reversal", noise_m=1.0, trials=2000)
    assert np.median(rev.std_m) == pytest.approx(1 / np.sqrt(2), rel=0.06)
    figures = {m: noise_propagation(template, method=m, noise_m=1.0, trials=300) for m in ("stp", "strp", "gtp", "combined")}
    # summing twice (STRP, and the combined method through its STRP yaw) is louder than once
    assert figures["strp"].mean_pv_m > figures["stp"].mean_pv_m > figures["gtp"].mean_pv_m
    assert figures["combined"].mean_pv_m > figures["gtp"].mean_pv_m
    assert figures["stp"].position_m.size == 21 and figures["gtp"].position_m.size == 61
    # the STP figure agrees with the closed form: a random walk about its least-squares line
    walk = np.cumsum(np.sqrt(2.0) * np.random.default_rng(1).standard_normal((4000, 20)), axis=1)
    walk = np.hstack([np.zeros((4000, 1)), walk])
    j = np.arange(21.0)
    fit = np.polynomial.polynomial.polyfit(j, walk.T, 1)
    expected = np.ptp(walk - (fit[0][:, None] + fit[1][:, None] * j), axis=1).mean()
    assert figures["stp"].mean_pv_m == pytest.approx(expected, rel=0.08)


# --- frequency domain ---------------------------------------------------------------------------


def periodic_profile(x, period):
    return UM * (0.5 * np.sin(2 * np.pi * 2 * x / period) + 0.2 * np.cos(2 * np.pi * 7 * x / period + 0.3))


def test_frequency_two_point_loses_the_harmonics_of_the_spacing():
    n = 240
    x = STEP * np.arange(n)
    rd = simulate_readings(x, lambda p: periodic_profile(p, n * STEP), paper_motion, spacing_ab_m=SPACING)
    sep = frequency_domain(rd, probes=2, parabola=False)
    # H = exp(2 pi i f m / N) - 1 vanishes where f m / N is whole: wavelengths 15 mm / j
    lost = np.sort(sep.lost_wavelength_m)
    for j in range(1, 8):
        assert np.min(np.abs(lost - SPACING / j)) < 1e-12
    assert separation_error(sep, lambda p: periodic_profile(p, n * STEP)) < 1e-9 * UM


def test_frequency_three_point_with_unequal_spacings_keeps_them_and_cancels_yaw():
    n = 240
    x = STEP * np.arange(n)

    def yaw(p):
        return 3 * ARCSEC * np.sin(2 * np.pi * p / 0.05)

    equal = simulate_readings(
        x, lambda p: periodic_profile(p, n * STEP), paper_motion, yaw, spacing_ab_m=SPACING, spacing_bc_m=SPACING
    )
    assert frequency_domain(equal, probes=3, parabola=False).lost_wavelength_m.size > 0
    unequal = simulate_readings(
        x, lambda p: periodic_profile(p, n * STEP), paper_motion, yaw, spacing_ab_m=SPACING, spacing_bc_m=2 * STEP
    )
    sep = frequency_domain(unequal, probes=3, parabola=False)
    assert sep.lost_wavelength_m.size == 0  # common harmonics of 15 and 17 mm: none above 2 mm
    assert separation_error(sep, lambda p: periodic_profile(p, n * STEP)) < 1e-9 * UM


@pytest.mark.parametrize("probes", [2, 3])
def test_frequency_domain_takes_a_bow_out_exactly(probes):
    n = 200
    x = STEP * np.arange(n)

    def bow(p):
        return 2 * UM * ((p - 0.1) / 0.1) ** 2 + 0.3 * UM * p / 0.2

    rd = simulate_readings(x, bow, paper_motion, spacing_ab_m=SPACING, spacing_bc_m=2 * STEP)
    sep = frequency_domain(rd, probes=probes)
    assert separation_error(sep, bow) < 1e-9 * UM
    assert separation_error(frequency_domain(rd, probes=probes, parabola=False), bow) > 0.05 * UM


def loop_frequency(signal, weights, offsets, min_gain):
    """Plain DFT sums: R_k = T_k / H_k where |H_k| is not suppressed, then the inverse sum."""
    n = len(signal)
    moment_order = 1 if len(weights) == 2 else 2
    moment = abs(sum(w * o**moment_order for w, o in zip(weights, offsets))) / math.factorial(moment_order)
    gains = [sum(w * cmath.exp(2j * math.pi * k * o / n) for w, o in zip(weights, offsets)) for k in range(n)]
    top = max(abs(g) for g in gains[: n // 2 + 1])
    spectrum = []
    for k in range(n):
        t_k = sum(signal[j] * cmath.exp(-2j * math.pi * k * j / n) for j in range(n))
        f = min(k, n - k)
        envelope = min(moment * (2 * math.pi * f / n) ** moment_order, top)
        spectrum.append(t_k / gains[k] if k and abs(gains[k]) >= min_gain * envelope else 0.0)
    r = [sum(spectrum[k] * cmath.exp(2j * math.pi * k * j / n) for k in range(n)).real / n for j in range(n)]
    return np.array(r) - r[0]


@pytest.mark.parametrize(("probes", "n"), [(2, 48), (3, 49)])
def test_frequency_domain_matches_plain_dft_sums(probes, n):
    rng = np.random.default_rng(probes)
    rd = random_readings(rng, n, 4 * STEP, 3 * STEP)
    sep = frequency_domain(rd, probes=probes, parabola=False)
    if probes == 2:
        expected = loop_frequency(rd.b_m - rd.a_m, [-1.0, 1.0], [0, 4], 0.05)
    else:
        w = [-3 / 7, 1.0, -4 / 7]
        expected = loop_frequency(w[0] * rd.a_m + w[1] * rd.b_m + w[2] * rd.c_m, w, [0, 4, 7], 0.05)
    np.testing.assert_allclose(sep.profile_m, expected, atol=1e-12 * np.abs(expected).max())


# --- combined method ---------------------------------------------------------------------------------


def test_combined_method_survives_offsets_and_yaw_up_to_the_eq17_bow():
    x = np.arange(0.0, N_PAPER * STEP - 2 * SPACING + 1e-12, STEP)
    offsets = (0.0, 0.05 * UM, 0.02 * UM)

    def readings(yaw_slope_per_m):
        def yaw(p):
            return 2 * ARCSEC + ARCSEC * np.sin(2 * np.pi * p / 0.2) + yaw_slope_per_m * p

        return simulate_readings(
            x, paper_profile, paper_motion, yaw, spacing_ab_m=SPACING, spacing_bc_m=SPACING, offsets_m=offsets
        )

    wavy_yaw = readings(0.0)
    comb = separation_error(combined(wavy_yaw))
    assert separation_error(sequential_three_point(wavy_yaw)) > 50 * comb  # offsets, eq (10)
    assert separation_error(sequential_two_point(wavy_yaw)) > 3 * comb  # yaw, eq (14)
    # what is left is each group's own yaw line (removed in step 3, back as a per-group eq 17)
    # a yaw slope is removed with the offsets' effect in step 3 and comes back as the eq (17) bow
    slope = 0.5 * ARCSEC / 0.3
    sloped = combined(readings(slope))
    assert np.allclose(np.diff(sloped.position_m), STEP)
    j = np.arange(x.size // 15 + 1)
    bow = stp_residual_yaw_error(j, spacing_m=SPACING, mean_rad=0.0, slope_rad_per_step=slope * SPACING)
    assert separation_error(sloped) == pytest.approx(np.ptp(detrended(j * SPACING, bow)), abs=0.015 * UM)


# --- bad input --------------------------------------------------------------------------------------


def test_bad_input_gives_one_line_errors():
    rng = np.random.default_rng(0)
    rd = random_readings(rng, 40, 3 * STEP, 3 * STEP)
    uneven = ProbeReadings(rd.position_m + np.r_[0, 0.3e-3, np.zeros(38)], rd.a_m, rd.b_m, rd.c_m, 3 * STEP, 3 * STEP)
    with pytest.raises(AxiscalError, match="evenly stepped"):
        sequential_two_point(uneven)
    not_multiple = ProbeReadings(rd.position_m, rd.a_m, rd.b_m, rd.c_m, 2.5 * STEP, 2.5 * STEP)
    for method in (sequential_two_point, sequential_three_point):
        with pytest.raises(AxiscalError, match="whole number of steps"):
            method(not_multiple)
    two = ProbeReadings(rd.position_m, rd.a_m, rd.b_m, None, 3 * STEP)
    for method in ("strp", "fstrp", "combined"):
        with pytest.raises(AxiscalError, match="c_um"):
            separate(two, method=method)
    with pytest.raises(AxiscalError, match="equal spacings"):
        sequential_three_point(ProbeReadings(rd.position_m, rd.a_m, rd.b_m, rd.c_m, 3 * STEP, 2 * STEP))
    with pytest.raises(AxiscalError, match="coprime"):
        fine_sequential_three_point(ProbeReadings(rd.position_m, rd.a_m, rd.b_m, rd.c_m, 2 * STEP, 2 * STEP))
    with pytest.raises(AxiscalError, match="calibration region"):
        combined(rd, calibration_m=(1.0, 2.0))
    with pytest.raises(AxiscalError, match="unknown separation method"):
        separate(rd, method="magic")
    with pytest.raises(AxiscalError, match="same positions"):
        reversal([0.0, 1.0], [0.0, 1.0], [0.0])
    with pytest.raises(AxiscalError, match="at least 2"):
        sequential_two_point(ProbeReadings(rd.position_m[:1], rd.a_m[:1], rd.b_m[:1], None, 3 * STEP))
    for spacing in (np.inf, np.nan, -STEP, 0.0):
        with pytest.raises(AxiscalError, match="positive, finite"):
            sequential_two_point(ProbeReadings(rd.position_m, rd.a_m, rd.b_m, None, spacing))
    with pytest.raises(AxiscalError, match="equal spacings"):
        sequential_three_point(ProbeReadings(rd.position_m, rd.a_m, rd.b_m, rd.c_m, 3 * STEP, np.nan))
    with pytest.raises(AxiscalError, match="families to meet"):
        fine_sequential_three_point(ProbeReadings(rd.position_m, rd.a_m, rd.b_m, rd.c_m, 30 * STEP, 11 * STEP))
    with pytest.raises(AxiscalError, match="more readings than the probes span"):
        frequency_domain(ProbeReadings(rd.position_m, rd.a_m, rd.b_m, rd.c_m, 20 * STEP, 20 * STEP))
    for min_gain in (-0.1, 1.0, np.nan):
        with pytest.raises(AxiscalError, match="min_gain"):
            frequency_domain(rd, min_gain=min_gain)


@pytest.mark.parametrize(("p", "q"), [(2, 3), (3, 5), (7, 11)])
def test_fstrp_needs_just_q_readings(p, q):
    # the common points n < N + p tie the p + q chains and the tilt together from N = q readings on
    x = np.arange(0.0, 0.1, STEP)
    rd = simulate_readings(x[:q], paper_profile, paper_motion, spacing_ab_m=p * STEP, spacing_bc_m=(q - p) * STEP)
    assert separation_error(fine_sequential_three_point(rd)) < 1e-9 * UM
    short = ProbeReadings(rd.position_m[:-1], rd.a_m[:-1], rd.b_m[:-1], rd.c_m[:-1], p * STEP, (q - p) * STEP)
    with pytest.raises(AxiscalError, match="families to meet"):
        fine_sequential_three_point(short)


@settings(max_examples=40, deadline=None)
@given(st.integers(2, 30), st.floats(0.01, 0.99), st.sampled_from(["stp", "strp", "fstrp", "gtp", "frequency", "combined"]))
def test_any_uneven_step_is_refused_by_every_method(n, jitter, method):
    rng = np.random.default_rng(n)
    d1, d2 = (2 * STEP, 3 * STEP) if method == "fstrp" else (3 * STEP, 3 * STEP)
    rd = random_readings(rng, 40, d1, d2)
    position = rd.position_m.copy()
    position[n:] += jitter * STEP  # one step of 1 + jitter steps
    with pytest.raises(AxiscalError, match="evenly stepped"):
        separate(ProbeReadings(position, rd.a_m, rd.b_m, rd.c_m, d1, d2), method=method)
