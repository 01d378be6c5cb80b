"""A positioning run driven by axiscal itself: the controller moves the axis to each step, the instrument reads it.

For every step of the plan in order (the overrun moves included) the axis alone makes an absolute
move; once the controller reports the move done, the instrument's reading is taken over the dwell:
the value of a step with a target is the mean over the last ``window_s`` of ``dwell_s`` (counted from
the move-done report). Where that window does not hold still (its peak to peak above the stability),
the window slides on, sample by sample, until it does, for at most ``max(10 window, 5 s)`` more; then the
run stops naming the step. A window that holds a fault of the instrument's stream (a sequence gap, a line
that is no reading) refuses its step; a fault outside every window is reported and the run goes on.
The deviation is ``(reading - offset) - target``, the air channels averaged over the same window; a reading
farther than the settings' tolerance from its target stops the run naming the step (as a capture refuses a
stop elsewhere): it is not the axis at that target but the wrong unit, scale or offset. The
result is a :class:`~axiscal.capture.run.Capture`, written to files exactly as ``axiscal capture`` writes it.

Before the first move every position of the plan is checked against the controller's soft limits
(where it can tell them) and the controller must say it is ready (homed, not in e-stop, alarm or
error). A resumed run drives the axis first to where the first missing step's approach begins (the
previous step's position), then goes on.
"""

from __future__ import annotations

import math
import threading
import time
from collections.abc import Callable, Sequence
from dataclasses import dataclass

import numpy as np

from axiscal.capture.run import Capture, CaptureProgress, CaptureSettings, StopReading
from axiscal.capture.steps import PlanSteps, _mm
from axiscal.errors import AxiscalError
from axiscal.io.arguments import check_count, check_instance, type_name
from axiscal.io.gcode.writer import MAX_FEED_MM_MIN
from axiscal.units import MM, UM

__all__ = ["DriveSettings", "InstrumentReader", "planned_moves", "drive_plan"]


def _check_device(name: str, value, methods: tuple[str, ...], what: str):
    """A controller or a source: an object with the methods the run calls, else refused naming the argument."""
    if not all(callable(getattr(value, m, None)) for m in methods):
        raise AxiscalError(f"{name} must be {what} (with {', '.join(methods)}), not {type_name(value)}")
    return value


@dataclass(frozen=True)
class DriveSettings:
    """How the axis is driven (SI units).

    Attributes
    ----------
    axis : str
        The axis moved (``X``).
    feed_m_per_s : float, m/s
        Feed of every move (default 1000 mm/min; at most 100 000 mm/min).
    dwell_s : float, seconds
        Dwell after each move-done report (default 1 s); the value is the mean of its last window.
    """

    axis: str = "X"
    feed_m_per_s: float = 1.0 / 60.0
    dwell_s: float = 1.0

    def __post_init__(self) -> None:
        if not isinstance(self.axis, str) or len(self.axis.strip()) != 1 or not self.axis.strip().isalpha():
            raise AxiscalError(f"axis must be one axis letter (X, Y, Z ...), not {self.axis!r}")
        if not (isinstance(self.feed_m_per_s, float) and math.isfinite(self.feed_m_per_s)
                and 0 < self.feed_m_per_s <= MAX_FEED_MM_MIN * MM / 60.0):
            raise AxiscalError(f"feed must be a positive speed of at most {MAX_FEED_MM_MIN:.0f} mm/min (what a control's F word"
                               f" holds), not {self.feed_m_per_s!r} m/s")
        if not (isinstance(self.dwell_s, float) and math.isfinite(self.dwell_s) and 0 < self.dwell_s <= 3600):
            raise AxiscalError(f"dwell must be a time between 0 and 3600 s, not {self.dwell_s!r}")


class InstrumentReader:
    """Reads an instrument source on a thread from start to close, keeping every sample.

    Parameters
    ----------
    source : an instrument or live source
    channel : int
        Column of the reading in the source's channels (millimetres).
    environment : sequence of str
        Air and material channels averaged over each window.
    """

    def __init__(self, source, *, channel: int = 0, environment: Sequence[str] = ()):
        self.source = _check_device("source", source, ("read", "close"), "an instrument or live source")
        names = tuple(getattr(source, "channels", ()))
        check_count("channel", channel, minimum=0, maximum=max(len(names) - 1, 0))
        if isinstance(environment, str) or any(n not in names for n in environment):
            raise AxiscalError(f"environment must name channels of the source ({', '.join(names)}), not {environment!r}")
        self.channel = channel
        self.environment = tuple(environment)
        self._env_index = [names.index(n) for n in self.environment]
        self._t: list[np.ndarray] = []
        self._x: list[np.ndarray] = []
        self._env: list[np.ndarray] = []
        self._bad: list[np.ndarray] = []
        self.count = 0
        self.error: BaseException | None = None
        self._lock = threading.Lock()
        self._arrived = threading.Condition(self._lock)
        self._stop = threading.Event()
        self._thread = threading.Thread(target=self._run, name="instrument-reader", daemon=True)
        self.last_m = math.nan
        #: the computer's monotonic clock less the instrument's time, smallest seen (the batch that arrived soonest)
        self.clock_offset_s = math.inf

    def start(self) -> "InstrumentReader":
        self._thread.start()
        return self

    def _run(self) -> None:
        try:
            while not self._stop.is_set():
                batch = self.source.read(0.05)
                if len(batch):
                    self.clock_offset_s = min(self.clock_offset_s, time.monotonic() - float(batch.t_s[-1]))
                    x = batch.values[:, self.channel] * MM
                    env = batch.values[:, self._env_index] if self._env_index else np.empty((len(batch), 0))
                    with self._arrived:
                        self._t.append(np.asarray(batch.t_s, dtype=float))
                        self._x.append(x)
                        self._env.append(env)
                        self._bad.append(np.asarray(batch.malformed, dtype=bool) | ~np.isfinite(x))
                        self.count += len(batch)
                        finite = x[np.isfinite(x)]
                        if finite.size:
                            self.last_m = float(finite[-1])
                        self._arrived.notify_all()
                if getattr(self.source, "finished", False):
                    with self._arrived:
                        self._arrived.notify_all()
                    return
        except BaseException as exc:  # handed to the driving thread
            with self._arrived:
                self.error = exc
                self._arrived.notify_all()

    def close(self) -> None:
        self._stop.set()
        self._thread.join(timeout=2)

    def wait_for(self, count: int, timeout_s: float) -> bool:
        """Wait until more than ``count`` samples have arrived; False at the timeout or when the source ended."""
        with self._arrived:
            deadline = time.monotonic() + timeout_s
            while self.count <= count and self.error is None and not getattr(self.source, "finished", False):
                remaining = deadline - time.monotonic()
                if remaining <= 0:
                    return False
                self._arrived.wait(remaining)
            if self.error is not None:
                raise self.error
            return self.count > count

    def wait_until(self, when_s: float, timeout_s: float) -> bool:
        """Wait until a sample taken at ``when_s`` or later (the computer's monotonic clock) has arrived.

        The instrument's time is put on the computer's clock by :attr:`clock_offset_s`; False at the
        timeout or when the source ended first.
        """
        deadline = time.monotonic() + timeout_s
        with self._arrived:
            while True:
                if self.error is not None:
                    raise self.error
                if self._t and self._t[-1].size and float(self._t[-1][-1]) + self.clock_offset_s >= when_s:
                    return True
                remaining = deadline - time.monotonic()
                if remaining <= 0 or getattr(self.source, "finished", False):
                    return False
                self._arrived.wait(min(remaining, 0.1))

    def since(self, count: int) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
        """Time, reading (metres), environment and no-reading flags of the samples after the first ``count``."""
        with self._lock:
            t = np.concatenate(self._t) if self._t else np.empty(0)
            x = np.concatenate(self._x) if self._x else np.empty(0)
            env = np.concatenate(self._env) if self._env else np.empty((0, len(self.environment)))
            bad = np.concatenate(self._bad) if self._bad else np.empty(0, dtype=bool)
            if len(self._t) > 1:  # keep the concatenation for the next call
                self._t, self._x, self._env, self._bad = [t], [x], [env], [bad]
        return t[count:], x[count:], env[count:], bad[count:]


def planned_moves(steps: PlanSteps, *, start: int = 0) -> list[tuple[int, float, bool]]:
    """The moves a run makes: (step index, position in metres, whether a reading is taken there).

    A resumed run (``start`` > 0) first moves to the previous step's position, where the approach of
    the first missing step begins.

    Parameters
    ----------
    steps : PlanSteps
    start : int, keyword-only
        The first step not yet taken (0-based).

    Returns
    -------
    list of tuple
    """
    check_instance("steps", steps, PlanSteps)
    start = check_count("start", start, minimum=0, maximum=steps.step.size)
    moves: list[tuple[int, float, bool]] = []
    if start > 0:
        moves.append((start - 1, float(steps.move_to_m[start - 1]), False))
    for k in range(start, steps.step.size):
        moves.append((k, float(steps.move_to_m[k]), bool(np.isfinite(steps.target_m[k]))))
    return moves


def _check_limits(steps: PlanSteps, moves, limits: tuple[float, float] | None, description: str) -> None:
    if limits is None:
        return
    low, high = limits
    for k, position, _ in moves:
        if not low - 1e-9 <= position <= high + 1e-9:
            raise AxiscalError(f"{steps.describe(k)}: the move to {position / MM:.4f} mm is beyond the soft limits of "
                               f"{description} ({low / MM:g} .. {high / MM:g} mm): nothing was moved")


def drive_plan(
    steps: PlanSteps,
    controller,
    source,
    *,
    drive: DriveSettings | None = None,
    settings: CaptureSettings | None = None,
    environment: Sequence[str] = (),
    resumed: Sequence[StopReading] = (),
    on_stop: Callable[[StopReading], None] | None = None,
    progress: Callable[[CaptureProgress], None] | None = None,
    on_fault: Callable[[str], None] | None = None,
    before_move: Callable[[], None] | None = None,
) -> Capture:
    """Drive the controller through the plan and take the instrument's reading at every target.

    Parameters
    ----------
    steps : PlanSteps
    controller : a controller of :mod:`axiscal.devices`
    source : an instrument source (``reading_mm`` first) or any live source
    drive : DriveSettings, keyword-only
        Axis, feed and dwell.
    settings : CaptureSettings, keyword-only
        Stability and window of a reading, and the offset (the reading at the datum).
    environment : sequence of str, keyword-only
        The source's air and material channels to average over each window.
    resumed : sequence of StopReading, keyword-only
        Steps already taken (a resumed run goes on after the last).
    on_stop : callable, keyword-only
        Called with each StopReading as it is taken (the partial file's writer).
    progress : callable, keyword-only
        Called with a :class:`~axiscal.capture.run.CaptureProgress` as the run goes.
    on_fault : callable, keyword-only
        Called with each fault of the instrument outside every window (reported, the run goes on).
    before_move : callable, keyword-only
        Called before each move: it may wait (a pause between steps) or raise AxiscalError (an abort).

    Returns
    -------
    Capture

    Raises
    ------
    AxiscalError
        One line naming the step for a move beyond the soft limits (before anything moves), a
        controller that is not ready, refuses a move or stops answering, a reading that does not hold
        still or is not within the tolerance of its target, or a fault inside a window; the readings
        taken before are kept (``on_stop``).
    """
    check_instance("steps", steps, PlanSteps)
    _check_device("controller", controller, ("check_ready", "limits", "move_to", "stop"), "a controller")
    _check_device("source", source, ("read", "close"), "an instrument or live source")
    drive = DriveSettings() if drive is None else check_instance("drive", drive, DriveSettings)
    settings = CaptureSettings() if settings is None else check_instance("settings", settings, CaptureSettings)
    readings = list(resumed)
    start = readings[-1].index + 1 if readings else 0
    moves = planned_moves(steps, start=start)
    axis = drive.axis.strip().upper()
    description = getattr(getattr(source, "status", None), "description", "the instrument")
    _check_limits(steps, moves, controller.limits(axis), controller.description)
    controller.check_ready(axis)
    reader = InstrumentReader(source, channel=0, environment=environment).start()
    window_s, dwell_s = settings.window_s, max(drive.dwell_s, settings.window_s)
    slide_s = max(10.0 * window_s, 5.0)
    reported = 0
    faults_of = getattr(source, "faults_between", None)
    all_faults = getattr(source, "faults", ())

    def report(k: int | None, still: bool) -> None:
        if progress is None:
            return
        taken = len(readings)
        progress(CaptureProgress(taken, steps.readings, None if k is None else int(steps.step[k]),
                                 math.nan if k is None else float(steps.target_m[k]), reader.last_m - settings.offset_m,
                                 still, reader.count))

    def settle(k: int) -> StopReading:
        mark = reader.count
        if not reader.wait_for(mark, 2.0 + dwell_s):
            raise AxiscalError(f"{steps.describe(k)}: no reading from {description} since the move ended"
                               f" ({getattr(getattr(source, 'status', None), 'message', '') or 'it went silent'})")
        t, x, env, bad = reader.since(mark)
        began = t[0]
        deadline = began + dwell_s + slide_s
        while True:
            last = t[-1]
            if last >= began + dwell_s - 1e-9:
                inside = t >= last - window_s - 1e-9
                xs, flagged = x[inside], bad[inside]
                if faults_of is not None:
                    window_faults = faults_of(float(t[inside][0]), float(last))
                    if window_faults:
                        raise AxiscalError(f"{steps.describe(k)}: the reading's window holds a fault of {description}:"
                                           f" {window_faults[0].message} (at {window_faults[0].time_s:.3f} s)")
                if flagged.any():
                    raise AxiscalError(f"{steps.describe(k)}: the reading's window holds samples that are no reading")
                ptp = float(np.ptp(xs)) if xs.size else math.inf
                if xs.size >= 2 and ptp <= settings.stability_m:
                    mean = float(np.mean(xs))
                    position = mean - settings.offset_m
                    if not abs(position - float(steps.target_m[k])) <= settings.tolerance_m:
                        raise AxiscalError(f"{steps.describe(k)}: the instrument reads {_mm(position, 4)} mm there (less"
                                           f" offset_m {settings.offset_m / MM:g} mm), not within tolerance_m"
                                           f" {settings.tolerance_m / MM:g} mm of the target: check the instrument's unit"
                                           " and scale and the reading at the datum; the steps before are kept")
                    channels = {}
                    for j, name in enumerate(environment):
                        values = env[inside, j]
                        values = values[np.isfinite(values)]
                        if values.size:
                            channels[name] = float(np.mean(values))
                    return StopReading(k, (mean - settings.offset_m) - float(steps.target_m[k]), float(t[inside][0]),
                                       float(np.std(xs, ddof=1)), int(xs.size), channels)
                if last > deadline:
                    raise AxiscalError(f"{steps.describe(k)}: the reading did not hold still within {settings.stability_m / UM:g} um"
                                       f" over {window_s:g} s in {dwell_s + slide_s:g} s after the move (last peak to peak"
                                       f" {ptp / UM:.3g} um): check the set-up, or raise stability_m or dwell_s")
            report(k, False)
            count = mark + t.size
            if not reader.wait_for(count, 2.0):
                raise AxiscalError(f"{steps.describe(k)}: {description} stopped streaming during the dwell"
                                   f" ({getattr(getattr(source, 'status', None), 'message', '') or 'no samples'})")
            t, x, env, bad = reader.since(mark)

    try:
        for k, position, reading in moves:
            report(k if reading else None, False)
            if before_move is not None:
                before_move()
            controller.move_to(axis, position, drive.feed_m_per_s)
            if not reading:
                continue
            taken = settle(k)
            readings.append(taken)
            if on_stop is not None:
                on_stop(taken)
            report(k, True)
            if on_fault is not None:
                faults = source.faults if hasattr(source, "faults") else all_faults
                for fault in faults[reported:]:
                    on_fault(f"{fault.message} at {fault.time_s:.3f} s (outside every window: the run goes on)")
                reported = len(faults)
    except KeyboardInterrupt:
        controller.stop()
        raise
    finally:
        reader.close()
    report(None, True)
    return Capture(steps, tuple(readings), settings, description,
                   tuple(n for n in environment if any(n in r.channels for r in readings)), {})
