"""The live loop: frames from a source through ``MeasurementSystem.process`` to the record and the dashboard.

One batch at a time (whatever the source has, at most its batch limit): process, flag faults
(``MeasurementSystem`` bits plus ``Fault.MALFORMED`` of :class:`~axiscal.measurement.faults.Fault`), append frames and
results to the :class:`~axiscal.live.recorder.Recorder`, fold them into the
:class:`~axiscal.live.state.LiveState`. A faulty frame is kept in the record with NaN results; it
never stops the run. The loop is bounded: it ends when ``stop`` is set, ``duration_s`` has passed
or a finite source is exhausted.

Latency: for sources that know their clock (``clock_offset_s``), the delay of each frame from
its time stamp to the moment its result was written to the record is kept in a fixed ring
(:meth:`Pipeline.latencies_s`).
"""

from __future__ import annotations

import gc
import sys
import threading
import time
from collections.abc import Callable
from dataclasses import dataclass

import numpy as np

from axiscal.errors import AxiscalError
from axiscal.io.arguments import check_count, check_number
from axiscal.io.arguments import check_instance, type_name
from axiscal.live.protocol import FrameBatch
from axiscal.live.recorder import Recorder
from axiscal.live.state import LiveState, result_columns
from axiscal.measurement.display import to_display
from axiscal.measurement.faults import mark_malformed
from axiscal.measurement.pipeline import MeasurementSystem

#: seconds per millisecond (delays are shown in ms)
MS = 1e-3
#: longest a thread keeps the interpreter lock while the loop waits for it, during a run, s
SWITCH_INTERVAL_S = 0.0005

__all__ = ["RunSummary", "Pipeline"]


@dataclass(frozen=True)
class RunSummary:
    """What a run did.

    Attributes
    ----------
    frames, faults, batches : int
        Frames processed, faulty frames, batches.
    elapsed_s : float
        Wall time, s.
    frames_written, frames_acknowledged : int
        Frames handed to the record and made durable.
    latency_p50_ms, latency_p99_ms, latency_max_ms : float
        Delay from time stamp to record, ms (NaN for sources without a clock).
    source_state : str
        The source's state at the end.
    """

    frames: int
    faults: int
    batches: int
    elapsed_s: float
    frames_written: int
    frames_acknowledged: int
    latency_p50_ms: float
    latency_p99_ms: float
    latency_max_ms: float
    source_state: str

    def progress_text(self, rate_hz: float, *, label: str = "live") -> str:
        """One status line: elapsed time, frames, rate, faults, record counts, delay and source state.

        Parameters
        ----------
        rate_hz : float
            The frame rate to show, Hz.
        label : str
            First word (``"live"`` while running, ``"done"`` at the end).

        Returns
        -------
        str
        """
        record = f"  recorded {self.frames_acknowledged}/{self.frames_written}" if self.frames_written or self.frames_acknowledged else ""
        delay = f"  delay p99 {self.latency_p99_ms:.2f} ms" if self.latency_p99_ms == self.latency_p99_ms else ""
        return (
            f"{label} {self.elapsed_s:6.1f} s  frames {self.frames}  rate {rate_hz:.0f} Hz  faults {self.faults}"
            f"{record}{delay}  source {self.source_state}"
        )

    @property
    def mean_rate_hz(self) -> float:
        """Frames per second over the whole run (0 before any time has passed)."""
        return self.frames / self.elapsed_s if self.elapsed_s > 0 else 0.0


class Pipeline:
    """Run frames from ``source`` through ``system`` into ``recorder`` and ``state``.

    Parameters
    ----------
    system : MeasurementSystem
        The measurement chain (:mod:`axiscal.measurement.pipeline`).
    source : source object
        See :mod:`axiscal.live.sources`.
    recorder : Recorder, optional
        Where frames and results are appended.
    state : LiveState, optional
        What a dashboard reads.
    latency_capacity : int
        Frames whose delay is kept (the most recent ones).
    batch_interval_s : float
        Shortest time between two reads of the source, s (0 to 0.1): the frames that arrive
        meanwhile make one batch. Every batch costs the measurement chain a fixed time (about
        0.3-0.7 ms on a 2-core laptop) besides its frames; reading again as soon as one frame is
        there keeps a core busy at 10 kHz, and a real-time thread that never rests is stopped by
        the kernel for 50 ms each second (``sched_rt_runtime_us``). 2 ms holds the loop near half
        a core and adds at most that to a frame's delay.

    Raises
    ------
    AxiscalError
        For a ``system`` that is not a measurement system, a ``source``, ``recorder`` or
        ``state`` of the wrong kind, a ``latency_capacity`` below 1; :meth:`run` for a bad
        ``duration_s``, ``progress`` or ``progress_interval_s``.
    """

    def __init__(
        self,
        system,
        source,
        *,
        recorder: Recorder | None = None,
        state: LiveState | None = None,
        latency_capacity: int = 1 << 20,
        batch_interval_s: float = 0.002,
    ):
        if not isinstance(system, MeasurementSystem) and not (hasattr(system, "channels") and hasattr(system, "axes")):
            raise AxiscalError(f"system must be a MeasurementSystem, not {type_name(system)}")
        if source is not None:  # None: a pipeline only fed by process() (checked again by run())
            _check_source(source)
        if recorder is not None:
            check_instance("recorder", recorder, Recorder)
        if state is not None:
            check_instance("state", state, LiveState)
        latency_capacity = check_count("latency_capacity", latency_capacity)
        self.batch_interval_s = check_number("batch_interval_s", batch_interval_s, low=0.0, high=0.1)
        self._next_read = 0.0
        self.system = system
        self.source = source
        self.recorder = recorder
        self.state = state
        self.channels = tuple(system.channels)
        self.result_columns = result_columns(tuple(system.axes))
        self.frames = 0
        self.faults = 0
        self.batches = 0
        self._latency = np.empty(latency_capacity)
        self._latency_count = 0
        #: the loop's scheduling priority in words (:mod:`axiscal.live.priority`), shown on the dashboard
        self.priority = ""

    def process(self, batch: FrameBatch) -> tuple[np.ndarray, dict[str, np.ndarray]]:
        """Process one batch.

        Parameters
        ----------
        batch : FrameBatch
            Frames as a source delivers them.

        Returns
        -------
        fault : ndarray of int64, shape (N,)
            Fault bits (:class:`~axiscal.measurement.faults.Fault`), 0 = good.
        results : dict of str to ndarray, shape (N,)
            The SI result columns of :meth:`MeasurementSystem.process` (NaN where faulty).
        """
        results = self.system.process(batch.frames(self.channels))
        return mark_malformed(results, batch.malformed)

    def step(self, timeout_s: float = 0.02) -> int:
        """Read what the source has, process and record it.

        Parameters
        ----------
        timeout_s : float
            Longest wait for frames, s.

        Returns
        -------
        int
            Frames handled (0 when none came).
        """
        now = time.monotonic()
        if now < self._next_read:  # frames arriving meanwhile join this batch
            time.sleep(self._next_read - now)
            now = self._next_read
        batch = self.source.read(timeout_s)
        n = len(batch)
        if n == 0:
            return 0
        self._next_read = now + self.batch_interval_s
        fault, results = self.process(batch)
        shown = to_display(results)  # the record and the dashboard show um, mm and urad
        if self.recorder is not None:
            self.recorder.append(batch.t_s, batch.values, fault, shown)
        offset = self.source.clock_offset_s
        if offset is not None:
            self._keep_latency(time.monotonic() - (batch.t_s + offset))
        if self.state is not None:
            self.state.update(batch, fault, shown)
        self.frames += n
        self.faults += int(np.count_nonzero(fault))
        self.batches += 1
        return n

    def _keep_latency(self, delays: np.ndarray) -> None:
        delays = delays[np.isfinite(delays)]
        size = len(self._latency)
        delays = delays[-size:]
        start = self._latency_count % size
        first = min(len(delays), size - start)
        self._latency[start : start + first] = delays[:first]
        self._latency[: len(delays) - first] = delays[first:]
        self._latency_count += len(delays)

    def latencies_s(self, last: int | None = None) -> np.ndarray:
        """Delays from time stamp to record of the most recent frames, oldest first.

        Parameters
        ----------
        last : int, optional
            At most this many (None: all kept).

        Returns
        -------
        ndarray
            Delays, s.
        """
        size = len(self._latency)
        count = min(self._latency_count, size if last is None else min(last, size))
        end = self._latency_count % size
        if count <= end:
            return self._latency[end - count : end].copy()
        return np.concatenate([self._latency[size - (count - end) :], self._latency[:end]])

    def summary(self, elapsed_s: float, *, recent: int | None = None) -> RunSummary:
        """The run so far.

        Parameters
        ----------
        elapsed_s : float
            Wall time of the run, s.
        recent : int, keyword-only
            Delay percentiles over the last ``recent`` frames (None: all kept).

        Returns
        -------
        RunSummary
        """
        delays = self.latencies_s(recent) / MS
        p50, p99, worst = (np.percentile(delays, [50, 99, 100]) if len(delays) else (np.nan, np.nan, np.nan))
        return RunSummary(
            frames=self.frames,
            faults=self.faults,
            batches=self.batches,
            elapsed_s=elapsed_s,
            frames_written=self.recorder.frames_written if self.recorder else 0,
            frames_acknowledged=self.recorder.frames_acknowledged if self.recorder else 0,
            latency_p50_ms=float(p50),
            latency_p99_ms=float(p99),
            latency_max_ms=float(worst),
            source_state=self.source.status.state,
        )

    def publish_status(self) -> None:
        """Put source, record and delay figures into the state's snapshot (the dashboard's header)."""
        if self.state is None:
            return
        status = self.source.status
        delays = self.latencies_s(20000) / MS
        self.state.extra = {
            "source": {"description": status.description, "state": status.state, "connections": status.connections, "retries": status.retries, "message": status.message},
            "record": None
            if self.recorder is None
            else {"path": str(self.recorder.path), "written": self.recorder.frames_written, "acknowledged": self.recorder.frames_acknowledged},
            "priority": self.priority,
            "latency_ms": None if not len(delays) else {"p50": round(float(np.percentile(delays, 50)), 3), "p99": round(float(np.percentile(delays, 99)), 3)},
        }

    def run(
        self,
        *,
        stop: threading.Event | None = None,
        duration_s: float | None = None,
        progress: Callable[[RunSummary], None] | None = None,
        progress_interval_s: float = 0.5,
    ) -> RunSummary:
        """Loop until ``stop`` is set, ``duration_s`` has passed or the source is finished; return the summary.

        Parameters
        ----------
        stop : threading.Event, keyword-only
            Set it to end the loop.
        duration_s : float, keyword-only
            Wall time, s (None: no limit).
        progress : callable, keyword-only
            Called with the running summary every ``progress_interval_s`` (from this thread).
        progress_interval_s : float, keyword-only
            Seconds between progress calls.

        Returns
        -------
        RunSummary
        """
        _check_source(self.source)
        _check_run(stop, duration_s, progress, progress_interval_s)
        start = time.monotonic()
        deadline = np.inf if duration_s is None else start + duration_s
        next_report = start + progress_interval_s
        stop = stop or threading.Event()
        self.publish_status()
        # what exists now (modules, the system, the state) is never garbage: left out of the collector's
        # full passes, which otherwise walk it all and stop the loop for 50 ms or more now and then
        gc.freeze()
        # another thread (the dashboard's server) holding the interpreter lock gives it up within
        # 0.5 ms when the loop asks, not 5 ms (Python's default)
        switch = sys.getswitchinterval()
        sys.setswitchinterval(min(switch, SWITCH_INTERVAL_S))
        try:
            self._loop(stop, start, deadline, next_report, progress, progress_interval_s)
        finally:
            gc.unfreeze()
            sys.setswitchinterval(switch)
        self.publish_status()
        return self.summary(time.monotonic() - start)

    def _loop(self, stop, start: float, deadline: float, next_report: float, progress, progress_interval_s: float) -> None:
        while not stop.is_set() and not self.source.finished:
            now = time.monotonic()
            if now >= deadline:
                break
            self.step(min(0.02, max(deadline - now, 0.0)))
            if now >= next_report:
                next_report = now + progress_interval_s
                self.publish_status()
                if progress is not None:
                    progress(self.summary(now - start, recent=20000))


def _check_source(source) -> None:
    """Refuse a source that is not one of :mod:`axiscal.live.sources` (or shaped like one)."""
    if not all(hasattr(source, name) for name in ("read", "close", "status", "finished", "clock_offset_s")):
        raise AxiscalError(f"source must be a source of axiscal.live.sources (with read, close and status), not {type_name(source)}")


def _check_run(stop, duration_s, progress, progress_interval_s) -> None:
    """Refuse the arguments of a run that would fail only later, inside the loop."""
    if stop is not None and not callable(getattr(stop, "is_set", None)):
        raise AxiscalError(f"stop must be a threading.Event, not {type_name(stop)}")
    if duration_s is not None:
        check_number("duration_s", duration_s, nonnegative=True)
    if progress is not None and not callable(progress):
        raise AxiscalError(f"progress must be a function of the running summary, not {type_name(progress)}")
    check_number("progress_interval_s", progress_interval_s, positive=True)
