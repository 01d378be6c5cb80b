"""The G-code reader: a program's moves and dwells, in SI, as the dialect's control would run them.

What each word means is taken from the dialect's description (:mod:`axiscal.io.gcode.dialects`):
the dwell's letter and unit, the units words, the comment syntax, the program end. The reader
follows a subset of ISO 6983 / RS-274 (LinuxCNC, Grbl, FANUC, SINUMERIK;
:mod:`axiscal.io.gcode.rs274`), the one-command-a-line printer firmware (Marlin, Klipper) and
HEIDENHAIN's conversational blocks (:mod:`axiscal.io.gcode.conversational`); a block it cannot
follow (a word it does not know, a macro, a subprogram call, a canned cycle, a move before the
units are set) is refused with an :class:`~axiscal.errors.AxiscalError` naming the source and the
line, never skipped.
"""

from __future__ import annotations

import heapq
import re
from collections.abc import Mapping
from functools import cached_property
from operator import attrgetter

from axiscal.errors import AxiscalError
from axiscal.io.arguments import check_instance, check_mapping, check_number
from axiscal.io.gcode.blocks import Block, ControlState, Motion
from axiscal.io.gcode.conversational import run_conversational_block
from axiscal.io.gcode.dialects import Dialect, dialect as find_dialect
from axiscal.io.gcode.columns import ProgramColumns, program_columns
from axiscal.io.gcode.fast import Bulk, BulkScan, walk
from axiscal.io.gcode.rs274 import run_block

__all__ = ["Motion", "Block", "Program", "program_motions", "read_program", "split_lines"]

_LINE_END = re.compile(r"\r\n|\r|\n")


def split_lines(text: str) -> list[str]:
    """The lines of ``text`` as an editor numbers them: only LF, CRLF and CR end a line.

    Parameters
    ----------
    text : str

    Returns
    -------
    list of str
        Without their line ends; a text ending with a line end has no empty line after it.

    Examples
    --------
    >>> split_lines("G1 X1\\r\\nG4 P1\\n")
    ['G1 X1', 'G4 P1']
    """
    lines = text.split("\n") if "\r" not in text else _LINE_END.split(text)
    if lines and lines[-1] == "":
        lines.pop()
    return lines


class Program:
    """A program as a dialect's control runs it.

    Attributes
    ----------
    dialect : Dialect
        The dialect it was read in.
    blocks : tuple of Block
        One per line of the text, in order (made on first use).
    motions : tuple of Motion
        Every move and dwell, in order (made on first use).
    line_end : str
        The line end the text uses ("\\n", "\\r\\n" or "\\r").
    lines : list of str
        The lines of the text, without their ends.
    first_line : int
        The 0-based number of ``lines[0]`` in the whole program: 0 unless the program is read in
        pieces (:mod:`axiscal.io.gcode.stream`); blocks and motions carry the whole program's lines.
    """

    def __init__(self, dialect: Dialect, lines: list[str], general: list[Block], taken: Bulk | None, line_end: str,
                 first_line: int = 0):
        self.dialect = dialect
        self.first_line = first_line
        self.lines = lines
        self.line_end = line_end
        self._general = general
        self._taken = taken if taken is not None and taken.runs else None
        self._bulk = None

    def bulk(self):
        """The lines read in bulk, as columns (None when there are none)."""
        if self._taken is not None and self._bulk is None:
            self._bulk = self._taken.columns()
        return self._bulk

    @cached_property
    def blocks(self) -> tuple[Block, ...]:
        if self._taken is None:
            return tuple(self._general)
        return tuple(heapq.merge(self._general, self.bulk().blocks(self.lines), key=attrgetter("line")))

    @cached_property
    def motions(self) -> tuple[Motion, ...]:
        return tuple(block.motion for block in self.blocks if block.motion is not None)

    @cached_property
    def columns(self) -> ProgramColumns:
        """The program's lines as columns (:class:`~axiscal.io.gcode.columns.ProgramColumns`)."""
        return program_columns(self)

    def general_blocks(self) -> list[Block]:
        """The blocks of the lines read one by one (every line but those read in bulk), in order."""
        return self._general


def read_program(
    text: str, *, dialect: str | Dialect, source: str | None = None, work_offset_m: Mapping[str, float] | None = None
) -> Program:
    """Read a program block by block as ``dialect``'s control runs it.

    Parameters
    ----------
    text : str
        The program.
    dialect : str or Dialect
        One of :data:`axiscal.io.gcode.DIALECT_NAMES`.
    source : str, optional
        The file the text came from, named in every error.
    work_offset_m : Mapping[str, float], optional
        Axis position minus program coordinate of the work offset the control starts in (the one
        ``G54`` selects), metres (radians for A, B, C); default none: the program's coordinates
        are the axes' positions.

    Returns
    -------
    Program
        Its blocks and motions.

    Raises
    ------
    AxiscalError
        As :func:`program_motions`.
    """
    check_instance("text", text, str)
    state = control_state(dialect, source, work_offset_m)
    lines = split_lines(text)
    taken = read_lines(lines, text, state)
    check_end(state, len(lines))
    ending = _LINE_END.search(text)
    return Program(state.spec, lines, state.blocks, taken, ending.group(0) if ending else "\n")


def control_state(dialect: str | Dialect, source: str | None, work_offset_m: Mapping[str, float] | None) -> ControlState:
    """The control's state at the start of a program, the arguments of :func:`read_program` checked."""
    spec = find_dialect(dialect)
    if source is not None:
        check_instance("source", source, str)
    offsets: dict[str, float] = {}
    if work_offset_m is not None:
        check_mapping("work_offset_m", work_offset_m)
        for letter, value in work_offset_m.items():
            if letter not in spec.axes:
                raise AxiscalError(f"work_offset_m names {letter!r}, not an axis of {spec.controller} ({', '.join(spec.axes)})")
            offsets[letter] = check_number(f"work_offset_m[{letter!r}]", value)
    return ControlState(spec, source, offsets)


def read_lines(lines: list[str], text: str, state: ControlState, *, first_line: int = 0,
               short_in_bulk: bool = False) -> Bulk | None:
    """Run ``lines`` (of ``text``; ``lines[0]`` is the program's line ``first_line + 1``) on ``state``.

    The blocks read one by one are appended to ``state.blocks``; the runs of plain lines read in
    bulk are returned (None when the lines are read block by block). Fewer lines than
    :data:`_BULK_FROM` are read block by block unless ``short_in_bulk`` (the compiled scan already
    loaded: the same motions, sooner).
    """
    spec = state.spec
    if spec.syntax == "conversational":
        for number, line in enumerate(lines, start=first_line + 1):
            state.line = number
            run_conversational_block(line, state, state.frame)
        return None
    if not _BULK or (len(lines) < _BULK_FROM and not short_in_bulk):
        for number, line in enumerate(lines, start=first_line + 1):
            state.line = number
            run_block(line, state)
        return None
    scan = BulkScan(text, lines, spec.axes, numbered=spec.syntax == "rs274", need_point=spec.decimal_point_needed)
    return walk(lines, state, scan, run_block, first_line=first_line)


def check_end(state: ControlState, lines: int) -> None:
    """Refuse a program of ``lines`` lines, all run on ``state``, without the end its dialect needs."""
    spec = state.spec
    state.line = max(lines, 1)
    if spec.end_required and not state.ended:
        ends = ", ".join(spec.end_words) + (" or a closing %" if spec.percent and spec.name == "linuxcnc" else "")
        raise state.fail(f"the program has no end ({ends})")


#: whether plain straight moves are read in bulk (False: every line block by block, as a reference)
_BULK = True
#: programs of fewer lines are read block by block (the compiled scan's start-up would cost more)
_BULK_FROM = 20_000


def program_motions(
    text: str, *, dialect: str, source: str | None = None, work_offset_m: Mapping[str, float] | None = None
) -> tuple[Motion, ...]:
    """The moves and dwells of a G-code program, in order, as ``dialect``'s control runs them.

    Parameters
    ----------
    text : str
        The program.
    dialect : str
        One of :data:`axiscal.io.gcode.DIALECT_NAMES` ("linuxcnc", "fanuc", "sinumerik",
        "heidenhain", "grbl", "marlin", "klipper").
    source : str, optional
        The file the text came from, named in every error.
    work_offset_m : Mapping[str, float], optional, keyword-only
        See :func:`read_program`.

    Returns
    -------
    tuple of Motion
        One per move (an axis word programmed) and per dwell. Positions in metres (radians for
        A, B, C), feeds in metres per second, dwells in seconds.

    Raises
    ------
    AxiscalError
        Naming ``source`` and the line, for a block the reader cannot follow: a word the dialect
        does not have or the reader does not follow, a macro, a subprogram call, a canned cycle,
        a move before the units or distance mode are set where the control's are a setting, a
        dwell word in the wrong unit (SINUMERIK ``G4 S``), an arc whose end is not on its circle,
        a program without its end where the dialect needs one.

    Examples
    --------
    >>> motions = program_motions("G21 G90 G94\\nG1 X10 F600\\nG4 P2\\nM2\\n", dialect="linuxcnc")
    >>> [(m.kind, round(m.end_m["X"], 6), m.dwell_s) for m in motions]
    [('feed', 0.01, 0.0), ('dwell', 0.01, 2.0)]
    >>> program_motions("G4 P2000\\n", dialect="marlin")[0].dwell_s
    2.0
    """
    return read_program(text, dialect=dialect, source=source, work_offset_m=work_offset_m).motions
