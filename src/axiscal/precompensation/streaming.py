"""A part program pre-compensated in pieces: read, rewritten and written in bounded memory, the same text as whole.

The program is read in pieces of whole lines (:mod:`axiscal.io.gcode.stream`) with the control's
state carried from one to the next, and rewritten a part at a time (:func:`rewrite_window`). How a
move is written depends only on the moves before it, but while the path is settled it may depend
on their passing states: a part is therefore written up to its last move whose command and whether
it is kept as written stayed as first found; the rest of the part is rewritten with the next one,
that move given as settled. So the output is, to the byte, the one the whole program read at once
gives (:func:`~axiscal.precompensation.program.rewrite_program`), and the memory is that of a part.
"""

from __future__ import annotations

import queue
import threading
from collections.abc import Callable, Iterable, Iterator, Mapping
from contextlib import closing
from dataclasses import dataclass
from pathlib import Path
from typing import BinaryIO

from axiscal.errors import AxiscalError
from axiscal.io.arguments import check_instance, check_path
from axiscal.io.atomic import atomic_write, remove_stale_temporaries
from axiscal.io.gcode.columns import joined
from axiscal.io.gcode.stream import ProgramPiece, read_pieces, text_pieces
from axiscal.model.machine import Machine
from axiscal.precompensation.program import _setup, rewrite_window
from axiscal.precompensation.text import header_at, header_line

__all__ = ["PrecompensationSummary", "precompensate_file", "precompensate_stream"]

#: bytes of program text read at a time (about 6 x 10^4 lines of a CAM finishing pass)
PIECE_BYTES = 2 << 20


@dataclass(frozen=True)
class PrecompensationSummary:
    """What was done to a program pre-compensated in pieces (its text went to the output).

    Attributes
    ----------
    lines_in, lines_out, moves, rewritten : int
    largest_correction_m, largest_residual_m, tolerance_m, max_segment_m : float
    machine, dialect : str
        As :class:`~axiscal.precompensation.program.Precompensation`.
    """

    lines_in: int
    lines_out: int
    moves: int
    rewritten: int
    largest_correction_m: float
    largest_residual_m: float
    tolerance_m: float
    max_segment_m: float
    machine: str
    dialect: str


class _Counter:
    """The output's text, written as it comes, and its lines counted as :func:`split_lines` counts them."""

    def __init__(self, write: Callable[[bytes], object]):
        self.write = write
        self.breaks = 0
        self.last = ""
        self.started = False

    def line(self, text: str, end: str) -> None:
        chunk = (end + text) if self.started else text
        self.started = True
        self._put(chunk, end)

    def lines(self, texts: list[str], end: str) -> None:
        if texts:
            self.line(end.join(texts), end)

    def _put(self, chunk: str, end: str) -> None:
        if chunk:
            # no line holds a line end of its own (the program was split there): every one is an `end`
            # joining two lines, or the pieces of one
            self.breaks += chunk.count(end)
            self.last = chunk[-1]
            self.write(chunk.encode("utf-8"))

    def close(self, end: str, ending: bool) -> int:
        if ending:
            self._put(end, end)
        return self.breaks + (1 if self.started and self.last not in "\n\r" else 0)


def rewrite_pieces(
    texts: Iterable[str],
    write: Callable[[bytes], object],
    machine: Machine | str,
    *,
    dialect: str,
    max_segment_m: float = 2e-3,
    tolerance_m: float = 0.5e-6,
    tool_m: tuple[float, float, float] | None = None,
    work_offset_m: Mapping[str, float] | None = None,
    source: str | None = None,
    progress: Callable[[int, int], None] | None = None,
    threaded: bool = True,
) -> PrecompensationSummary:
    """Pre-compensate the program given as pieces of whole lines ``texts``, handing its text to ``write``.

    ``texts`` joined is the program; ``write`` takes the output's UTF-8 bytes in order;
    ``progress`` is called with the bytes and lines taken so far after each piece; ``threaded``: the
    next piece is read on a thread while this one is rewritten (:func:`_read_ahead`; False: one after
    the other, the reference). The other arguments are those of
    :func:`~axiscal.precompensation.program.rewrite_program`.
    """
    setup = _setup(machine, dialect, max_segment_m, tolerance_m, tool_m, source)
    out = _Counter(write)
    header = True
    settled = None
    columns = lines = None
    written_from = 0
    lines_in = moves = rewritten = taken = 0
    largest = residual = 0.0
    line_end = "\n"
    ending = False
    pieces = read_pieces(texts, dialect=setup.spec, source=source, work_offset_m=work_offset_m)
    if threaded:
        pieces = _read_ahead(pieces)
    with closing(pieces):  # the reading thread stopped (and joined) whatever stops the rewriting
        for piece in pieces:
            line_end = piece.line_end
            lines_in += len(piece.lines)
            taken += piece.size
            if columns is None:
                columns, lines = piece.columns, piece.lines
            else:
                columns = joined(columns, piece.columns, piece.columns.axes)
                lines = lines + piece.lines
            window = rewrite_window(setup, columns, lines, line_end, settled, final=piece.last, written_from=written_from)
            if progress is not None:
                progress(taken, lines_in)
            if window is None:  # no move of these lines is settled yet: read on
                continue
            text = window.lines
            if header:
                at = header_at(setup.spec, text)
                if at < len(text) or piece.last:
                    text = text[:at] + [header_line(setup.spec, setup.header)] + text[at:]
                    header = False
            out.lines(text, line_end)
            moves += window.moves
            rewritten += window.rewritten
            largest = max(largest, window.largest_correction_m)
            residual = max(residual, window.largest_residual_m)
            settled = window.settled
            start = window.settled_line if settled is not None else window.written_to
            columns = columns.tail(start)
            lines = lines[start:]
            written_from = window.written_to - start
            ending = piece.ends_with_line_end
    lines_out = out.close(line_end, ending)
    model = setup.model
    return PrecompensationSummary(lines_in, lines_out, moves, rewritten, largest, residual, setup.tolerance_m,
                                  setup.max_segment_m, model.name or model.chain, setup.spec.name)


def _read_ahead(pieces: Iterator[ProgramPiece]) -> Iterator[ProgramPiece]:
    """``pieces`` in order, the next one read on a thread while the caller works on this one.

    The reading (the stream, the compiled scan, the columns) runs beside the rewriting wherever either
    leaves the interpreter's lock (the compiled passes, NumPy's larger operations, the file's reads
    and writes). At most one piece waits, so the memory is that of two pieces; what the reading
    raises is raised here in its place, after the pieces before it; a caller that stops early stops
    the thread after the piece it is reading.
    """
    slot: queue.Queue = queue.Queue(maxsize=1)
    stop = threading.Event()
    done = object()

    def read() -> None:
        try:
            for piece in pieces:
                slot.put((piece, None))
                if stop.is_set():
                    return
            slot.put((done, None))
        except BaseException as error:  # handed to the caller, raised there
            slot.put((None, error))

    thread = threading.Thread(target=read, name="axiscal-read-ahead", daemon=True)
    thread.start()
    try:
        while True:
            piece, error = slot.get()
            if error is not None:
                raise error
            if piece is done:
                return
            yield piece
    finally:
        stop.set()
        while thread.is_alive():  # free a reader waiting to put its piece, then let it end
            try:
                slot.get(timeout=0.05)
            except queue.Empty:
                pass
        thread.join()


def precompensate_stream(
    reader: BinaryIO,
    writer: BinaryIO,
    machine: Machine | str,
    *,
    dialect: str,
    max_segment_m: float = 2e-3,
    tolerance_m: float = 0.5e-6,
    tool_m: tuple[float, float, float] | None = None,
    work_offset_m: Mapping[str, float] | None = None,
    source: str | None = None,
    progress: Callable[[int, int], None] | None = None,
) -> PrecompensationSummary:
    """Pre-compensate the program read from ``reader`` (bytes, UTF-8) and write it to ``writer``, in pieces.

    The output is, to the byte, :func:`~axiscal.precompensation.program.precompensate_program`'s; the
    memory taken does not grow with the program's length. Written as it is made: on an error, what
    was written before it stays written (:func:`precompensate_file` writes a file whole or not at all).

    Parameters
    ----------
    reader, writer : binary file objects
        Where the program is read and where the pre-compensated one goes (standard input and output).
    machine, dialect, max_segment_m, tolerance_m, tool_m, work_offset_m : keyword-only
        See :func:`~axiscal.precompensation.program.precompensate_program`.
    source : str, optional, keyword-only
        The program's name in errors.
    progress : callable, optional, keyword-only
        Called with the bytes and the lines of the program rewritten so far, after each piece.

    Returns
    -------
    PrecompensationSummary

    Raises
    ------
    AxiscalError
        As :func:`~axiscal.precompensation.program.precompensate_program`, naming ``source`` and the line.
    """
    if source is not None:
        check_instance("source", source, str)
    texts = text_pieces(reader, piece_bytes=PIECE_BYTES, source=source)
    return rewrite_pieces(texts, writer.write, machine, dialect=dialect, max_segment_m=max_segment_m,
                          tolerance_m=tolerance_m, tool_m=tool_m, work_offset_m=work_offset_m, source=source,
                          progress=progress)


def precompensate_file(
    program_path: str | Path | BinaryIO,
    machine: Machine | str | Path,
    output_path: str | Path | BinaryIO,
    *,
    dialect: str,
    max_segment_m: float = 2e-3,
    tolerance_m: float = 0.5e-6,
    tool_m: tuple[float, float, float] | None = None,
    work_offset_m: Mapping[str, float] | None = None,
    progress: Callable[[int, int], None] | None = None,
) -> PrecompensationSummary:
    """Pre-compensate the program in ``program_path`` and write it to ``output_path``, in pieces.

    The program is read, rewritten and written a piece at a time (:func:`precompensate_stream`), so
    the memory taken does not grow with its length. A file ``output_path`` is written atomically: it is
    the old file or the new one, whole, whatever stops the run, and the temporary files that earlier
    runs of the same output left when they were killed are removed. A binary stream (standard input,
    standard output) is read or written as the pieces come.

    Parameters
    ----------
    program_path, output_path : str, Path or binary file object
        The program read and the program written.
    machine : Machine, str or Path
        The machine model or its description file.
    dialect, max_segment_m, tolerance_m, tool_m, work_offset_m : keyword-only
        See :func:`~axiscal.precompensation.program.precompensate_program`.
    progress : callable, optional, keyword-only
        Called with the bytes and the lines of the program rewritten so far, after each piece.

    Returns
    -------
    PrecompensationSummary
        Lines, moves, the largest correction and the largest residual.

    Raises
    ------
    AxiscalError
        As :func:`~axiscal.precompensation.program.precompensate_program`, naming ``program_path``;
        a file that cannot be read or written.
    """
    if isinstance(machine, Path):
        machine = str(machine)
    check_instance("machine", machine, (Machine, str))
    reading = not isinstance(program_path, (str, Path))
    if reading:
        _check_stream("program_path", program_path, "read")
        name = None
    else:
        program_path = check_path("program_path", program_path)
        name = str(program_path)
    output = output_path
    if not isinstance(output, (str, Path)):
        _check_stream("output_path", output, "write")
    else:
        output = check_path("output_path", output)
    settings = dict(dialect=dialect, max_segment_m=max_segment_m, tolerance_m=tolerance_m, tool_m=tool_m,
                    work_offset_m=work_offset_m, source=name, progress=progress)
    if reading:
        reader = program_path
    else:
        try:
            reader = open(program_path, "rb")
        except FileNotFoundError:
            raise AxiscalError("file not found", path=program_path) from None
        except OSError as exc:
            raise AxiscalError(f"cannot read file ({exc})", path=program_path) from None
    try:
        if not isinstance(output, Path):
            return precompensate_stream(reader, output, machine, **settings)
        result: list[PrecompensationSummary] = []

        def fill(target: Path) -> None:
            with open(target, "wb") as writer:
                result.append(precompensate_stream(reader, writer, machine, **settings))

        remove_stale_temporaries(output)  # what runs of this output killed before their end left beside it
        atomic_write(output, fill)
        return result[0]
    finally:
        if not reading:
            reader.close()


def _check_stream(name: str, stream, verb: str) -> None:
    if not callable(getattr(stream, verb, None)):
        raise AxiscalError(f"{name} must be a file name or a binary file object to {verb}, not {stream!r}")
