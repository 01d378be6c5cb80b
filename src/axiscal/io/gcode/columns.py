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

__all__ = ["ProgramColumns", "KINDS", "MOTION_WORDS", "program_columns"]

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
        For a line read in bulk, its row among those lines; -1 for the others.
    general : dict of int to Block
        The Block of every line read block by block, by line index.
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
    general: dict[int, Block]
    motion_line: np.ndarray
    end_m: np.ndarray
    known: np.ndarray
    start_m: np.ndarray
    start_known: np.ndarray
    offset_m: np.ndarray


def program_columns(program) -> ProgramColumns:
    """The columns of ``program`` (a :class:`~axiscal.io.gcode.reader.Program`).

    Returns
    -------
    ProgramColumns
    """
    spec = program.dialect
    n = len(program.lines)
    blocks = program.general_blocks()
    bulk = program.bulk()
    scan = bulk.bulk.scan if bulk is not None else None
    seen = set(scan.axes) if scan is not None else set()
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
    general: dict[int, Block] = {}
    g_line, g_end, g_known, g_offset = [], [], [], []
    for block in blocks:
        i = block.line - 1
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
        kind[i] = bulk.kinds()
        run = bulk.run_of
        per_unit[i] = np.array([r[3] for r in runs])[run]
        extruder_relative[i] = np.array([r[7] for r in runs], dtype=bool)[run]
        written = scan.g[i]
        motion_word[i] = np.where(written >= 0, written, -1)
        if not np.isnan(scan.feed[i]).all():
            for line, raw in zip(i.tolist(), scan.raw(i, "F")):
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
    motion_line = np.concatenate(lines)
    order = np.argsort(motion_line, kind="stable")
    motion_line = motion_line[order]
    end_m = np.concatenate(ends)[order]
    known_m = np.concatenate(knowns)[order]
    offset_m = np.concatenate(offsets)[order]
    start_m = np.vstack([np.full((min(1, motion_line.size), a), np.nan), end_m[:-1]])
    start_known = np.vstack([np.zeros((min(1, motion_line.size), a), dtype=bool), known_m[:-1]])
    return ProgramColumns(
        axes=axes, kind=kind, absolute=absolute, extruder_relative=extruder_relative, metres_per_unit=per_unit,
        motion_word=motion_word, feed_word=feed_word, bulk_row=bulk_row, general=general, motion_line=motion_line,
        end_m=end_m, known=known_m, start_m=start_m, start_known=start_known, offset_m=offset_m,
    )
