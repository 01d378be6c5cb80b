"""A program read in pieces for its pre-compensation: the reader's pieces, short ones read in bulk too.

The same pieces as :func:`axiscal.io.gcode.stream.read_pieces` gives, to the bit: each piece's
lines run through the reader (:func:`~axiscal.io.gcode.reader.read_lines`) with the control's
state carried from the piece before; only the columns (:class:`~axiscal.io.gcode.columns.ProgramColumns`)
are built here, the F numbers as written looked up on the lines that have one instead of on every
line read in bulk (a CAM program writes its feed once in a thousand blocks: the lookup was half the
reading's time), and once a piece was read in bulk, the plain lines of every piece after it are,
however short (the program's last piece, read block by block, took a tenth of the whole time).
"""

from __future__ import annotations

import re
from collections.abc import Iterable, Iterator, Mapping

import numpy as np

from axiscal.io.gcode.columns import KINDS, MOTION_WORDS, ProgramColumns
from axiscal.io.gcode.dialects import Dialect
from axiscal.io.gcode import reader
from axiscal.io.gcode.fast import BulkScan, walk
from axiscal.io.gcode.reader import Program, check_end, control_state, read_lines, split_lines
from axiscal.io.gcode.rs274 import run_block
from axiscal.io.gcode.stream import ProgramPiece

__all__ = ["read_pieces", "piece_columns"]

_LINE_END = re.compile(r"\r\n|\r|\n")
_KIND_CODE = {kind: code for code, kind in enumerate(KINDS)}
_WORD_CODE = {word: code for code, word in enumerate(MOTION_WORDS)}


def read_pieces(texts: Iterable[str], *, dialect: str | Dialect, source: str | None = None,
                work_offset_m: Mapping[str, float] | None = None) -> Iterator[ProgramPiece]:
    """:func:`axiscal.io.gcode.stream.read_pieces`, the columns built by :func:`piece_columns`."""
    state = control_state(dialect, source, work_offset_m)
    spec = state.spec
    first_line = 0
    line_end = None
    axes: tuple[str, ...] = ()
    word_before = -1
    scanned = False  # whether a piece was read in bulk: the compiled scan is loaded, short pieces read in bulk too
    iterator = iter(texts)
    text = next(iterator, None)
    while text is not None:
        following = next(iterator, None)
        while following == "":
            following = next(iterator, None)
        if text == "" and following is not None:
            text = following
            continue
        if line_end is None:
            ending = _LINE_END.search(text)
            line_end = ending.group(0) if ending else None
        lines = split_lines(text)
        start = dict(state.position)
        if scanned or len(lines) >= reader._BULK_FROM:
            taken = _read_in_bulk(lines, text, state, first_line)
            scanned = taken is not None
        else:
            taken = read_lines(lines, text, state, first_line=first_line)
        program = Program(spec, lines, state.blocks, taken, line_end or "\n", first_line)
        last = following is None
        if last:
            check_end(state, first_line + len(lines))
        columns = piece_columns(program, axes_before=axes, start_m=start, motion_word_before=word_before)
        state.blocks = []
        state.motions = state.motions[-1:]  # what the reader asks of it: whether anything moved yet
        axes = columns.axes
        written = np.flatnonzero(columns.motion_word >= 0)
        if written.size:
            word_before = int(columns.motion_word[written[-1]])
        yield ProgramPiece(spec, lines, columns, line_end or "\n", last, last and text.endswith(("\n", "\r")),
                           len(text.encode("utf-8")))
        first_line += len(lines)
        text = following
    if first_line == 0:
        check_end(state, 0)
        yield ProgramPiece(spec, [], piece_columns(Program(spec, [], [], None, "\n")), "\n", True, False)


def _read_in_bulk(lines: list[str], text: str, state, first_line: int):
    """:func:`~axiscal.io.gcode.reader.read_lines` with the plain lines read in bulk however few they are
    (the reader reads a short text block by block, as the whole program's last piece often is: the same
    motions, slower)."""
    spec = state.spec
    if not reader._BULK or spec.syntax == "conversational":
        return read_lines(lines, text, state, first_line=first_line)
    scan = BulkScan(text, lines, spec.axes, numbered=spec.syntax == "rs274", need_point=spec.decimal_point_needed)
    return walk(lines, state, scan, run_block, first_line=first_line)


def piece_columns(program: Program, *, axes_before: tuple[str, ...] = (), start_m=None,
                  motion_word_before: int = -1) -> ProgramColumns:
    """The columns of ``program``, equal to :func:`axiscal.io.gcode.columns.program_columns`'s."""
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
    general = {}
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
        fed = i[~np.isnan(scan.feed[i])]  # only the lines with an F word have its number as written
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
    # the motions in line order: each line holds one at most, read one way or the other
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
