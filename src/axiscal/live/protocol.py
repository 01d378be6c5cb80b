"""The frame batch and the line protocol of the TCP and serial sources (docs/live.md, "Line protocol").

One frame per line, UTF-8, fields separated by commas, ``\\n``, ``\\r\\n`` or ``\\r`` at the end::

    t_s,x_scale_mm,x_psd_y_um,...          <- optional header (any line naming t_s): the columns of the lines after it
    0.000100,12.500031,0.8123,...          <- t_s, then the channels of MeasurementSystem.channels

Without a header the columns are ``t_s`` and then the channels in ``MeasurementSystem.channels``
order. A header may give the columns in any order and may leave channels out (they are then
missing in every frame); a column it names that the system does not know is ignored. Lines
starting with ``#`` and empty lines are skipped. An empty cell, ``nan`` or a cell that is not a
number is a missing channel; a frame whose ``t_s`` cannot be read, or whose line has more fields
than there are columns (the sender's columns are not the ones assumed: send a header), is kept but
marked malformed. A line longer than :data:`MAX_LINE_BYTES` is not kept in memory: it counts as one
malformed frame and the decoder resynchronises on the next line end.
Nothing a sender writes can stop the stream: bad lines become faulty frames, never errors.
"""

from __future__ import annotations

from collections.abc import Iterable, Sequence
from dataclasses import dataclass

import numpy as np

from axiscal.errors import AxiscalError
from axiscal.io.arguments import check_array, check_count, check_same_length
from axiscal.io.arguments import type_name

__all__ = ["MAX_LINE_BYTES", "FrameBatch", "LineDecoder", "encode_lines", "header_line"]

#: longest line the decoder keeps, bytes without its line end (a frame of 100 channels at 25 characters is 2.5 kB)
MAX_LINE_BYTES = 65536


@dataclass(frozen=True)
class FrameBatch:
    """Frames as they arrive from a source, before processing.

    Attributes
    ----------
    t_s : ndarray, shape (N,)
        Time stamp of each frame, seconds (NaN when it could not be read).
    values : ndarray, shape (N, C)
        Raw channel readings in ``channels`` order, each in its own unit; NaN = missing.
    malformed : ndarray of bool, shape (N,)
        Frames whose line or row could not be read as a frame.
    """

    t_s: np.ndarray
    values: np.ndarray
    malformed: np.ndarray

    def __len__(self) -> int:
        return len(self.t_s)

    def frames(self, channels: Sequence[str]) -> dict[str, np.ndarray]:
        """The mapping ``MeasurementSystem.process`` takes: ``"t_s"`` and every channel, shape (N,)."""
        out = {"t_s": self.t_s}
        out.update({name: self.values[:, i] for i, name in enumerate(channels)})
        return out

    @classmethod
    def from_frames(cls, frames: dict[str, np.ndarray], channels: Sequence[str]) -> "FrameBatch":
        """Build a batch from a mapping of ``"t_s"`` and channel arrays (a missing key is a missing channel)."""
        t = np.asarray(frames["t_s"], dtype=float)
        values = np.full((len(t), len(channels)), np.nan)
        for i, name in enumerate(channels):
            if name in frames:
                values[:, i] = frames[name]
        return cls(t, values, ~np.isfinite(t))

    @classmethod
    def empty(cls, width: int) -> "FrameBatch":
        """No frames, ``width`` channels (what a source returns when nothing arrived)."""
        return cls(np.empty(0), np.empty((0, width)), np.zeros(0, dtype=bool))

    @classmethod
    def concatenate(cls, batches: Sequence["FrameBatch"], width: int) -> "FrameBatch":
        if not batches:
            return cls.empty(width)
        return cls(
            np.concatenate([b.t_s for b in batches]),
            np.concatenate([b.values for b in batches]),
            np.concatenate([b.malformed for b in batches]),
        )


def _checked_channels(channels: Sequence[str], name: str = "channels") -> tuple[str, ...]:
    """``channels`` as a tuple of non-empty names, else refused naming ``name`` (checked once, where a
    source, decoder or record is made, never per frame)."""
    if isinstance(channels, (str, bytes)) or not isinstance(channels, Iterable):
        raise AxiscalError(f"{name} must be a sequence of channel names, not {type_name(channels) if not isinstance(channels, str) else repr(channels)}")
    out = tuple(channels)
    for channel in out:
        if not isinstance(channel, str) or not channel.strip():
            raise AxiscalError(f"{name} must be a sequence of channel names, not holding {channel!r}")
    return out


def _cell(text: str) -> float:
    try:
        return float(text)
    except ValueError:
        return np.nan


class LineDecoder:
    """Turns the bytes of the line protocol into :class:`FrameBatch` es, keeping a partial last line.

    Parameters
    ----------
    channels : sequence of str
        The channel names of the measurement system, in frame order.
    max_line_bytes : int, keyword-only
        Longest line kept; a longer one is one malformed frame, the rest of it up to the next line
        end is dropped as it arrives (memory stays bounded whatever a sender writes).

    Attributes
    ----------
    lines, malformed_lines, overlong_lines : int
        Lines decoded, of them malformed, of them too long.
    ignored_columns : tuple of str
        Columns the last header named that the system does not know.

    Raises
    ------
    AxiscalError
        For ``channels`` that are not a sequence of names or a ``max_line_bytes`` below 1;
        :meth:`feed` for data that is not bytes.

    Examples
    --------
    >>> decoder = LineDecoder(["a_mm"], max_line_bytes=16)
    >>> batch = decoder.feed(b"0.1,1\\r" + b"9" * 40 + b"\\r0.2,2\\r")
    >>> batch.t_s.tolist(), batch.malformed.tolist()
    ([0.1, nan, 0.2], [False, True, False])
    """

    def __init__(self, channels: Sequence[str], *, max_line_bytes: int = MAX_LINE_BYTES):
        check_count("max_line_bytes", max_line_bytes, minimum=1)
        self.channels = _checked_channels(channels)
        self.max_line_bytes = int(max_line_bytes)
        self._discarding = False
        self.overlong_lines = 0
        self._pending = b""
        self._columns: tuple[str, ...] = ("t_s",) + self.channels
        self._order = np.arange(len(self._columns))
        self.lines = 0
        self.malformed_lines = 0
        self.ignored_columns: tuple[str, ...] = ()

    def reset(self) -> None:
        """Forget a partial line and any header (a new connection starts afresh)."""
        self._pending = b""
        self._discarding = False
        self._set_columns(("t_s",) + self.channels)

    def _set_columns(self, columns: Sequence[str]) -> None:
        self._columns = tuple(columns)
        position = {name: i for i, name in enumerate(self._columns)}
        wanted = ("t_s",) + self.channels
        self._order = np.array([position.get(name, -1) for name in wanted])
        self.ignored_columns = tuple(name for name in self._columns if name not in wanted)

    def feed(self, data: bytes) -> FrameBatch:
        """Decode the complete lines in ``data`` (plus what was pending); keep the incomplete tail.

        ``\\n``, ``\\r\\n`` and ``\\r`` end a line. A line longer than ``max_line_bytes`` is one
        malformed frame; what follows of it up to the next line end is dropped.
        """
        if not isinstance(data, (bytes, bytearray)):
            raise AxiscalError(f"data must be the bytes a source read, not {type_name(data)}")
        data = data.replace(b"\r", b"\n")  # CR-only and CRLF ends; the empty line a CRLF leaves is skipped
        if self._discarding:  # inside an overlong line: drop up to its end
            end = data.find(b"\n")
            if end < 0:
                return self.decode_lines(())
            self._discarding = False
            data = data[end + 1 :]
        data = self._pending + data
        cut = data.rfind(b"\n")
        block, tail = (b"", data) if cut < 0 else (data[:cut], data[cut + 1 :])
        cap = self.max_line_bytes
        if len(block) <= cap:
            lines: list[str | None] = block.decode("utf-8", errors="replace").split("\n") if cut >= 0 else []
        else:
            lines = [None if len(raw) > cap else raw.decode("utf-8", errors="replace") for raw in block.split(b"\n")]
        if len(tail) > cap:
            lines.append(None)
            self._discarding = True
            tail = b""
        self._pending = tail
        return self.decode_lines(lines)

    def flush(self) -> FrameBatch:
        """Decode a last line that had no newline (at the end of a stream)."""
        tail, self._pending = self._pending, b""
        return self.decode_lines([tail.decode("utf-8", errors="replace")] if tail.strip() else [])

    def decode_lines(self, lines: Iterable[str | None]) -> FrameBatch:
        """Decode text lines (without their newline) into frames; a header applies to the lines after it.

        ``None`` stands for a line that was too long to keep: it becomes one malformed frame.
        """
        if isinstance(lines, (str, bytes)) or not isinstance(lines, Iterable):
            raise AxiscalError(f"lines must be an iterable of text lines, not {type_name(lines)}")
        segments: list[FrameBatch] = []
        rows: list[list[str]] = []
        for line in lines:
            if line is None:
                self.overlong_lines += 1
                rows.append([])  # no readable time stamp: a malformed frame
                continue
            line = line.strip()
            if not line or line.startswith("#"):
                continue
            cells = line.split(",")
            if "t_s" in line and "t_s" in (names := [c.strip() for c in cells]):
                segments.append(self._decode_rows(rows))
                rows = []
                self._set_columns(names)
                continue
            rows.append(cells)
        segments.append(self._decode_rows(rows))
        batches = [b for b in segments if len(b)]
        return batches[0] if len(batches) == 1 else FrameBatch.concatenate(batches, len(self.channels))

    def _decode_rows(self, rows: list[list[str]]) -> FrameBatch:
        width = len(self._columns)
        self.lines += len(rows)
        if not rows:
            return FrameBatch.concatenate([], len(self.channels))
        too_long = np.zeros(len(rows), dtype=bool)
        try:
            parsed = np.array(rows, dtype=float)
            if parsed.shape[1] != width:
                raise ValueError("wrong number of cells")
        except ValueError:
            parsed = np.full((len(rows), width), np.nan)
            for k, cells in enumerate(rows):
                too_long[k] = len(cells) > width
                cells = cells[:width]
                parsed[k, : len(cells)] = [_cell(c) for c in cells]
        full = np.concatenate([parsed, np.full((len(rows), 1), np.nan)], axis=1)
        ordered = full[:, self._order]
        ordered[~np.isfinite(ordered)] = np.nan
        t = ordered[:, 0]
        malformed = np.isnan(t) | too_long
        self.malformed_lines += int(malformed.sum())
        return FrameBatch(np.ascontiguousarray(t), np.ascontiguousarray(ordered[:, 1:]), malformed)


def encode_lines(t_s: np.ndarray, values: np.ndarray) -> bytes:
    """Frames as protocol lines (no header): what an acquisition box sends; used by tests and benchmarks.

    Parameters
    ----------
    t_s : ndarray, shape (N,)
        Time stamps, s.
    values : ndarray, shape (N, C)
        Channel values in frame order, each in its own unit.

    Returns
    -------
    bytes
        One UTF-8 line per frame.

    Raises
    ------
    AxiscalError
        For ``t_s`` that is not one-dimensional, ``values`` that is not two-dimensional, or
        lengths that differ.
    """
    t_s = check_array("t_s", t_s, ndim=1, finite=False)
    values = check_array("values", values, ndim=2, finite=False)
    check_same_length(t_s=t_s, values=values)
    table = np.column_stack([t_s, values])
    text = "".join(",".join(repr(v) for v in row) + "\n" for row in table.tolist())
    return text.encode("utf-8")


def header_line(channels: Sequence[str]) -> bytes:
    """The optional header line naming the columns.

    Parameters
    ----------
    channels : sequence of str
        Channel names in the order the lines carry them.

    Returns
    -------
    bytes
        ``t_s,<channels>`` and a newline.

    Raises
    ------
    AxiscalError
        For ``channels`` that are not a sequence of names.
    """
    return (",".join(("t_s",) + _checked_channels(channels)) + "\n").encode("utf-8")
