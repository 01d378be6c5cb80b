"""``axiscal dynamics``: a timebase recording's moves and stops, its derivatives and its spectrum.

:func:`axis_dynamics` takes a :class:`~axiscal.capture.recording.Recording` (what ``axiscal
capture`` reads: a CSV with ``time_s`` and the reading, or an ``.rtx`` capture) and, optionally,
the plan the program ran, whose steps then name the stops. The methods are those of
:mod:`axiscal.dynamics.motion`.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from pathlib import Path
from typing import Any

import numpy as np

from axiscal.capture.recording import Recording, read_recording
from axiscal.capture.steps import PlanSteps, plan_steps
from axiscal.dynamics.motion import (
    Derivatives,
    MoveDynamics,
    Spectrum,
    StopDynamics,
    _derivatives,
    _stop_dynamics,
    _time_problem,
    _welch,
    _welch_pieces,
)
from axiscal.errors import AxiscalError
from axiscal.io.arguments import check_count, check_instance, check_number, render_checked
from axiscal.io.templates import render_template
from axiscal.positioning.plan import PositioningTestPlan
from axiscal.units import MM, UM

__all__ = ["DynamicsSettings", "AxisDynamics", "axis_dynamics", "dynamics_from_file"]


@dataclass(frozen=True)
class DynamicsSettings:
    """How a recording is differentiated and cut into moves and stops (SI units).

    Attributes
    ----------
    window_s : float, seconds
        Savitzky-Golay window (default 20 ms).
    polyorder : int
        Its polynomial degree (default 3).
    moving_m_s : float, metres per second
        Speed above which the axis is moving (default 1 mm/s).
    band_m : float, metres
        Half-width of the settling band about the final value (default 1 um).
    final_window_s : float, seconds
        The final value of a stop is the mean over its last window (default 0.5 s).
    ring_s : float, seconds
        Length of a stop's start over which the ringing is fitted (default 0.5 s).
    segment_s : float, seconds
        Length of Welch's segments (default 1 s).
    tolerance_m : float, metres
        How far from a plan's position a stop may be to be that step's (default 0.5 mm).
    """

    window_s: float = 0.02
    polyorder: int = 3
    moving_m_s: float = 1e-3
    band_m: float = 1e-6
    final_window_s: float = 0.5
    ring_s: float = 0.5
    segment_s: float = 1.0
    tolerance_m: float = 0.5e-3

    def __post_init__(self) -> None:
        for name in ("window_s", "moving_m_s", "band_m", "final_window_s", "ring_s", "segment_s", "tolerance_m"):
            check_number(name, getattr(self, name), positive=True)
        check_count("polyorder", self.polyorder, minimum=3, maximum=7)

    def as_dict(self) -> dict[str, float]:
        """The settings in the units of the command line's flags."""
        return {"window_ms": self.window_s * 1e3, "polyorder": self.polyorder, "moving_mm_s": self.moving_m_s / MM,
                "band_um": self.band_m / UM, "final_window_s": self.final_window_s, "ring_s": self.ring_s,
                "segment_s": self.segment_s, "tolerance_mm": self.tolerance_m / MM}


@dataclass(frozen=True)
class AxisDynamics:
    """The dynamics of a recording.

    Attributes
    ----------
    derivatives : Derivatives
        Smoothed position, velocity, acceleration and jerk.
    spectrum : Spectrum
        Welch's amplitude spectral density of the reading at the stops (of the whole recording
        when there is no stop).
    moves : tuple of MoveDynamics
    stops : tuple of StopDynamics
        One after each move that the axis rests after for at least ``final_window_s`` (a
        turnaround is not a stop).
    settings : DynamicsSettings
    source : str
        The recording.
    """

    derivatives: Derivatives
    spectrum: Spectrum
    moves: tuple[MoveDynamics, ...]
    stops: tuple[StopDynamics, ...]
    settings: DynamicsSettings
    source: str

    def summary(self) -> dict[str, float]:
        """The largest figures over the recording: speed (mm/s), acceleration (m/s^2), settling (s), overshoot (um)."""
        def largest(values):
            values = [v for v in values if math.isfinite(v)]
            return max(values) if values else math.nan

        settled = [s.settling_s for s in self.stops]
        return {
            "peak_velocity_mm_s": largest(m.peak_velocity_m_s / MM for m in self.moves),
            "peak_acceleration_m_s2": largest(m.peak_acceleration_m_s2 for m in self.moves),
            "peak_jerk_m_s3": largest(m.peak_jerk_m_s3 for m in self.moves),
            "settling_s": math.nan if any(math.isnan(s) for s in settled) else largest(settled),
            "overshoot_um": largest(s.overshoot_m / UM for s in self.stops),
            "ringing_hz": float(np.nanmedian([s.ringing_hz for s in self.stops])) if any(
                math.isfinite(s.ringing_hz) for s in self.stops) else math.nan,
            "damping_ratio": float(np.nanmedian([s.damping_ratio for s in self.stops])) if any(
                math.isfinite(s.damping_ratio) for s in self.stops) else math.nan,
        }

    def report(self) -> str:
        """The readable summary: the differentiator, the largest figures, a line per stop."""
        return render_checked(render_template, "dynamics.txt.j2", **self.payload()).rstrip("\n")

    def payload(self) -> dict[str, Any]:
        """Everything as plain numbers in the units people use (mm, um, s, Hz), for ``--json`` and results.json."""
        d = self.derivatives
        return {
            "source": self.source,
            "settings": self.settings.as_dict(),
            "differentiator": {"method": "Savitzky-Golay", "window_ms": d.window_s * 1e3, "polyorder": d.polyorder,
                               "bandwidth_hz": d.bandwidth_hz, "resampled": d.resampled,
                               "rate_hz": 1 / float(d.time_s[1] - d.time_s[0])},
            "spectrum": {"method": f"Welch (Hann, half overlap, linear detrend) over the {self.spectrum.over}",
                         "segment_s": self.spectrum.segment_s,
                         "resolution_hz": self.spectrum.resolution_hz, "peak_hz": self.spectrum.peak_hz},
            **self.summary(),
            "moves": [{"start_s": m.start_s, "end_s": m.end_s, "from_mm": m.from_m / MM, "to_mm": m.to_m / MM,
                       "direction": m.direction, "peak_velocity_mm_s": m.peak_velocity_m_s / MM,
                       "peak_acceleration_m_s2": m.peak_acceleration_m_s2, "peak_jerk_m_s3": m.peak_jerk_m_s3}
                      for m in self.moves],
            "stops": [{"step": s.step, "arrival_s": s.arrival_s, "departure_s": s.departure_s, "final_mm": s.final_m / MM,
                       "direction": s.direction, "settling_s": s.settling_s, "overshoot_um": s.overshoot_m / UM,
                       "ringing_hz": s.ringing_hz, "decay_s": s.decay_s, "damping_ratio": s.damping_ratio}
                      for s in self.stops],
        }


def _runs(mask: np.ndarray) -> list[tuple[int, int]]:
    """(first, last + 1) of each run of True."""
    edges = np.diff(np.concatenate(([0], mask.astype(np.int8), [0])))
    return list(zip(np.flatnonzero(edges == 1).tolist(), np.flatnonzero(edges == -1).tolist()))


def _moves(d: Derivatives, settings: DynamicsSettings) -> list[tuple[int, int, float]]:
    """(first, last + 1, sign) of each move: runs of speed above the threshold in one direction.

    Runs of one sign closer than a window are one move (the smoothing may dip below the threshold
    within a slow move); a reversal always starts a new move.
    """
    step = float(d.time_s[1] - d.time_s[0])
    gap = max(1, int(round(settings.window_s / step)))
    found: list[tuple[int, int, float]] = []
    for sign in (1.0, -1.0):
        merged: list[list[int]] = []
        for a, b in _runs(sign * d.velocity_m_s > settings.moving_m_s):
            if merged and a - merged[-1][1] <= gap and not np.any(-sign * d.velocity_m_s[merged[-1][1]:a] > 0):
                merged[-1][1] = b
            else:
                merged.append([a, b])
        found += [(a, b, sign) for a, b in merged if abs(d.position_m[b - 1] - d.position_m[a]) > 2 * settings.band_m]
    return sorted(found)


def _label(stops: list[StopDynamics], steps: PlanSteps, tolerance_m: float) -> list[StopDynamics]:
    """Each stop named by the plan's next step whose move ends within the tolerance, walking the plan in order."""
    out, k = [], 0
    for stop in stops:
        ahead = [j for j in range(k, steps.step.size)
                 if abs(stop.final_m - steps.move_to_m[j]) <= tolerance_m and steps.direction[j] == stop.direction]
        if ahead:
            k = ahead[0] + 1
            stop = StopDynamics(**{**stop.__dict__, "step": int(steps.step[ahead[0]])})
        out.append(stop)
    return out


def _unmatched(stops: list[StopDynamics], steps: PlanSteps, tolerance_m: float, plan: Any, source: str) -> AxiscalError:
    """The refusal of a plan none of whose steps a stop is at: the nearest pair named."""
    gaps = np.array([[abs(s.final_m - steps.move_to_m[j]) if steps.direction[j] == s.direction else np.inf
                      for j in range(steps.step.size)] for s in stops])
    if not np.any(np.isfinite(gaps)):
        nearest = "no stop is in the direction of a step"
    else:
        i, j = np.unravel_index(int(np.argmin(gaps)), gaps.shape)
        nearest = (f"the nearest, the stop at {stops[i].final_m / MM:.4f} mm, is {gaps[i, j] / MM:.4g} mm from step "
                   f"{int(steps.step[j])} ({steps.move_to_m[j] / MM:.4f} mm, {steps.direction[j]})")
    named = str(plan) if isinstance(plan, (str, Path)) else None
    return AxiscalError(
        f"the plan does not fit the recording {source}: none of its {len(stops)} stops is within "
        f"{tolerance_m / MM:g} mm of a step's position in its direction; {nearest}. Is it the plan the program ran?",
        path=named)


def axis_dynamics(
    recording: Recording,
    plan: PositioningTestPlan | PlanSteps | str | Path | None = None,
    *,
    settings: DynamicsSettings | None = None,
) -> AxisDynamics:
    """Velocity, acceleration, jerk, spectrum, every move's peaks and every stop's settling.

    Parameters
    ----------
    recording : Recording
        The laser's reading over time (:func:`axiscal.capture.recording.read_recording`).
    plan : PositioningTestPlan, PlanSteps, str or Path, optional
        The plan the program ran (or its cycle CSV): each stop is named by its step.
    settings : DynamicsSettings, optional, keyword-only
        Window, thresholds and band (defaults of :class:`DynamicsSettings`).

    Returns
    -------
    AxisDynamics

    Raises
    ------
    AxiscalError
        For a recording with a missing reading (NaN), two samples at one time, a gap longer than the
        differentiator's window, samples too sparse for an even grid (each naming the sample's line),
        a window the recording cannot hold, a plan :func:`axiscal.capture.steps.plan_steps` refuses,
        or a plan none of whose steps any stop of the recording is at.

    Examples
    --------
    >>> result = axis_dynamics(read_recording("recording_x.csv"))  # doctest: +SKIP
    >>> result.summary()["peak_velocity_mm_s"]  # doctest: +SKIP
    33.3
    """
    check_instance("recording", recording, Recording)
    settings = DynamicsSettings() if settings is None else check_instance("settings", settings, DynamicsSettings)
    steps = None if plan is None else (plan if isinstance(plan, PlanSteps) else plan_steps(plan))
    if not np.all(np.isfinite(recording.reading_m)):
        k = int(np.flatnonzero(~np.isfinite(recording.reading_m))[0])
        raise AxiscalError("a reading is missing (not a number): the derivatives need every sample", path=recording.source,
                           line=recording.line_of(k))
    if recording.time_s.size < 8:
        raise AxiscalError(f"{recording.time_s.size} samples: a recording for the dynamics needs at least 8",
                           path=recording.source)
    if np.any(np.diff(recording.time_s) < 0):
        k = int(np.flatnonzero(np.diff(recording.time_s) < 0)[0]) + 1
        raise AxiscalError("the time goes back", path=recording.source, line=recording.line_of(k))
    problem = _time_problem(recording.time_s, settings.window_s, settings.polyorder)
    if problem is not None:
        k, words = problem
        raise AxiscalError(words if recording.locate is not None else f"sample {k}: {words}", path=recording.source,
                           line=recording.line_of(k))
    try:
        d = _derivatives(recording.time_s, recording.reading_m, settings.window_s, settings.polyorder)
    except AxiscalError as exc:
        raise exc.located(path=recording.source) from None
    spans = _moves(d, settings)
    step = float(d.time_s[1] - d.time_s[0])
    pad = int(round(settings.window_s / step))
    moves, stops = [], []
    for a, b, sign in spans:
        # acceleration and jerk peak where the speed is still below the threshold: a window each side counts
        lo, hi = max(0, a - pad), min(d.time_s.size, b + pad)
        moves.append(MoveDynamics(
            float(d.time_s[a]), float(d.time_s[b - 1]), float(d.position_m[a]), float(d.position_m[b - 1]),
            float(np.max(np.abs(d.velocity_m_s[a:b]))), float(np.max(np.abs(d.acceleration_m_s2[lo:hi]))),
            float(np.max(np.abs(d.jerk_m_s3[lo:hi]))), "+" if sign > 0 else "-"))
    # a stop: a rest of at least final_window_s after a move (a turnaround, or ringing fast enough to pass the
    # threshold, belongs to the approach); it is measured from the approach's last long move
    group_start = 0
    for i, (a, b, sign) in enumerate(spans):
        nxt = spans[i + 1][0] if i + 1 < len(spans) else None
        departure = float(d.time_s[nxt]) - 0.5 * d.window_s if nxt is not None else float(d.time_s[-1]) + step
        rest = float(d.time_s[b - 1])
        if departure - rest < settings.final_window_s:
            continue
        group = moves[group_start:i + 1]
        longest = max(abs(m.to_m - m.from_m) for m in group)
        last_long = [m for m in group if abs(m.to_m - m.from_m) >= 0.9 * longest][-1]
        stops.append(_stop_dynamics(d.time_s, d.reading_m, move_s=last_long.start_s, rest_s=rest, departure_s=departure,
                                    direction=last_long.direction, band_m=settings.band_m,
                                    final_window_s=settings.final_window_s, ring_s=settings.ring_s))
        group_start = i + 1
    if steps is not None:
        stops = _label(stops, steps, settings.tolerance_m)
        if stops and all(s.step is None for s in stops):
            raise _unmatched(stops, steps, settings.tolerance_m, plan, recording.source)
    # the spectrum where the axis rests (its moves would hide its vibration), else of the whole recording
    pieces = [d.reading_m[a:b] for a, b in (np.searchsorted(d.time_s, [s.arrival_s, s.departure_s]) for s in stops) if b - a >= 8]
    spectrum = (_welch_pieces(pieces, step, settings.segment_s, "stops") if pieces
                else _welch(d.reading_m, step, settings.segment_s))
    return AxisDynamics(d, spectrum, tuple(moves), tuple(stops), settings, recording.source)


def dynamics_from_file(
    path: str | Path,
    plan: PositioningTestPlan | PlanSteps | str | Path | None = None,
    *,
    unit: str | None = None,
    channel: str | None = None,
    settings: DynamicsSettings | None = None,
) -> AxisDynamics:
    """:func:`axis_dynamics` of a recording file (``axiscal dynamics RECORDING``).

    Parameters
    ----------
    path : str or Path
        An ``.rtx`` capture or a CSV with ``time_s`` and the reading (:func:`read_recording`).
    plan : optional
        As :func:`axis_dynamics` takes it.
    unit, channel : str, optional, keyword-only
        As :func:`read_recording` takes them.
    settings : DynamicsSettings, optional, keyword-only

    Returns
    -------
    AxisDynamics

    Raises
    ------
    AxiscalError
        As :func:`read_recording` and :func:`axis_dynamics`; a channel that is a sensor's column
        (an air or material temperature, the pressure, the humidity), not a length.
    """
    if settings is not None:
        check_instance("settings", settings, DynamicsSettings)
    recording = read_recording(path, unit=unit, channel=channel)
    if channel is not None and channel in recording.channels:
        raise AxiscalError(f"the channel {channel} is a sensor's column, not the laser's reading: give the column of the "
                           "reading, a length", path=recording.source)
    return axis_dynamics(recording, plan, settings=settings)
