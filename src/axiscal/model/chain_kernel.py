"""The kinematic chain carried point by point in one compiled pass (numba): the forward model's fast core.

Implements exactly the composition of :mod:`axiscal.model.kinematics` (paper 000 eqs 6-10 for
linear axes, ISO 230-7 for rotary axes): per point, the six error motions of every axis are
interpolated from its table, and the functional point (and, when asked, the tool direction) is
carried through ``T_wp⁻¹ · T_tool`` with and without errors, as three scalars. Nothing is
linearised: the inverse of ``I + [e]x`` is applied in closed form, as in the NumPy composition.
One loop over the points replaces some hundred array passes, so no temporary array is made; the
loop releases the GIL and large inputs are split into chunks run on threads. The model runs it
from 65536 points on; fewer points take the NumPy arrays of :mod:`axiscal.model.kinematics`.

The interpolation is that of :meth:`axiscal.model.tables.ErrorTable.evaluate` (same segment, same
arithmetic); a cubic table, and error motions given per point, are evaluated before and passed
in. The compiled functions are cached on disk by numba, so a new process loads them instead of
compiling them again.
"""

from __future__ import annotations

import math
import os
from concurrent.futures import ThreadPoolExecutor
from dataclasses import dataclass

import numpy as np
from numba import njit

from axiscal.conventions import ROTARY_LETTERS
from axiscal.model.tables import _TURN

#: nothing public: the entries are :class:`axiscal.model.Machine` and :mod:`axiscal.model.kinematics`
__all__: list[str] = []

#: what :func:`run_chain` returns per point: the position error (3 columns), or the position error
#: and the orientation error of the tool axis (5 columns)
ERROR, POSE = 0, 1
#: points per chunk of work (the unit the threads share)
CHUNK = 65536


@dataclass(frozen=True)
class PackedChain:
    """A chain's links as flat arrays in the order they are applied to the tool point.

    The tool-side links come first, from the last carriage inward (forward), then the workpiece-side
    links from the frame outward (inverted). ``L`` links; the tables' rows are concatenated.

    Parameters
    ----------
    letters : tuple of str
        Axis letter of each link, shape (L,).
    rotary, axis, forward : ndarray of int64, shape (L,)
        1 for a rotary link; the coordinate (0, 1, 2) it moves along or turns about; 1 when applied
        forward (tool side), 0 when inverted (workpiece side).
    origin, offset : ndarray, shape (L, 3)
        Carriage origin or pivot (m); position error of a rotary axis line (m, zero for a linear link).
    square : ndarray, shape (L, 4)
        Squareness of a linear link or tilt of a rotary one (rad), and ``1 / (1 + |s|²)``.
    first_row, rows : ndarray of int64, shape (L,)
        Where each table's rows start in ``position``, and how many there are.
    start, end, inverse_step : ndarray, shape (L,)
        Table range (m or rad) and ``1 / step`` of a table of even steps (0 otherwise).
    first_bin, inverse_bin : ndarray, shape (L,)
        For an uneven table, where its bins start in ``bins`` (-1: none, search the rows) and
        ``1 / width`` of a bin (:class:`~axiscal.model.tables.ErrorTable` makes them).
    bins : ndarray of int64, shape (B,)
        Every uneven table's row at the start of each bin.
    periodic : ndarray of int64, shape (L,)
        1 for a table that wraps every 360 degrees.
    position : ndarray, shape (T,)
        Every table's positions.
    values, slopes : ndarray, shape (T, 6)
        Every table's rows and the slopes to the next row.
    tables : tuple of ErrorTable
        The links' tables, shape (L,).
    """

    letters: tuple[str, ...]
    rotary: np.ndarray
    axis: np.ndarray
    forward: np.ndarray
    origin: np.ndarray
    square: np.ndarray
    offset: np.ndarray
    first_row: np.ndarray
    rows: np.ndarray
    start: np.ndarray
    end: np.ndarray
    inverse_step: np.ndarray
    first_bin: np.ndarray
    inverse_bin: np.ndarray
    bins: np.ndarray
    periodic: np.ndarray
    position: np.ndarray
    values: np.ndarray
    slopes: np.ndarray
    tables: tuple


def pack_chain(tool_links, workpiece_links) -> PackedChain:
    """The links of a chain (ChainLink or RotaryLink, each branch from the frame outward) packed for the kernel."""
    order = [(link, 1) for link in reversed(tuple(tool_links))] + [(link, 0) for link in workpiece_links]
    tables = [link.table for link, _ in order]
    rotary = [link.letter in ROTARY_LETTERS for link, _ in order]  # a RotaryLink turns about A, B or C
    first_row = np.cumsum([0] + [table.position_m.size for table in tables])[:-1]
    binned = [table._bin_rows if table._uniform_step is None and table._bin_rows is not None else None for table in tables]
    first_bin = np.cumsum([0] + [0 if rows is None else rows.size for rows in binned])[:-1]
    zero = np.zeros(3)

    def vectors(rows) -> np.ndarray:
        return np.ascontiguousarray(np.reshape(rows, (len(order), 3)), dtype=np.float64)

    def stacked(arrays, width: int) -> np.ndarray:
        return np.ascontiguousarray(np.vstack(arrays) if arrays else np.zeros((0, width)))

    return PackedChain(
        letters=tuple(link.letter for link, _ in order),
        rotary=np.array(rotary, dtype=np.int64),
        axis=np.array([link.index for link, _ in order], dtype=np.int64),
        forward=np.array([f for _, f in order], dtype=np.int64),
        origin=vectors([link.origin_m for link, _ in order]),
        square=_with_scale(vectors([link.tilt_rad if r else link.squareness_rad for (link, _), r in zip(order, rotary)])),
        offset=vectors([link.offset_m if r else zero for (link, _), r in zip(order, rotary)]),
        first_row=np.array(first_row, dtype=np.int64),
        rows=np.array([table.position_m.size for table in tables], dtype=np.int64),
        start=np.array([table.start_m for table in tables], dtype=np.float64),
        end=np.array([table.end_m for table in tables], dtype=np.float64),
        inverse_step=np.array([0.0 if t._uniform_step is None else 1.0 / t._uniform_step for t in tables], dtype=np.float64),
        first_bin=np.array([-1 if rows is None else k for rows, k in zip(binned, first_bin)], dtype=np.int64),
        inverse_bin=np.array([1.0 / table._bin_width for table in tables], dtype=np.float64),
        bins=np.ascontiguousarray(np.concatenate([rows for rows in binned if rows is not None] or [np.zeros(0)]), dtype=np.int64),
        periodic=np.array([int(table.periodic) for table in tables], dtype=np.int64),
        position=np.ascontiguousarray(np.concatenate([table.position_m for table in tables] or [np.zeros(0)])),
        values=stacked([table.values.T for table in tables], 6),
        slopes=stacked([np.vstack([table._slopes.T, np.zeros((1, 6))]) for table in tables], 6),
        tables=tuple(tables),
    )


def _with_scale(rotations: np.ndarray) -> np.ndarray:
    """Rotation vectors (L, 3) with ``1 / (1 + |e|²)`` as a fourth column (as :func:`_scale` works it out)."""
    scale = np.array([1.0 / (1.0 + ex * ex + ey * ey + ez * ez) for ex, ey, ez in rotations.tolist()]).reshape(-1, 1)
    return np.ascontiguousarray(np.hstack([rotations, scale]))


def run_chain(chain: PackedChain, positions: dict, tool_m, *, mode: int = ERROR, errors=None, workers=None) -> np.ndarray:
    """Error of the functional point (and of the tool axis) at N sets of axis positions, on threads.

    Parameters
    ----------
    chain : PackedChain
        From :func:`pack_chain`.
    positions : dict of str to ndarray, shape (N,)
        Checked positions of every axis (finite; m, rad for a rotary axis).
    tool_m : ndarray, shape (3,)
        The functional point in the last tool-side carriage, m.
    mode : {ERROR, POSE}
    errors : dict of str to ndarray, shape (6, N), optional
        Checked error motions of every axis, instead of its table.
    workers : int, optional
        Threads (default: the number of cores).

    Returns
    -------
    ndarray, shape (N, 3) or (N, 5)
        Metres (and radians for the two orientation columns of POSE).

    Raises
    ------
    AxiscalError
        A position outside a table that neither holds its ends nor is periodic.
    """
    q = tuple(_plain(positions[letter]) for letter in chain.letters)
    n = q[0].size if q else len(next(iter(positions.values())))
    given = np.zeros(len(q), dtype=np.int64)
    motions = []
    for k, letter in enumerate(chain.letters):
        table = chain.tables[k]
        if errors is not None:
            given[k] = 1
            motions.append(_plain(errors[letter]))
        elif table.interpolation != "linear":
            given[k] = 1
            motions.append(_plain(table.evaluate(q[k])))
        else:
            if not (table.hold_ends or table.periodic) and n and (
                q[k].min() < table.start_m or q[k].max() > table.end_m
            ):
                table.check_range(q[k])
            motions.append(None)
    out = np.empty((n, 5 if mode == POSE else 3))
    tool = np.ascontiguousarray(tool_m, dtype=np.float64)
    if not q:  # a chain of no axis: no error
        out[:] = 0.0
        return out
    any_given = bool(given.any())

    def fill(start: int) -> None:
        # one array of the chunk's positions (and given motions) per chunk, whatever the number of
        # links: one compiled signature serves every machine
        stop = min(start + CHUNK, n)
        chunk = np.stack([v[start:stop] for v in q])
        given_chunk = np.stack([m[:, start:stop] if g else _no_motions(stop - start) for m, g in zip(motions, given)]) \
            if any_given else _NO_MOTIONS
        _carry_points(chunk, given_chunk, given, chain.rotary, chain.axis, chain.forward, chain.origin, chain.square,
                      chain.offset, chain.first_row, chain.rows, chain.start, chain.end, chain.inverse_step,
                      chain.first_bin, chain.inverse_bin, chain.bins, chain.periodic, chain.position, chain.values,
                      chain.slopes, tool, mode, _TURN, start, stop, out)

    workers = workers or os.cpu_count() or 1
    if workers == 1 or n <= CHUNK:
        for start in range(0, n, CHUNK):
            fill(start)
    else:
        with ThreadPoolExecutor(min(workers, -(-n // CHUNK))) as pool:
            list(pool.map(fill, range(0, n, CHUNK)))
    return out


_NO_MOTIONS = np.zeros((1, 6, 1))


def _no_motions(size: int) -> np.ndarray:
    """Zero motions of one link over ``size`` points (a link read from its table among given ones)."""
    return np.zeros((6, size))


def _plain(values) -> np.ndarray:
    """``values`` as a C-contiguous, aligned, writable float64 array (one type for the compiled
    function, whatever view a caller passed: a read-only column of a table, a strided slice)."""
    return np.require(values, np.float64, ("C", "A", "W"))


@njit(cache=True, nogil=True, inline="always")
def _rotate(ex, ey, ez, px, py, pz):
    """``(I + [e]x) p``."""
    return px + (ey * pz - ez * py), py + (ez * px - ex * pz), pz + (ex * py - ey * px)


@njit(cache=True, nogil=True, inline="always")
def _unrotate(ex, ey, ez, scale, px, py, pz):
    """``(I + [e]x)⁻¹ p = (p - e × p + e (e · p)) / (1 + |e|²)``, exact; ``scale`` is ``1 / (1 + |e|²)``
    (:func:`_scale`), worked out once for every use of the same e."""
    dot = ex * px + ey * py + ez * pz
    return (
        (px - (ey * pz - ez * py) + ex * dot) * scale,
        (py - (ez * px - ex * pz) + ey * dot) * scale,
        (pz - (ex * py - ey * px) + ez * dot) * scale,
    )


@njit(cache=True, nogil=True, inline="always")
def _scale(ex, ey, ez):
    """``1 / (1 + |e|²)``."""
    return 1.0 / (1.0 + ex * ex + ey * ey + ez * ez)


@njit(cache=True, nogil=True, inline="always")
def _turn(index, c, s, px, py, pz):
    """Exact rotation of p about coordinate axis ``index`` by the angle with cosine c and sine s."""
    if index == 0:
        return px, c * py - s * pz, s * py + c * pz
    if index == 1:
        return c * px + s * pz, py, -s * px + c * pz
    return c * px - s * py, s * px + c * py, pz


@njit(cache=True, nogil=True, inline="always")
def _carry(px, py, pz, errors, point, q, v, cs, rotary, axis, forward, origin, square, offset):
    """``T_wp⁻¹ · T_tool`` applied to p (a point, or a direction if not ``point``), with or without errors.

    ``q``: position of each link; ``v``: its six error motions (L, 6); ``cs``: cos and sin of a
    rotary link's angle (L, 2). Per link: ``A_k`` forward (tool side) or ``A_k⁻¹`` (workpiece side), as the module
    docstring of :mod:`axiscal.model.kinematics` writes them."""
    for k in range(rotary.size):
        if rotary[k]:
            c, s = cs[k, 0], cs[k, 1]
            ox = oy = oz = 0.0
            if point:
                ox, oy, oz = origin[k, 0], origin[k, 1], origin[k, 2]
            dx = dy = dz = 0.0
            if errors and point:
                dx, dy, dz = offset[k, 0], offset[k, 1], offset[k, 2]
            if forward[k]:
                px, py, pz = px - dx, py - dy, pz - dz
                if errors:
                    px, py, pz = _unrotate(square[k, 0], square[k, 1], square[k, 2], square[k, 3], px, py, pz)
                px, py, pz = _turn(axis[k], c, s, px, py, pz)
                if errors:
                    px, py, pz = _rotate(v[k, 3], v[k, 4], v[k, 5], px, py, pz)
                    if point:
                        px, py, pz = px + v[k, 0], py + v[k, 1], pz + v[k, 2]
                    px, py, pz = _rotate(square[k, 0], square[k, 1], square[k, 2], px, py, pz)
                px, py, pz = px + dx + ox, py + dy + oy, pz + dz + oz
            else:
                px, py, pz = px - dx - ox, py - dy - oy, pz - dz - oz
                if errors:
                    px, py, pz = _unrotate(square[k, 0], square[k, 1], square[k, 2], square[k, 3], px, py, pz)
                    if point:
                        px, py, pz = px - v[k, 0], py - v[k, 1], pz - v[k, 2]
                    px, py, pz = _unrotate(v[k, 3], v[k, 4], v[k, 5], v[k, 6], px, py, pz)
                px, py, pz = _turn(axis[k], c, -s, px, py, pz)
                if errors:
                    px, py, pz = _rotate(square[k, 0], square[k, 1], square[k, 2], px, py, pz)
                px, py, pz = px + dx, py + dy, pz + dz
            continue
        along = axis[k]
        if forward[k]:
            if errors:
                px, py, pz = _rotate(v[k, 3], v[k, 4], v[k, 5], px, py, pz)
                if point:
                    px, py, pz = px + v[k, 0], py + v[k, 1], pz + v[k, 2]
            if point:
                px, py, pz = px + origin[k, 0], py + origin[k, 1], pz + origin[k, 2]
                if along == 0:
                    px += q[k]
                elif along == 1:
                    py += q[k]
                else:
                    pz += q[k]
            if errors:
                px, py, pz = _rotate(square[k, 0], square[k, 1], square[k, 2], px, py, pz)
        else:
            if errors:
                px, py, pz = _unrotate(square[k, 0], square[k, 1], square[k, 2], square[k, 3], px, py, pz)
            if point:
                px, py, pz = px - origin[k, 0], py - origin[k, 1], pz - origin[k, 2]
                if along == 0:
                    px -= q[k]
                elif along == 1:
                    py -= q[k]
                else:
                    pz -= q[k]
                if errors:
                    px, py, pz = px - v[k, 0], py - v[k, 1], pz - v[k, 2]
            if errors:
                px, py, pz = _unrotate(v[k, 3], v[k, 4], v[k, 5], v[k, 6], px, py, pz)
    return px, py, pz


@njit(cache=True, nogil=True)
def _carry_points(positions, motions, given, rotary, axis, forward, origin, square, offset, first_row, rows,
                  start, end, inverse_step, first_bin, inverse_bin, bins, periodic, table_position, table_values, table_slopes, tool, mode, turn,
                  begin, stop, out):
    """Points ``begin`` to ``stop``: interpolate every link's motions, carry, write ``out`` rows.

    ``positions`` (L, stop - begin) and ``motions`` (L, 6, stop - begin) hold the chunk's points;
    ``motions[k]`` is read only for a link with ``given[k]``."""
    links = rotary.size
    q = np.empty(links)
    v = np.empty((links, 7))  # the six motions and _scale of the three rotations
    cs = np.empty((links, 2))
    for i in range(begin, stop):
        for k in range(links):
            qk = positions[k, i - begin]
            q[k] = qk
            if rotary[k]:
                cs[k, 0] = math.cos(qk)
                cs[k, 1] = math.sin(qk)
            if given[k]:
                for r in range(6):
                    v[k, r] = motions[k, r, i - begin]
                if not forward[k]:
                    v[k, 6] = _scale(v[k, 3], v[k, 4], v[k, 5])
                continue
            # the table's segment and arithmetic (ErrorTable.evaluate), held at the ends, wrapped for a
            # periodic table; written out here: called as a function of these many arrays, numba's code
            # for it took five times as long (0.65 against 0.14 us a point of XFYZ)
            x = qk
            if periodic[k]:
                d = x - start[k]
                if d < 0.0 or d >= turn:  # the remainder of a value already in [0, turn) is itself
                    d = d % turn
                x = start[k] + d
            if x < start[k]:
                x = start[k]
            elif x > end[k]:
                x = end[k]
            base = first_row[k]
            last = rows[k] - 2
            if inverse_step[k] > 0.0:
                j = int((x - start[k]) * inverse_step[k])
                if j > last:
                    j = last
            elif first_bin[k] >= 0:  # the bin's first row, or the next one when x is past it
                j = bins[first_bin[k] + int((x - start[k]) * inverse_bin[k])]
                if x >= table_position[base + j + 1]:
                    j += 1
                if j > last:
                    j = last
            else:  # the last row at or below x, as searchsorted(side="right") - 1
                lo, hi = 0, rows[k]
                while lo < hi:
                    mid = (lo + hi) // 2
                    if table_position[base + mid] <= x:
                        lo = mid + 1
                    else:
                        hi = mid
                j = min(max(lo - 1, 0), last)
            row = base + j
            dq = x - table_position[row]
            for r in range(6):
                v[k, r] = table_values[row, r] + table_slopes[row, r] * dq
            if not forward[k]:  # only an inverted link undoes its rotations
                v[k, 6] = _scale(v[k, 3], v[k, 4], v[k, 5])
        ax, ay, az = _carry(tool[0], tool[1], tool[2], True, True, q, v, cs, rotary, axis, forward, origin, square, offset)
        nx, ny, nz = _carry(tool[0], tool[1], tool[2], False, True, q, v, cs, rotary, axis, forward, origin, square, offset)
        out[i, 0], out[i, 1], out[i, 2] = ax - nx, ay - ny, az - nz
        if mode == POSE:
            # the turn of the tool direction t about the nominal frame's x and y axes: x · (z × t) and
            # y · (z × t), which for the right-handed orthonormal (x, y, z) are -(y · t) and x · t
            tx, ty, tz = _carry(0.0, 0.0, 1.0, True, False, q, v, cs, rotary, axis, forward, origin, square, offset)
            xx, xy, xz = _carry(1.0, 0.0, 0.0, False, False, q, v, cs, rotary, axis, forward, origin, square, offset)
            yx, yy, yz = _carry(0.0, 1.0, 0.0, False, False, q, v, cs, rotary, axis, forward, origin, square, offset)
            out[i, 3] = -(yx * tx + yy * ty + yz * tz)
            out[i, 4] = xx * tx + xy * ty + xz * tz
