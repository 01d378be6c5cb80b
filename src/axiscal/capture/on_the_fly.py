"""On-the-fly capture: the reading at each target taken as the axis passes it, without stopping.

A recording for an on-the-fly capture carries two streams: the laser's reading and, beside it,
the machine's own position (``position_mm``, as the controller reports it), both time-stamped
(one ``time_s`` column for both, or ``position_time_s`` for the position's own stamps). Each
step of the plan is taken where the position stream crosses the step's target in the step's
direction; the laser's reading at that instant is a straight line fitted to its samples over
``window_s`` about it (the reading moves at the feed rate), and the deviation is ``(reading -
offset) - target`` as a stop-and-go capture takes it.

The two streams are seldom stamped by one clock: the position arrives late by the controller's
and the link's delay, and at the feed rate ``v`` a delay ``d`` moves every forward reading by
``+v d`` and every backward reading by ``-v d``, which looks exactly like a reversal error. The
delay is therefore estimated from the velocities, not the positions: the shift of the position
stream that best aligns its steps from sample to sample (a cubic spline through its samples,
taken at the laser's sample times shifted) with the laser's, by least squares over the forward
and backward passes (the accelerations into and out of each turnaround carry the timing). The axis's
positioning errors are offsets in position, nearly constant in velocity, and do not move the
estimate; its reversal error is taken up where the axis reverses, so the samples where it moves
slower than a quarter of its top speed are left out. The delay found is removed before the
readings are taken.
"""

from __future__ import annotations

import math
from collections.abc import Mapping
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

import numpy as np

from axiscal.capture.recording import READING_UNITS, environment_columns
from axiscal.capture.run import Capture, CaptureSettings, StopReading
from axiscal.capture.steps import PlanSteps, plan_steps
from axiscal.errors import AxiscalError
from axiscal.io.arguments import check_array, check_instance, check_number, check_optional_number, check_path
from axiscal.io.jsonio import named_from, write_sidecar
from axiscal.io.tabular import read_csv, write_csv
from axiscal.positioning.evaluation import PositioningRun
from axiscal.positioning.plan import PositioningTestPlan
from axiscal.units import MM, UM

#: samples where the axis moves slower than this fraction of its top speed are left out of the delay's estimate
_REVERSING = 0.25

__all__ = [
    "FlyRecording",
    "OnTheFly",
    "read_fly_recording",
    "estimate_delay",
    "on_the_fly",
    "on_the_fly_run",
    "on_the_fly_to_file",
]


@dataclass(frozen=True)
class FlyRecording:
    """A laser reading and the machine's position stream, each over time.

    Attributes
    ----------
    time_s : ndarray, shape (n,), seconds
        The laser's sample times, increasing.
    reading_m : ndarray, shape (n,), metres
        The laser's reading.
    position_time_s : ndarray, shape (k,), seconds
        The position stream's time stamps, increasing.
    position_m : ndarray, shape (k,), metres
        The machine's position.
    channels : dict of str to ndarray, shape (n,)
        Environment columns on the laser's clock, each in the unit its name ends in.
    source : str
        The file read.
    """

    time_s: np.ndarray
    reading_m: np.ndarray
    position_time_s: np.ndarray
    position_m: np.ndarray
    channels: Mapping[str, np.ndarray] = field(default_factory=dict)
    source: str = "<recording>"

    def __post_init__(self) -> None:
        t = check_array("time_s", self.time_s, ndim=1, min_len=4, unit="s")
        x = check_array("reading_m", self.reading_m, ndim=1, unit="m")
        tp = check_array("position_time_s", self.position_time_s, ndim=1, min_len=4, unit="s")
        p = check_array("position_m", self.position_m, ndim=1, unit="m")
        if x.size != t.size:
            raise AxiscalError(f"reading_m must hold one reading per time ({t.size}), not {x.size}")
        if p.size != tp.size:
            raise AxiscalError(f"position_m must hold one position per time stamp ({tp.size}), not {p.size}")
        if np.any(np.diff(t) <= 0) or np.any(np.diff(tp) <= 0):
            raise AxiscalError("time_s and position_time_s must increase")
        for name, values in self.channels.items():
            if not isinstance(name, str) or np.shape(values) != t.shape:
                raise AxiscalError(f"channels must map names to arrays of {t.size} values, not {name!r}")
        check_instance("source", self.source, str)


def read_fly_recording(path: str | Path, *, unit: str | None = None, channel: str | None = None) -> FlyRecording:
    """Read a recording with the machine's position stream: ``time_s``, the reading, ``position_mm``.

    Parameters
    ----------
    path : str or Path
        A CSV: ``time_s``; the reading (the column named by ``channel``, else the only column
        besides ``position_mm`` named with a length unit); ``position_mm`` (the machine's
        position); optionally ``position_time_s`` (the position's own time stamps; rows where it
        is empty hold no position sample) and the air and material sensors.
    unit : str, optional, keyword-only
        Unit of a reading column whose name has none.
    channel : str, optional, keyword-only
        The reading's column.

    Returns
    -------
    FlyRecording

    Raises
    ------
    AxiscalError
        Naming the file and line: no time or position column, no reading column or more than
        one, a unit missing or contradicting the name, times that do not increase, a missing
        value.
    """
    path = check_path("path", path)
    if unit is not None and unit not in READING_UNITS:
        raise AxiscalError(f"unknown unit '{unit}' for the readings; use one of {', '.join(READING_UNITS)}")
    table = read_csv(path, min_rows=4)
    table.require("time_s", "position_mm")
    environment = environment_columns(table.header)
    others = [n for n in table.header if n not in ("time_s", "position_mm", "position_time_s") and n not in environment]
    if channel is not None:
        if not table.has(channel):
            raise AxiscalError(f"no column '{channel}' (the reading's channel)", path=path, line=table.header_line)
        name = channel
    else:
        named = [n for n in others if n.rpartition("_")[2] in READING_UNITS and "_" in n]
        candidates = named or others
        if len(candidates) != 1:
            raise AxiscalError("channel must name the column that holds the laser's reading: candidates "
                               f"{', '.join(candidates) or 'none'}", path=path, line=table.header_line)
        name = candidates[0]
    suffix = name.rpartition("_")[2] if "_" in name else None
    named_unit = suffix if suffix in READING_UNITS else None
    if named_unit is not None and unit is not None and unit != named_unit:
        raise AxiscalError(f"column {name} is in {named_unit}, not in {unit} as the unit given says", path=path,
                           line=table.header_line)
    used = named_unit or unit
    if used is None:
        raise AxiscalError(f"unit must be given (mm, um, nm, m or in): column {name} does not say its unit", path=path,
                           line=table.header_line)
    time_s = table.numeric("time_s")
    reading = table.numeric(name) * READING_UNITS[used]
    if table.has("position_time_s"):
        stamp = table.numeric_or_missing("position_time_s")
        held = np.isfinite(stamp)
        position_time, position = stamp[held], table.numeric_or_missing("position_mm")[held] * MM
        if not np.all(np.isfinite(position)):
            k = int(np.flatnonzero(held)[np.flatnonzero(~np.isfinite(position))[0]])
            raise AxiscalError("a position_time_s without its position_mm", path=path, line=table.line_of(k))
    else:
        position_time, position = time_s, table.numeric("position_mm") * MM
    for label, stamps in (("time_s", time_s), ("position_time_s", position_time)):
        back = np.flatnonzero(np.diff(stamps) <= 0)
        if back.size:
            raise AxiscalError(f"{label} must increase ({stamps[back[0]]:g} s, then {stamps[back[0] + 1]:g} s)", path=path,
                               line=table.line_of(int(back[0]) + 1) if label == "time_s" else None)
    channels = {c: table.numeric(c) for c in environment}
    return FlyRecording(time_s, reading, position_time, position, channels, str(path))


def estimate_delay(recording: FlyRecording, *, max_delay_s: float = 0.5) -> float:
    """The delay of the position stream behind the laser, from the two streams' motion (see the module).

    Parameters
    ----------
    recording : FlyRecording
    max_delay_s : float, seconds, keyword-only
        Largest delay looked for, either way (default 0.5 s).

    Returns
    -------
    float, seconds
        ``d`` such that the position stamped ``t`` is where the axis was at ``t - d`` on the
        laser's clock (positive: the position arrives late).

    Raises
    ------
    AxiscalError
        For a recording in which the axis does not move, or a delay at the edge of the range.

    Examples
    --------
    >>> t = np.arange(0, 4, 1e-3)
    >>> x = 0.01 * np.sin(2 * np.pi * 0.5 * t)
    >>> rec = FlyRecording(t, x, t, 0.01 * np.sin(2 * np.pi * 0.5 * (t - 0.0123)))
    >>> round(estimate_delay(rec) * 1e3, 3)
    12.3
    """
    check_instance("recording", recording, FlyRecording)
    max_delay_s = check_number("max_delay_s", max_delay_s, positive=True, unit="s")
    return _delay(recording, max_delay_s)


def _delay(rec: FlyRecording, max_delay_s: float) -> float:
    """The delay minimising the squared differences between the laser's steps and the position stream's, shifted.

    Steps (first differences) rather than positions, so that an offset does not count; the
    position stream is a cubic spline through its samples, evaluated at the laser's sample times
    shifted by the trial delay, so that both streams are differenced at the same instants.
    """
    from scipy.interpolate import make_interp_spline
    from scipy.optimize import minimize_scalar

    if not np.ptp(rec.position_m) > 0:
        raise AxiscalError("the position stream never moves: no delay can be found", path=rec.source)
    t, dt = rec.time_s, np.diff(rec.time_s)
    laser_steps = np.diff(rec.reading_m)
    spline = make_interp_spline(rec.position_time_s, rec.position_m, k=3)
    step = float(np.median(dt))
    lo, hi = rec.position_time_s[0], rec.position_time_s[-1]
    speed = np.abs(np.diff(rec.position_m) / np.diff(rec.position_time_s))
    fast = _REVERSING * float(np.max(speed))

    def steps_at(d: float, smooth: bool = True) -> tuple[np.ndarray, np.ndarray]:
        shifted = np.clip(t + d, lo, hi)
        inside = (t[:-1] + d >= lo) & (t[1:] + d <= hi)
        at = spline(shifted) if smooth else np.interp(shifted, rec.position_time_s, rec.position_m)
        return np.diff(at), inside

    def cost(d: float, keep: np.ndarray | None = None, smooth: bool = True) -> float:
        moved, inside = steps_at(d, smooth)
        use = inside & (np.abs(moved) > fast * dt if keep is None else keep)
        return float(np.mean((laser_steps[use] - moved[use]) ** 2)) if use.any() else math.inf

    # a coarse grid (about 200 lags) over the range, then every sample's lag about its best (the position
    # stream interpolated linearly, which is quicker); the spline for the refinement
    lags = np.linspace(-max_delay_s, max_delay_s, 201)
    k = int(np.argmin([cost(d, smooth=False) for d in lags]))
    if k not in (0, lags.size - 1):
        near = lags[k] + step * np.arange(-int(np.ceil((lags[1] - lags[0]) / step)) - 1,
                                          int(np.ceil((lags[1] - lags[0]) / step)) + 2)
        lags = near[np.abs(near) <= max_delay_s]
        k = int(np.argmin([cost(d, smooth=False) for d in lags]))
    if lags[k] in (-max_delay_s, max_delay_s) or abs(lags[k]) >= max_delay_s - step:
        raise AxiscalError(f"the delay between the streams is {lags[k] * 1e3:g} ms, at the edge of the range looked"
                           f" at (+/-{max_delay_s * 1e3:g} ms): widen it or check that they are the same axis",
                           path=rec.source)
    # the samples kept (the axis above a quarter of its speed) are fixed for the refinement, so the cost is smooth
    moved, inside = steps_at(float(lags[k]))
    keep = inside & (np.abs(moved) > fast * dt)
    found = minimize_scalar(lambda d: cost(d, keep), bounds=(lags[k] - 2 * step, lags[k] + 2 * step), method="bounded",
                            options={"xatol": 1e-8})
    return float(found.x)


@dataclass(frozen=True)
class OnTheFly:
    """An on-the-fly capture.

    Attributes
    ----------
    capture : Capture
        The readings as a stop-and-go capture holds them (``capture.run`` is the positioning run,
        compensated for the air where the recording carries the sensors); a reading's
        ``start_s`` is when the axis crossed the target (laser's clock), ``window_std_m`` the
        spread of the reading about its fitted line.
    delay_s : float, seconds
        The delay removed (the position stream's lateness).
    delay_estimated : bool
        True when it was estimated, False when given.
    speed_m_s : ndarray, shape (k,), metres per second
        The axis's speed as it crossed each target (signed).
    window_s : float, seconds
        The reading's fitting window.
    """

    capture: Capture
    delay_s: float
    delay_estimated: bool
    speed_m_s: np.ndarray
    window_s: float

    @property
    def run(self) -> PositioningRun:
        """The positioning run (``capture.run``)."""
        return self.capture.run

    def payload(self) -> dict[str, Any]:
        """Delay, speeds and readings in ms, mm/min and um, for ``--json`` and the sidecar."""
        steps = self.capture.steps
        return {
            "source": self.capture.source, "delay_ms": self.delay_s * 1e3, "delay_estimated": self.delay_estimated,
            "window_ms": self.window_s * 1e3, "readings": len(self.capture.readings),
            "speed_mm_min": float(np.median(np.abs(self.speed_m_s))) / MM * 60 if self.speed_m_s.size else math.nan,
            "crossings": [{"step": int(steps.step[r.index]), "target_mm": steps.target_m[r.index] / MM,
                           "run": int(steps.run[r.index]), "direction": str(steps.direction[r.index]),
                           "deviation_um": r.deviation_m / UM, "time_s": r.start_s,
                           "speed_mm_min": float(v) / MM * 60, "fit_std_um": r.window_std_m / UM}
                          for r, v in zip(self.capture.readings, self.speed_m_s)],
        }


def _crossing(t: np.ndarray, p: np.ndarray, start: int, target: float, sign: float) -> int | None:
    """First i >= start with the position going past ``target`` in direction ``sign`` between i and i + 1."""
    a = sign * (p[start:-1] - target)
    b = sign * (p[start + 1:] - target)
    hit = np.flatnonzero((a < 0) & (b >= 0))
    return None if hit.size == 0 else start + int(hit[0])


def _reading_at(t: np.ndarray, x: np.ndarray, when: float, window_s: float) -> tuple[float, float, int]:
    """A straight line through the reading over ``window_s`` about ``when``: its value there, the spread, the samples."""
    a, b = np.searchsorted(t, [when - window_s / 2, when + window_s / 2])
    a, b = max(0, min(a, t.size - 2)), min(t.size, max(b, a + 2))
    if b - a < 3:
        j = int(np.clip(np.searchsorted(t, when) - 1, 0, t.size - 2))
        w = (when - t[j]) / (t[j + 1] - t[j])
        return float(x[j] + w * (x[j + 1] - x[j])), math.nan, 2
    tt = t[a:b] - when
    slope, value = np.polyfit(tt, x[a:b], 1)
    spread = float(np.std(x[a:b] - (value + slope * tt), ddof=2)) if b - a > 2 else math.nan
    return float(value), spread, b - a


def on_the_fly(
    plan: PositioningTestPlan | PlanSteps | str | Path,
    recording: FlyRecording | str | Path,
    *,
    delay_s: float | None = None,
    window_s: float = 0.01,
    offset_m: float = 0.0,
    max_delay_s: float = 0.5,
    tolerance_m: float = 0.5e-3,
    unit: str | None = None,
    channel: str | None = None,
) -> OnTheFly:
    """Take each target's reading where the position stream crosses it (see the module).

    Parameters
    ----------
    plan : PositioningTestPlan, PlanSteps, str or Path
        The plan, or its cycle CSV.
    recording : FlyRecording, str or Path
        The recording (:func:`read_fly_recording`) or its file.
    delay_s : float, seconds, optional, keyword-only
        The position stream's delay behind the laser when known; default: estimated
        (:func:`estimate_delay`).
    window_s : float, seconds, keyword-only
        The reading's line is fitted over this window about each crossing (default 10 ms).
    offset_m : float, metres, keyword-only
        The reading at the datum, subtracted from every reading (default 0).
    max_delay_s : float, seconds, keyword-only
        Largest delay looked for (default 0.5 s).
    tolerance_m : float, metres, keyword-only
        How far from its target a reading (less the offset) may be (default 0.5 mm, as a stop of
        :func:`~axiscal.capture.run.capture`): one farther off is the wrong unit, scale or offset.
    unit, channel : str, optional, keyword-only
        As :func:`read_fly_recording` takes them (for a file).

    Returns
    -------
    OnTheFly

    Raises
    ------
    AxiscalError
        Naming the step (target, run and direction) the position never crosses in its
        direction, a crossing outside the laser's recording, a reading not within ``tolerance_m``
        of its target, a target the axis comes to rest at
        (crossed at less than half the median speed); and what the reader and the estimate
        refuse.
    """
    steps = plan if isinstance(plan, PlanSteps) else plan_steps(plan)
    if isinstance(recording, (str, Path)):
        recording = read_fly_recording(recording, unit=unit, channel=channel)
    check_instance("recording", recording, FlyRecording, what="a FlyRecording or its file")
    delay = check_optional_number("delay_s", delay_s, low=-10.0, high=10.0)
    window_s = check_number("window_s", window_s, positive=True, high=10.0, unit="s")
    offset_m = check_number("offset_m", offset_m, unit="m")
    max_delay_s = check_number("max_delay_s", max_delay_s, positive=True, high=10.0, unit="s")
    tolerance_m = CaptureSettings(tolerance_m=tolerance_m, offset_m=offset_m).tolerance_m
    estimated = delay is None
    if estimated:
        delay = _delay(recording, max_delay_s)
    t, x, tp, p = recording.time_s, recording.reading_m, recording.position_time_s, recording.position_m
    names = tuple(recording.channels)
    readings: list[StopReading] = []
    speeds: list[float] = []
    cursor = 0
    for k in np.flatnonzero(np.isfinite(steps.target_m)):
        target = float(steps.target_m[k])
        sign = 1.0 if steps.direction[k] == "+" else -1.0
        i = _crossing(tp, p, cursor, target, sign)
        if i is None:
            raise AxiscalError(f"{steps.describe(int(k))}: the position stream does not pass the target going"
                               f" {steps.direction[k]} after the step before", path=recording.source)
        stamp = tp[i] + (target - p[i]) / (p[i + 1] - p[i]) * (tp[i + 1] - tp[i])
        when = stamp - delay
        if not t[0] <= when <= t[-1]:
            raise AxiscalError(f"{steps.describe(int(k))}: the axis crossed the target at {when:.3f} s, outside the laser's"
                               f" recording ({t[0]:g} to {t[-1]:g} s)", path=recording.source)
        value, spread, samples = _reading_at(t, x, when, window_s)
        if not abs(value - offset_m - target) <= tolerance_m:
            raise AxiscalError(f"{steps.describe(int(k))}: the instrument reads {(value - offset_m) / MM:.4f} mm there (less"
                               f" offset_m {offset_m / MM:g} mm), not within tolerance_m {tolerance_m / MM:g} mm of the target:"
                               " check the instrument's unit and scale and the reading at the datum", path=recording.source)
        sensors = {n: float(np.interp(when, t, recording.channels[n])) for n in names}
        readings.append(StopReading(int(k), value - offset_m - target, float(when), spread, samples,
                                    {n: v for n, v in sensors.items() if math.isfinite(v)}))
        speeds.append(float((p[i + 1] - p[i]) / (tp[i + 1] - tp[i])))
        cursor = i + 1
    passing = np.abs(np.array(speeds))
    stopping = np.flatnonzero(passing < 0.5 * np.median(passing))
    if stopping.size:
        k = readings[int(stopping[0])].index
        raise AxiscalError(f"{steps.describe(k)}: the axis comes to rest at the target ({passing[stopping[0]] / MM * 60:.4g}"
                           f" mm/min, not {np.median(passing) / MM * 60:.4g}): an on-the-fly program runs past every target"
                           " without stopping (an on-the-fly plan's program does)", path=recording.source)
    settings = CaptureSettings(window_s=window_s, offset_m=offset_m, tolerance_m=tolerance_m)
    carried = tuple(n for n in names if all(n in r.channels for r in readings))
    capture = Capture(steps, tuple(readings), settings, recording.source, carried, {})
    return OnTheFly(capture, float(delay), estimated, np.array(speeds), window_s)


def on_the_fly_run(plan, recording, **options: Any) -> PositioningRun:
    """The positioning run of an on-the-fly capture: :func:`on_the_fly` ``(...).run``.

    A pure function of a plan and a recording: nothing is read but what they name, nothing written.

    Parameters
    ----------
    plan, recording, **options
        As :func:`on_the_fly` takes them.

    Returns
    -------
    PositioningRun
        Deviations per target and run, metres (compensated for the air where the recording
        carries the sensors).

    Raises
    ------
    AxiscalError
        As :func:`on_the_fly`.
    """
    return on_the_fly(plan, recording, **options).run


def on_the_fly_to_file(plan, recording, output: str | Path, **options: Any) -> tuple[OnTheFly, Path, Path]:
    """An on-the-fly capture written as ``axiscal capture`` writes a run: the CSV and its sidecar, atomically.

    Parameters
    ----------
    plan, recording, **options
        As :func:`on_the_fly` takes them.
    output : str or Path
        The run CSV (``target_mm, run, direction, deviation_um`` and the sensors).

    Returns
    -------
    result : OnTheFly
    run_csv, sidecar : Path

    Raises
    ------
    AxiscalError
        As :func:`on_the_fly`, or a file that cannot be written.
    """
    output = check_path("output", output)
    result = on_the_fly(plan, recording, **options)
    capture = result.capture
    write_csv(output, capture.columns(), fmt={"target_mm": "{:.6f}", "deviation_um": "{:.5f}",
                                               **{n: "{:.6g}" for n in capture.environment}})
    steps = capture.steps
    payload = result.payload()
    sidecar = write_sidecar(
        output,
        kind="positioning run (captured on the fly)",
        units={"deviation_um": "um, (reading - offset) - target where the position stream crosses the target" + (
            "; the raw reading, compensated for the air when read" if capture.environment else "")},
        sources=[named_from(s, output) for s in (steps.source, capture.source) if s and not s.startswith("<")
                 and Path(s).is_file()],
        standard="ISO 230-2",
        plan=named_from(steps.source, output) if Path(steps.source).is_file() else steps.source,
        plan_seed=steps.seed,
        source=named_from(capture.source, output) if Path(capture.source).is_file() else capture.source,
        delay_ms=payload["delay_ms"], delay_estimated=payload["delay_estimated"], window_ms=payload["window_ms"],
        offset_mm=capture.settings.offset_m / MM, crossings=payload["crossings"],
    )
    return result, output, sidecar
