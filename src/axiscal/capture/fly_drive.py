"""``axiscal run --on-the-fly``: the axis driven through the targets without stopping, both streams recorded.

Each pass of the plan (every run, each way) is one move from the overrun before its first target to past
its last, at the feed asked; meanwhile the instrument's reading (on its own clock) and the controller's
position (asked as fast as it answers, on the computer's clock) are recorded, from the axis standing before
the first pass until the instrument's samples (late by the link and the computer's load) reach past the end of
the last, so the recording covers every pass it evaluates. The instrument's clock is
put on the computer's by the batch that arrived soonest after its last sample (its time of arrival less
its last sample's time, the smallest over the run); what delay is left between the streams is estimated
from the forward and backward passes and removed by :func:`axiscal.capture.on_the_fly.on_the_fly`, which
takes each target's reading where the position stream crosses it.
"""

from __future__ import annotations

import math
import threading
import time
from collections.abc import Callable, Sequence
from pathlib import Path

import numpy as np

from axiscal.capture.drive import DriveSettings, InstrumentReader, _check_device, _check_limits
from axiscal.capture.on_the_fly import FlyRecording, OnTheFly, on_the_fly_to_file
from axiscal.capture.steps import PlanSteps, plan_steps
from axiscal.errors import AxiscalError
from axiscal.io.arguments import check_instance, check_number, check_path
from axiscal.io.tabular import write_csv
from axiscal.units import MM, UM

__all__ = ["pass_moves", "fly_plan", "FlyFiles", "FLY_AGREEMENT_M", "FLY_SPEED_LIMIT_M_S"]

#: how close on the fly comes to stop and go below :data:`FLY_SPEED_LIMIT_M_S`, metres
FLY_AGREEMENT_M = 1e-6
#: the speed of crossing a target up to which the delay estimate keeps on the fly within
#: :data:`FLY_AGREEMENT_M` of stop and go, m/s: measured on the virtual controller by
#: ``benchmarks/run_on_the_fly_speed.py`` (the median over 3 repeats of the largest difference over 20 crossings:
#: 0.2 um up to 4000 mm/min, then 2.4 um at 6000, 4.8 um at 8000 and 9.1 um at 12 000 mm/min)
FLY_SPEED_LIMIT_M_S = 4000 * MM / 60.0

#: the axis is recorded standing this long before the first pass and after the last, seconds
_STILL_S = 0.2
#: the longest a position answer may take and still be kept (its time is known to half of it), seconds
_SHARP_S = 0.002
#: the longest the instrument's samples may lag behind the motion (a loaded computer, a slow link), seconds
_LATE_S = 5.0


def pass_moves(steps: PlanSteps) -> list[tuple[int, float]]:
    """The moves of an on-the-fly run: where each pass turns, and past the last target at the end.

    Parameters
    ----------
    steps : PlanSteps

    Returns
    -------
    list of (step index, position in metres)
        The first move goes to the plan's first position; each later one to where the travel turns
        (or the plan ends), so the axis passes every target between without stopping. The last move
        goes past the last target by the plan's overrun.
    """
    check_instance("steps", steps, PlanSteps)
    x = steps.move_to_m
    moves = [(0, float(x[0]))]
    for k in range(1, x.size - 1):  # the plan's last position is passed, not stopped at (below)
        if np.sign(x[k + 1] - x[k]) != np.sign(x[k] - x[k - 1]):
            moves.append((k, float(x[k])))
    finite = np.isfinite(steps.target_m)
    overrun = abs(float(x[0] - steps.target_m[finite][0])) if not finite[0] else 0.0
    sign = np.sign(x[-1] - x[-2]) if x.size > 1 else 1.0
    moves.append((x.size - 1, float(x[-1]) + sign * max(overrun, 0.002)))
    return moves


class FlyFiles:
    """What an on-the-fly run wrote.

    Attributes
    ----------
    result : OnTheFly
    run_csv, sidecar, recording_csv : Path
        The run, its sidecar, and the recording of both streams (``time_s, reading_mm,
        position_time_s, position_mm``: what ``axiscal on-the-fly --from`` reads again).
    """

    def __init__(self, result: OnTheFly, run_csv: Path, sidecar: Path, recording_csv: Path):
        self.result, self.run_csv, self.sidecar, self.recording_csv = result, run_csv, sidecar, recording_csv

    @property
    def fastest_m_s(self) -> float:
        """The fastest the axis crossed a target, m/s."""
        speeds = np.abs(self.result.speed_m_s)
        return float(speeds.max()) if speeds.size else 0.0

    @property
    def agreement(self) -> str:
        """The speed up to which on the fly agrees with stop and go, and whether this run stayed below it, in words."""
        limit = FLY_SPEED_LIMIT_M_S / MM * 60
        return (f"the delay estimate keeps on the fly within {FLY_AGREEMENT_M / UM:g} um of stop and go up to {limit:.0f} mm/min"
                f" (measured on the virtual controller); this run crossed its targets at up to {self.fastest_m_s / MM * 60:.0f} mm/min")

    @property
    def warning(self) -> str | None:
        """What to say when a target was crossed faster than :data:`FLY_SPEED_LIMIT_M_S` (None otherwise)."""
        if self.fastest_m_s <= FLY_SPEED_LIMIT_M_S * (1 + 1e-9):
            return None
        return (f"targets crossed at up to {self.fastest_m_s / MM * 60:.0f} mm/min, above the"
                f" {FLY_SPEED_LIMIT_M_S / MM * 60:.0f} mm/min up to which the delay estimate keeps on the fly within"
                f" {FLY_AGREEMENT_M / UM:g} um of stop and go: the readings may be off by several um (a lower feed, or stop"
                " and go, for a figure to trust)")


class _PositionRecorder:
    """Asks the controller its position as fast as it answers, on a thread, with the computer's time."""

    def __init__(self, controller, axis: str, t0: float):
        self.controller, self.axis, self.t0 = controller, axis, t0
        self._t: list[float] = []
        self._x: list[float] = []
        self._took: list[float] = []
        self.error: Exception | None = None
        self._stop = threading.Event()
        self._thread = threading.Thread(target=self._run, name="position-recorder", daemon=True)

    def _run(self) -> None:
        while not self._stop.is_set():
            try:
                before = time.monotonic()
                x = float(self.controller.position(self.axis))
                after = time.monotonic()
            except Exception as exc:  # handed to the driving thread
                self.error = exc
                return
            self._t.append((before + after) / 2 - self.t0)
            self._x.append(x)
            self._took.append(after - before)
            time.sleep(0.001)

    def samples(self) -> tuple[np.ndarray, np.ndarray]:
        """Time (from ``t0``) and position of the answers whose time is sharp.

        An answer is stamped at the middle of its question and its answer, so its time is known to half
        the time it took: one that took longer than 2 ms, or than three times the answers' median (a
        thread held up by a loaded computer: 1 ms is 17 um at 1000 mm/min), is left out.
        """
        took = np.array(self._took)
        if not took.size:
            return np.empty(0), np.empty(0)
        sharp = took <= min(_SHARP_S, max(3.0 * float(np.median(took)), 20e-6))
        return np.array(self._t)[sharp], np.array(self._x)[sharp]

    def __enter__(self) -> "_PositionRecorder":
        self._thread.start()
        return self

    def __exit__(self, *exc) -> None:
        self._stop.set()
        self._thread.join(timeout=3)


def fly_plan(
    plan: str | Path | PlanSteps,
    controller,
    source,
    output: str | Path,
    *,
    drive: DriveSettings | None = None,
    environment: Sequence[str] = (),
    window_s: float = 0.01,
    offset_m: float = 0.0,
    progress: Callable[[int, int], None] | None = None,
) -> FlyFiles:
    """Drive the plan's passes without stopping, record both streams, and capture each target where it is passed.

    Parameters
    ----------
    plan : str, Path or PlanSteps
        The plan (``axiscal plan``; the same plan as a stop-and-go run).
    controller, source :
        An open controller and instrument (:func:`axiscal.capture.connected.open_run_devices`).
    output : str or Path
        The run CSV; the recording of both streams goes beside it (``RUN.recording.csv``).
    drive : DriveSettings, keyword-only
        Axis and feed (the dwell is not used).
    environment : sequence of str, keyword-only
        The source's air and material channels.
    window_s : float, seconds, keyword-only
        The reading's line is fitted over this window about each crossing.
    offset_m : float, metres, keyword-only
        The reading at the datum.
    progress : callable, keyword-only
        Called with (passes done, passes) as the run goes.

    Returns
    -------
    FlyFiles

    Raises
    ------
    AxiscalError
        For a move beyond the soft limits (before anything moves), a controller that is not ready,
        refuses a move or stops answering, an instrument that goes silent, and what
        :func:`~axiscal.capture.on_the_fly.on_the_fly` refuses.
    """
    steps = plan if isinstance(plan, PlanSteps) else plan_steps(plan)
    _check_device("controller", controller, ("check_ready", "limits", "move_to", "position", "stop"), "a controller")
    _check_device("source", source, ("read", "close"), "an instrument or live source")
    drive = DriveSettings() if drive is None else check_instance("drive", drive, DriveSettings)
    output = check_path("output", output)
    window_s = check_number("window_s", window_s, positive=True, high=10.0, unit="s")
    offset_m = check_number("offset_m", offset_m, unit="m")
    axis = drive.axis.strip().upper()
    moves = pass_moves(steps)
    _check_limits(steps, [(k, x, False) for k, x in moves], controller.limits(axis), controller.description)
    controller.check_ready(axis)
    t0 = time.monotonic()
    reader = InstrumentReader(source, environment=environment).start()
    description = str(getattr(getattr(source, "status", None), "description", "the instrument"))
    try:
        controller.move_to(axis, moves[0][1], drive.feed_m_per_s)
        with _PositionRecorder(controller, axis, t0) as positions:
            # the passes begin once the instrument's samples cover the axis standing at the start
            _cover(reader, time.monotonic() + _STILL_S, description, "the start of the first pass")
            for n, (_, x) in enumerate(moves[1:], start=1):
                controller.move_to(axis, x, drive.feed_m_per_s)
                if positions.error is not None:
                    raise AxiscalError(f"{controller.description} stopped answering its position: {positions.error}")
                if progress is not None:
                    progress(n, len(moves) - 1)
            # the recording ends once the instrument's samples (late by the link and the load) reach past the motion
            _cover(reader, time.monotonic() + _STILL_S, description, "the end of the last pass")
        if reader.error is not None:
            raise reader.error
    except KeyboardInterrupt:
        controller.stop()
        raise
    finally:
        reader.close()
    t, x, env, bad = reader.since(0)
    keep = ~bad & np.isfinite(x)
    position_t, position_x = positions.samples()
    if keep.sum() < 4 or position_t.size < 4 or not math.isfinite(reader.clock_offset_s):
        raise AxiscalError(f"too few readings from {source.status.description if hasattr(source, 'status') else 'the instrument'}"
                           f" ({int(keep.sum())}) or positions ({position_t.size}) to capture on the fly")
    time_s = t[keep] + reader.clock_offset_s - t0  # the instrument's samples on the computer's clock
    recording = FlyRecording(time_s, x[keep], position_t, position_x,
                             {n: env[keep, j] for j, n in enumerate(environment) if np.isfinite(env[keep, j]).all()},
                             source=str(getattr(getattr(source, "status", None), "description", "the instrument")))
    recording_csv = output.with_name(output.stem + ".recording.csv")
    write_csv(recording_csv, _recording_columns(recording), fmt={"time_s": "{:.6f}", "reading_mm": "{:.7f}"})
    result, run_csv, sidecar = on_the_fly_to_file(steps, recording, output, window_s=window_s, offset_m=offset_m)
    return FlyFiles(result, run_csv, sidecar, recording_csv)


def _cover(reader: InstrumentReader, when_s: float, description: str, what: str) -> None:
    """Wait until the instrument's samples reach ``when_s`` (monotonic clock), else refuse naming ``what``."""
    if not reader.wait_until(when_s, _STILL_S + _LATE_S):
        raise AxiscalError(f"{description}'s samples did not reach {what} within {_LATE_S:g} s (a stream that stopped or"
                           " fell behind): nothing was captured; run it again")


def _recording_columns(recording: FlyRecording) -> dict[str, np.ndarray]:
    """The laser's samples with the position stream interpolated onto them (one time line, as a file holds it)."""
    position = np.interp(recording.time_s, recording.position_time_s, recording.position_m)
    return {"time_s": recording.time_s, "reading_mm": recording.reading_m / MM, "position_mm": position / MM,
            **{n: v for n, v in recording.channels.items()}}
