"""Pre-compensation of a part program: every point moved to its pre-compensated command, paths kept in tolerance.

A control moves straight between the points it is given, so correcting only the end points of a
move leaves the error's variation along it: with the commands c0, c1 at the ends of the programmed
move p0 -> p1, the tool is off the nominal path by ``e(c(t)) - [(1 - t) e(c0) + t e(c1)]``, the
error's departure from its chord (the nominal kinematics being linear in the axes). Each move is
sampled at least every half ``max_segment_m``; where the tool would leave the nominal path by more
than the tolerance (the distance along the directions the machine's axes move), the move is cut
into pieces of at most ``max_segment_m`` (halved again where that is not enough) and each piece
end is pre-compensated. Arcs are linearised into chords whose sagitta is a quarter of the
tolerance, the rest of it left to the error along each chord. Rapid moves get their end points
corrected; their path is not checked, a control need not move straight at rapid.

Positions are written with 0.1 um resolution (4 decimals in mm, 6 in inch), in the block's units
and distance mode, relative to its work offset and G92 shift. Blocks whose correction rounds to
nothing are written as they were, so a program on a machine without errors comes out unchanged
apart from the header comment.
"""

from __future__ import annotations

from collections.abc import Mapping
from dataclasses import dataclass

import numpy as np

from axiscal.conventions import AXIS_INDEX
from axiscal.errors import AxiscalError
from axiscal.io.arguments import check_number
from axiscal.io.gcode import dialect as find_dialect, read_program
from axiscal.model.machine import Machine
from axiscal.precompensation.moves import Moves
from axiscal.precompensation.path import Pieces, build_pieces, settle, solve
from axiscal.precompensation.points import machine_with_tool
from axiscal.precompensation.text import PLACES, header_at, header_line, program_lines
from axiscal.units import UM
from axiscal.version import __version__

__all__ = ["Precompensation", "precompensate_program", "rewrite_program", "rewrite_window", "PLACES"]

_MM = 1e-3
#: shortest ``max_segment_m``: pieces shorter than 1 um are never cut again (positions are written to 0.1 um)
MIN_SEGMENT_M = 1e-6


@dataclass(frozen=True)
class Precompensation:
    """A rewritten program and what was done to it.

    Attributes
    ----------
    text : str
        The pre-compensated program.
    lines_in, lines_out : int
        Lines of the program read and written.
    moves, rewritten : int
        Moves read, and moves written anew (the others kept as they were).
    largest_correction_m : float
        Largest distance between a programmed point and its command, metres.
    largest_residual_m : float
        Largest distance of the tool from the nominal path the model predicts, over the sampled
        path of every straight move and arc and the end of every rapid move, along the directions
        the machine's axes move, metres.
    tolerance_m, max_segment_m : float
        The settings used, metres.
    machine : str
        The machine model's name.
    dialect : str
        The program's dialect.
    """

    text: str
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


def rewrite_program(
    text: str,
    machine: Machine | str,
    *,
    dialect: str,
    max_segment_m: float = 2e-3,
    tolerance_m: float = 0.5e-6,
    tool_m: tuple[float, float, float] | None = None,
    work_offset_m: Mapping[str, float] | None = None,
    source: str | None = None,
) -> Precompensation:
    """Pre-compensate a part program and say what was done; see :func:`precompensate_program`.

    Returns
    -------
    Precompensation
        The program written anew, with the counts, the largest correction and the largest residual.
    """
    setup = _setup(machine, dialect, max_segment_m, tolerance_m, tool_m, source)
    program = read_program(text, dialect=setup.spec, source=source, work_offset_m=work_offset_m)
    window = rewrite_window(setup, program.columns, program.lines, program.line_end, None, final=True)
    out = window.lines
    at = header_at(setup.spec, out)
    out.insert(at, header_line(setup.spec, setup.header))
    lines = program.line_end.join(out) + (program.line_end if text.endswith(("\n", "\r")) else "")
    return Precompensation(
        text=lines, lines_in=len(program.lines), lines_out=_count_lines(lines), moves=window.moves,
        rewritten=window.rewritten, largest_correction_m=window.largest_correction_m,
        largest_residual_m=window.largest_residual_m, tolerance_m=setup.tolerance_m, max_segment_m=setup.max_segment_m,
        machine=setup.model.name or setup.model.chain, dialect=setup.spec.name,
    )


@dataclass(frozen=True)
class Setup:
    """What a rewriting keeps from start to end: the dialect, the model with its tool, the settings."""

    spec: object
    model: Machine
    linear: list
    rotary: list
    reach: list
    tolerance_m: float
    max_segment_m: float
    source: str | None
    header: str


def _setup(machine, dialect, max_segment_m, tolerance_m, tool_m, source) -> Setup:
    """The arguments of :func:`rewrite_program` checked, the model loaded with its tool."""
    spec = find_dialect(dialect)
    if spec.syntax == "conversational":
        raise AxiscalError(f"{spec.controller} programs are not pre-compensated; use a word dialect"
                           " (linuxcnc, fanuc, sinumerik, grbl, marlin, klipper)")
    tolerance_m = check_number("tolerance_m", tolerance_m, positive=True)
    max_segment_m = check_number("max_segment_m", max_segment_m, positive=True)
    if tolerance_m < 0.2 * UM:
        raise AxiscalError(f"tolerance_m must be at least 0.2 um (positions are written to 0.1 um), not {tolerance_m / UM:g} um")
    if max_segment_m < MIN_SEGMENT_M:
        raise AxiscalError(f"max_segment_m must be at least {MIN_SEGMENT_M / _MM:g} mm (pieces shorter than 1 um are"
                           f" not cut again), not {max_segment_m / _MM:g} mm")
    model = machine_with_tool(machine, tool_m)
    rotary = list(model.rotary)
    linear = [k for k in model.letters if k not in model.rotary]
    if rotary and len(linear) != 3:
        raise AxiscalError(f"a machine with rotary axes is pre-compensated with three linear axes, not chain '{model.chain}'")
    reach = [AXIS_INDEX[k] for k in linear] if not rotary else [0, 1, 2]
    header = (f"axiscal {__version__} precompensate: machine {model.name or model.chain} ({model.chain}),"
              f" tolerance {tolerance_m / UM:g} um, segments up to {max_segment_m / _MM:g} mm")
    return Setup(spec, model, linear, rotary, reach, tolerance_m, max_segment_m, source, header)


@dataclass(frozen=True)
class Settled:
    """The last move written of a part of the program: the context the next part is rewritten in.

    Its pieces (as :class:`_Pieces` rows) and whether it was kept as written; ``first_line`` is the
    program's first move's line (named when the path cannot be held).
    """

    pieces: dict
    kept: bool
    first_line: int


@dataclass(frozen=True)
class Window:
    """Lines of a part of a program, rewritten: what of it is final, and what the next part needs.

    Attributes
    ----------
    lines : list of str
        The output of the input lines ``[written_from, written_to)`` (a line cut into pieces holds
        them joined by the program's line end).
    written_to : int
        Index of the first input line not written (the part's length when all is).
    settled : Settled or None
        The last move written, for the next part (None: no move yet).
    settled_line : int
        Index of that move's line: the next part starts there.
    moves, rewritten : int
        Moves written, and those written anew.
    largest_correction_m, largest_residual_m : float
        As :class:`Precompensation`, over the part.
    """

    lines: list
    written_to: int
    settled: Settled | None
    settled_line: int
    moves: int
    rewritten: int
    largest_correction_m: float
    largest_residual_m: float


def rewrite_window(setup: Setup, columns, lines: list[str], line_end: str, settled: Settled | None, *,
                   final: bool, written_from: int = 0) -> Window | None:
    """Rewrite the lines ``lines`` (with their ``columns``), the moves before them ``settled``.

    When ``settled`` is given, ``lines[0]`` is its move's line (written already, with the lines up to
    ``written_from``). Unless ``final``, the moves are written up to the last one whose command and
    decision stayed as first found while the path was settled (the moves after it may still depend
    on it as the whole program's rewriting would); None when no move is such (read more lines).
    """
    model, linear, rotary, source = setup.model, setup.linear, setup.rotary, setup.source
    moves = Moves(columns, model, linear, rotary, source)
    first_line = settled.first_line if settled is not None else (int(moves.line[0]) if len(moves) else 0)
    pieces = build_pieces(moves, linear, rotary, setup.tolerance_m, setup.max_segment_m, source, settled is not None)
    todo = np.ones(pieces.p1.shape[0], dtype=bool)
    if settled is not None:
        pieces.prepend(settled.pieces)
        todo = pieces.move != 0
    solve(model, pieces, todo, moves, linear, rotary, source)
    verbatim, residual, moved = settle(model, pieces, moves, linear, rotary, setup.reach, setup.tolerance_m,
                                        setup.max_segment_m, source, None if settled is None else settled.kept, first_line)
    m = len(moves)
    start = 0 if settled is None else 1
    if final:
        stop = m
    else:
        steady = np.flatnonzero(~moved[start:]) + start
        if not steady.size:
            if m > start:
                return None
            stop = m
        else:
            stop = int(steady[-1]) + 1
    written_to = int(moves.index[stop]) if stop < m else len(lines)
    output = np.zeros(m, dtype=bool)
    output[start:stop] = True
    out, rewritten = program_lines(setup.spec, lines, moves, pieces, verbatim, output, linear, rotary, line_end)
    mine = (pieces.move >= start) & (pieces.move < stop)
    corrections = np.linalg.norm(pieces.exact[mine] - pieces.p1[mine], axis=1) if mine.any() else np.zeros(1)
    last = stop - 1
    if last >= start:
        rows = pieces.move == last
        keep = {name: getattr(pieces, name)[rows] for name in Pieces.FIELDS}
        keep["move"] = np.zeros(int(rows.sum()), dtype=np.int64)
        settled_next = Settled(keep, bool(verbatim[last]), first_line)
        settled_line = int(moves.index[last])
    else:
        settled_next = settled
        settled_line = 0
    return Window(out[written_from:written_to], written_to, settled_next, settled_line, stop - start, rewritten,
                  float(corrections.max(initial=0.0)), float(residual))


def precompensate_program(
    text: str,
    machine: Machine | str,
    *,
    dialect: str,
    max_segment_m: float = 2e-3,
    tolerance_m: float = 0.5e-6,
    tool_m: tuple[float, float, float] | None = None,
    work_offset_m: Mapping[str, float] | None = None,
    source: str | None = None,
) -> str:
    """A part program with every point moved to its pre-compensated command.

    Parameters
    ----------
    text : str
        The program, in ``dialect`` (:data:`axiscal.io.gcode.DIALECT_NAMES` but "heidenhain").
    machine : Machine or str
        The machine model, or its description file. The program's coordinates, shifted by the
        work offset and G92, are the positions of the model's axes.
    dialect : str, keyword-only
        The control's dialect.
    max_segment_m : float, keyword-only
        Longest piece a move is cut into where it must be cut, metres (default 2 mm); the error is
        sampled along every move at least every half of it.
    tolerance_m : float, keyword-only
        Largest distance of the tool from the nominal path the model may predict along the
        rewritten program, metres (default 0.5 um, at least 0.2 um).
    tool_m : sequence of 3 floats, optional, keyword-only
        The functional point in the last tool-side carriage's frame, metres (default: the machine's).
    work_offset_m : Mapping[str, float], optional, keyword-only
        Axis position minus program coordinate of the work offset the program runs in (G54),
        metres; default none.
    source : str, optional, keyword-only
        The program's file, named in errors.

    Returns
    -------
    str
        The program written anew: a header comment naming the machine, axiscal's version and the
        tolerance; every block that moves written with its pre-compensated commands (cut into
        pieces, arcs linearised, where the error varies along it), with its block number, its
        other words (feed, spindle, coolant) and its comment on the first piece; every other line
        as it was. A block whose correction rounds to nothing is kept as it was.

    Raises
    ------
    AxiscalError
        Naming the line: a block the dialect's reader cannot follow (macros, subprogram calls,
        canned cycles, unknown words, an arc whose end is not on its circle), a move of an axis the
        machine does not have, a move before every axis of the machine is set, a rotary axis that
        turns while cutting, a command outside the error tables.

    Examples
    --------
    >>> out = precompensate_program(open("part.ngc").read(), "machine.toml", dialect="linuxcnc")  # doctest: +SKIP
    """
    return rewrite_program(text, machine, dialect=dialect, max_segment_m=max_segment_m, tolerance_m=tolerance_m,
                           tool_m=tool_m, work_offset_m=work_offset_m, source=source).text


def _count_lines(text: str) -> int:
    """Lines of ``text`` as :func:`~axiscal.io.gcode.split_lines` counts them (LF, CRLF or CR ends one)."""
    count = text.count("\n") + text.count("\r") - text.count("\r\n")
    return count + (1 if text and not text.endswith(("\n", "\r")) else 0)
