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
    """Per line of a program (index = line number - 1), as columns.

    Attributes
    ----------
    axes : tuple of str
        The axes the program moves or knows, in the dialect's order.
    kind : numpy.ndarray of int8, shape (n,)
        Code of the line's motion in :data:`KINDS` (0: none).
    end_m : numpy.ndarray, shape (n, len(axes))
        Position of each axis after the line (metres, radians for A, B, C); NaN where not known.
    known : numpy.ndarray of bool, shape (n, len(axes))
        Whether the axis's position is known after the line.
    absolute, extruder_relative : numpy.ndarray of bool, shape (n,)
        The distance mode (G90) and the extruder's mode in force in the line.
    metres_per_unit : numpy.ndarray, shape (n,)
        Metres one program unit stands for in the line.
    offset_m : numpy.ndarray, shape (n, len(axes))
        Axis position minus program coordinate in the line (0 for an axis not yet known).
    motion_word : numpy.ndarray of int8, shape (n,)
        Code of the motion word written in the line in :data:`MOTION_WORDS`, -1 for none.
    feed_word : list of (str or None)
        The F number written in each line read in bulk; None for the others.
    bulk_row : numpy.ndarray of int64, shape (n,)
        For a line read in bulk, its row in the bulk reader's words; -1 for the others.
    general : dict of int to Block
        The Block of every line read block by block, by line index.
    """

    axes: tuple[str, ...]
    kind: np.ndarray
    end_m: np.ndarray
    known: np.ndarray
    absolute: np.ndarray
    extruder_relative: np.ndarray
    metres_per_unit: np.ndarray
    offset_m: np.ndarray
    motion_word: np.ndarray
    feed_word: list
    bulk_row: np.ndarray
    general: dict[int, Block]


def program_columns(program) -> ProgramColumns:
    """The columns of ``program`` (a :class:`~axiscal.io.gcode.reader.Program`).

    Returns
    -------
    ProgramColumns
    """
    spec = program.dialect
    n = len(program.lines)
    all_axes = spec.axes
    where = {k: j for j, k in enumerate(all_axes)}
    a = len(all_axes)
    kind = np.zeros(n, dtype=np.int8)
    value = np.full((n, a), np.nan)
    valid = np.zeros((n, a), dtype=bool)
    absolute = np.ones(n, dtype=bool)
    extruder_relative = np.zeros(n, dtype=bool)
    per_unit = np.full(n, 1e-3)
    offset = np.zeros((n, a))
    motion_word = np.full(n, -1, dtype=np.int8)
    feed_word: list = [None] * n
    bulk_row = np.full(n, -1, dtype=np.int64)
    general: dict[int, Block] = {}
    for block in program.general_blocks():
        i = block.line - 1
        general[i] = block
        motion = block.motion
        if motion is not None:
            kind[i] = _KIND_CODE[motion.kind]
            for letter, position in motion.end_m.items():
                value[i, where[letter]] = position
                valid[i, where[letter]] = True
        absolute[i] = block.absolute
        extruder_relative[i] = block.extruder_relative
        per_unit[i] = block.metres_per_unit
        for letter, shift in block.offset_m.items():
            offset[i, where[letter]] = shift
        if block.motion_word is not None:
            motion_word[i] = _WORD_CODE[block.motion_word]
    bulk = program.bulk()
    if bulk is not None:
        runs = bulk.bulk.runs
        scan = bulk.bulk.scan
        i = bulk.lines
        bulk_row[i] = np.arange(i.size)
        kind[i] = bulk.kinds()
        columns = [where[k] for k in scan.axes]
        value[i[:, None], columns] = bulk.end
        valid[i[:, None], columns] = bulk.known
        run = bulk.run_of
        per_unit[i] = np.array([r[3] for r in runs])[run]
        extruder_relative[i] = np.array([r[7] for r in runs], dtype=bool)[run]
        # the general lines' positions before each run, carried into its lines
        run_offsets = np.array([[r[4][k] for k in all_axes] for r in runs]).reshape(len(runs), a)
        starts = np.array([[k in r[2] for k in all_axes] for r in runs], dtype=bool).reshape(len(runs), a)
        start_values = np.array([[r[2].get(k, np.nan) for k in all_axes] for r in runs]).reshape(len(runs), a)
        carried = [j for j in range(a) if all_axes[j] not in scan.axes]
        if carried:
            value[i[:, None], carried] = start_values[run][:, carried]
            valid[i[:, None], carried] = starts[run][:, carried]
        known_all = valid[i]
        offset[i] = np.where(known_all, run_offsets[run], 0.0)
        written = scan.g[i]
        motion_word[i] = np.where(written >= 0, written, -1)
        feeds = scan.raw(i, "F") if not np.isnan(scan.feed[i]).all() else []
        for line, raw in zip(i.tolist(), feeds):
            if raw is not None:
                feed_word[line] = raw
    rows_index = np.arange(n)[:, None]
    index = np.maximum.accumulate(np.where(valid, rows_index, 0), axis=0)
    cols = np.arange(a)[None, :]
    end, known = value[index, cols], valid[index, cols]
    used = known.any(axis=0) if n else np.zeros(a, dtype=bool)
    keep = np.flatnonzero(used)
    return ProgramColumns(
        axes=tuple(all_axes[j] for j in keep), kind=kind, end_m=end[:, keep], known=known[:, keep],
        absolute=absolute, extruder_relative=extruder_relative, metres_per_unit=per_unit, offset_m=offset[:, keep],
        motion_word=motion_word, feed_word=feed_word, bulk_row=bulk_row, general=general,
    )
