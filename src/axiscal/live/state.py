"""The dashboard's view of a live run: bounded summaries the pipeline updates and a server reads.

The pipeline calls :meth:`LiveState.update` once per batch, which only keeps it; the batches are
folded into the summaries together (vectorised) every :data:`FOLD_S` seconds or when a server
calls :meth:`LiveState.snapshot` at its own pace, so the fold's cost, the same for one frame as
for a thousand, is paid twenty times a second instead of once a batch. Memory is fixed at construction: the
error profiles hold ``bins`` cells per axis (the latest mean in each cell of the travel), the
spatial-error history ``history_points`` samples over the last ``history_s`` seconds (NaN where
the frame was faulty, so the curve has a gap), and the sensor table one entry per channel.
Nothing is queued per frame or per client.
"""

from __future__ import annotations

import math
import threading
import time
from collections.abc import Mapping
from typing import Any

import numpy as np

from axiscal.errors import AxiscalError
from axiscal.io.arguments import check_count, check_number
from axiscal.io.arguments import check_instance
from axiscal.live.protocol import FrameBatch
from axiscal.measurement.faults import fault_text
from axiscal.measurement.pipeline import MeasurementSystem
from axiscal.units import MM

__all__ = ["UPDATE_HZ_RANGE", "FOLD_S", "FOLD_FRAMES", "SPATIAL", "CORRECTED", "axis_error_columns", "result_columns", "LiveState"]

#: the dashboard's refresh rates allowed, per second: slower is useless, faster only burns the pipeline's core
UPDATE_HZ_RANGE = (0.1, 60.0)
SPATIAL = ("ex_um", "ey_um", "ez_um", "e_um")
#: the state folds the batches it was given once this much time or this many frames of them wait
FOLD_S = 0.05
FOLD_FRAMES = 2000
CORRECTED = ("px_mm", "py_mm", "pz_mm")


def axis_error_columns(letter: str) -> tuple[str, ...]:
    """The six ISO 230-1 error columns of axis ``letter`` as records and the dashboard show them.

    Parameters
    ----------
    letter : str
        Axis letter.

    Returns
    -------
    tuple of str
        ``EX<L>_um``, ``EY<L>_um``, ``EZ<L>_um``, ``EA<L>_urad``, ``EB<L>_urad``, ``EC<L>_urad``.

    Raises
    ------
    AxiscalError
        For a ``letter`` that is not one capital letter.

    Examples
    --------
    >>> axis_error_columns("Z")[:2]
    ('EXZ_um', 'EYZ_um')
    """
    _check_letter(letter)
    return _error_columns(letter)


def _error_columns(letter: str) -> tuple[str, ...]:
    """:func:`axis_error_columns` unchecked, for the state's per-batch updates."""
    return tuple(f"E{d}{letter}_um" for d in "XYZ") + tuple(f"E{r}{letter}_urad" for r in "ABC")


def result_columns(axes: tuple[str, ...]) -> tuple[str, ...]:
    """Result columns of a live record, in order: spatial error, corrected point, positions, six errors per axis.

    Parameters
    ----------
    axes : tuple of str
        Axis letters in chain order.

    Returns
    -------
    tuple of str
        Display names (``ex_um`` ... ``px_mm`` ... ``x_mm`` ... ``EXX_um`` ...).

    Raises
    ------
    AxiscalError
        For ``axes`` that are not a tuple of capital letters.
    """
    if not isinstance(axes, (tuple, list, str)):
        raise AxiscalError(f"axes must be a tuple of axis letters, not {axes!r}")
    for letter in axes:
        _check_letter(letter, "axes")
    positions = tuple(f"{letter.lower()}_mm" for letter in axes)
    errors = tuple(name for letter in axes for name in _error_columns(letter))
    return SPATIAL + CORRECTED + positions + errors


def _check_letter(letter: str, name: str = "letter") -> None:
    """Refuse an axis letter that is not one letter."""
    if not isinstance(letter, str) or len(letter) != 1 or not letter.isalpha() or not letter.isupper():
        raise AxiscalError(f"{name} must hold axis letters (one capital letter each), not {letter!r}")


def _plain(values: np.ndarray, digits: int = 6) -> list[float | None]:
    """The values rounded to ``digits`` decimals as a JSON-ready list (NaN -> None), in one vectorised pass."""
    rounded = np.round(np.asarray(values, dtype=float), digits)
    plain = rounded.astype(object)
    plain[np.isnan(rounded)] = None
    return plain.tolist()


def _number(value: float) -> float | None:
    return None if not math.isfinite(value) else float(value)


class LiveState:
    """Latest values, error profiles, spatial-error history and sensor status of a live run.

    Parameters
    ----------
    system : MeasurementSystem
        Gives the channels, their limits, the axes and (through ``system.machine``) the travels.
    bins : int
        Cells of each axis's error profile along its travel.
    history_s : float
        Length of the spatial-error history, seconds of stream time.
    history_points : int
        Samples kept in that history.

    Raises
    ------
    AxiscalError
        For a ``system`` that is not a MeasurementSystem, ``bins`` or ``history_points``
        below 1, a ``history_s`` that is not positive.
    """

    def __init__(self, system, *, bins: int = 96, history_s: float = 20.0, history_points: int = 400):
        check_instance("system", system, MeasurementSystem)
        bins = check_count("bins", bins)
        history_s = check_number("history_s", history_s, positive=True)
        history_points = check_count("history_points", history_points)
        channels = tuple(system.channels)
        limits = [system.channel_limits.get(name, (-np.inf, np.inf)) for name in channels]
        travels = {letter: tuple(end / MM for end in system.machine.travel_m(letter)) for letter in system.axes}
        self._setup(channels, limits, travels, bins, history_s, history_points)

    def _setup(self, channels, limits, travels, bins, history_s, history_points) -> None:
        """Allocate everything from the layout (what :meth:`layout` gives); the arguments are checked."""
        self._layout = {"channels": list(channels), "limits": [list(map(float, pair)) for pair in limits],
                        "travels_mm": {letter: list(map(float, pair)) for letter, pair in travels.items()},
                        "bins": bins, "history_s": history_s, "history_points": history_points}
        self.channels = tuple(channels)
        self.axes = tuple(travels)
        self._low = np.array([lo for lo, _ in limits], dtype=float)
        self._high = np.array([hi for _, hi in limits], dtype=float)
        self.bins = bins
        self._edges: dict[str, np.ndarray] = {}
        for letter, (start_mm, end_mm) in travels.items():
            self._edges[letter] = np.linspace(start_mm, end_mm, bins + 1)
        self._profiles = {letter: np.full((6, bins), np.nan) for letter in self.axes}
        self._history_dt = history_s / history_points
        self._history = np.full((history_points, 1 + len(SPATIAL)), np.nan)
        self._history_next = 0
        self._history_bucket = -np.inf
        self._lock = threading.Lock()
        self.frames = 0
        self.faults = 0
        self._channel_value = np.full(len(self.channels), np.nan)
        self._channel_missing = np.zeros(len(self.channels), dtype=np.int64)
        self._channel_range = np.zeros(len(self.channels), dtype=np.int64)
        self._channel_state = ["waiting"] * len(self.channels)
        self._latest: dict[str, Any] = {}
        self._last_t = math.nan
        self._last_fault = 0
        self._rate_mark = (time.monotonic(), 0)
        self.rate_hz = 0.0
        self._extra: dict[str, Any] = {}
        self._feed = None
        self._pending: list[tuple[FrameBatch, np.ndarray, Mapping[str, np.ndarray]]] = []
        self._pending_frames = 0
        self._pending_since = 0.0

    @classmethod
    def _from_layout(cls, layout: Mapping[str, Any]) -> "LiveState":
        """A state laid out as another's ``_layout`` says (the dashboard's process builds its own)."""
        state = cls.__new__(cls)
        state._setup(layout["channels"], [tuple(pair) for pair in layout["limits"]],
                     {letter: tuple(pair) for letter, pair in layout["travels_mm"].items()},
                     layout["bins"], layout["history_s"], layout["history_points"])
        return state

    @property
    def extra(self) -> dict[str, Any]:
        """Entries added to every snapshot as they are (the pipeline's source, record and delay figures)."""
        return self._extra

    @extra.setter
    def extra(self, value: dict[str, Any]) -> None:
        self._extra = value
        if self._feed is not None:
            self._feed.extra(value)

    def update(self, batch: FrameBatch, fault: np.ndarray, results: Mapping[str, np.ndarray]) -> None:
        """Take one processed batch (called by the pipeline thread); it is folded in with the next ones.

        Batches wait, unchanged, until :data:`FOLD_S` seconds or :data:`FOLD_FRAMES` frames of them
        have come, or a reader asks (:meth:`snapshot`, :meth:`measure_rate`, :meth:`fold`): each fold
        costs the same whatever its size, and the dashboard shows ten states a second.

        While a dashboard of its own process is fed from this state
        (:class:`~axiscal.live.dashboard.DashboardProcess`), the batch is written to it instead and
        folded there; this state then only counts the frames and faults (:meth:`measure_rate` goes
        on; :meth:`snapshot` shows no profiles, history or sensors).
        """
        n = len(batch)
        if n == 0:
            return
        if self._feed is not None:
            self.frames += n
            self.faults += int(np.count_nonzero(fault))
            self._feed.batch(batch, fault, results)
            return
        with self._lock:
            if not self._pending:
                self._pending_since = time.monotonic()
            self._pending.append((batch, fault, results))
            self._pending_frames += n
            due = self._pending_frames >= FOLD_FRAMES or time.monotonic() - self._pending_since >= FOLD_S
        if due:
            self.fold()

    def fold(self) -> None:
        """Fold the batches taken so far into the summaries (a run of batches whose clock goes on at once)."""
        with self._lock:
            pending, self._pending, self._pending_frames = self._pending, [], 0
            start = 0
            for k in range(1, len(pending) + 1):
                if k < len(pending) and not pending[k][0].t_s[:1] < pending[k - 1][0].t_s[-1:]:
                    continue  # the clock goes on: same run
                run = pending[start:k]
                start = k
                if len(run) == 1:
                    self._fold(*run[0])
                    continue
                batch = FrameBatch.concatenate([b for b, _, _ in run], len(self.channels))
                fault = np.concatenate([f for _, f, _ in run])
                names = run[0][2].keys()
                self._fold(batch, fault, {name: np.concatenate([r[name] for _, _, r in run]) for name in names})

    def _fold(self, batch: FrameBatch, fault: np.ndarray, results: Mapping[str, np.ndarray]) -> None:
        """Fold one run of frames into the summaries (the lock is held)."""
        n = len(batch)
        if n == 0:
            return
        values = batch.values
        missing = np.isnan(values)
        out_of_range = ~missing & ((values < self._low) | (values > self._high))
        good = fault == 0
        self.frames += n
        self.faults += int(np.count_nonzero(~good))
        self._last_t = float(batch.t_s[-1])
        self._last_fault = int(fault[-1])
        self._channel_value = values[-1].copy()
        self._channel_missing += missing.sum(axis=0)
        self._channel_range += out_of_range.sum(axis=0)
        self._channel_state = [
            "missing" if m else ("out of range" if r else "ok") for m, r in zip(missing[-1].tolist(), out_of_range[-1].tolist())
        ]
        stamped = np.isfinite(batch.t_s)
        if stamped.any():  # faulty frames go in too (NaN results): the curve shows a gap while they last
            self._update_history(batch.t_s[stamped], {name: results[name][stamped] for name in SPATIAL})
        if not good.any():
            return
        last = int(np.flatnonzero(good)[-1])
        self._latest = {"t_s": float(batch.t_s[last])}
        self._latest.update({name: float(results[name][last]) for name in results if name != "t_s"})
        self._update_profiles(good, results)

    def _update_profiles(self, good: np.ndarray, results: Mapping[str, np.ndarray]) -> None:
        for letter in self.axes:
            position = results[f"{letter.lower()}_mm"][good]
            cell = np.searchsorted(self._edges[letter], position, side="right") - 1
            inside = (cell >= 0) & (cell < self.bins) & np.isfinite(position)
            if not inside.any():
                continue
            cell = cell[inside]
            count = np.bincount(cell, minlength=self.bins)
            touched = count > 0
            for row, name in enumerate(_error_columns(letter)):
                sums = np.bincount(cell, weights=results[name][good][inside], minlength=self.bins)
                self._profiles[letter][row, touched] = sums[touched] / count[touched]

    def _update_history(self, t: np.ndarray, spatial: Mapping[str, np.ndarray]) -> None:
        """Keep one frame per slot of ``history_s / history_points`` seconds: the worst one.

        The worst is a faulty frame (NaN results: the curve shows a gap) before any good one, else
        the one with the largest ``e_um``; frames of a later batch in the slot already shown can
        replace its entry. So a single faulty or extreme frame anywhere in a slot is drawn.
        """
        bucket = np.floor(t / self._history_dt)
        if bucket.max() < self._history_bucket:  # the stream's clock went back (a new connection or replay): start afresh
            self._history[:] = np.nan
            self._history_next = 0
            self._history_bucket = -np.inf
        keep = bucket >= self._history_bucket
        if not keep.any():
            return
        t, bucket = t[keep], bucket[keep]
        rows = np.column_stack([t] + [spatial[name][keep] for name in SPATIAL])
        severity = np.where(np.isnan(rows[:, SPATIAL.index("e_um") + 1]), np.inf, rows[:, SPATIAL.index("e_um") + 1])
        # the worst frame of each slot: sort by slot, then by severity (descending; the earliest on a tie)
        order = np.lexsort((np.arange(len(t)), -severity, bucket))
        slots, first = np.unique(bucket[order], return_index=True)
        worst = order[first]
        size = len(self._history)
        if slots[0] == self._history_bucket and self._history_next:  # the slot shown last goes on
            last = (self._history_next - 1) % size
            shown = self._history[last, SPATIAL.index("e_um") + 1]
            shown = np.inf if np.isnan(shown) else shown
            if severity[worst[0]] > shown:
                self._history[last] = rows[worst[0]]
            slots, worst = slots[1:], worst[1:]
        for index in worst[-size:]:
            self._history[self._history_next % size] = rows[index]
            self._history_next += 1
        if len(slots):
            self._history_bucket = float(slots[-1])

    def describe_fault(self, fault: int) -> str:
        """The fault bits in words: the measurement system's bits and the live pipeline's own."""
        return fault_text(fault) if fault else ""

    def measure_rate(self) -> float:
        """Frames per second since the previous call (the progress line and snapshots use it)."""
        self.fold()
        now = time.monotonic()
        then, frames = self._rate_mark
        if now - then >= 0.2:
            self.rate_hz = (self.frames - frames) / (now - then)
            self._rate_mark = (now, self.frames)
        return self.rate_hz

    def snapshot(self) -> dict[str, Any]:
        """Everything the dashboard draws, as plain JSON-ready values (NaN -> None)."""
        rate = self.measure_rate()  # folds what waits
        with self._lock:  # copies only: the lists are made after, so update() never waits on them
            size = len(self._history)
            count = min(self._history_next, size)
            order = (np.arange(self._history_next - count, self._history_next)) % size
            history = self._history[order]
            profiles = {letter: self._profiles[letter].copy() for letter in self.axes}
            channels = (self._channel_value.copy(), list(self._channel_state), self._channel_missing.copy(),
                        self._channel_range.copy())
            latest = dict(self._latest)
            last_t, frames, faults, last_fault = self._last_t, self.frames, self.faults, self._last_fault
            extra = dict(self.extra)
        axes = {}
        for letter in self.axes:
            edges = self._edges[letter]  # fixed at construction
            axes[letter] = {
                "travel_mm": [float(edges[0]), float(edges[-1])],
                "position_mm": _plain(0.5 * (edges[1:] + edges[:-1]), 3),
                "errors": {name: _plain(profiles[letter][row]) for row, name in enumerate(_error_columns(letter))},
            }
        value, state, missing, out_of_range = channels
        sensors = [
            {
                "name": name,
                "value": _number(float(value[i])),
                "state": state[i],
                "low": _number(float(self._low[i])),
                "high": _number(float(self._high[i])),
                "missing": int(missing[i]),
                "out_of_range": int(out_of_range[i]),
            }
            for i, name in enumerate(self.channels)
        ]
        return {
            "t_s": _number(last_t),
            "frames": frames,
            "faults": faults,
            "rate_hz": round(rate, 1),
            "last_fault": last_fault,
            "last_fault_text": self.describe_fault(last_fault),
            "latest": {name: _number(v) for name, v in latest.items()},
            "axes": axes,
            "history": {"t_s": _plain(history[:, 0])} | {name: _plain(history[:, k + 1]) for k, name in enumerate(SPATIAL)},
            "sensors": sensors,
        } | extra
