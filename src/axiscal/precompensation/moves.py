"""The moves of a part of a program, as columns: where each starts and ends, its kind, units, offsets and frame.

Built from the program's columns (:class:`~axiscal.io.gcode.columns.ProgramColumns`) for the
rewriting (:mod:`axiscal.precompensation.program`), with the checks a move must pass to be
pre-compensated: every axis of the model programmed, no axis the model does not have, no rotary
axis turning while cutting, each refused naming its line.
"""

from __future__ import annotations

import numpy as np

from axiscal.errors import AxiscalError
from axiscal.model.machine import Machine

__all__ = ["Moves", "fail"]


def fail(message: str, source: str | None, line: int) -> AxiscalError:
    return AxiscalError(message, path=source, line=int(line))


class Moves:
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
            raise fail(message, source, int(self.line[move]))
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
