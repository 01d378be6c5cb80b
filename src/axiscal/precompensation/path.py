"""The path of a part of a program: moves cut into straight pieces, their ends commanded, the path checked.

Each straight move is one piece, each arc chords of a sagitta a quarter of the tolerance; every
piece end gets the model's pre-compensated command, rounded as it will be written (:func:`solve`);
the path between the commands is sampled at least every half ``max_segment_m`` and the pieces that
leave the tolerance are cut, or their move written anew where it was kept as written, until every
sample holds (:func:`settle`).
"""

from __future__ import annotations

import math

import numpy as np

from axiscal.errors import AxiscalError
from axiscal.io.gcode import PLANE_AXES
from axiscal.precompensation.kept import kept_as_written as _keep
from axiscal.precompensation.moves import Moves, fail
from axiscal.precompensation.points import CommandError, solve_commands
from axiscal.precompensation.text import PLACES
from axiscal.units import UM

__all__ = ["Pieces", "build_pieces", "solve", "settle", "MAX_SAMPLES"]

_MM = 1e-3
_MAX_ROUNDS = 40
#: most points the path may be sampled at in one pass (pieces, chords and the samples along them):
#: about 2 GB of working arrays; a program and ``max_segment_m`` asking for more are refused up front
MAX_SAMPLES = 20_000_000


class Pieces:
    """The straight pieces the program's moves are followed by: programmed ends, commands, checks."""

    FIELDS = ("move", "p0", "p1", "rot", "t0", "t1", "limit", "check", "command", "exact")

    def __init__(self, move, p0, p1, rot, t0, t1, limit, check):
        self.move, self.p0, self.p1, self.rot = move, p0, p1, rot
        self.t0, self.t1, self.limit, self.check = t0, t1, limit, check
        self.command = np.empty_like(p1)
        self.exact = np.empty_like(p1)

    def prepend(self, first: dict) -> None:
        """Put ``first`` (the FIELDS of move 0's pieces, settled before) in place of move 0's pieces."""
        if first["move"].size == 1 and self.move.size and self.move[0] == 0 and (self.move.size == 1 or self.move[1] != 0):
            for name in self.FIELDS:  # one piece for one: in place
                getattr(self, name)[0] = first[name][0]
            return
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


def build_pieces(moves: Moves, linear, rotary, tolerance_m, max_segment_m, source, settled: bool = False) -> Pieces:
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
    arcs = np.flatnonzero((moves.kind == 3) & path)
    shape = _arc_chords(moves, arcs, linear, tolerance_m, max_segment_m, source, m) if arcs.size else None
    if shape is not None:
        counts[arcs] = shape[0]
    owner = np.repeat(np.arange(m), counts)
    first = np.cumsum(counts) - counts
    within = np.arange(owner.size) - first[owner]
    p1 = end[owner].copy()
    t1 = np.ones(owner.size)
    limit = np.full(owner.size, tolerance_m)
    if shape is not None:
        # every chord's end at once, with each arc's arithmetic as one arc alone would do it
        count, theta0, sweep, ca, cb, radius, ja, jb, jn = shape
        arc_of = np.repeat(np.arange(arcs.size), count)
        rows = np.repeat(first[arcs], count) + (np.arange(arc_of.size) - np.repeat(np.cumsum(count) - count, count))
        f = (within[rows] + 1) / count[arc_of]
        moving = arcs[arc_of]
        points = start[moving]
        theta = theta0[arc_of] + sweep[arc_of] * f
        for column, centre, trig in ((ja, ca, np.cos), (jb, cb, np.sin)):
            here = column[arc_of] >= 0
            points[here, column[arc_of][here]] = centre[arc_of][here] + radius[arc_of][here] * trig(theta[here])
        here = jn[arc_of] >= 0
        j = jn[arc_of][here]
        s0 = start[moving[here], j]
        points[here, j] = s0 + f[here] * (end[moving[here], j] - s0)
        last = np.cumsum(count) - 1
        points[last] = end[arcs]
        p1[rows] = points
        t1[rows] = f
        limit[rows] = 0.75 * tolerance_m
    p0 = np.where((within == 0)[:, None], start[owner], np.vstack([p1[:1], p1[:-1]]))
    t0 = np.where(within == 0, 0.0, np.r_[0.0, t1[:-1]])
    return Pieces(owner, p0, p1, rot[owner], t0, t1, limit, path[owner])


def _arc_chords(moves: Moves, arcs: np.ndarray, linear, tolerance_m, max_segment_m, source, m: int):
    """Per arc of ``arcs`` (move numbers): its chords' count, the angle of its start, its sweep, its centre
    and radius in its plane, and the columns of ``linear`` its plane's axes and its normal are (-1: none);
    an arc of more chords than :data:`MAX_SAMPLES` (or all of them together) refused naming its line."""
    chord_sagitta = tolerance_m / 4.0
    pieces_total = m
    n = arcs.size
    count = np.empty(n, dtype=np.int64)
    values = np.empty((5, n))
    columns = np.empty((3, n), dtype=np.int64)
    for i, number in enumerate(arcs.tolist()):
        motion = moves.motion(number)
        a, b, normal = PLANE_AXES[motion.plane]
        ca, cb = motion.centre_m[a], motion.centre_m[b]
        radius = math.hypot(motion.start_m[a] - ca, motion.start_m[b] - cb)
        sweep = motion.sweep_rad
        if not (math.isfinite(radius) and math.isfinite(sweep) and radius > 0.0):
            raise fail("the arc's centre or radius is not a finite number (a number too large for the control?)",
                       source, moves.line[number])
        # the angle of a chord of sagitta s: 1 - cos(step / 2) = s / r, written so that it does not
        # round to nothing for a radius much larger than s
        step = min(4.0 * math.asin(math.sqrt(min(chord_sagitta / (2.0 * radius), 1.0))), max_segment_m / radius)
        chords_wanted = abs(sweep) / step if step > 0.0 else math.inf
        if chords_wanted > MAX_SAMPLES:
            raise fail(f"the arc (radius {radius / _MM:.6g} mm, {math.degrees(abs(sweep)):.6g} degrees) would be cut"
                       f" into {chords_wanted:.3g} chords (at most {MAX_SAMPLES:.3g}): take a longer max segment"
                       " or a larger tolerance", source, moves.line[number])
        count[i] = max(1, math.ceil(chords_wanted - 1e-9))
        pieces_total += int(count[i]) - 1
        if pieces_total > MAX_SAMPLES:
            raise fail(f"the program's arcs would be cut into more than {MAX_SAMPLES:.3g} chords:"
                       " take a longer max segment or a larger tolerance", source, moves.line[number])
        values[:, i] = (math.atan2(motion.start_m[b] - cb, motion.start_m[a] - ca), sweep, ca, cb, radius)
        columns[:, i] = [linear.index(k) if k in linear else -1 for k in (a, b, normal)]
    return (count, *values, *columns)


def _check_finite(moves: Moves, end: np.ndarray, letters, source) -> None:
    """Refuse, naming the line, a move whose end (one row of ``end`` per move) is not a finite number."""
    finite = np.isfinite(end).all(axis=1)
    if not finite.all():
        number = int(np.argmin(finite))
        letter = letters[int(np.argmin(np.isfinite(end[number])))]
        raise fail(f"{letter} is not a finite number here (a number too large for the control?)", source, moves.line[number])


def _units(moves: Moves, pieces: Pieces):
    """Offset (metres) and metres per unit of each piece's block."""
    return moves.offset[pieces.move], moves.per_unit[pieces.move]


def solve(model, pieces: Pieces, which: np.ndarray, moves, linear, rotary, source) -> None:
    """Pre-compensated commands of the pieces' ends where ``which``, rounded as they will be written."""
    if not which.any():
        return
    programmed = {k: pieces.p1[which, j] for j, k in enumerate(linear)} | {k: pieces.rot[which, j] for j, k in enumerate(rotary)}
    try:
        solved = solve_commands(model, programmed)
    except CommandError as error:
        piece = np.flatnonzero(which)[error.index]
        raise fail(error.message, source, moves.line[pieces.move[piece]]) from None
    command = np.column_stack([solved[k] for k in linear])
    rows = np.flatnonzero(which)
    move = pieces.move[rows]
    offset, per_unit = moves.offset[move], moves.per_unit[move]
    places = np.where(per_unit == _MM, PLACES["mm"], PLACES["inch"])
    scale = (10.0 ** places / per_unit)[:, None]
    pieces.exact[rows] = command
    pieces.command[rows] = np.round((command - offset) * scale) / scale + offset


def settle(model, pieces, moves, linear, rotary, reach, tolerance_m, max_segment_m, source, first_kept, first_line):
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
            owner = np.repeat(idx, counts)
            c_t, p_t = _samples(start, out, pieces.p0, pieces.p1, idx, counts)
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
            raise fail(f"the path cannot be held within {tolerance_m / UM:g} um of the nominal one", source, line)
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
            solve(model, pieces, inner, moves, linear, rotary, source)
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
    raise fail("the path could not be held within the tolerance", source, first_line)


#: whether the samples are laid by the compiled kernel (False: in NumPy, the reference)
_COMPILED = True


def _samples(start, out, p0, p1, idx, counts):
    """The commands and programmed points sampled along pieces ``idx``, ``counts`` samples each, at
    ``t = (s + 1) / count``."""
    if _COMPILED:
        from axiscal.precompensation import path_kernel  # numba takes a moment to load

        return path_kernel.samples(np.ascontiguousarray(start), np.ascontiguousarray(out), np.ascontiguousarray(p0),
                                   np.ascontiguousarray(p1), idx, counts)
    rep = np.repeat(np.arange(idx.size), counts)
    owner = idx[rep]
    t = (np.arange(owner.size) - (np.cumsum(counts) - counts)[rep] + 1) / counts[rep]
    c_0, p_0 = np.take(start, owner, axis=0), np.take(p0, owner, axis=0)
    c_t = c_0 + t[:, None] * (np.take(out, owner, axis=0) - c_0)
    p_t = p_0 + t[:, None] * (np.take(p1, owner, axis=0) - p_0)
    return c_t, p_t


def _too_many(count: float, length: np.ndarray, max_segment_m: float, source, line: int) -> AxiscalError:
    """The one-line refusal of a path that would take more than :data:`MAX_SAMPLES` points, with what would do."""
    room = MAX_SAMPLES - 3.0 * length.size
    advice = (f"take a longer max segment (at least {2.0 * float(length.sum()) / room / _MM:.3g} mm for this program)"
              if room > 0 else "cut the program into parts")
    return fail(f"the path would be checked at {count:.3g} points (at most {MAX_SAMPLES:.3g}) with segments up to"
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
