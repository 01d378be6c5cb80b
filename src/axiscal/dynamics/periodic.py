"""Periodic (short-period) positioning error: its amplitude and period, by a fit and by a spectrum.

ISO 230-2:2014 Annex C considers the periodic positioning error a screw, a rack or a scale
leaves along a linear axis, with a period such as the screw's pitch, and Annex B the step cycle
that samples it: targets closely and evenly spaced over a short travel (one or a few periods),
approached in steps (:func:`axiscal.positioning.step_cycle.plan_step_cycle`). From the mean
deviation of each direction at each target (a line removed, the axis's slope and offset):

- **by spectrum**: the least-squares (Lomb-Scargle) amplitude spectrum (Lomb, Astrophysics and
  Space Science 39, 1976; Scargle, Astrophysical Journal 263, 1982): at each trial period the
  sine and cosine fitted by least squares together with the line; the period whose sine explains
  most of the deviations (the periodogram's peak), and the amplitude there. For a sine over whole
  periods of evenly spaced targets it gives the discrete Fourier transform's amplitude; unlike the
  transform it holds for uneven targets too (an ordinary ISO 230-2 run).
- **by fit**: ``x(P) = a + b P + A sin(2 pi P / p + phi)`` fitted by least squares with the
  period ``p`` free (started at the spectrum's peak) or fixed where it is known (the pitch).

The amplitude ``A`` is the sine's semi-amplitude; the periodic error is reported as its peak to
peak ``2 A``.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from pathlib import Path
from typing import Any

import numpy as np

from axiscal.errors import AxiscalError
from axiscal.io.arguments import check_instance, check_number, check_optional_number, render_checked
from axiscal.io.templates import render_template
from axiscal.positioning.evaluation import PositioningRun
from axiscal.units import MM, UM

__all__ = ["PeriodicComponent", "PeriodicError", "periodic_error", "periodic_from_file", "amplitude_spectrum"]


@dataclass(frozen=True)
class PeriodicComponent:
    """The periodic error of one direction (or of the bidirectional mean).

    Attributes
    ----------
    direction : str
        ``"+"``, ``"-"`` or ``"mean"`` (the mean of both directions).
    targets_m : ndarray, shape (m,), metres
    mean_m : ndarray, shape (m,), metres
        Mean deviation at each target.
    period_m, amplitude_m, phase_rad : float
        The fitted sine ``A sin(2 pi P / p + phi)`` (period in metres, semi-amplitude in metres).
    slope, offset_m : float
        The fitted line ``a + b P`` (b dimensionless).
    residual_m : float, metres
        Standard deviation of what the line and sine leave.
    spectrum_period_m, spectrum_amplitude_m : float, metres
        Period and amplitude at the spectrum's largest peak.
    periods_m, amplitudes_m : ndarray, shape (k,), metres
        The amplitude spectrum: trial periods (decreasing) and amplitudes.
    """

    direction: str
    targets_m: np.ndarray
    mean_m: np.ndarray
    period_m: float
    amplitude_m: float
    phase_rad: float
    slope: float
    offset_m: float
    residual_m: float
    spectrum_period_m: float
    spectrum_amplitude_m: float
    periods_m: np.ndarray
    amplitudes_m: np.ndarray

    def fitted(self, positions_m: np.ndarray) -> np.ndarray:
        """The fitted line and sine at ``positions_m`` (metres), metres."""
        p = np.asarray(positions_m, dtype=float)
        return self.offset_m + self.slope * p + self.amplitude_m * np.sin(2 * np.pi * p / self.period_m + self.phase_rad)


@dataclass(frozen=True)
class PeriodicError:
    """The periodic error of a positioning run, per direction and for the bidirectional mean.

    Attributes
    ----------
    components : tuple of PeriodicComponent
        ``+``, ``-`` (those measured) and ``mean`` (when both were).
    period_given : bool
        True when the period was given (fixed in the fit), False when it was found.
    source : str
    """

    components: tuple[PeriodicComponent, ...]
    period_given: bool
    source: str

    @property
    def main(self) -> PeriodicComponent:
        """The bidirectional mean's component (the one direction's where only one was measured)."""
        return self.components[-1]

    def report(self) -> str:
        """The readable summary: a line per direction (fit and spectrum)."""
        return render_checked(render_template, "periodic.txt.j2", **self.payload()).rstrip("\n")

    def payload(self) -> dict[str, Any]:
        """Figures in mm and um for ``--json`` and results.json; ``periodic_um`` is the main component's 2 A."""
        main = self.main
        return {
            "source": self.source,
            "period_given": self.period_given,
            "period_mm": main.period_m / MM,
            "amplitude_um": main.amplitude_m / UM,
            "periodic_um": 2 * main.amplitude_m / UM,
            "spectrum_period_mm": main.spectrum_period_m / MM,
            "spectrum_amplitude_um": main.spectrum_amplitude_m / UM,
            "components": [{
                "direction": c.direction, "period_mm": c.period_m / MM, "amplitude_um": c.amplitude_m / UM,
                "peak_to_peak_um": 2 * c.amplitude_m / UM, "phase_rad": c.phase_rad, "slope_um_per_m": c.slope / UM,
                "offset_um": c.offset_m / UM, "residual_um": c.residual_m / UM,
                "spectrum_period_mm": c.spectrum_period_m / MM, "spectrum_amplitude_um": c.spectrum_amplitude_m / UM,
            } for c in self.components],
        }


def _design(p: np.ndarray, period: np.ndarray) -> np.ndarray:
    """Design matrices (k, m, 4): 1, P, cos, sin at each trial period."""
    angle = 2 * np.pi * p[None, :] / period[:, None]
    ones = np.ones_like(angle)
    return np.stack([ones, np.broadcast_to(p, angle.shape), np.cos(angle), np.sin(angle)], axis=-1)


def _fits(p: np.ndarray, y: np.ndarray, periods: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Semi-amplitude of the sine fitted with the line at each trial period, and what each fit leaves (sum of squares)."""
    a = _design(p, periods)
    ata = np.einsum("kmi,kmj->kij", a, a)
    aty = np.einsum("kmi,m->ki", a, y)
    try:
        sol = np.linalg.solve(ata, aty[..., None])[..., 0]
    except np.linalg.LinAlgError:  # a trial period the targets cannot tell from the line: the least-squares solution
        sol = np.einsum("kij,kj->ki", np.linalg.pinv(ata), aty)
    left = np.maximum(float(y @ y) - np.einsum("ki,ki->k", sol, aty), 0.0)
    return np.hypot(sol[:, 2], sol[:, 3]), left


def amplitude_spectrum(positions_m: Any, values_m: Any, *, oversample: int = 32) -> tuple[np.ndarray, np.ndarray]:
    """The least-squares amplitude spectrum of values along an axis (a line fitted with each sine).

    Parameters
    ----------
    positions_m : array_like, shape (m,), metres
        Positions, strictly increasing (even or uneven).
    values_m : array_like, shape (m,), metres
        Values there.
    oversample : int, keyword-only
        Trial frequencies per ``1 / record`` (default 32).

    Returns
    -------
    periods_m : ndarray, shape (k,), metres
        Trial periods from the record's length (span + one spacing) down to 2.5 mean spacings.
    amplitudes_m : ndarray, shape (k,), metres
        The fitted sine's semi-amplitude at each.

    Raises
    ------
    AxiscalError
        For fewer than 6 positions, positions that do not increase, arrays of different lengths.

    Examples
    --------
    >>> p = np.arange(16) * 0.5e-3
    >>> periods, amps = amplitude_spectrum(p, 1e-6 * np.sin(2 * np.pi * p / 4e-3))
    >>> k = int(np.argmin(np.abs(periods - 4e-3)))
    >>> round(float(periods[k]) * 1e3, 3), round(float(amps[k]) * 1e6, 6)
    (4.0, 1.0)
    """
    from axiscal.io.arguments import check_array, check_count

    p = check_array("positions_m", positions_m, ndim=1, min_len=6, unit="m")
    y = check_array("values_m", values_m, ndim=1, unit="m")
    if y.size != p.size:
        raise AxiscalError(f"values_m must hold one value per position ({p.size}), not {y.size}")
    if np.any(np.diff(p) <= 0):
        raise AxiscalError("positions_m must increase")
    oversample = check_count("oversample", oversample, minimum=1, maximum=64)
    return _spectrum(p, y, oversample)[:2]


def _spectrum(p: np.ndarray, y: np.ndarray, oversample: int) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    span = p[-1] - p[0]
    spacing = span / (p.size - 1)
    # frequencies on the DFT's grid of the record (span + one spacing), oversampled; up to 0.4 / spacing
    # (a sine at the Nyquist frequency vanishes at evenly spaced points: periods stop at 2.5 spacings)
    record = span + spacing
    f = np.arange(oversample, int(math.floor(0.4 * record / spacing * oversample)) + 1) / (oversample * record)
    periods = 1 / f
    amplitudes, left = _fits(p, y, periods)
    return periods, amplitudes, left


def _fit(p: np.ndarray, y: np.ndarray, period: float, free: bool) -> tuple[float, np.ndarray]:
    from scipy.optimize import minimize_scalar

    def solve(q):
        a = _design(p, np.array([q]))[0]
        coef, *_ = np.linalg.lstsq(a, y, rcond=None)
        return coef, float(np.sum((a @ coef - y) ** 2))

    if free:
        found = minimize_scalar(lambda q: solve(q)[1], bracket=None, bounds=(0.8 * period, 1.25 * period),
                                method="bounded", options={"xatol": period * 1e-9})
        period = float(found.x)
    return period, solve(period)[0]


def _component(direction: str, p: np.ndarray, y: np.ndarray, period_m: float | None, oversample: int) -> PeriodicComponent:
    periods, amps, left = _spectrum(p, y, oversample)
    k = int(np.argmin(left))  # the periodogram's peak: the trial period whose sine explains most
    start = period_m if period_m is not None else float(periods[k])
    period, coef = _fit(p, y, start, period_m is None)
    offset, slope, c, s = coef
    amplitude = math.hypot(c, s)
    phase = math.atan2(c, s)  # c cos + s sin = A sin(theta + phi)
    residual = y - (offset + slope * p + amplitude * np.sin(2 * np.pi * p / period + phase))
    dof = max(p.size - 4 - (period_m is None), 1)
    return PeriodicComponent(direction, p, y, period, amplitude, phase, float(slope), float(offset),
                             float(math.sqrt(np.sum(residual**2) / dof)), float(periods[k]), float(amps[k]), periods, amps)


def periodic_error(run: PositioningRun, *, period_m: float | None = None, oversample: int = 32) -> PeriodicError:
    """The periodic error of a positioning run: amplitude and period by fit and by spectrum.

    Parameters
    ----------
    run : PositioningRun
        A linear axis's run, best a step cycle (evenly and closely spaced targets over one or a few
        periods); at least 6 targets.
    period_m : float, metres, optional, keyword-only
        The period when it is known (the screw's pitch): the fit keeps it; the spectrum is
        computed all the same. Default: found.
    oversample : int, keyword-only
        Trial periods per step of the record's own frequency grid (default 32).

    Returns
    -------
    PeriodicError

    Raises
    ------
    AxiscalError
        For a rotary run, fewer than 6 targets, a period that is not positive or longer than
        the travel measured, or shorter than 2.5 times the targets' spacing.

    Examples
    --------
    >>> import numpy as np
    >>> targets = np.arange(17) * 0.625e-3  # 2 periods of 5 mm, 8 steps a period
    >>> up = (0.5e-6 * np.sin(2 * np.pi * targets / 5e-3))[:, None] + np.zeros((1, 3))
    >>> result = periodic_error(PositioningRun(targets, up, None))
    >>> round(result.main.amplitude_m * 1e6, 6), round(result.main.period_m * 1e3, 6)
    (0.5, 5.0)
    """
    from axiscal.io.arguments import check_count

    check_instance("run", run, PositioningRun)
    if run.rotary:
        raise AxiscalError("the periodic error is evaluated on a linear axis's run, not a rotary one", path=run.source)
    period_m = check_optional_number("period_m", period_m, positive=True)
    oversample = check_count("oversample", oversample, minimum=1, maximum=64)
    p = run.targets
    if p.size < 6:
        raise AxiscalError(f"{p.size} targets: a periodic error needs at least 6 (best a step cycle over a period or more)",
                           path=run.source)
    spacing = (p[-1] - p[0]) / (p.size - 1)
    if period_m is not None and not 2.5 * spacing <= period_m <= (p[-1] - p[0]) * 1.0000001:
        raise AxiscalError(f"period_m ({period_m / MM:g} mm) must lie between 2.5 times the targets' mean spacing"
                           f" ({2.5 * spacing / MM:g} mm) and the travel measured ({(p[-1] - p[0]) / MM:g} mm)", path=run.source)
    means = {}
    if run.deviations_up is not None:
        means["+"] = run.deviations_up.mean(axis=1)
    if run.deviations_down is not None:
        means["-"] = run.deviations_down.mean(axis=1)
    if len(means) == 2:
        means["mean"] = 0.5 * (means["+"] + means["-"])
    components = tuple(_component(d, p, y, period_m, oversample) for d, y in means.items())
    return PeriodicError(components, period_m is not None, run.source)


def periodic_from_file(path: str | Path, *, period_m: float | None = None, **reader: Any) -> PeriodicError:
    """:func:`periodic_error` of a positioning run file (``axiscal periodic RUN``).

    Parameters
    ----------
    path : str or Path
        A run as :func:`axiscal.positioning.reader.read_positioning_run` reads it (a step cycle's
        capture, or the plan's CSV with its deviations typed in).
    period_m : float, metres, optional, keyword-only
        As :func:`periodic_error` takes it.
    **reader
        ``wavelength_nm``, ``expansion_per_k`` ... of the run's reader.

    Returns
    -------
    PeriodicError

    Raises
    ------
    AxiscalError
        As the reader and :func:`periodic_error`.
    """
    from axiscal.positioning.reader import read_positioning_run

    if period_m is not None:
        check_number("period_m", period_m, positive=True)
    return periodic_error(read_positioning_run(path, **reader).run, period_m=period_m)
