"""Frequency-domain error separation (paper 001): two- or three-point inversion of the difference signal by DFT, with the suppressed harmonics reported and left out."""

from __future__ import annotations

import math

import numpy as np

from axiscal.errors import AxiscalError
from axiscal.io.arguments import is_real
from axiscal.straightness.probes import (
    ProbeReadings,
    Separation,
    _finish,
    _readings,
    _step,
    _steps_in,
    _third_probe,
    _yaw_from_profile,
)
from axiscal.units import MM

__all__ = [
    "frequency_domain",
]


def frequency_domain(
    readings: ProbeReadings, *, probes: int = 3, min_gain: float = 0.05, parabola: bool = True
) -> Separation:
    """Frequency-domain two- or three-point separation with the suppressed harmonics left out.

    The difference signal ``T(n) = sum_k w_k y_k(n) = sum_k w_k R(n + o_k)`` (offsets o_k in steps)
    removes S; its DFT is ``H(f) R(f)`` with ``H(f) = sum_k w_k exp(2 pi i f o_k / N)``.

    * ``probes=2``: ``T = b - a``, ``H = exp(2 pi i f p / N) - 1``; yaw neglected.
    * ``probes=3``: ``w = (-d2, d1 + d2, -d1) / (d1 + d2)`` cancels S and the yaw; with d1 != d2
      H vanishes only at the common harmonics of d1 and d2, which is how the three-point version
      handles the harmonic suppression of the two-point one (zeros at every wavelength d1 / j).

    The record is treated as one period of N = number of readings. A straight line in R is
    invisible (it is the undetermined line). With ``parabola=True`` (default) the parabola, which
    the periodic model cannot hold, is taken out first in closed form (from the trend of T for two
    probes, from the mean of T for three); this suits open straightness profiles, whose bow is
    their largest term. ``parabola=False`` treats R as exactly periodic over the record.

    Harmonic suppression: at low frequencies |H| falls as (2 pi f / N)^j times the first
    non-zero moment of the weights (j = 1 for two probes, 2 for three) -- that is the integration,
    not a loss. A harmonic whose |H| is below ``min_gain`` times that envelope (capped at
    max |H|) sits at or near a zero of H; inverting it would amplify noise by 1/|H|, so it is left
    out and its wavelength is returned in ``lost_wavelength_m``.

    Parameters
    ----------
    readings : ProbeReadings
        Evenly stepped, spacings whole numbers of steps, more readings than the probes span steps.
    probes : {2, 3}, keyword-only
        Probes used (default 3).
    min_gain : float, keyword-only
        Fraction of the gain envelope below which a harmonic is left out, 0 <= min_gain < 1
        (default 0.05). Harmonics where H is exactly zero are always left out.
    parabola : bool, keyword-only
        Take the parabola out in closed form first (default True).

    Returns
    -------
    Separation
        Profile at every reading; the yaw with three probes; ``lost_wavelength_m`` the wavelengths
        left out.

    Raises
    ------
    AxiscalError
        ``min_gain`` outside [0, 1), probes not 2 or 3, probe C missing for three, uneven steps,
        spacings not whole numbers of steps, or no more readings than the probes span steps.
    """
    _readings(readings)
    if not (is_real(min_gain) and 0.0 <= min_gain < 1.0):
        raise AxiscalError(f"the frequency-domain method needs 0 <= min_gain < 1, got {min_gain!r}")
    if not isinstance(parabola, (bool, np.bool_)):
        raise AxiscalError(f"parabola must be True or False, not {parabola!r}")
    x = readings.position_m
    step = _step(x, "the frequency-domain method")
    p = _steps_in(readings.spacing_ab_m, step, "the frequency-domain method", "A-B spacing")
    n_pts = x.size
    n = np.arange(n_pts, dtype=float)
    if probes == 2:
        offsets, weights = np.array([0, p]), np.array([-1.0, 1.0])
        signal = readings.b_m - readings.a_m
        curvature = np.polyfit(n, signal, 1)[0] / (2.0 * p) if parabola else 0.0
    elif probes == 3:
        c, d2 = _third_probe(readings, "the three-point frequency-domain method")
        q = p + _steps_in(d2, step, "the frequency-domain method", "B-C spacing")
        d1, d12 = readings.spacing_ab_m, readings.spacing_ab_m + d2
        offsets = np.array([0, p, q])
        weights = np.array([-d2 / d12, 1.0, -d1 / d12])
        signal = weights[0] * readings.a_m + weights[1] * readings.b_m + weights[2] * c
        second_moment = float(np.dot(weights, offsets.astype(float) ** 2))
        curvature = float(np.mean(signal)) / second_moment if parabola else 0.0
    else:
        raise AxiscalError(f"the frequency-domain method uses 2 or 3 probes, not {probes}")
    if offsets[-1] >= n_pts:
        raise AxiscalError(
            f"the frequency-domain method needs more readings than the probes span steps: the probes span "
            f"{offsets[-1]} steps of {step / MM:g} mm, the record has {n_pts} readings"
        )
    bow = curvature * n**2
    residual = signal - sum(w * curvature * (n + o) ** 2 for w, o in zip(weights, offsets))
    freq = np.arange(n_pts // 2 + 1)
    gain = (weights[None, :] * np.exp(2j * np.pi * np.outer(freq, offsets) / n_pts)).sum(axis=1)
    spectrum = np.fft.rfft(residual)
    order = 1 if probes == 2 else 2
    moment = abs(float(np.dot(weights, offsets.astype(float) ** order))) / math.factorial(order)
    envelope = np.minimum(moment * (2.0 * np.pi * freq / n_pts) ** order, np.abs(gain).max())
    usable = (np.abs(gain) >= min_gain * envelope) & (np.abs(gain) > 0.0)
    usable[0] = False
    solved = np.zeros_like(spectrum)
    solved[usable] = spectrum[usable] / gain[usable]
    profile = np.fft.irfft(solved, n=n_pts) + bow
    profile -= profile[0]
    lost = n_pts * step / freq[1:][~usable[1:]]
    name = f"frequency-{'two' if probes == 2 else 'three'}-point"
    if probes == 2:
        return _finish(name, x.copy(), profile, readings, lost=lost)
    return _finish(name, x.copy(), profile, readings, _yaw_from_profile(readings, x, profile), lost)
