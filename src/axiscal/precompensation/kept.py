"""Which moves of a pre-compensated program are written as they were.

A move whose every piece's correction rounds to nothing at the written resolution is kept as
written, unless keeping it would change what the control does: a move that relies on the modal
motion word needs the output's modal word to be the program's there, and an incremental move needs
the output to stand where the program stands before it. Decided for all moves at once; only the
moves whose decision waits on the one before are walked in order.
"""

from __future__ import annotations

import numpy as np

from axiscal.precompensation.text import PLACES

__all__ = ["kept_as_written"]

_MM = 1e-3


def kept_as_written(moves, pieces, per_unit, forced: np.ndarray | None = None, first_kept: bool | None = None) -> np.ndarray:
    """Which moves are written as they were: corrections below half the written resolution, modes consistent.

    A move kept as written that relies on the modal motion word needs the output's modal word to be
    the program's there: the move before it (or the mode word before it) was kept, or was written
    anew with the word it had. An incremental move kept as written needs the output to stand where
    the program stands before it. ``first_kept``, where given, is the decision already taken for the
    first move (the last one of the part of the program written before).
    """
    half = 0.5 * np.where(per_unit == _MM, 10.0 ** -PLACES["mm"], 10.0 ** -PLACES["inch"]) * per_unit
    small = np.all(np.abs(pieces.command - pieces.p1) < half[:, None], axis=1)
    first = np.r_[0, np.flatnonzero(np.diff(pieces.move)) + 1]
    move_small = np.logical_and.reduceat(small, first) if small.size else np.zeros(0, dtype=bool)
    keep = move_small if forced is None else move_small & forced
    if first_kept is not None and keep.size:
        keep = keep.copy()
        keep[0] = first_kept
    if not keep.any():
        return keep
    last = np.r_[first[1:] - 1, small.size - 1]
    columns = moves.columns
    word = columns.motion_word
    n = word.size
    lines = np.arange(n)
    written_at = np.maximum.accumulate(np.where(word >= 0, lines, -1))
    in_force = np.where(written_at >= 0, word[np.maximum(written_at, 0)], columns.motion_word_before)  # the program's modal word after each line
    move_of_line = np.full(n, -1, dtype=np.int64)
    move_of_line[moves.index] = np.arange(len(moves))
    events = np.flatnonzero((word >= 0) | (move_of_line >= 0))
    at = np.searchsorted(events, moves.index)
    before = np.where(at > 0, events[np.maximum(at - 1, 0)], -1)  # the event line before each move, -1: none
    previous = np.where(before >= 0, move_of_line[np.maximum(before, 0)], -1)  # ... when it is a move
    derived = np.where(moves.kind == 1, 0, 1)  # the word a move written anew gets: G0 at rapid, else G1
    own = word[moves.index] >= 0
    mode_fixed = own | (previous < 0) | (derived[np.maximum(previous, 0)] == in_force[np.maximum(before, 0)])
    if first_kept is not None:
        mode_fixed[0] = True
    absolute = moves.absolute
    candidates = keep.copy()
    # moves whose decision waits for the one before's: in order, one by one
    waits = candidates & ((~mode_fixed & candidates[np.maximum(previous, 0)] & (previous >= 0))
                          | (~absolute & np.r_[False, candidates[:-1]]))
    settled = candidates & ~waits
    keep = settled & mode_fixed
    if (keep & ~absolute).any():
        keep &= _stands(keep & ~absolute, keep, moves, pieces, first, last, half) | absolute
    for number in np.flatnonzero(waits).tolist():
        ok = True
        if not mode_fixed[number]:
            p = previous[number]
            ok = p >= 0 and bool(keep[p])
        if ok and not absolute[number] and number > 0:
            q = number - 1
            here = pieces.p1[last[q]] if keep[q] else pieces.command[last[q]]
            ok = bool(np.all(np.abs(here - pieces.p0[first[number]]) < half[first[number]]))
        keep[number] = ok
    return keep


def _stands(which: np.ndarray, keep: np.ndarray, moves, pieces, first, last, half) -> np.ndarray:
    """For the incremental moves ``which`` (the move before each one decided in ``keep``): whether the
    output stands where the program does before it."""
    out = np.ones(which.size, dtype=bool)
    numbers = np.flatnonzero(which & (np.arange(which.size) > 0))
    q = numbers - 1
    here = np.where(keep[q][:, None], pieces.p1[last[q]], pieces.command[last[q]])
    out[numbers] = np.all(np.abs(here - pieces.p0[first[numbers]]) < half[first[numbers]][:, None], axis=1)
    return out
