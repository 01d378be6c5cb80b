"""The plain straight moves of a word program read in bulk, with NumPy over the program's bytes.

Most lines of a CAM system's program are absolute straight moves: an optional ``G0``/``G1``, axis
words in the dialect's order and an optional feed (``G1 X10.5 Y3.25 Z-1 F600``). Such a line
changes nothing but the position, the modal motion and the feed. :class:`BulkScan` finds these
lines and parses their numbers for the whole text at once; the reader
(:mod:`axiscal.io.gcode.reader`) takes every other line through the block-by-block reader
(:mod:`axiscal.io.gcode.rs274`) and the runs of plain lines between them in one step each
(:func:`walk`). Positions, feeds and motions of the plain lines are computed with the same
arithmetic as the block reader (the number times the metres per unit, plus the offset), so the
two give the same motions to the bit; :class:`~axiscal.io.gcode.blocks.Block` and
:class:`~axiscal.io.gcode.blocks.Motion` objects of these lines are made only when asked for.

A number is parsed as its digits over a power of ten (both exact in a double when it has at most
15 digits and 22 decimals, so the one rounding of the division is the correctly rounded value, as
``float()`` gives); longer numbers go through ``float()``.

A plain line is taken in bulk only when the control's state makes its meaning plain: the program
not ended, units and absolute distance mode set, a feed programmed, and the modal motion (or the
line's own ``G0``/``G1``) a straight move; a printer line must carry its ``G0``/``G1`` (one command
a line), and its E word is taken only while the extruder is absolute. Any other line, and a plain
one the state does not allow, is read block by block. FANUC programs (numbers without a point
count increments) and conversational programs are read block by block throughout.
"""

from __future__ import annotations

import math
import re
from types import MappingProxyType

import numpy as np

from axiscal.io.gcode.blocks import ROTARY, Block, ControlState, Motion
from axiscal.io.lines import Lines

__all__ = ["BulkScan", "Bulk", "walk"]

_DEG = math.pi / 180.0
_MOTION_CODE = {"G0": 0, "G1": 1}
_WIDTH = 24  # characters of a number parsed in NumPy (longer ones: float())
_CHUNK = 1 << 19  # words parsed at a time (bounds the working arrays)
_POW10 = np.array([10.0 ** k for k in range(23)])


class BulkScan:
    """Which lines of a program are plain straight moves, and their words' numbers.

    Parameters
    ----------
    text : str
        The program.
    count : int
        Its number of lines (as :func:`~axiscal.io.gcode.reader.split_lines` counts them).
    axes : tuple of str
        The dialect's axis letters.

    Attributes
    ----------
    plain : numpy.ndarray of bool, shape (count,)
        Lines of plain words in order: optional G0/G1, axis words in the dialect's order, optional
        positive F; at least one axis word.
    g : numpy.ndarray of int8
        The G word's motion (0 or 1), -1 where none.
    axes : tuple of str
        The axes written on some plain line (a column each below).
    value : numpy.ndarray, shape (count, len(axes))
        The numbers of the axis words as written (program units, degrees), NaN where none.
    feed : numpy.ndarray
        The F number, NaN where none.
    has_e : numpy.ndarray of bool
        Whether the line has an E word.
    """

    def __init__(self, text: str, count: int, axes: tuple[str, ...]):
        letters = ("G",) + tuple(axes) + ("F",)
        rank = np.full(256, -1, dtype=np.int16)
        for r, letter in enumerate(letters):
            rank[ord(letter)] = rank[ord(letter.lower())] = r
        data = text.encode("utf-8", errors="replace")
        compact = data.translate(None, b" \t")
        lines = Lines(compact)
        if len(lines) != count:  # cannot happen: the line ends are the same; read everything block by block
            self._empty(count)
            return
        arr = np.frombuffer(compact, dtype=np.uint8)
        starts, ends = lines.starts, lines.ends
        number_char = np.zeros(256, dtype=bool)
        number_char[list(b"0123456789.+-")] = True
        word_rank = rank[arr]
        letter_pos = np.flatnonzero(word_rank >= 0)
        bad_pos = np.flatnonzero(~number_char[arr] & (word_rank < 0))
        plain = ends > starts
        # a character that is neither an allowed letter nor part of a number, inside a line
        line_of_bad = np.searchsorted(starts, bad_pos, side="right") - 1
        inside = (line_of_bad >= 0) & (bad_pos < ends[np.maximum(line_of_bad, 0)])
        plain[line_of_bad[inside]] = False
        split = _split_numbers(data, number_char)
        if split.size:  # the same lines, counted in the original bytes
            plain[np.searchsorted(Lines(data).starts, split, side="right") - 1] = False
        line_of = np.searchsorted(starts, letter_pos, side="right") - 1
        keep = plain[line_of]
        letter_pos, line_of = letter_pos[keep], line_of[keep]
        ranks = word_rank[letter_pos].astype(np.int16)
        # each word's number runs to the next letter of its line, or the line's end
        same_line_next = np.r_[line_of[1:] == line_of[:-1], False]
        stop = np.where(same_line_next, np.r_[letter_pos[1:], 0], ends[line_of])
        begin = letter_pos + 1
        first_word = np.r_[True, line_of[1:] != line_of[:-1]]
        bad = np.zeros(letter_pos.size, dtype=bool)
        bad |= first_word & (letter_pos != starts[line_of])  # a number before the first letter
        bad |= ~first_word & (ranks <= np.r_[-1, ranks[:-1]])  # letters out of order, or twice
        values, ok = _numbers(arr, compact, begin, stop)
        bad |= ~ok
        is_g = ranks == 0
        bad |= is_g & ~((stop - begin <= 2) & ((values == 0.0) | (values == 1.0)) & ~_has_point_or_sign(arr, begin, stop))
        is_f = ranks == len(letters) - 1
        bad |= is_f & ~(values > 0.0)
        axis_word = ~is_g & ~is_f
        # a line is plain when none of its words is bad and it has an axis word
        plain_lines = np.zeros(count, dtype=bool)
        has_axis = np.zeros(count, dtype=bool)
        has_axis[line_of[axis_word]] = True
        line_bad = np.zeros(count, dtype=bool)
        line_bad[line_of[bad]] = True
        plain_lines[:] = plain & has_axis & ~line_bad
        self.plain = plain_lines
        take = plain_lines[line_of]
        line_of, ranks, values, begin, stop = line_of[take], ranks[take], values[take], begin[take], stop[take]
        self.g = np.full(count, -1, dtype=np.int8)
        gw = ranks == 0
        self.g[line_of[gw]] = values[gw].astype(np.int8)
        self.feed = np.full(count, np.nan)
        fw = ranks == len(letters) - 1
        self.feed[line_of[fw]] = values[fw]
        used = [r for r in range(1, len(letters) - 1) if np.any(ranks == r)]
        self.axes = tuple(letters[r] for r in used)
        self.value = np.full((count, len(used)), np.nan)
        for j, r in enumerate(used):
            w = ranks == r
            self.value[line_of[w], j] = values[w]
        self.present = ~np.isnan(self.value)
        self.has_e = self.present[:, self.axes.index("E")] if "E" in self.axes else np.zeros(count, dtype=bool)
        # the words as written, for the Block of a plain line: its words are contiguous, in order
        self._compact = compact
        self._word_line, self._word_rank, self._word_begin, self._word_stop = line_of, ranks, begin, stop
        self._letters = letters

    def _empty(self, count: int) -> None:
        self.plain = np.zeros(count, dtype=bool)
        self.g = np.full(count, -1, dtype=np.int8)
        self.feed = np.full(count, np.nan)
        self.axes = ()
        self.value = np.zeros((count, 0))
        self.present = np.zeros((count, 0), dtype=bool)
        self.has_e = np.zeros(count, dtype=bool)
        self._word_line = np.zeros(0, dtype=np.int64)

    def words(self, lines: np.ndarray) -> list[tuple[tuple[str, str], ...]]:
        """The words (letter, number as written) of the plain lines ``lines`` (0-based, sorted)."""
        first = np.searchsorted(self._word_line, lines, side="left")
        last = np.searchsorted(self._word_line, lines, side="right")
        compact, letters = self._compact, self._letters
        ranks, begin, stop = self._word_rank.tolist(), self._word_begin.tolist(), self._word_stop.tolist()
        return [tuple((letters[ranks[k]], compact[begin[k]:stop[k]].decode("ascii")) for k in range(a, b))
                for a, b in zip(first.tolist(), last.tolist())]

    def raw(self, lines: np.ndarray, letter: str) -> list[str | None]:
        """The number written with ``letter`` on each of the plain lines ``lines`` (sorted), or None."""
        r = self._letters.index(letter)
        w = np.flatnonzero(self._word_rank == r)
        found = np.searchsorted(self._word_line[w], lines)
        found = np.minimum(found, max(w.size - 1, 0))
        out: list[str | None] = []
        compact = self._compact
        for line, k in zip(lines.tolist(), found.tolist()):
            if w.size and self._word_line[w[k]] == line:
                out.append(compact[self._word_begin[w[k]]:self._word_stop[w[k]]].decode("ascii"))
            else:
                out.append(None)
        return out


def _split_numbers(data: bytes, number_char: np.ndarray) -> np.ndarray:
    """Offsets of the runs of spaces and tabs that stand between two characters of numbers ("X1 2")."""
    arr = np.frombuffer(data, dtype=np.uint8)
    blank = (arr == 32) | (arr == 9)
    if not blank.any():
        return np.zeros(0, dtype=np.int64)
    edge = np.diff(blank.view(np.int8), prepend=np.int8(0), append=np.int8(0))
    first = np.flatnonzero(edge == 1)
    stop = np.flatnonzero(edge == -1)  # one past each run's last blank
    inner = (first > 0) & (stop < arr.size)
    first, stop = first[inner], stop[inner]
    between = number_char[arr[first - 1]] & number_char[arr[stop]]
    return first[between]


def _has_point_or_sign(arr: np.ndarray, begin: np.ndarray, stop: np.ndarray) -> np.ndarray:
    """Whether each (short) number holds a point or a sign (a G number is ``0``, ``1``, ``00`` or ``01``)."""
    out = np.zeros(begin.size, dtype=bool)
    for k in range(2):
        at = begin + k
        inside = at < stop
        c = arr[np.minimum(at, arr.size - 1)]
        out |= inside & ((c == ord(".")) | (c == ord("+")) | (c == ord("-")))
    return out


def _numbers(arr: np.ndarray, compact: bytes, begin: np.ndarray, stop: np.ndarray):
    """The value of each number ``arr[begin:stop]`` (the grammar ``[+-]?(\\d+\\.?\\d*|\\.\\d+)``) and
    whether it is one."""
    n = begin.size
    values = np.full(n, np.nan)
    ok = np.zeros(n, dtype=bool)
    length = stop - begin
    columns = np.arange(_WIDTH)
    for lo in range(0, n, _CHUNK):
        hi = min(n, lo + _CHUNK)
        b, ln = begin[lo:hi], length[lo:hi]
        width = int(min(_WIDTH, ln.max(initial=0)))
        if width == 0:
            continue
        inside = columns[None, :width] < ln[:, None]
        chars = np.where(inside, arr[np.minimum(b[:, None] + columns[None, :width], arr.size - 1)], 0)
        digit = (chars >= 48) & (chars <= 57)
        point = chars == 46
        sign = (chars == 43) | (chars == 45)
        digits = np.count_nonzero(digit, axis=1)
        points = np.count_nonzero(point, axis=1)
        good = (ln >= 1) & (ln <= width) & (digits >= 1) & (points <= 1) & ~sign[:, 1:].any(axis=1)
        good &= digits + points + sign[:, 0] == ln
        after = np.logical_or.accumulate(point, axis=1)
        decimals = np.count_nonzero(digit & after, axis=1)
        exact = good & (digits <= 15) & (decimals <= 22)
        mantissa = np.zeros(hi - lo, dtype=np.int64)
        for c in range(width):
            d = digit[:, c]
            mantissa = np.where(d, mantissa * 10 + (chars[:, c].astype(np.int64) - 48), mantissa)
        value = mantissa / _POW10[np.minimum(decimals, 22)]
        value = np.where(chars[:, 0] == 45, -value, value)
        values[lo:hi] = np.where(exact, value, np.nan)
        ok[lo:hi] = good
        for k in np.flatnonzero(good & ~exact):  # long numbers: Python's own parse
            values[lo + k] = float(compact[b[k]:b[k] + ln[k]])
    # a number longer than the parsed width: Python's grammar check and parse
    for k in np.flatnonzero(length > _WIDTH):
        raw = compact[begin[k]:stop[k]]
        if re.fullmatch(rb"[+-]?(?:\d+\.?\d*|\.\d+)", raw):
            values[k], ok[k] = float(raw), True
    return values, ok


class Bulk:
    """The runs of plain lines taken in bulk, with the control's state at the start of each.

    Parameters
    ----------
    scan : BulkScan
    state : ControlState
    """

    def __init__(self, scan: BulkScan, state: ControlState):
        self.scan = scan
        self.state = state
        self.lines = np.zeros(0, dtype=np.int64)
        #: per run: (first line, stop line, start position, metres per unit, offsets, motion, feed, extruder relative)
        self.runs: list[tuple] = []

    def _take(self, first: int, stop: int) -> None:
        """Take lines [first, stop) (0-based) in one step, and bring the state to their end."""
        state, scan = self.state, self.scan
        per_unit = state.metres_per_unit
        offsets = {k: state.offset(k) for k in state.spec.axes}
        self.runs.append((first, stop, dict(state.position), per_unit, offsets, state.motion, state.feed,
                          state.extruder_relative()))
        position = dict(state.position)
        for j, letter in enumerate(scan.axes):
            column = scan.present[first:stop, j]
            if column.any():
                last = stop - 1 - int(np.argmax(column[::-1]))
                scale = _DEG if letter in ROTARY else per_unit
                position[letter] = float(scan.value[last, j] * scale + offsets[letter])
        feeds = scan.feed[first:stop]
        given = ~np.isnan(feeds)
        if given.any():
            state.feed = float(feeds[stop - first - 1 - int(np.argmax(given[::-1]))] * per_unit / 60.0)
        motions = scan.g[first:stop]
        written = motions >= 0
        if written.any():
            state.motion = "G1" if motions[stop - first - 1 - int(np.argmax(written[::-1]))] == 1 else "G0"
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
    rows = np.arange(value.shape[0])[:, None]
    index = np.maximum.accumulate(np.where(valid, rows, 0), axis=0)
    columns = np.arange(value.shape[1])[None, :]
    return value[index, columns], valid[index, columns]


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
            motion = Motion(line + 1, kind, end, float(self.feed[i]) if kind == "feed" else None, 0.0, previous)
            previous = end
            word = next((f"G{int(raw)}" for letter, raw in written if letter == "G"), None)
            out.append(Block(line + 1, texts[line], motion, written, "", "", word, True, per_unit, offsets_view,
                             extruder_relative))
        return out


def walk(lines: list[str], state: ControlState, scan: BulkScan, run_block) -> Bulk:
    """Read ``lines``: the runs of plain lines the state allows in bulk, every other line with ``run_block``."""
    bulk = Bulk(scan, state)
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
                state.line = i + 1
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
                state.line = i + 1
                run_block(lines[i], state)
                i += 1
        if j < n:
            state.line = j + 1
            run_block(lines[j], state)
        i = j + 1
    return bulk
