"""A program's lines as columns: what a whole-program computation (pre-compensation) needs, in NumPy.

:class:`ProgramColumns` holds, per line of the program, the motion's kind, the position of every
axis after the line, the modes in force (units, distance mode, extruder mode), the offsets and
the motion word written; the lines read block by block keep their
:class:`~axiscal.io.gcode.blocks.Block` for what only a block says (its words, number, comment,
an arc's centre). Built from a :class:`~axiscal.io.gcode.reader.Program` without making a
Block object for the lines read in bulk.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from axiscal.io.gcode.blocks import Block

__all__ = ["ProgramColumns", "KINDS", "MOTION_WORDS", "program_columns", "joined"]

#: the motion kinds by their code in :attr:`ProgramColumns.kind` (0: the line moves nothing)
KINDS = ("", "rapid", "feed", "arc", "dwell")
#: the motion words by their code in :attr:`ProgramColumns.motion_word` (-1: none written)
MOTION_WORDS = ("G0", "G1", "G2", "G3")
_KIND_CODE = {kind: code for code, kind in enumerate(KINDS)}
_WORD_CODE = {word: code for code, word in enumerate(MOTION_WORDS)}


@dataclass(frozen=True)
class ProgramColumns:
    """A program as columns: per line (index = line number - 1), and per motion (move or dwell).

    Attributes
    ----------
    axes : tuple of str
        The axes the program moves, in the dialect's order (a column each below).
    kind : numpy.ndarray of int8, shape (n,)
        Code of the line's motion in :data:`KINDS` (0: none).
    absolute, extruder_relative : numpy.ndarray of bool, shape (n,)
        The distance mode (G90) and the extruder's mode in force in the line.
    metres_per_unit : numpy.ndarray, shape (n,)
        Metres one program unit stands for in the line.
    motion_word : numpy.ndarray of int8, shape (n,)
        Code of the motion word written in the line in :data:`MOTION_WORDS`, -1 for none.
    feed_word : list of (str or None)
        The F number written in each line read in bulk; None for the others.
    bulk_row : numpy.ndarray of int64, shape (n,)
        For a line read in bulk, 0 or more (its row among those lines); -1 for the others.
    has_e : numpy.ndarray of bool, shape (n,)
        Whether a line that moves has an E word written on it.
    number_at : numpy.ndarray of int32, shape (n, 2)
        Where the block number's digits start and stop in a line read in bulk (0, 0: none; the
        others' is their Block's).
    general : dict of int to Block
        The Block of every line read block by block, by line index.
    first_line : int
        The 0-based number of the first line in the whole program (a program read in pieces).
    motion_word_before : int
        Code in :data:`MOTION_WORDS` of the last motion word written before the first line, -1 for none.
    motion_line : numpy.ndarray of int64, shape (m,)
        The line index of every motion, in order.
    end_m, start_m : numpy.ndarray, shape (m, len(axes))
        Position of each axis after and before each motion (metres, radians for A, B, C); NaN where
        not known.
    known, start_known : numpy.ndarray of bool, shape (m, len(axes))
        Whether the axis's position is known after and before the motion.
    offset_m : numpy.ndarray, shape (m, len(axes))
        Axis position minus program coordinate in the motion's line (0 for an axis not yet known).
    """

    axes: tuple[str, ...]
    kind: np.ndarray
    absolute: np.ndarray
    extruder_relative: np.ndarray
    metres_per_unit: np.ndarray
    motion_word: np.ndarray
    feed_word: list
    bulk_row: np.ndarray
    has_e: np.ndarray
    number_at: np.ndarray
    general: dict[int, Block]
    motion_line: np.ndarray
    end_m: np.ndarray
    known: np.ndarray
    start_m: np.ndarray
    start_known: np.ndarray
    offset_m: np.ndarray
    first_line: int = 0
    motion_word_before: int = -1

    def tail(self, line: int) -> "ProgramColumns":
        """The columns of the lines from index ``line`` on."""
        rows = int(np.searchsorted(self.motion_line, line))
        written = np.flatnonzero(self.motion_word[:line] >= 0)
        before = int(self.motion_word[written[-1]]) if written.size else self.motion_word_before
        return ProgramColumns(
            axes=self.axes, kind=self.kind[line:], absolute=self.absolute[line:],
            extruder_relative=self.extruder_relative[line:], metres_per_unit=self.metres_per_unit[line:],
            motion_word=self.motion_word[line:], feed_word=self.feed_word[line:], bulk_row=self.bulk_row[line:],
            has_e=self.has_e[line:], number_at=self.number_at[line:],
            general={i - line: block for i, block in self.general.items() if i >= line},
            motion_line=self.motion_line[rows:] - line, end_m=self.end_m[rows:], known=self.known[rows:],
            start_m=self.start_m[rows:], start_known=self.start_known[rows:], offset_m=self.offset_m[rows:],
            first_line=self.first_line + line, motion_word_before=before)

    def widened(self, axes: tuple[str, ...]) -> "ProgramColumns":
        """The same columns over ``axes`` (a superset of :attr:`axes`, in the dialect's order)."""
        if axes == self.axes:
            return self
        where = [axes.index(k) for k in self.axes]
        m = self.motion_line.size

        def spread(values, fill):
            out = np.full((m, len(axes)), fill, dtype=values.dtype)
            out[:, where] = values
            return out

        return ProgramColumns(**{**self.__dict__, "axes": axes, "end_m": spread(self.end_m, np.nan),
                                 "known": spread(self.known, False), "start_m": spread(self.start_m, np.nan),
                                 "start_known": spread(self.start_known, False), "offset_m": spread(self.offset_m, 0.0)})


def joined(first: ProgramColumns, second: ProgramColumns, axes: tuple[str, ...]) -> ProgramColumns:
    """The columns of ``first``'s lines followed by ``second``'s, over ``axes`` (both theirs, in order)."""
    a, b = first.widened(axes), second.widened(axes)
    n = a.kind.size
    return ProgramColumns(
        axes=axes, kind=np.concatenate([a.kind, b.kind]), absolute=np.concatenate([a.absolute, b.absolute]),
        extruder_relative=np.concatenate([a.extruder_relative, b.extruder_relative]),
        metres_per_unit=np.concatenate([a.metres_per_unit, b.metres_per_unit]),
        motion_word=np.concatenate([a.motion_word, b.motion_word]), feed_word=a.feed_word + b.feed_word,
        bulk_row=np.concatenate([a.bulk_row, b.bulk_row]), has_e=np.concatenate([a.has_e, b.has_e]),
        number_at=np.concatenate([a.number_at, b.number_at]),
        general={**a.general, **{i + n: block for i, block in b.general.items()}},
        motion_line=np.concatenate([a.motion_line, b.motion_line + n]), end_m=np.concatenate([a.end_m, b.end_m]),
        known=np.concatenate([a.known, b.known]), start_m=np.concatenate([a.start_m, b.start_m]),
        start_known=np.concatenate([a.start_known, b.start_known]), offset_m=np.concatenate([a.offset_m, b.offset_m]),
        first_line=a.first_line, motion_word_before=a.motion_word_before)


def program_columns(program, *, axes_before: tuple[str, ...] = (), start_m=None, motion_word_before: int = -1) -> ProgramColumns:
    """The columns of ``program`` (a :class:`~axiscal.io.gcode.reader.Program`).

    Parameters
    ----------
    program : Program
    axes_before : tuple of str, keyword-only
        Axes the lines before ``program`` moved (a program read in pieces): columns of theirs too.
    start_m : Mapping[str, float], optional, keyword-only
        Where the axes stand before the first line (a program read in pieces); default: nowhere known.
    motion_word_before : int, keyword-only
        Code of the motion word last written before the first line, -1 for none.

    Returns
    -------
    ProgramColumns
    """
    spec = program.dialect
    n = len(program.lines)
    first_line = program.first_line
    blocks = program.general_blocks()
    bulk = program.bulk()
    scan = bulk.bulk.scan if bulk is not None else None
    seen = set(scan.axes) if scan is not None else set()
    seen.update(axes_before)
    for block in blocks:
        if block.motion is not None:
            seen.update(block.motion.end_m)
    axes = tuple(k for k in spec.axes if k in seen)
    where = {k: j for j, k in enumerate(axes)}
    a = len(axes)
    kind = np.zeros(n, dtype=np.int8)
    absolute = np.ones(n, dtype=bool)
    extruder_relative = np.zeros(n, dtype=bool)
    per_unit = np.full(n, 1e-3)
    motion_word = np.full(n, -1, dtype=np.int8)
    feed_word: list = [None] * n
    bulk_row = np.full(n, -1, dtype=np.int64)
    has_e = np.zeros(n, dtype=bool)
    number_at = np.zeros((n, 2), dtype=np.int32)
    general: dict[int, Block] = {}
    g_line, g_end, g_known, g_offset = [], [], [], []
    for block in blocks:
        i = block.line - 1 - first_line
        general[i] = block
        motion = block.motion
        absolute[i] = block.absolute
        extruder_relative[i] = block.extruder_relative
        per_unit[i] = block.metres_per_unit
        if block.motion_word is not None:
            motion_word[i] = _WORD_CODE[block.motion_word]
        if motion is not None:
            kind[i] = _KIND_CODE[motion.kind]
            end = [np.nan] * a
            known = [False] * a
            offset = [0.0] * a
            for letter, position in motion.end_m.items():
                end[where[letter]] = position
                known[where[letter]] = True
            for letter, shift in block.offset_m.items():
                if letter in where:
                    offset[where[letter]] = shift
            has_e[i] = any(letter == "E" for letter, _ in block.words)
            g_line.append(i)
            g_end.append(end)
            g_known.append(known)
            g_offset.append(offset)
    lines = [np.array(g_line, dtype=np.int64)]
    ends = [np.array(g_end, dtype=float).reshape(len(g_line), a)]
    knowns = [np.array(g_known, dtype=bool).reshape(len(g_line), a)]
    offsets = [np.array(g_offset, dtype=float).reshape(len(g_line), a)]
    if bulk is not None:
        runs = bulk.bulk.runs
        i = bulk.lines
        bulk_row[i] = np.arange(i.size)
        has_e[i] = scan.has_e[i]
        number_at[i] = scan.number_at[i]
        kind[i] = bulk.kinds()
        run = bulk.run_of
        per_unit[i] = np.array([r[3] for r in runs])[run]
        extruder_relative[i] = np.array([r[7] for r in runs], dtype=bool)[run]
        written = scan.g[i]
        motion_word[i] = np.where(written >= 0, written, -1)
        # the F number as written is looked up on the lines that have one only (a CAM program writes its
        # feed once in a thousand blocks: looked up on every line, it took half the reading's time)
        fed = i[~np.isnan(scan.feed[i])]
        for line, raw in zip(fed.tolist(), scan.raw(fed, "F")):
            if raw is not None:
                feed_word[line] = raw
        end = np.empty((i.size, a))
        known = np.empty((i.size, a), dtype=bool)
        offset = np.empty((i.size, a))
        for j, letter in enumerate(axes):
            if letter in scan.axes:
                c = scan.axes.index(letter)
                end[:, j] = bulk.end[:, c]
                known[:, j] = bulk.known[:, c]
            else:  # an axis the plain lines never write: where the run started
                end[:, j] = np.array([r[2].get(letter, np.nan) for r in runs])[run]
                known[:, j] = np.array([letter in r[2] for r in runs], dtype=bool)[run]
            offset[:, j] = np.where(known[:, j], np.array([r[4][letter] for r in runs])[run], 0.0)
        lines.append(i)
        ends.append(end)
        knowns.append(known)
        offsets.append(offset)
    # the motions in line order: each line holds one at most, read one way or the other (no sort needed)
    moving = np.zeros(n, dtype=bool)
    for at in lines:
        moving[at] = True
    motion_line = np.flatnonzero(moving)
    row_of = np.cumsum(moving) - 1
    end_m = np.empty((motion_line.size, a))
    known_m = np.empty((motion_line.size, a), dtype=bool)
    offset_m = np.empty((motion_line.size, a))
    for at, end, known, offset in zip(lines, ends, knowns, offsets):
        rows = row_of[at]
        end_m[rows], known_m[rows], offset_m[rows] = end, known, offset
    first_start = np.full((min(1, motion_line.size), a), np.nan)
    first_known = np.zeros((min(1, motion_line.size), a), dtype=bool)
    if start_m and motion_line.size:
        for letter, position in start_m.items():
            if letter in where:
                first_start[0, where[letter]] = position
                first_known[0, where[letter]] = True
    start = np.vstack([first_start, end_m[:-1]])
    start_known = np.vstack([first_known, known_m[:-1]])
    return ProgramColumns(
        axes=axes, kind=kind, absolute=absolute, extruder_relative=extruder_relative, metres_per_unit=per_unit,
        motion_word=motion_word, feed_word=feed_word, bulk_row=bulk_row, has_e=has_e, number_at=number_at,
        general=general, motion_line=motion_line, end_m=end_m, known=known_m, start_m=start, start_known=start_known,
        offset_m=offset_m, first_line=first_line, motion_word_before=motion_word_before,
    )
