"""Capture a positioning run: the plan's steps walked through a recording or a live stream, stop by stop.

Each stop the reading makes (:mod:`axiscal.capture.stops`) is matched to the plan's next step
(:mod:`axiscal.capture.steps`); its deviation is ``(reading - offset) - target``. The result is the
positioning run ``axiscal positioning`` reads: ``target_mm, run, direction, deviation_um`` and, when
the recording carries them, the air and material sensors averaged over each stop's window (the
deviation is then that of the raw reading, compensated for the air when the run is read).

The files of a capture (the partial file, resume, the run and its sidecar) are
:mod:`axiscal.capture.files`.
"""

from __future__ import annotations

import math
from collections.abc import Callable, Mapping, Sequence
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

import numpy as np

from axiscal.capture.recording import READING_UNITS, Recording, environment_columns, read_recording
from axiscal.capture.steps import PlanSteps, StepMatcher, plan_steps
from axiscal.capture.stops import Stop, StopDetector
from axiscal.errors import AxiscalError
from axiscal.io.arguments import check_instance, check_number
from axiscal.positioning.evaluation import PositioningRun
from axiscal.positioning.plan import PositioningTestPlan
from axiscal.positioning.reader import ENVIRONMENT_REQUIRED
from axiscal.units import MM, UM, split_unit

__all__ = [
    "CaptureSettings",
    "StopReading",
    "Capture",
    "CaptureProgress",
    "capture",
    "capture_run",
]

#: the bounds of a capture's settings: a stop holds within 1 mm, for at most an hour, within 100 mm of its target,
#: and an instrument reads within 100 m of its datum
MAX_STABILITY_M = 1e-3
MAX_WINDOW_S = 3600.0
MAX_TOLERANCE_M = 0.1
MAX_OFFSET_M = 100.0


@dataclass(frozen=True)
class CaptureSettings:
    """How stops are found and matched (SI units).

    Attributes
    ----------
    stability_m : float, metres
        Largest peak to peak of the reading over the window for a stop (default 1 um; at most 1 mm).
    window_s : float, seconds
        How long the reading must hold still; the value is the mean over the stop's last window
        (0.5 s; at most an hour).
    tolerance_m : float, metres
        How far from the plan's target a reading may be (0.5 mm; at most 100 mm): a reading
        farther off is not the axis at that target (the wrong unit, scale or offset).
    offset_m : float, metres
        The reading at the datum, subtracted from every reading (0; within 100 m).
    """

    stability_m: float = 1e-6
    window_s: float = 0.5
    tolerance_m: float = 0.5e-3
    offset_m: float = 0.0

    def __post_init__(self) -> None:
        check_number("stability_m", self.stability_m, positive=True, high=MAX_STABILITY_M)
        check_number("window_s", self.window_s, positive=True, high=MAX_WINDOW_S)
        check_number("tolerance_m", self.tolerance_m, positive=True, high=MAX_TOLERANCE_M)
        check_number("offset_m", self.offset_m, low=-MAX_OFFSET_M, high=MAX_OFFSET_M)

    def as_dict(self) -> dict[str, float]:
        """The settings in the units of the command line's flags."""
        return {"stability_um": self.stability_m / UM, "window_s": self.window_s,
                "tolerance_mm": self.tolerance_m / MM, "offset_mm": self.offset_m / MM}


@dataclass(frozen=True)
class StopReading:
    """The reading captured at one step of the plan.

    Attributes
    ----------
    index : int
        The step's index in the plan (0-based).
    deviation_m : float, metres
        ``(reading - offset) - target``.
    start_s : float, seconds
        When the stop began (the axis arrived within the stability).
    window_std_m : float, metres
        Standard deviation of the reading over the stop's window.
    samples : int
        Samples in that window.
    channels : dict of str to float
        The environment columns averaged over the window (each in its own unit).
    """

    index: int
    deviation_m: float
    start_s: float
    window_std_m: float
    samples: int
    channels: Mapping[str, float] = field(default_factory=dict)


@dataclass(frozen=True)
class CaptureProgress:
    """Where a capture stands, for a progress line.

    Attributes
    ----------
    taken, total : int
        Stops taken and needed.
    step : int or None
        The plan's number of the step awaited (None when done).
    target_m : float, metres
        Its target (NaN when done).
    reading_m : float, metres
        The latest reading less the offset (NaN before the first).
    still : bool
        Whether the reading is holding still now.
    samples : int
        Samples read so far.
    """

    taken: int
    total: int
    step: int | None
    target_m: float
    reading_m: float
    still: bool
    samples: int


@dataclass(frozen=True)
class Capture:
    """A captured positioning run.

    Attributes
    ----------
    steps : PlanSteps
        The plan walked.
    readings : tuple of StopReading
        One per step with a target, in the plan's order.
    settings : CaptureSettings
    source : str
        The recording or stream.
    environment : tuple of str
        The environment columns carried (empty when the source had none).
    header : dict of str to str
        The recording's header (an ``.rtx`` capture's), empty otherwise.
    """

    steps: PlanSteps
    readings: tuple[StopReading, ...]
    settings: CaptureSettings
    source: str
    environment: tuple[str, ...] = ()
    header: Mapping[str, str] = field(default_factory=dict)

    def columns(self) -> dict[str, Any]:
        """The run's columns as ``axiscal positioning`` reads them (mm, um, the sensors' units)."""
        k = np.array([r.index for r in self.readings], dtype=int)
        out: dict[str, Any] = {
            "target_mm": self.steps.target_m[k] / MM,
            "run": [str(int(v)) for v in self.steps.run[k]],
            "direction": [str(v) for v in self.steps.direction[k]],
            "deviation_um": np.array([r.deviation_m for r in self.readings]) / UM,
        }
        for name in self.environment:
            out[name] = np.array([r.channels[name] for r in self.readings])
        return out

    @property
    def run(self) -> PositioningRun:
        """The deviations arranged per target and run (compensated for the air when sensors were recorded)."""
        k = np.array([r.index for r in self.readings], dtype=int)
        targets = self.steps.target_m[k]
        deviation = np.array([r.deviation_m for r in self.readings])
        if all(name in self.environment for name in ENVIRONMENT_REQUIRED):
            from axiscal.instruments.interferometer import compensated_length

            material = [n for n in self.environment if n.startswith("material_temperature")]
            env = {n: np.array([r.channels[n] for r in self.readings]) for n in self.environment}
            actual = compensated_length(
                targets + deviation,
                air_temperature_c=env["air_temperature_c"], pressure_pa=env["pressure_pa"], humidity_pct=env["humidity_pct"],
                material_temperature_c=np.column_stack([env[n] for n in material]) if material else None,
            )
            deviation = actual - targets
        return _arranged(targets, self.steps.run[k], self.steps.direction[k], deviation, self.source)


def _arranged(targets: np.ndarray, runs: np.ndarray, directions: np.ndarray, deviation: np.ndarray, source: str) -> PositioningRun:
    unique = np.unique(np.round(targets / UM) * UM)
    labels = np.unique(runs)
    arrays: dict[str, np.ndarray | None] = {}
    for d in ("+", "-"):
        sel = directions == d
        if not sel.any():
            arrays[d] = None
            continue
        grid = np.full((unique.size, labels.size), np.nan)
        i = np.searchsorted(unique, np.round(targets[sel] / UM) * UM)
        j = np.searchsorted(labels, runs[sel])
        grid[i, j] = deviation[sel]
        arrays[d] = grid
    return PositioningRun(unique, arrays["+"], arrays["-"], source=source)


class _Replay:
    """Which stops of a resumed capture's source are the partial capture's own, found again.

    A resume takes only the stops that come after the partial's last one. A source may reach back
    over the partial (the same recording again, the sim replaying the plan from its first step):
    its stops up to the partial's last are then the partial's, each found again where and when the
    partial took it (its start within a tenth of a window, its position within the stability), with
    the ends of overrun moves between them. A source whose first stop is none of the partial's goes
    on after it (the rest of the run, its clock going on or started again) and every stop is taken.
    """

    def __init__(self, steps: PlanSteps, readings: Sequence[StopReading], settings: CaptureSettings):
        self.start_s = np.array([r.start_s for r in readings])
        self.position_m = np.array([steps.target_m[r.index] + r.deviation_m for r in readings])
        self.settings = settings
        # where the overrun moves up to the partial's last step end (a stop there is passed over either way)
        upto = readings[-1].index + 1 if readings else 0
        self.overrun_m = steps.move_to_m[:upto][~np.isfinite(steps.target_m[:upto])]
        self.target_m = steps.target_m[np.isfinite(steps.target_m)]
        # the next stop starts a whole window after the partial's last at the earliest
        self.after_s = readings[-1].start_s + settings.window_s / 2 if readings else -math.inf
        self.matched = 0
        self.over = not readings

    def beyond(self, start_s: float) -> bool:
        """Whether a stop that began at ``start_s`` cannot be one the partial holds."""
        return self.over or start_s > self.after_s

    def passes_over(self, stop: Stop) -> bool:
        """Whether ``stop`` is the partial's (or lies among its stops, in a source that replays them)."""
        if self.beyond(stop.start_s):
            self.over = True
            return False
        if stop.first_index == 0:
            return False  # where the axis stood when the source began: the walk passes it over
        w = self.settings
        same = (np.abs(self.start_s - stop.start_s) <= w.window_s / 10) & \
            (np.abs(self.position_m - (stop.value_m - w.offset_m)) <= w.stability_m)
        if same.any():
            self.matched += 1
            self.over = bool(same[-1])  # the partial's last: the stops after it are the run's
            return True
        if self.matched:
            return True  # between the partial's stops (the end of an overrun move)
        position = stop.value_m - w.offset_m
        overrun = np.abs(self.overrun_m - position).min(initial=np.inf)
        if overrun <= w.tolerance_m and overrun < np.abs(self.target_m - position).min():
            return True  # the end of an overrun move (nearer than any target), before the first of them
        self.over = True
        return False


def _recording_source(recording: Any, unit: str | None, channel: str | None) -> Recording | Any:
    if isinstance(recording, Recording):
        return recording
    if isinstance(recording, (str, Path)):
        return read_recording(recording, unit=unit, channel=channel)
    if callable(getattr(recording, "read", None)) and hasattr(recording, "channels"):
        return recording
    raise AxiscalError(f"recording must be a Recording, a recording's path or a live source, not {type(recording).__name__}")


def _feed_recording(recording: Recording, detector: StopDetector, take: Callable[[Stop], None]) -> None:
    for stop in detector.feed(recording.time_s, recording.reading_m, recording.channels):
        take(stop)
    for stop in detector.finish():
        take(stop)


def _feed_source(source: Any, detector: StopDetector, take: Callable[[Stop], None], channel: str | None, unit: str | None,
                 done: Callable[[], bool], last_step: Callable[[], bool], report: Callable[[float, bool], None],
                 timeout_s: float | None) -> None:
    names = tuple(source.channels)
    if channel is None:
        lengths = [n for n in names if split_unit(n)[1] in READING_UNITS and n not in detector.channels]
        if len(lengths) != 1:
            raise AxiscalError(f"channel must name the channel that holds the reading: the source has {', '.join(names) or 'none'}")
        channel = lengths[0]
    if channel not in names:
        raise AxiscalError(f"the source has no channel '{channel}' (it has {', '.join(names)})")
    named = split_unit(channel)[1]
    factor = READING_UNITS.get(named) or (READING_UNITS.get(unit) if unit else None)
    if factor is None:
        raise AxiscalError(f"unit must be given (mm, um, nm, m or in): channel {channel} does not say its unit")
    column = names.index(channel)
    env_columns = [names.index(n) for n in detector.channels]
    import time

    began = time.monotonic()
    while not done():
        batch = source.read(0.05)
        if len(batch):
            good = ~batch.malformed
            t, values = batch.t_s[good], batch.values[good]
            reading = values[:, column] * factor
            for stop in detector.feed(t, reading, {n: values[:, c] for n, c in zip(detector.channels, env_columns)}):
                take(stop)
            if reading.size:
                report(float(reading[-1]), detector.holding)
            if last_step() and detector.held_s >= detector.window_s and not detector.standing_start:
                # the plan's last stop: nothing moves the axis on, so it is taken once it has held a
                # whole window after first holding still (the mean of its last window); not where the
                # axis stood when the stream began (a stop it has not come to)
                for stop in detector.finish():
                    take(stop)
        if getattr(source, "finished", False):
            break
        if timeout_s is not None and time.monotonic() - began > timeout_s:
            break
    if not done():
        for stop in detector.finish():
            take(stop)


def capture(
    plan: PositioningTestPlan | PlanSteps | str | Path,
    recording: Recording | str | Path | Any,
    *,
    settings: CaptureSettings | None = None,
    unit: str | None = None,
    channel: str | None = None,
    environment: Sequence[str] | None = None,
    resumed: Sequence[StopReading] = (),
    on_stop: Callable[[StopReading], None] | None = None,
    progress: Callable[[CaptureProgress], None] | None = None,
    timeout_s: float | None = None,
) -> Capture:
    """Walk a plan through a recording or a live source and take the reading at every stop.

    Parameters
    ----------
    plan : PositioningTestPlan, PlanSteps, str or Path
        The plan, or its cycle CSV as ``axiscal plan`` writes it.
    recording : Recording, str, Path or a live source
        A recording (:func:`~axiscal.capture.recording.read_recording`), its file, or a source of
        :mod:`axiscal.live.sources` (read until every stop is taken or it finishes).
    settings : CaptureSettings, optional, keyword-only
        Stability, window, tolerance and offset (defaults: 1 um, 0.5 s, 0.5 mm, 0).
    unit, channel : str, optional, keyword-only
        Unit and column (channel) of the reading, for a file or a source (see :func:`read_recording`).
    environment : sequence of str, optional, keyword-only
        The environment channels of a live source to average over each stop (default: those of its
        channels named as air and material sensors).
    resumed : sequence of StopReading, keyword-only
        Stops already taken (a resumed capture): the plan goes on after the last, with the stops of
        the source that come after it. A source that reaches back over them (the same recording
        again, the sim replaying the plan) is known by its stops found again where and when they
        were taken, and passed over up to the last.
    on_stop : callable, optional, keyword-only
        Called with each new StopReading as it is taken (the partial file's writer).
    progress : callable, optional, keyword-only
        Called with a :class:`CaptureProgress` as a live source's batches arrive.
    timeout_s : float, optional, keyword-only
        Longest a live source is read, seconds (default: until done or finished).

    Returns
    -------
    Capture

    Raises
    ------
    AxiscalError
        One line naming the step, its target, run and direction, for a stop elsewhere, a missing
        stop, an approach in the other direction, or a recording that ends before the last step;
        for a window longer than the recording; and whatever the recording's reader or the plan's
        refuse.
    """
    settings = CaptureSettings() if settings is None else check_instance("settings", settings, CaptureSettings)
    steps = plan if isinstance(plan, PlanSteps) else plan_steps(plan)
    source = _recording_source(recording, unit, channel)
    live = not isinstance(source, Recording)
    if live:
        names = tuple(environment) if environment is not None else environment_columns(source.channels)
        description = getattr(getattr(source, "status", None), "description", type(source).__name__)
    else:
        names = tuple(source.channels)
        description = source.source
        duration = float(source.time_s[-1] - source.time_s[0]) if source.time_s.size else 0.0
        if settings.window_s > duration:
            raise AxiscalError(f"window_s {settings.window_s:.6g} s is longer than the recording ({duration:.6g} s): no stop"
                               " can hold still for a whole window", path=description)
    readings = list(resumed)
    start = readings[-1].index + 1 if readings else 0
    replay = _Replay(steps, readings, settings)
    if readings and not live:
        stated = tuple(readings[0].channels)
        if set(stated) != set(names):
            raise AxiscalError(f"the partial capture carries the sensors {', '.join(stated) or 'none'}, the recording"
                               f" {', '.join(names) or 'none'}: resume with a recording of the same kind", path=description)

    def locate(stop: Stop) -> tuple[str | None, int | None]:
        return description, (None if live else source.line_of(stop.first_index))

    matcher = StepMatcher(steps, tolerance_m=settings.tolerance_m, offset_m=settings.offset_m, start=start, locate=locate)
    detector = StopDetector(stability_m=settings.stability_m, window_s=settings.window_s, channels=names)

    faults_of = getattr(source, "faults_between", None) if live else None

    def take(stop: Stop) -> None:
        if replay.passes_over(stop):
            return  # a stop the partial capture holds, the source replaying it
        if matcher.done and stop.first_index != 0:
            return  # the axis may go on moving after the plan's last step (back home): not a reading
        taken = matcher.take(stop)
        if taken is None:
            return
        if faults_of is not None:  # an instrument's fault inside the stop's window refuses the stop
            inside = faults_of(stop.end_s - settings.window_s, stop.end_s)
            if inside:
                raise AxiscalError(f"{steps.describe(taken.index)}: the stop's window holds a fault of {description}:"
                                   f" {inside[0].message} (at {inside[0].time_s:.3f} s)")
        sensors = {name: value for name, value in stop.channels.items() if np.isfinite(value)}
        reading = StopReading(taken.index, taken.deviation_m, stop.start_s, stop.std_m, stop.samples, sensors)
        readings.append(reading)
        if on_stop is not None:
            on_stop(reading)

    def report(last_m: float, still: bool) -> None:
        if progress is None:
            return
        k = matcher.next_index
        progress(CaptureProgress(matcher.taken, steps.readings, None if k is None else int(steps.step[k]),
                                 math.nan if k is None else float(steps.target_m[k]), last_m - settings.offset_m, still,
                                 detector.samples))

    if live:
        def last_step() -> bool:
            # the stop in progress may be the plan's last: not one a resume passes over
            return matcher.next_index is not None and matcher.taken == steps.readings - 1 and replay.beyond(detector.start_s)

        _feed_source(source, detector, take, channel, unit, lambda: matcher.done, last_step, report, timeout_s)
    else:
        _feed_recording(source, detector, take)
    if not matcher.done:
        raise matcher.missing(description)
    header = {} if live else dict(source.header)
    carried = tuple(name for name in names if any(name in r.channels for r in readings))
    for r in readings:
        lacking = [name for name in carried if name not in r.channels]
        if lacking:
            raise AxiscalError(f"{steps.describe(r.index)}: no {', '.join(lacking)} reading over its window (the sensor"
                               " dropped out): the run's air compensation needs it at every stop", path=description)
    return Capture(steps, tuple(readings), settings, description, carried, header)


def capture_run(plan, recording, **options) -> PositioningRun:
    """The positioning run captured from a recording or a live source: :func:`capture` ``(...).run``.

    Parameters
    ----------
    plan, recording, **options
        As :func:`capture` takes them.

    Returns
    -------
    PositioningRun
        Deviations per target and run, metres (compensated for the air where sensors were recorded).

    Raises
    ------
    AxiscalError
        As :func:`capture`.

    Examples
    --------
    >>> run = capture_run("plan.csv", "recording.csv")  # doctest: +SKIP
    >>> run.runs  # doctest: +SKIP
    5
    """
    return capture(plan, recording, **options).run
