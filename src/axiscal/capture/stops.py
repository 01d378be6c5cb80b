"""Stops in a laser reading over time: where the axis held still, and the value it settled at.

A sample ``i`` is *still* when every sample in the window ``[t_i - window_s, t_i]`` lies within
``stability_m`` peak to peak, and the recording reaches back at least ``window_s`` before it. A
*stop* is a run of consecutive still samples; runs whose windows overlap are one stop (a ringing
axis whose peak to peak over the window hovers at the stability breaks its stillness for a few
samples, at the same place: the stops are disjoint). Its value is the mean of the reading over the
last window of the stop, the ``window_s`` before the axis moved on: machines ring and creep after
they arrive, so the value is where the axis settled, not where it first held still. A stop the
axis stood at when the recording began (every sample up to its first still one within the
stability) starts at sample 0, however unevenly the samples are spaced. The window is
measured in time, so a recording with an uneven sample interval is read as it was taken; where
the samples are evenly spaced (to a millionth of the interval) it is the ``floor(window_s /
interval) + 1`` samples ending at each one.

The detector is streaming: :class:`StopDetector` takes the samples in batches of any size and
gives each stop once the axis has left it; :func:`detect_stops` is the same detector fed a whole
recording at once, so a live capture and a capture from a file find the same stops. The peak to
peak over each window is a running maximum and minimum where the samples are evenly spaced
(``O(n)``), else a range-maximum query over a sparse table (``O(n log w)`` for ``w`` samples per
window), batched with NumPy.
"""

from __future__ import annotations

from collections.abc import Mapping, Sequence
from dataclasses import dataclass, field

import numpy as np

from axiscal.errors import AxiscalError
from axiscal.io.arguments import check_array, check_number

__all__ = ["SETTLE_S", "Stop", "StopDetector", "detect_stops", "least_dwell_s"]

#: new samples a batch is cut into (bounds the sparse table's memory to a few tens of MB)
_CHUNK = 1 << 18

#: time allowed for an axis to come within the stability after it arrives, seconds (the virtual
#: machine's 2 um ring, decaying in 60 ms, takes about 0.08 s to fall within 1 um)
SETTLE_S = 0.2


def least_dwell_s(window_s: float, *, settle_s: float = SETTLE_S) -> float:
    """The shortest dwell at a target in which the detector can find the stop, seconds.

    A sample is still only when a whole window before it lies within the stability, and the axis
    first has to settle: a dwell shorter than ``settle_s + window_s`` holds no still sample, the axis
    moves on without a stop and the plan's step cannot be taken.

    Parameters
    ----------
    window_s : float, seconds
        The detector's window (> 0).
    settle_s : float, seconds, keyword-only
        Time allowed for the axis to settle within the stability after it arrives (default
        :data:`SETTLE_S`, 0.2 s; >= 0).

    Returns
    -------
    float, seconds
        ``settle_s + window_s``.

    Raises
    ------
    AxiscalError
        For a window that is not a positive, finite number of seconds, or a negative settling time.

    Examples
    --------
    >>> least_dwell_s(0.5)
    0.7
    """
    window_s = check_number("window_s", window_s, positive=True, unit="s")
    settle_s = check_number("settle_s", settle_s, nonnegative=True, unit="s")
    return round(settle_s + window_s, 9)


@dataclass(frozen=True)
class Stop:
    """One stop of the axis.

    Attributes
    ----------
    start_s : float, seconds
        Time of the first sample of the stop's first still window (when the axis arrived, within
        the stability).
    still_s : float, seconds
        Time the reading first held still for a whole window.
    end_s : float, seconds
        Time of the stop's last still sample (the axis moves on after it).
    value_m : float, metres
        Mean of the reading over the last window of the stop.
    std_m : float, metres
        Standard deviation of the reading over that window (n - 1).
    samples : int
        Samples in that window.
    first_index, last_index : int
        Index (from the first sample ever fed) of the first sample of the stop and of its last
        still sample. ``first_index`` is 0 exactly for a stop the axis stood at when the
        recording began (a standing start).
    low_m, high_m : float, metres
        Lowest and highest reading between the previous stop and this one (the move that
        brought the axis here): the side it came from.
    channels : dict of str to float
        Mean of each extra channel (air and material sensors ...) over the same window.
    """

    start_s: float
    still_s: float
    end_s: float
    value_m: float
    std_m: float
    samples: int
    first_index: int
    last_index: int
    low_m: float
    high_m: float
    channels: Mapping[str, float] = field(default_factory=dict)

    @property
    def approach(self) -> str:
        """The side the axis came from: ``"+"`` from below (the reading rose to the stop), else ``"-"``."""
        return "+" if self.value_m - self.low_m >= self.high_m - self.value_m else "-"


def _sparse_max_min(x: np.ndarray, levels: int) -> tuple[list[np.ndarray], list[np.ndarray]]:
    """Sparse tables: level k holds the max (min) of ``x[i : i + 2**k]`` at i."""
    highs, lows = [x], [x]
    for k in range(1, levels):
        half = 1 << (k - 1)
        highs.append(np.maximum(highs[-1][:-half], highs[-1][half:]))
        lows.append(np.minimum(lows[-1][:-half], lows[-1][half:]))
    return highs, lows


def _running_extremes(x: np.ndarray, size: int, start: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Max and min of ``x[a : a + size]`` for every a in ``start`` (van Herk / Gil-Werman, ``O(n)``).

    The array is cut into blocks of ``size``: a window spans the end of one block (its suffix
    extreme) and the start of the next (its prefix extreme).
    """
    blocks = -(-x.size // size) + 1
    padded = np.full(blocks * size, np.nan)
    padded[: x.size] = x
    grid = padded.reshape(blocks, size)
    out = []
    for accumulate in (np.fmax, np.fmin):
        prefix = accumulate.accumulate(grid, axis=1).ravel()
        suffix = accumulate.accumulate(grid[:, ::-1], axis=1)[:, ::-1].ravel()
        out.append(accumulate(suffix[start], prefix[start + size - 1]))
    return out[0], out[1]


def _range_ptp(x: np.ndarray, start: np.ndarray, stop: np.ndarray) -> np.ndarray:
    """Peak to peak of ``x[start[i] : stop[i] + 1]`` for every i (start <= stop).

    Windows of one length (evenly sampled readings) take running extremes (``O(n)``); windows of
    several lengths a sparse table (``O(n log w)``).
    """
    length = stop - start + 1
    if length.size == 0:
        return np.empty(0)
    shortest, longest = int(length.min()), int(length.max())
    if shortest == longest:
        high, low = _running_extremes(x, longest, start)
        return high - low
    level = np.floor(np.log2(length)).astype(np.int64)
    low_level, high_level = int(np.log2(shortest)), int(np.log2(longest))
    highs, lows = _sparse_max_min(x, high_level + 1)
    out_high = np.empty(length.size)
    out_low = np.empty(length.size)
    for k in range(low_level, high_level + 1):
        sel = np.nonzero(level == k)[0]
        if sel.size == 0:
            continue
        a, b = start[sel], stop[sel] - (1 << k) + 1
        out_high[sel] = np.maximum(highs[k][a], highs[k][b])
        out_low[sel] = np.minimum(lows[k][a], lows[k][b])
    return out_high - out_low


class StopDetector:
    """Find stops in a reading fed in batches (see the module's description).

    Parameters
    ----------
    stability_m : float, metres
        Largest peak to peak of the reading over a window for the axis to count as still (> 0).
    window_s : float, seconds
        How long the reading must hold still; the stop's value is the mean over its last window (> 0).
    channels : sequence of str, optional
        Names of extra channels fed beside the reading (air and material sensors ...), averaged
        over each stop's window.

    Raises
    ------
    AxiscalError
        For a stability or window that is not a positive, finite number.

    Examples
    --------
    >>> import numpy as np
    >>> t = np.arange(3000) / 1000.0
    >>> x = np.where((t > 1.0) & (t < 2.0), 0.1, 0.0)
    >>> d = StopDetector(stability_m=1e-6, window_s=0.2)
    >>> [round(s.value_m, 3) for s in d.feed(t, x) + d.finish()]
    [0.0, 0.1, 0.0]
    """

    def __init__(self, *, stability_m: float, window_s: float, channels: Sequence[str] = ()):
        self.stability_m = check_number("stability_m", stability_m, positive=True, unit="m")
        self.window_s = check_number("window_s", window_s, positive=True, unit="s")
        if isinstance(channels, str) or not all(isinstance(c, str) for c in channels):
            raise AxiscalError(f"channels must be a sequence of column names, not {channels!r}")
        self.channels = tuple(channels)
        width = 2 + len(self.channels)
        self._buffer = np.empty((0, width))  # t, reading, channels: the tail kept for the next batch
        self._offset = 0  # index of the buffer's first sample among all samples fed
        self._fed = 0
        self._last_t = -np.inf
        self._open: dict | None = None  # the stop in progress: first index, start and still times
        # a stop whose stillness broke: given once the next still run cannot overlap its window, else
        # joined by it (the stop, and the state it was opened with)
        self._pending: tuple[Stop, dict] | None = None
        self._began = False  # whether any stop has begun (only the first can be a standing start)
        self._low = np.inf
        self._high = -np.inf

    @property
    def samples(self) -> int:
        """Samples fed so far."""
        return self._fed

    @property
    def holding(self) -> bool:
        """Whether the reading is holding still now (a stop is in progress)."""
        return self._open is not None

    def feed(self, time_s: np.ndarray, reading_m: np.ndarray, channels: Mapping[str, np.ndarray] | None = None) -> list[Stop]:
        """Take a batch of samples; return the stops the axis has left within it.

        Parameters
        ----------
        time_s : ndarray, shape (n,), seconds
            Sample times, increasing, continuing the previous batch.
        reading_m : ndarray, shape (n,), metres
            The reading at each time (NaN: no reading; the window around it is not still).
        channels : mapping of str to ndarray, shape (n,), optional
            The extra channels named when the detector was made.

        Returns
        -------
        list of Stop
            Stops that ended in this batch, in order.

        Raises
        ------
        AxiscalError
            For times that go back, or channels that are missing or of another length.
        """
        t = np.asarray(time_s, dtype=float)
        x = np.asarray(reading_m, dtype=float)
        if t.shape != x.shape or t.ndim != 1:
            raise AxiscalError(f"time_s and reading_m must be 1-D arrays of one length, got {t.shape} and {x.shape}")
        extra = []
        for name in self.channels:
            values = None if channels is None else channels.get(name)
            if values is None or np.shape(values) != t.shape:
                raise AxiscalError(f"channel {name} is missing from the batch or not {t.size} samples long")
            extra.append(np.asarray(values, dtype=float))
        stops: list[Stop] = []
        for start in range(0, t.size, _CHUNK):
            part = slice(start, start + _CHUNK)
            stops += self._feed(t[part], x[part], [e[part] for e in extra])
        return stops

    def _feed(self, t: np.ndarray, x: np.ndarray, extra: list[np.ndarray]) -> list[Stop]:
        if t.size == 0:
            return []
        if not (np.all(np.isfinite(t)) and np.all(np.diff(t) >= 0) and t[0] >= self._last_t):
            raise AxiscalError("sample times must be finite and never go back")
        new = np.column_stack([t, x, *extra]) if extra else np.column_stack([t, x])
        buffer = np.concatenate([self._buffer, new])
        old = self._buffer.shape[0]
        bt, bx = buffer[:, 0], buffer[:, 1]
        idx = np.arange(old, buffer.shape[0])
        # the window of sample i: the samples with t >= t_i - window; covered when an earlier sample
        # lies at or before t_i - window (the recording reaches back a whole window)
        reach_back = bt[idx] - self.window_s
        step = np.diff(bt)
        if step.size and step.min() > 0 and step.max() - step.min() <= 1e-6 * step.min():
            # evenly sampled: the window is the floor(window / interval) + 1 samples ending at i
            # (a window longer than the buffer reaches before its first sample: capped, it is not covered either)
            span = int(min(np.floor(self.window_s / float(0.5 * (step.min() + step.max())) + 1e-6), buffer.shape[0]))
            first = np.maximum(idx - span, 0)
            covered = (idx - span >= 0) | (self._offset > 0)
        else:
            first = np.searchsorted(bt, reach_back, side="left")
            covered = (bt[0] <= reach_back) | (self._offset > 0)
        safe = np.nan_to_num(bx, nan=np.inf)
        ptp = _range_ptp(safe, first, idx)
        still = covered & (ptp <= self.stability_m)
        stops = self._runs(buffer, idx, first, still)
        self._fed += t.size
        self._last_t = float(t[-1])
        # keep every sample back to one window before the last, plus the one before that
        keep_from = max(0, int(np.searchsorted(bt, bt[-1] - self.window_s, side="right")) - 1)
        self._buffer = buffer[keep_from:].copy()
        self._offset += keep_from
        return stops

    def _runs(self, buffer: np.ndarray, idx: np.ndarray, first: np.ndarray, still: np.ndarray) -> list[Stop]:
        """Turn the still flags of a batch into stops, carrying an open (or broken-off) stop over batches."""
        bx = buffer[:, 1]
        stops: list[Stop] = []
        prev = self._open is not None
        edges = np.flatnonzero(np.diff(np.concatenate([[prev], still]).astype(np.int8)))
        cursor = 0  # local position in the batch up to which the motion's extremes are taken
        for e in edges:
            if still[e]:  # a still run begins at batch sample e
                start = int(first[e])
                if self._pending is not None:
                    stop, opened = self._pending
                    self._pending = None
                    if self._offset + start <= stop.last_index:
                        # its window reaches back into the stop that broke off: the same stop, still ringing
                        self._open = opened
                        continue
                    stops.append(stop)
                moving = bx[idx[cursor] : idx[e]]
                moving = moving[np.isfinite(moving)]
                if moving.size:
                    self._low = min(self._low, float(moving.min()))
                    self._high = max(self._high, float(moving.max()))
                standing = not self._began and self._offset == 0 and self._still_since_start(bx[: idx[e] + 1])
                self._began = True
                if standing:
                    start = 0  # the axis stood here when the recording began
                self._open = {
                    "first_index": self._offset + start,
                    "start_s": float(buffer[start, 0]),
                    "still_s": float(buffer[idx[e], 0]),
                    "low": self._low,
                    "high": self._high,
                }
            else:  # the still run ended at batch sample e - 1
                opened = self._open
                self._pending = (self._close(buffer, int(idx[e] - 1)), opened)
                cursor = e
        if self._open is None:
            tail = bx[idx[cursor] :]
            tail = tail[np.isfinite(tail)]
            if tail.size:
                self._low = min(self._low, float(tail.min()))
                self._high = max(self._high, float(tail.max()))
            if self._pending is not None and idx.size and self._offset + int(first[-1]) > self._pending[0].last_index:
                # the window has moved past the stop: no still run to come can reach back into it
                stops.append(self._pending[0])
                self._pending = None
        return stops

    def _still_since_start(self, x: np.ndarray) -> bool:
        """Whether the samples ``x`` (from the first ever fed) all lie within the stability."""
        return bool(np.all(np.isfinite(x)) and float(x.max() - x.min()) <= self.stability_m)

    def _close(self, buffer: np.ndarray, last: int) -> Stop:
        """The open stop, ended at buffer sample ``last``."""
        opened = self._open
        assert opened is not None
        bt = buffer[:, 0]
        start = int(np.searchsorted(bt, bt[last] - self.window_s * (1 + 1e-9), side="left"))
        window = buffer[start : last + 1]
        value = float(window[:, 1].mean())
        std = float(window[:, 1].std(ddof=1)) if window.shape[0] > 1 else 0.0
        low = opened["low"] if np.isfinite(opened["low"]) else value
        high = opened["high"] if np.isfinite(opened["high"]) else value
        stop = Stop(
            start_s=opened["start_s"],
            still_s=opened["still_s"],
            end_s=float(bt[last]),
            value_m=value,
            std_m=std,
            samples=int(window.shape[0]),
            first_index=int(opened["first_index"]),
            last_index=self._offset + last,
            low_m=float(low),
            high_m=float(high),
            channels={name: float(window[:, 2 + k].mean()) for k, name in enumerate(self.channels)},
        )
        self._open = None
        # the next move starts from here
        self._low = self._high = value
        return stop

    @property
    def standing_start(self) -> bool:
        """Whether the stop in progress is one the axis stood at when the recording began (not a stop it came to)."""
        return self._open is not None and self._open["first_index"] == 0

    @property
    def start_s(self) -> float:
        """When the stop in progress began (the first sample of its first still window), seconds; NaN when moving."""
        return float("nan") if self._open is None else self._open["start_s"]

    @property
    def held_s(self) -> float:
        """How long the reading has been still, seconds (0 when it is moving)."""
        return 0.0 if self._open is None else self._last_t - self._open["still_s"]

    def finish(self) -> list[Stop]:
        """End of the recording: the stop the axis is still at, if any (it held for a whole window).

        Returns
        -------
        list of Stop
            Zero or one stop.
        """
        if self._pending is not None:
            stop, self._pending = self._pending[0], None
            return [stop]
        if self._open is None or self._buffer.shape[0] == 0:
            return []
        return [self._close(self._buffer, self._buffer.shape[0] - 1)]


def detect_stops(
    time_s: np.ndarray,
    reading_m: np.ndarray,
    *,
    stability_m: float,
    window_s: float,
    channels: Mapping[str, np.ndarray] | None = None,
) -> list[Stop]:
    """Every stop of a recorded reading (see the module's description).

    Parameters
    ----------
    time_s : ndarray, shape (n,), seconds
        Sample times, increasing.
    reading_m : ndarray, shape (n,), metres
        The reading (a laser's position reading).
    stability_m : float, metres, keyword-only
        Largest peak to peak over a window for the axis to count as still.
    window_s : float, seconds, keyword-only
        How long the reading must hold still; a stop's value is the mean over its last window.
    channels : mapping of str to ndarray, shape (n,), optional, keyword-only
        Extra channels averaged over each stop's window (air and material sensors).

    Returns
    -------
    list of Stop
        In time order; a stop still held at the end of the recording is included.

    Raises
    ------
    AxiscalError
        For arrays of different lengths or not 1-D, times that are not finite or go back, or a
        stability or window that is not a positive, finite number.

    Examples
    --------
    >>> import numpy as np
    >>> t = np.arange(0, 4, 0.001)
    >>> x = np.interp(t, [0, 1, 1.2, 2.5, 2.7, 4], [0, 0, 0.01, 0.01, 0.02, 0.02])
    >>> [round(s.value_m * 1e3, 3) for s in detect_stops(t, x, stability_m=1e-6, window_s=0.5)]
    [0.0, 10.0, 20.0]
    """
    t = check_array("time_s", time_s, finite=True, unit="s")
    x = check_array("reading_m", reading_m, finite=False, unit="m")
    if t.shape != x.shape:
        raise AxiscalError(f"time_s and reading_m must have one length, got {t.size} and {x.size}")
    detector = StopDetector(stability_m=stability_m, window_s=window_s, channels=tuple(channels or {}))
    return detector.feed(t, x, channels) + detector.finish()
