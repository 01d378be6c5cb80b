"""The plain straight moves of a word program read in bulk: one compiled pass over its bytes, then NumPy.

Most lines of a CAM system's program are absolute straight moves: an optional ``G0``/``G1``, axis
words in the dialect's order and an optional feed (``G1 X10.5 Y3.25 Z-1 F600``). Such a line
changes nothing but the position, the modal motion and the feed. :class:`BulkScan` finds these
lines and parses their numbers for the whole text at once (:mod:`axiscal.io.gcode.scan_kernel`);
the reader (:mod:`axiscal.io.gcode.reader`) takes every other line through the block-by-block
reader (:mod:`axiscal.io.gcode.rs274`) and the runs of plain lines between them in one step each
(:func:`walk`). Positions, feeds and motions of the plain lines are computed with the same
arithmetic as the block reader (the number times the metres per unit, plus the offset), so the
two give the same motions to the bit; :class:`~axiscal.io.gcode.blocks.Block` and
:class:`~axiscal.io.gcode.blocks.Motion` objects of these lines are made only when asked for.

A plain line is taken in bulk only when the control's state makes its meaning plain: the program
not ended, units and absolute distance mode set, a feed programmed, and the modal motion (or the
line's own ``G0``/``G1``) a straight move; a printer line must carry its ``G0``/``G1`` (one command
a line), and its E word is taken only while the extruder is absolute. Any other line, and a plain
one the state does not allow, is read block by block. FANUC programs (numbers without a point
count increments), conversational programs and short programs are read block by block throughout.
"""

from __future__ import annotations

import math
import re
from types import MappingProxyType

import numpy as np

from axiscal.io.gcode.blocks import ROTARY, Block, ControlState, Motion

__all__ = ["BulkScan", "Bulk", "walk", "plain_words"]

_DEG = math.pi / 180.0
_MOTION_CODE = {"G0": 0, "G1": 1}


class BulkScan:
    """Which lines of a program are plain straight moves, and their words' numbers.

    Parameters
    ----------
    text : str
        The program.
    lines : list of str
        Its lines (:func:`~axiscal.io.gcode.reader.split_lines`).
    axes : tuple of str
        The dialect's axis letters.
    numbered : bool, keyword-only
        Whether a first word N is the block number (the RS-274 dialects; a printer has none).
    need_point : bool, keyword-only
        Whether an axis number without a decimal point counts increments (FANUC): such a line is
        read block by block.

    Attributes
    ----------
    plain : numpy.ndarray of bool, shape (len(lines),)
        Lines of plain words in order: optional G0/G1, axis words in the dialect's order, optional
        positive F; at least one axis word.
    g : numpy.ndarray of int8
        The G word's motion (0 or 1), -1 where none.
    axes : tuple of str
        The axes written on some plain line (a column each below).
    value : numpy.ndarray, shape (len(lines), len(axes))
        The numbers of the axis words as written (program units, degrees), NaN where none.
    present : numpy.ndarray of bool, shape (len(lines), len(axes))
        Whether the line has the axis word.
    feed : numpy.ndarray
        The F number, NaN where none.
    has_e : numpy.ndarray of bool
        Whether the line has an E word.
    number_at : numpy.ndarray of int32, shape (len(lines), 2)
        Where the block number's digits start and stop in the line (0, 0: no block number).
    """

    def __init__(self, text: str, lines: list[str], axes: tuple[str, ...], *, numbered: bool = False,
                 need_point: bool = False):
        from axiscal.io.gcode import scan_kernel  # numba takes a moment to load: only for programs read in bulk

        letters = ("G",) + tuple(axes) + ("F",)
        rank = np.full(256, -1, dtype=np.int16)
        for r, letter in enumerate(letters):
            rank[ord(letter)] = rank[ord(letter.lower())] = r
        data = np.frombuffer(text.encode("utf-8", errors="replace"), dtype=np.uint8)
        count = len(lines)
        status, g, feed, value, present, number_at = scan_kernel.scan(data, rank, len(axes), count, scan_kernel._POW10,
                                                                      numbered, need_point)
        for line in np.flatnonzero(status == scan_kernel.LONG).tolist():  # a number of more than 15 digits: float()
            for letter, raw in plain_words(lines[line]):
                if letter in axes:
                    value[line, axes.index(letter)] = float(raw)
        self.plain = status != scan_kernel.OTHER
        used = np.flatnonzero(present.any(axis=0))
        self.axes = tuple(axes[j] for j in used)
        self.g = g
        self.feed = feed
        self.value = value[:, used]
        self.present = present[:, used]
        self.has_e = self.present[:, self.axes.index("E")] if "E" in self.axes else np.zeros(count, dtype=bool)
        self.number_at = number_at
        self._lines = lines

    def number(self, line: int) -> str:
        """The block number of the plain line ``line`` as written (``N120``), or ""."""
        start, stop = self.number_at[line]
        return f"N{self._lines[line][start:stop]}" if stop > start else ""

    def words(self, lines: np.ndarray) -> list[tuple[tuple[str, str], ...]]:
        """The words (letter, number as written) of the plain lines ``lines`` (0-based)."""
        return [plain_words(self._lines[line]) for line in lines.tolist()]

    def raw(self, lines: np.ndarray, letter: str) -> list[str | None]:
        """The number written with ``letter`` on each of the plain lines ``lines``, or None."""
        return [dict(plain_words(self._lines[line])).get(letter) for line in lines.tolist()]


_WORD = re.compile(r"([A-Za-z])[ \t]*([+-]?(?:\d+\.?\d*|\.\d+))")


def plain_words(line: str) -> tuple[tuple[str, str], ...]:
    """The words of a plain line (one :class:`BulkScan` found plain): (letter upper-cased, number as
    written), its block number left out."""
    return tuple((letter.upper(), raw) for letter, raw in _WORD.findall(line) if letter not in "Nn")


class Bulk:
    """The runs of plain lines taken in bulk, with the control's state at the start of each.

    Parameters
    ----------
    scan : BulkScan
    state : ControlState
    """

    def __init__(self, scan: BulkScan, state: ControlState, first_line: int = 0):
        self.scan = scan
        self.state = state
        self.first_line = first_line
        self.lines = np.zeros(0, dtype=np.int64)
        #: per run: (first line, stop line, start position, metres per unit, offsets, motion, feed, extruder relative)
        self.runs: list[tuple] = []
        # per line, the last line at or before it that writes each axis, an F and a G word (-1: none), so
        # that a run's end state is looked up, not searched for (a CAM program's arcs cut it into thousands of runs)
        written = np.column_stack([scan.present, ~np.isnan(scan.feed), scan.g >= 0])
        rows = np.arange(written.shape[0])[:, None]
        self._last = np.maximum.accumulate(np.where(written, rows, -1), axis=0) if written.size else written.astype(np.int64)
        self._offsets_key: tuple | None = None
        self._offsets: dict[str, float] = {}

    def _take(self, first: int, stop: int) -> None:
        """Take lines [first, stop) (0-based) in one step, and bring the state to their end."""
        state, scan = self.state, self.scan
        per_unit = state.metres_per_unit
        key = (state._shift_version, len(state.shift))  # the offsets change only with G92 and its clearing
        if self._offsets_key != key:
            self._offsets_key, self._offsets = key, {k: state.offset(k) for k in state.spec.axes}
        offsets = self._offsets
        self.runs.append((first, stop, dict(state.position), per_unit, offsets, state.motion, state.feed,
                          state.extruder_relative()))
        position = dict(state.position)
        last = self._last[stop - 1].tolist()
        naxes = len(scan.axes)
        for j, letter in enumerate(scan.axes):
            if last[j] >= first:
                scale = _DEG if letter in ROTARY else per_unit
                position[letter] = float(scan.value[last[j], j] * scale + offsets[letter])
        if last[naxes] >= first:
            state.feed = float(scan.feed[last[naxes]] * per_unit / 60.0)
        if last[naxes + 1] >= first:
            state.motion = "G1" if scan.g[last[naxes + 1]] == 1 else "G0"
        state.position = position
        state._view = MappingProxyType(position)
        state.moved = True

    def allowed(self) -> tuple[bool, bool] | None:
        """(G word needed, E word taken) in the state as it now is, or None: no line is taken."""
        state = self.state
        if state.ended or state.absolute is not True or state.metres_per_unit is None or state.feed is None:
            return None
        need_g = state.spec.syntax == "printer" or state.motion not in _MOTION_CODE
        return need_g, "E" in state.spec.axes and not state.extruder_relative()

    # ---- afterwards, in bulk

    def columns(self) -> "_Taken":
        """End positions, known axes, feeds and motions of every line taken (see :class:`_Taken`)."""
        scan = self.scan
        runs = self.runs
        lengths = np.array([r[1] - r[0] for r in runs], dtype=np.int64)
        lines = np.concatenate([np.arange(r[0], r[1]) for r in runs]) if runs else np.zeros(0, dtype=np.int64)
        n = lines.size
        naxes = len(scan.axes)
        run_of = np.repeat(np.arange(len(runs)), lengths)
        # the extended arrays: one seed row (the run's start) before each run's rows
        at = np.arange(n) + run_of + 1
        seeds = np.r_[0, np.cumsum(lengths + 1)[:-1]].astype(np.int64) if runs else np.zeros(0, dtype=np.int64)
        total = n + len(runs)
        value = np.full((total, naxes), np.nan)
        valid = np.zeros((total, naxes), dtype=bool)
        for r, run in enumerate(runs):
            for j, letter in enumerate(scan.axes):
                if letter in run[2]:
                    value[seeds[r], j] = run[2][letter]
                    valid[seeds[r], j] = True
        per_unit = np.array([r[3] for r in runs], dtype=float)
        present = scan.present[lines]
        numbers = scan.value[lines]
        for j, letter in enumerate(scan.axes):
            rows = np.flatnonzero(present[:, j])
            scale = _DEG if letter in ROTARY else per_unit[run_of[rows]]
            offset = np.array([r[4][letter] for r in runs], dtype=float)[run_of[rows]]
            value[at[rows], j] = numbers[rows, j] * scale + offset
            valid[at[rows], j] = True
        end, known = _filled(value, valid)
        feed_ext = np.full(total, np.nan)
        feed_ext[seeds] = [np.nan if r[6] is None else r[6] for r in runs]
        feed_valid = np.zeros(total, dtype=bool)
        feed_valid[seeds] = True
        feeds = scan.feed[lines]
        rows = np.flatnonzero(~np.isnan(feeds))
        feed_ext[at[rows]] = feeds[rows] * per_unit[run_of[rows]] / 60.0
        feed_valid[at[rows]] = True
        feed_all, _ = _filled(feed_ext[:, None], feed_valid[:, None])
        motion_ext = np.full(total, -1, dtype=np.int8)
        motion_ext[seeds] = [_MOTION_CODE.get(r[5], -1) for r in runs]
        motion_valid = np.zeros(total, dtype=bool)
        motion_valid[seeds] = True
        g = scan.g[lines]
        rows = np.flatnonzero(g >= 0)
        motion_ext[at[rows]] = g[rows]
        motion_valid[at[rows]] = True
        index = np.maximum.accumulate(np.where(motion_valid, np.arange(total), 0))
        return _Taken(self, lines, end[at], known[at], feed_all[at, 0], motion_ext[index][at], run_of)


def _filled(value: np.ndarray, valid: np.ndarray):
    """``value`` with each invalid entry taken from the last valid one above it (per column), and
    the mask of entries that have one."""
    rows = np.arange(value.shape[0])
    out, known = np.empty_like(value), np.empty_like(valid)
    for j in range(value.shape[1]):
        index = np.maximum.accumulate(np.where(valid[:, j], rows, 0))
        out[:, j] = value[index, j]
        known[:, j] = valid[index, j]
    return out, known


class _Taken:
    """The lines taken in bulk: their positions and modes as columns, their Blocks on demand.

    Attributes
    ----------
    lines : numpy.ndarray of int64
        The lines taken (0-based), in order.
    end, known : numpy.ndarray, shape (len(lines), len(scan.axes))
        Position of each axis after the line (SI), and whether it is known.
    feed : numpy.ndarray
        The feed in force, metres per second (NaN: none).
    motion : numpy.ndarray of int8
        The motion in force: 0 G0, 1 G1.
    run_of : numpy.ndarray of int64
        The run each line belongs to (an index of ``bulk.runs``).
    """

    def __init__(self, bulk: Bulk, lines, end, known, feed, motion, run_of):
        self.bulk = bulk
        self.lines, self.end, self.known, self.feed, self.motion, self.run_of = lines, end, known, feed, motion, run_of

    def kinds(self) -> np.ndarray:
        """1 for a rapid move, 2 for a straight move at the feed (codes of :data:`~axiscal.io.gcode.columns.KINDS`)."""
        if self.bulk.state.spec.rapid_at_feed:
            return np.full(self.motion.size, 2, dtype=np.int8)
        return np.where(self.motion == 1, 2, 1).astype(np.int8)

    def blocks(self, texts: list[str]) -> list[Block]:
        """The Block (with its Motion) of every line taken, as the block reader records it."""
        scan = self.bulk.scan
        axes = scan.axes
        kinds = self.kinds()
        words = scan.words(self.lines)
        out: list[Block] = []
        keys: list[str] = []
        offsets_view = previous = None
        run = -1
        first = self.bulk.first_line
        for i, line in enumerate(self.lines.tolist()):
            if self.run_of[i] != run:
                run = self.run_of[i]
                _, _, start, per_unit, offsets, _, _, extruder_relative = self.bulk.runs[run]
                keys = list(start)
                offsets_view = None
                previous = MappingProxyType(dict(start))
            written = words[i]
            added = False
            for letter, _ in written:
                if letter in offsets and letter not in keys:
                    keys.append(letter)
                    added = True
            if added or offsets_view is None:
                offsets_view = MappingProxyType({k: offsets[k] for k in keys})
            end = MappingProxyType({k: (float(self.end[i, axes.index(k)]) if k in axes else start[k]) for k in keys})
            kind = "feed" if kinds[i] == 2 else "rapid"
            motion = Motion(first + line + 1, kind, end, float(self.feed[i]) if kind == "feed" else None, 0.0, previous)
            previous = end
            word = next((f"G{int(raw)}" for letter, raw in written if letter == "G"), None)
            out.append(Block(first + line + 1, texts[line], motion, written, scan.number(line), "", word, True, per_unit,
                             offsets_view, extruder_relative))
        return out


def walk(lines: list[str], state: ControlState, scan: BulkScan, run_block, *, first_line: int = 0) -> Bulk:
    """Read ``lines``: the runs of plain lines the state allows in bulk, every other line with ``run_block``.

    ``first_line`` is the 0-based number of ``lines[0]`` in the whole program (a program read in pieces).
    """
    bulk = Bulk(scan, state, first_line)
    n = len(lines)
    plain = scan.plain
    others = np.flatnonzero(~plain).tolist() + [n]
    no_g = scan.g < 0
    has_e = scan.has_e
    i = 0
    for j in others:  # lines [i, j) are plain, line j is not (or the end)
        while i < j:
            allowed = bulk.allowed()
            if allowed is None:
                state.line = first_line + i + 1
                run_block(lines[i], state)
                i += 1
                continue
            need_g, e_taken = allowed
            k = j
            if need_g or not e_taken:
                refused = (no_g[i:j] if need_g else False) | (has_e[i:j] if not e_taken else False)
                if np.any(refused):
                    k = i + int(np.argmax(refused))
            if k > i:
                bulk._take(i, k)
                i = k
            if i < j:  # a plain line the state does not take
                state.line = first_line + i + 1
                run_block(lines[i], state)
                i += 1
        if j < n:
            state.line = first_line + j + 1
            run_block(lines[j], state)
        i = j + 1
    return bulk
