"""Sources played by the clock: the virtual instrument in real time, a recorded file, a Renishaw .rtx capture.

Each delivers frame k once its time stamp has passed on the monotonic clock (a replay may also run
as fast as the pipeline takes it), so each knows its ``clock_offset_s`` and the delay of every
frame to the record can be measured. The interface is the one of :mod:`axiscal.live.sources`.
"""

from __future__ import annotations

import time
from collections.abc import Sequence
from pathlib import Path

import numpy as np

from axiscal.errors import AxiscalError
from axiscal.io.arguments import check_choice, check_count, check_instance, check_path, is_real, type_name
from axiscal.io.importers.rtx import read_rtx
from axiscal.live.protocol import FrameBatch, _checked_channels
from axiscal.live.recorder import read_record
from axiscal.live.status import SourceStatus
from axiscal.measurement.virtual import PATHS
from axiscal.units import length_factor, split_unit

__all__ = ["MAX_RATE_HZ", "AHEAD_S", "SimSource", "ReplaySource", "RtxSource"]

#: highest frame rate of the sim source, Hz (ten times the rate the benchmark keeps up with)
MAX_RATE_HZ = 100_000.0
#: stream time the sim source computes at once, s (before its frames are due)
AHEAD_S = 0.02


class SimSource:
    """The virtual instrument streamed in real time: ``VirtualModule.frames(t)`` at ``rate_hz``.

    Frame k has time stamp k / rate_hz and is delivered once that time has passed on the monotonic
    clock (so its delay to the record is measurable); at most ``max_batch_s`` of frames per read.
    The module computes its frames :data:`AHEAD_S` of stream at a time, before they are due, as an
    instrument's own electronics would: a call of ``VirtualModule.frames`` costs about the same
    for one frame as for two hundred, and one call a batch took the live loop most of a core at
    10 kHz.

    Parameters
    ----------
    module : VirtualModule
        The instrument (:mod:`axiscal.measurement.virtual`).
    channels : sequence of str
        Channel order of the measurement system.
    rate_hz : float
        Frames per second, at most :data:`MAX_RATE_HZ`.
    path : str
        Motion of the module (``"diagonal"``, ``"raster"``, ``"back-and-forth"``).
    max_batch_s : float
        Most stream time delivered by one read, s (at most 1).

    Raises
    ------
    AxiscalError
        For a rate that is not finite, not positive or above :data:`MAX_RATE_HZ`.
    """

    def __init__(self, module, channels: Sequence[str], *, rate_hz: float = 1000.0, path: str = "diagonal", max_batch_s: float = 0.05):
        if not (is_real(rate_hz) and np.isfinite(rate_hz) and 0 < rate_hz <= MAX_RATE_HZ):
            raise AxiscalError(f"rate_hz: the frame rate must be a positive number of frames per second up to {MAX_RATE_HZ:g}, not {rate_hz!r}")
        if not (is_real(max_batch_s) and np.isfinite(max_batch_s) and 0 < max_batch_s <= 1.0):
            raise AxiscalError(f"max_batch_s (the longest batch) must be 0 to 1 s, not {max_batch_s!r}")
        if not callable(getattr(module, "frames", None)):
            raise AxiscalError(f"module must be a VirtualModule, not {type_name(module)}")
        check_choice("path", path, PATHS)
        self.module = module
        self.channels = _checked_channels(channels)
        self.rate_hz = float(rate_hz)
        self.path = path
        self.max_batch = max(1, int(round(max_batch_s * rate_hz)))
        self.status = SourceStatus(f"sim ({rate_hz:g} Hz, {path})", state="streaming", connections=1)
        self.finished = False
        self.clock_offset_s: float | None = None
        self._next = 0
        self._ahead = max(1, int(round(AHEAD_S * rate_hz)))
        self._computed = FrameBatch.empty(len(self.channels))  # frames _next, _next + 1, ... made, not yet delivered

    def _compute(self, due: int) -> None:
        """Make sure the first ``due`` frames not yet delivered are computed (and :data:`AHEAD_S` more)."""
        have = len(self._computed)
        if have >= due:
            return
        first = self._next + have
        t = (first + np.arange(max(due - have, self._ahead))) / self.rate_hz
        frames, _truth = self.module.frames(t, path=self.path)
        self._computed = FrameBatch.concatenate([self._computed, FrameBatch.from_frames(frames, self.channels)], len(self.channels))

    def read(self, timeout_s: float) -> FrameBatch:
        now = time.monotonic()
        if self.clock_offset_s is None:
            self.clock_offset_s = now
        due = int(np.floor((now - self.clock_offset_s) * self.rate_hz)) + 1 - self._next
        if due <= 0:
            wait = (self._next / self.rate_hz + self.clock_offset_s) - now
            if wait > timeout_s:
                time.sleep(max(timeout_s, 0.0))
                return FrameBatch.empty(len(self.channels))
            time.sleep(max(wait, 0.0))
            due = 1
        due = min(due, self.max_batch)
        self._compute(due)
        computed = self._computed
        self._computed = FrameBatch(computed.t_s[due:], computed.values[due:], computed.malformed[due:])
        self._next += due
        return FrameBatch(computed.t_s[:due], computed.values[:due], computed.malformed[:due])

    def close(self) -> None:
        self.status.state = "finished"


class ReplaySource:
    """A recorded CSV (a live record, or any file with ``t_s`` and every channel) played back.

    Parameters
    ----------
    path : str or Path
        The file; read with :func:`axiscal.live.recorder.read_record` (a cut last line is dropped).
    channels : sequence of str
        Channel order of the measurement system; each must be a column of the file.
    pace : bool
        True: frames are delivered when their ``t_s`` (relative to the first) has passed;
        False: as fast as the pipeline takes them.

    Raises
    ------
    AxiscalError
        For a bad ``path`` or ``channels``, a ``pace`` that is not a bool, a ``max_batch``
        below 1, a file that lacks a channel column.
    """

    def __init__(self, path: str | Path, channels: Sequence[str], *, pace: bool = True, max_batch: int = 2000):
        channels = _checked_channels(channels)
        _check_playback(pace, max_batch)
        record = read_record(path)
        missing = [name for name in channels if name not in record.columns]
        if missing:
            raise AxiscalError(f"replay file lacks channel column(s) {', '.join(missing)}", path=path)
        t = record.columns["t_s"]
        values = np.column_stack([record.columns[name] for name in channels]) if channels else np.empty((len(t), 0))
        self._play(f"replay {path}", channels, t, values, pace=pace, max_batch=max_batch)

    def _play(self, description: str, channels: Sequence[str], t: np.ndarray, values: np.ndarray, *, pace: bool, max_batch: int) -> None:
        """Set up the playback of frames ``t`` (N,) and ``values`` (N, C)."""
        self.channels = tuple(channels)
        self._t = t
        self._values = values
        self.pace = pace
        self.max_batch = max_batch
        self.status = SourceStatus(description + ("" if pace else " (as fast as possible)"), state="streaming", connections=1)
        self.finished = len(self._t) == 0
        self.clock_offset_s: float | None = None
        self._start: float | None = None
        self._next = 0
        self._t0 = float(self._t[np.isfinite(self._t)][0]) if np.isfinite(self._t).any() else 0.0

    def read(self, timeout_s: float) -> FrameBatch:
        if self.finished:
            return FrameBatch.empty(len(self.channels))
        stop = min(self._next + self.max_batch, len(self._t))
        if self.pace:
            now = time.monotonic()
            if self._start is None:
                self._start = now
                self.clock_offset_s = now - self._t0
            elapsed = now - self._start
            times = self._t[self._next : stop] - self._t0
            # a row is due when its t_s and every t_s before it has passed (NaN times never hold a row back)
            due_at = np.maximum.accumulate(np.where(np.isfinite(times), times, -np.inf))
            ready = int(np.searchsorted(due_at, elapsed, side="right"))
            if ready == 0:
                wait = min(float(due_at[0]) - elapsed, timeout_s)
                time.sleep(max(wait, 0.0))
                return FrameBatch.empty(len(self.channels))
            stop = self._next + ready
        t = self._t[self._next : stop]
        batch = FrameBatch(t.copy(), self._values[self._next : stop].copy(), ~np.isfinite(t))
        self._next = stop
        if self._next >= len(self._t):
            self.finished = True
            self.status.state = "finished"
        return batch

    def close(self) -> None:
        self.status.state = "finished"


def _check_playback(pace: bool, max_batch: int) -> None:
    """Refuse a ``pace`` that is not a bool or a ``max_batch`` that is not a positive whole number."""
    check_instance("pace", pace, bool)
    check_count("max_batch", max_batch)


class RtxSource(ReplaySource):
    """A Renishaw ``.rtx`` dynamic capture played back as the reading of one channel.

    The capture holds one reading at a fixed sample rate (:func:`axiscal.io.importers.rtx.read_rtx`):
    frame k has ``t_s = k / rate`` and carries the sample k in ``channel`` (converted to the unit
    its name ends in); every other channel is missing, so those frames carry the missing-channel
    fault unless the system has no other channel.

    Parameters
    ----------
    path : str or Path
        The ``.rtx`` file.
    unit : str
        Unit the samples were stored in (the file does not say): ``nm``, ``um``, ``mm``, ``m``, ``in``.
    channel : str
        The measurement system's channel the reading feeds (a length channel, e.g. ``x_scale_mm``).
    channels : sequence of str
        Channel order of the measurement system.
    pace : bool
        True: at the capture's sample rate; False: as fast as the pipeline takes them.

    Raises
    ------
    AxiscalError
        For an unreadable capture, an unknown unit, or a channel the system does not have or that
        is not a length.
    """

    def __init__(self, path: str | Path, unit: str, channel: str, channels: Sequence[str], *, pace: bool = True, max_batch: int = 2000):
        channels = _checked_channels(channels)
        _check_playback(pace, max_batch)
        path = check_path("path", path)
        if not isinstance(channel, str) or channel not in channels:
            raise AxiscalError(f"channel '{channel}' is not one of the measurement system's: {', '.join(channels)}")
        factor = length_factor(split_unit(channel)[1], allowed=("nm", "um", "mm"), what=f"channel {channel}")
        capture = read_rtx(path, unit=unit)
        values = np.full((len(capture.samples_m), len(channels)), np.nan)
        values[:, channels.index(channel)] = capture.samples_m / factor
        description = f"rtx {path} ({capture.sample_rate_hz:g} Hz, {unit}) as {channel}"
        self._play(description, channels, capture.time_s, values, pace=pace, max_batch=max_batch)
