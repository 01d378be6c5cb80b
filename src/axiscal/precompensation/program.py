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

import math
from collections.abc import Mapping
from dataclasses import dataclass

import numpy as np

from axiscal.conventions import AXIS_INDEX
from axiscal.errors import AxiscalError
from axiscal.io.arguments import check_number
from axiscal.io.gcode import PLANE_AXES, dialect as find_dialect, read_program
from axiscal.model.machine import Machine
from axiscal.precompensation.kept import kept_as_written as _keep
from axiscal.precompensation.points import CommandError, machine_with_tool, solve_commands
from axiscal.precompensation.text import PLACES, header_at, header_line, program_lines
from axiscal.units import UM
from axiscal.version import __version__

__all__ = ["Precompensation", "precompensate_program", "rewrite_program", "rewrite_window", "PLACES"]

_MM = 1e-3
_MAX_ROUNDS = 40
#: shortest ``max_segment_m``: pieces shorter than 1 um are never cut again (positions are written to 0.1 um)
MIN_SEGMENT_M = 1e-6
#: most points the path may be sampled at in one pass (pieces, chords and the samples along them):
#: about 2 GB of working arrays; a program and ``max_segment_m`` asking for more are refused up front
MAX_SAMPLES = 20_000_000


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


class _Pieces:
    """The straight pieces the program's moves are followed by: programmed ends, commands, checks."""

    FIELDS = ("move", "p0", "p1", "rot", "t0", "t1", "limit", "check", "command", "exact")

    def __init__(self, move, p0, p1, rot, t0, t1, limit, check):
        self.move, self.p0, self.p1, self.rot = move, p0, p1, rot
        self.t0, self.t1, self.limit, self.check = t0, t1, limit, check
        self.command = np.empty_like(p1)
        self.exact = np.empty_like(p1)

    def prepend(self, first: dict) -> None:
        """Put ``first`` (the FIELDS of move 0's pieces, settled before) in place of move 0's pieces."""
        rest = self.move != 0
        for name in self.FIELDS:
            setattr(self, name, np.concatenate([first[name], getattr(self, name)[rest]]))

    def split(self, counts: np.ndarray) -> np.ndarray:
        """Cut piece i into ``counts[i]`` equal pieces; return the mask of the new inner ends."""
        idx = np.repeat(np.arange(counts.size), counts)
        j = np.arange(idx.size) - np.repeat(np.cumsum(counts) - counts, counts)
        k = counts[idx].astype(float)
        f0, f1 = j / k, (j + 1) / k
        span = (self.p1 - self.p0)[idx]
        tspan = (self.t1 - self.t0)[idx]
        self.p0, self.p1 = self.p0[idx] + f0[:, None] * span, self.p0[idx] + f1[:, None] * span
        self.t0, self.t1 = self.t0[idx] + f0 * tspan, self.t0[idx] + f1 * tspan
        self.move, self.rot, self.limit, self.check = self.move[idx], self.rot[idx], self.limit[idx], self.check[idx]
        self.command, self.exact = self.command[idx], self.exact[idx]
        return j < counts[idx] - 1


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
    moves = _Moves(columns, model, linear, rotary, source)
    first_line = settled.first_line if settled is not None else (int(moves.line[0]) if len(moves) else 0)
    pieces = _build_pieces(moves, linear, rotary, setup.tolerance_m, setup.max_segment_m, source, settled is not None)
    todo = np.ones(pieces.p1.shape[0], dtype=bool)
    if settled is not None:
        pieces.prepend(settled.pieces)
        todo = pieces.move != 0
    _solve(model, pieces, todo, moves, linear, rotary, source)
    verbatim, residual, moved = _settle(model, pieces, moves, linear, rotary, setup.reach, setup.tolerance_m,
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
    mine = np.isin(pieces.move, np.arange(start, stop))
    corrections = np.linalg.norm(pieces.exact[mine] - pieces.p1[mine], axis=1) if mine.any() else np.zeros(1)
    last = stop - 1
    if last >= start:
        rows = pieces.move == last
        keep = {name: getattr(pieces, name)[rows] for name in _Pieces.FIELDS}
        keep["move"] = np.zeros(int(rows.sum()), dtype=np.int64)
        settled_next = Settled(keep, bool(verbatim[last]), first_line)
        settled_line = int(moves.index[last])
    else:
        settled_next = settled
        settled_line = 0
    return Window(out[written_from:written_to], written_to, settled_next, settled_line, stop - start, rewritten,
                  float(corrections.max(initial=0.0)), float(residual))


def _fail(message: str, source: str | None, line: int) -> AxiscalError:
    return AxiscalError(message, path=source, line=int(line))


class _Moves:
    """The program's moves (line indices) with what each line says about its frame, per move, as columns."""

    def __init__(self, columns, model: Machine, linear, rotary, source):
        self.columns = columns
        kind = columns.kind
        moving = (kind[columns.motion_line] >= 1) & (kind[columns.motion_line] <= 3)
        rows = np.flatnonzero(moving)  # the moves among the motions (dwells left out)
        index = columns.motion_line[rows]
        self.index = index
        self.rows = rows
        self.line = index + 1 + columns.first_line
        axes = columns.axes
        allowed = set(model.letters) | {"E"}
        known = columns.known[rows]
        problems: list[tuple[int, int, str]] = []  # (move, order, message) of the first of each kind of problem
        foreign = [j for j, k in enumerate(axes) if k not in allowed]
        if foreign:
            bad = known[:, foreign]
            found = np.flatnonzero(bad.any(axis=1))
            if found.size:
                letter = axes[foreign[int(np.argmax(bad[found[0]]))]]
                problems.append((int(found[0]), 0, f"{letter} is not an axis of the machine model (chain '{model.chain}')"))
        have = np.column_stack([known[:, axes.index(k)] if k in axes else np.zeros(rows.size, dtype=bool)
                                for k in model.letters]) if rows.size else np.ones((0, len(model.letters)), dtype=bool)
        found = np.flatnonzero(~have.all(axis=1))
        if found.size:
            missing = [k for k, h in zip(model.letters, have[found[0]]) if not h]
            problems.append((int(found[0]), 1, f"a move before the program has set {', '.join(missing)}, an axis of the"
                             " machine model: program every axis in the first move"))
        if rotary and rows.size:
            cols = [axes.index(k) for k in rotary]
            end = columns.end_m[rows][:, cols]
            start = columns.start_m[rows][:, cols]
            turned = (~columns.start_known[rows][:, cols] | (start != end)) & (kind[index] != 1)[:, None]
            found = np.flatnonzero(turned.any(axis=1))
            if found.size:
                which = [k for k, t in zip(rotary, turned[found[0]]) if t]
                problems.append((int(found[0]), 2, f"a move that turns {', '.join(which)} while it cuts is not"
                                 " pre-compensated (rotary axes stand still in the moves pre-compensated)"))
        if problems:
            move, _, message = min(problems)
            raise _fail(message, source, int(self.line[move]))
        self.kind = kind[index]
        self.absolute = columns.absolute[index]
        self.offset = _axis_columns(columns.offset_m[rows], axes, linear)
        self.per_unit = columns.metres_per_unit[index]
        self.end = _axis_columns(columns.end_m[rows], axes, linear)
        self.rot = _axis_columns(columns.end_m[rows], axes, rotary)

    def extruder(self) -> tuple[np.ndarray, np.ndarray, np.ndarray] | None:
        """E after and before each move (0 where not known) and E's offset, metres; None without E."""
        columns = self.columns
        if "E" not in columns.axes:
            return None
        e = columns.axes.index("E")
        rows = self.rows
        return (np.where(columns.known[rows, e], columns.end_m[rows, e], 0.0),
                np.where(columns.start_known[rows, e], columns.start_m[rows, e], 0.0), columns.offset_m[rows, e])

    def __len__(self) -> int:
        return len(self.index)

    def motion(self, number: int):
        """The Motion of move ``number`` (a line read block by block: arcs, and moves with other words)."""
        return self.columns.general[int(self.index[number])].motion


def _axis_columns(values: np.ndarray, axes: tuple[str, ...], letters) -> np.ndarray:
    """The columns of ``letters`` of ``values`` (one column per axis of ``axes``); zeros for a letter not there."""
    out = np.zeros((values.shape[0], len(letters)))
    for j, k in enumerate(letters):
        if k in axes:
            out[:, j] = values[:, axes.index(k)]
    return out


def _build_pieces(moves: _Moves, linear, rotary, tolerance_m, max_segment_m, source, settled: bool = False) -> _Pieces:
    """One piece per straight move, chords for each arc; rapid moves and the first move: their end only.

    ``settled``: the first move is the last of the part written before (its pieces are put in after).
    """
    m = len(moves)
    end = moves.end
    rot = moves.rot
    _check_finite(moves, end, linear, source)
    _check_finite(moves, rot, rotary, source)
    extruder = moves.extruder()
    if extruder is not None:
        _check_finite(moves, np.column_stack(extruder[:2]), "EE", source)
    path = moves.kind != 1
    if m:
        path[0] = False  # the program's first move, or the one settled before
    start = np.where(path[:, None], np.vstack([end[:1], end[:-1]]), end)
    counts = np.ones(m, dtype=np.int64)
    chords: dict[int, np.ndarray] = {}
    chord_sagitta = tolerance_m / 4.0
    pieces_total = m
    for number in np.flatnonzero((moves.kind == 3) & path).tolist():
        motion = moves.motion(number)
        a, b, normal = PLANE_AXES[motion.plane]
        ca, cb = motion.centre_m[a], motion.centre_m[b]
        radius = math.hypot(motion.start_m[a] - ca, motion.start_m[b] - cb)
        sweep = motion.sweep_rad
        if not (math.isfinite(radius) and math.isfinite(sweep) and radius > 0.0):
            raise _fail("the arc's centre or radius is not a finite number (a number too large for the control?)",
                        source, moves.line[number])
        # the angle of a chord of sagitta s: 1 - cos(step / 2) = s / r, written so that it does not
        # round to nothing for a radius much larger than s
        step = min(4.0 * math.asin(math.sqrt(min(chord_sagitta / (2.0 * radius), 1.0))), max_segment_m / radius)
        chords_wanted = abs(sweep) / step if step > 0.0 else math.inf
        if chords_wanted > MAX_SAMPLES:
            raise _fail(f"the arc (radius {radius / _MM:.6g} mm, {math.degrees(abs(sweep)):.6g} degrees) would be cut"
                        f" into {chords_wanted:.3g} chords (at most {MAX_SAMPLES:.3g}): take a longer max segment"
                        " or a larger tolerance", source, moves.line[number])
        count = max(1, math.ceil(chords_wanted - 1e-9))
        pieces_total += count - 1
        if pieces_total > MAX_SAMPLES:
            raise _fail(f"the program's arcs would be cut into more than {MAX_SAMPLES:.3g} chords:"
                        " take a longer max segment or a larger tolerance", source, moves.line[number])
        f = np.arange(1, count + 1) / count
        points = np.repeat(start[number][None, :], count, axis=0)
        theta = math.atan2(motion.start_m[b] - cb, motion.start_m[a] - ca) + sweep * f
        for letter, value in ((a, ca + radius * np.cos(theta)), (b, cb + radius * np.sin(theta))):
            if letter in linear:
                points[:, linear.index(letter)] = value
        if normal in linear:
            j = linear.index(normal)
            points[:, j] = start[number][j] + f * (end[number][j] - start[number][j])
        points[-1] = end[number]
        chords[number] = points
        counts[number] = count
    owner = np.repeat(np.arange(m), counts)
    first = np.cumsum(counts) - counts
    within = np.arange(owner.size) - first[owner]
    p1 = end[owner].copy()
    t1 = np.ones(owner.size)
    limit = np.full(owner.size, tolerance_m)
    for number, points in chords.items():
        rows = slice(first[number], first[number] + counts[number])
        p1[rows] = points
        t1[rows] = np.arange(1, counts[number] + 1) / counts[number]
        limit[rows] = 0.75 * tolerance_m
    p0 = np.where((within == 0)[:, None], start[owner], np.vstack([p1[:1], p1[:-1]]))
    t0 = np.where(within == 0, 0.0, np.r_[0.0, t1[:-1]])
    return _Pieces(owner, p0, p1, rot[owner], t0, t1, limit, path[owner])


def _check_finite(moves: _Moves, end: np.ndarray, letters, source) -> None:
    """Refuse, naming the line, a move whose end (one row of ``end`` per move) is not a finite number."""
    finite = np.isfinite(end).all(axis=1)
    if not finite.all():
        number = int(np.argmin(finite))
        letter = letters[int(np.argmin(np.isfinite(end[number])))]
        raise _fail(f"{letter} is not a finite number here (a number too large for the control?)", source, moves.line[number])


def _units(moves: _Moves, pieces: _Pieces):
    """Offset (metres) and metres per unit of each piece's block."""
    return moves.offset[pieces.move], moves.per_unit[pieces.move]


def _solve(model, pieces: _Pieces, which: np.ndarray, moves, linear, rotary, source) -> None:
    """Pre-compensated commands of the pieces' ends where ``which``, rounded as they will be written."""
    if not which.any():
        return
    programmed = {k: pieces.p1[which, j] for j, k in enumerate(linear)} | {k: pieces.rot[which, j] for j, k in enumerate(rotary)}
    try:
        solved = solve_commands(model, programmed)
    except CommandError as error:
        piece = np.flatnonzero(which)[error.index]
        raise _fail(error.message, source, moves.line[pieces.move[piece]]) from None
    command = np.column_stack([solved[k] for k in linear])
    offset, per_unit = _units(moves, pieces)
    places = np.where(per_unit[which] == _MM, PLACES["mm"], PLACES["inch"])
    scale = (10.0 ** places / per_unit[which])[:, None]
    pieces.exact[which] = command
    pieces.command[which] = np.round((command - offset[which]) * scale) / scale + offset[which]


def _settle(model, pieces, moves, linear, rotary, reach, tolerance_m, max_segment_m, source, first_kept, first_line):
    """Decide which moves are kept as written and cut pieces until every sampled path is in tolerance.

    Returns the decisions, the largest residual, and per move whether its last command or its
    decision changed after they were first found (``first_kept``: move 0 settled before, not checked
    again).
    """
    offset, per_unit = _units(moves, pieces)
    verbatim = _keep(moves, pieces, per_unit, first_kept=first_kept)
    moved = np.zeros(len(moves), dtype=bool)
    dirty = np.ones(pieces.p1.shape[0], dtype=bool)
    if first_kept is not None:
        dirty &= pieces.move != 0
    worst = 0.0
    for _ in range(_MAX_ROUNDS):
        out = np.where(verbatim[pieces.move][:, None], pieces.p1, pieces.command)
        start = np.vstack([out[:1], out[:-1]])
        check = pieces.check & dirty
        ends = ~pieces.check & dirty
        if ends.any():
            miss = _deviation(model, out[ends], pieces.p1[ends], pieces.rot[ends], linear, rotary, reach)
            worst = max(worst, float(miss.max()))
        failing = np.zeros(pieces.p1.shape[0], dtype=bool)
        if check.any():
            idx = np.flatnonzero(check)
            length = np.linalg.norm(pieces.p1[idx] - pieces.p0[idx], axis=1)
            wanted = np.maximum(2.0, np.ceil(length / (max_segment_m / 2.0)))
            if wanted.sum() > MAX_SAMPLES:
                raise _too_many(wanted.sum(), length, max_segment_m, source, moves.line[pieces.move[idx[np.argmax(length)]]])
            counts = wanted.astype(np.int64)
            rep = np.repeat(np.arange(idx.size), counts)
            owner = idx[rep]
            t = (np.arange(owner.size) - (np.cumsum(counts) - counts)[rep] + 1) / counts[rep]
            c_0, p_0 = np.take(start, owner, axis=0), np.take(pieces.p0, owner, axis=0)
            c_t = c_0 + t[:, None] * (np.take(out, owner, axis=0) - c_0)
            p_t = p_0 + t[:, None] * (np.take(pieces.p1, owner, axis=0) - p_0)
            miss = _deviation(model, c_t, p_t, pieces.rot[owner], linear, rotary, reach)
            largest = np.maximum.reduceat(miss, np.cumsum(counts) - counts)
            bad = largest > pieces.limit[idx]
            failing[idx[bad]] = True
            excess = np.ones(pieces.p1.shape[0])
            excess[idx] = largest / pieces.limit[idx]
            ok = largest[~bad]
            if ok.size:
                worst = max(worst, float(ok.max()))
        if not failing.any():
            return verbatim, worst, moved
        flips = np.unique(pieces.move[failing & verbatim[pieces.move]])
        if flips.size:
            before = verbatim.copy()
            verbatim[flips] = False
            verbatim = _keep(moves, pieces, per_unit, forced=verbatim, first_kept=first_kept)
            moved |= verbatim != before
        cut = failing & ~np.isin(pieces.move, flips)
        tiny = cut & (np.linalg.norm(pieces.p1 - pieces.p0, axis=1) < 1e-6)
        if tiny.any():
            line = moves.line[pieces.move[np.argmax(tiny)]]
            raise _fail(f"the path cannot be held within {tolerance_m / UM:g} um of the nominal one", source, line)
        old_out = out
        if cut.any():
            # the departure from the chord grows with the square of the piece's length
            need = np.ceil(1.25 * np.sqrt(np.maximum(excess, 1.0)))
            wanted = np.where(cut, np.maximum(need, 2), 1)
            if wanted.sum() > MAX_SAMPLES:
                length = np.linalg.norm(pieces.p1 - pieces.p0, axis=1)
                raise _too_many(wanted.sum(), length, max_segment_m, source, moves.line[pieces.move[np.argmax(wanted)]])
            counts = wanted.astype(np.int64)
            inner = pieces.split(counts)
            _solve(model, pieces, inner, moves, linear, rotary, source)
            offset, per_unit = _units(moves, pieces)
            old_out = old_out[np.repeat(np.arange(counts.size), counts)]
            changed_piece = np.repeat(cut, counts)
        else:
            changed_piece = np.zeros(pieces.p1.shape[0], dtype=bool)
        new_out = np.where(verbatim[pieces.move][:, None], pieces.p1, pieces.command)
        shifted = np.any(new_out != old_out, axis=1)
        ends = np.r_[pieces.move[1:] != pieces.move[:-1], True]
        moved[pieces.move[shifted & ends]] = True
        # a move written anew because its path failed is checked again, even where its commands
        # round to the programmed points (its output then unchanged, its path still failing)
        changed = changed_piece | shifted | np.isin(pieces.move, flips)
        dirty = changed | np.concatenate([[False], changed[:-1]])
    raise _fail("the path could not be held within the tolerance", source, first_line)


def _too_many(count: float, length: np.ndarray, max_segment_m: float, source, line: int) -> AxiscalError:
    """The one-line refusal of a path that would take more than :data:`MAX_SAMPLES` points, with what would do."""
    room = MAX_SAMPLES - 3.0 * length.size
    advice = (f"take a longer max segment (at least {2.0 * float(length.sum()) / room / _MM:.3g} mm for this program)"
              if room > 0 else "cut the program into parts")
    return _fail(f"the path would be checked at {count:.3g} points (at most {MAX_SAMPLES:.3g}) with segments up to"
                 f" {max_segment_m / _MM:g} mm: {advice}", source, line)


def _deviation(model, command, programmed, rot, linear, rotary, reach) -> np.ndarray:
    """Distance of the tool at ``command`` from the nominal point of ``programmed``, along the axes' directions."""
    at = {k: command[:, j] for j, k in enumerate(linear)} | {k: rot[:, j] for j, k in enumerate(rotary)}
    want = {k: programmed[:, j] for j, k in enumerate(linear)} | {k: rot[:, j] for j, k in enumerate(rotary)}
    miss = model.actual_point(at) - model.nominal_point(want)
    squares = miss[:, reach[0]] ** 2
    for j in reach[1:]:
        squares += miss[:, j] ** 2
    return np.sqrt(squares)


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
