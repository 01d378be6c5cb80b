"""A program read in pieces of whole lines: the same blocks, motions and columns as read whole, in bounded memory.

:func:`text_pieces` cuts a byte stream (a file, standard input) into pieces of whole lines of about
a given size, decoded as UTF-8; :func:`read_pieces` reads them one after another with one
control's state carried from each to the next (:func:`~axiscal.io.gcode.reader.read_lines`), so a
block and a motion read in a piece are the ones the whole program gives, numbered by the whole
program's lines. Each piece comes with its columns (:mod:`axiscal.io.gcode.columns`), whose first
motion starts where the piece before left the axes. Once a piece was read in bulk, the plain lines
of every piece after it are too, however short (the program's short last piece, read block by
block, took a tenth of a long program's time).
"""

from __future__ import annotations

import re
from collections.abc import Callable, Iterable, Iterator, Mapping
from dataclasses import dataclass
from typing import BinaryIO

import numpy as np

from axiscal.errors import AxiscalError
from axiscal.io.gcode.columns import ProgramColumns, program_columns
from axiscal.io.gcode.dialects import Dialect
from axiscal.io.gcode.reader import Program, check_end, control_state, read_lines, split_lines

__all__ = ["ProgramPiece", "read_pieces", "text_pieces"]

_LINE_END = re.compile(r"\r\n|\r|\n")
#: bytes read from the stream at a time
_READ_BYTES = 1 << 20


@dataclass(frozen=True)
class ProgramPiece:
    """Consecutive whole lines of a program, read with the control's state the lines before left.

    Attributes
    ----------
    dialect : Dialect
    lines : list of str
        The piece's lines, without their ends.
    columns : ProgramColumns
        Its lines as columns (``columns.first_line`` is the 0-based number of ``lines[0]``).
    line_end : str
        The line end the program uses (the first one it has; "\\n" for a program without any).
    last : bool
        Whether the piece is the program's last.
    ends_with_line_end : bool
        For the last piece: whether the program's text ends with a line end.
    size : int
        Bytes of the piece's text (UTF-8).
    """

    dialect: Dialect
    lines: list[str]
    columns: ProgramColumns
    line_end: str
    last: bool
    ends_with_line_end: bool
    size: int = 0


def text_pieces(stream: BinaryIO, *, piece_bytes: int = 4 << 20, source: str | None = None,
                progress: Callable[[int], None] | None = None) -> Iterator[str]:
    """The UTF-8 text of ``stream`` in pieces of whole lines of about ``piece_bytes`` bytes.

    A piece ends after a line end (LF, CRLF or CR), except the last; a byte-order mark at the start
    is dropped. ``progress`` is called with the bytes read so far after each read.

    Raises
    ------
    AxiscalError
        Naming ``source`` and the line of the first byte that is not UTF-8, or a stream that cannot
        be read.
    """
    pending = b""
    lines_before = 0
    done = 0
    first = True
    while True:
        try:
            chunk = stream.read(max(piece_bytes, 1))
        except OSError as exc:
            raise AxiscalError(f"cannot read the program ({exc.strerror or exc})", path=source) from None
        done += len(chunk)
        if progress is not None and chunk:
            progress(done)
        data = pending + chunk
        if first and (len(data) >= 3 or not chunk):
            first = False
            if data.startswith(b"\xef\xbb\xbf"):
                data = data[3:]
        if not chunk:
            if data:
                yield _decoded(data, lines_before, source)
            return
        # cut after the last line end that cannot be the first half of a CRLF
        cut = max(data.rfind(b"\n"), data.rfind(b"\r", 0, len(data) - 1)) + 1
        if first or cut <= 0:
            pending = data
            continue
        piece, pending = data[:cut], data[cut:]
        text = _decoded(piece, lines_before, source)
        lines_before += len(split_lines(text))
        yield text


def _decoded(data: bytes, lines_before: int, source: str | None) -> str:
    try:
        return data.decode("utf-8")
    except UnicodeDecodeError as exc:
        before = data[: exc.start]
        line = lines_before + before.count(b"\n") + before.count(b"\r") - before.count(b"\r\n") + 1
        raise AxiscalError(f"not UTF-8 text (byte 0x{data[exc.start]:02x})", path=source, line=line) from None


def read_pieces(texts: Iterable[str], *, dialect: str | Dialect, source: str | None = None,
                work_offset_m: Mapping[str, float] | None = None) -> Iterator[ProgramPiece]:
    """Read a program given as pieces of whole lines (each but the last ending with a line end).

    Parameters
    ----------
    texts : iterable of str
        The program's text in pieces (:func:`text_pieces`); joined, the whole program.
    dialect, source, work_offset_m
        As :func:`~axiscal.io.gcode.reader.read_program`.

    Yields
    ------
    ProgramPiece
        One per non-empty text piece. The last is checked for the program's end before it is
        handed on, so a program without its end is refused before its last piece is.

    Raises
    ------
    AxiscalError
        As :func:`~axiscal.io.gcode.reader.read_program`, naming the whole program's line.
    """
    state = control_state(dialect, source, work_offset_m)
    spec = state.spec
    first_line = 0
    line_end = None
    axes: tuple[str, ...] = ()
    word_before = -1
    scanned = False  # a piece was read in bulk: the compiled scan is loaded, a short piece is read in bulk too
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
        taken = read_lines(lines, text, state, first_line=first_line, short_in_bulk=scanned)
        scanned = scanned or taken is not None
        program = Program(spec, lines, state.blocks, taken, line_end or "\n", first_line)
        last = following is None
        if last:
            check_end(state, first_line + len(lines))
        columns = program_columns(program, axes_before=axes, start_m=start, motion_word_before=word_before)
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
        yield ProgramPiece(spec, [], program_columns(Program(spec, [], [], None, "\n")), "\n", True, False)
