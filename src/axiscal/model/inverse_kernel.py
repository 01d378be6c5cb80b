"""The model's inverse carried point by point in one compiled pass (numba): the fast core of ``command_for``.

The same fixed-point iteration as :meth:`axiscal.model.machine.Machine.command_for` on a chain of
linear axes, done per point inside one compiled loop instead of one NumPy pass over all points per
iteration: start from the nominal inverse ``c = s (target - nominal_point(0))`` (``s`` +1 for a
tool-side axis, -1 for a workpiece-side one), then repeat ``c <- c - s * miss`` along each axis,
where ``miss = actual_point(c) - target`` comes from the forward chain of
:mod:`axiscal.model.chain_kernel` (the same table lookup and the same composition), until the miss
along every axis is within the tolerance. A point whose command leaves an error table (that neither
holds its ends nor is periodic) stops there and is reported with the axis; a point that does not
converge is reported with its miss. Large inputs are split into chunks run on threads (the loop
releases the GIL). The model uses it from 65536 points on, for chains of linear axes whose tables
interpolate linearly; other chains and fewer points take the NumPy iteration.
"""

from __future__ import annotations

import os
from concurrent.futures import ThreadPoolExecutor

import numpy as np
from numba import njit

from axiscal.model.chain_kernel import CHUNK, PackedChain, _carry, _scale
from axiscal.model.tables import _TURN
from axiscal.units import LENGTH_UNITS, MM

#: nothing public: the entry is :meth:`axiscal.model.Machine.command_for`
__all__: list[str] = []

#: status of a point: converged, a command outside an error table, no convergence
DONE, OUTSIDE, STUCK = 0, 1, 2


def solve(chain: PackedChain, target_m: np.ndarray, sign: dict, tool_m, workpiece_m, start_m, tolerance_m: float,
          max_iterations: int, *, order) -> tuple[dict[str, np.ndarray], int | None, str]:
    """:meth:`axiscal.model.Machine._solve` compiled: (commands by letter in ``order``, index of the
    first point whose command left a table, or of the worst that did not converge, or None; why)."""
    rows, status, link, miss = invert_chain(chain, target_m, np.array([sign[k] for k in chain.letters]), tool_m,
                                            workpiece_m, start_m, tolerance_m, max_iterations)
    packed = {k: rows[j] for j, k in enumerate(chain.letters)}
    command = {k: packed[k] for k in order}
    outside = np.flatnonzero(status == OUTSIDE)
    if outside.size:
        k = int(outside[0])
        letter = chain.letters[link[k]]
        table = chain.tables[link[k]]
        return command, k, (f"needs {letter} = {command[letter][k] / MM:.6g} mm, outside the error table of axis "
                            f"{letter} ({table.start_m / MM:.6g} to {table.end_m / MM:.6g} mm)")
    if np.any(status == STUCK):
        worst = int(np.argmax(np.where(status == STUCK, miss, -1.0)))
        return command, worst, f"inverse kinematics did not converge (miss {miss[worst] / LENGTH_UNITS['nm']:.3g} nm)"
    return command, None, ""


def invert_chain(chain: PackedChain, target_m: np.ndarray, sign: np.ndarray, tool_m, workpiece_m, start_m: np.ndarray,
                 tolerance_m: float, max_iterations: int, *, workers: int | None = None):
    """Commands of every link that put the tool point on ``target_m``, per point, on threads.

    Parameters
    ----------
    chain : PackedChain
        From :func:`axiscal.model.chain_kernel.pack_chain`, linear links with linear tables only.
    target_m : ndarray, shape (N, 3)
        Checked finite targets relative to the workpiece point, workpiece frame, m.
    sign : ndarray, shape (L,)
        +1 for a tool-side link, -1 for a workpiece-side one, in the chain's link order.
    tool_m, workpiece_m : ndarray, shape (3,)
        The functional point and the workpiece point, m.
    start_m : ndarray, shape (3,)
        ``nominal_point`` at all axes zero, m.
    tolerance_m : float
        Largest miss accepted along each axis, m.
    max_iterations : int
        Iterations before a point is given up.
    workers : int, optional
        Threads (default: the number of cores).

    Returns
    -------
    command : ndarray, shape (L, N)
        The command of every link (m), where the point stopped for one that failed.
    status : ndarray of int64, shape (N,)
        :data:`DONE`, :data:`OUTSIDE` or :data:`STUCK`.
    link : ndarray of int64, shape (N,)
        For :data:`OUTSIDE`, the link whose command left its table.
    miss : ndarray, shape (N,)
        The last miss along the axes, m.
    """
    n = target_m.shape[0]
    links = chain.rotary.size
    command = np.empty((links, n))
    status = np.empty(n, dtype=np.int64)
    link = np.full(n, -1, dtype=np.int64)
    miss = np.empty(n)
    target = np.ascontiguousarray(target_m, dtype=np.float64)
    check = np.array([0 if (t.hold_ends or t.periodic) else 1 for t in chain.tables], dtype=np.int64)
    tool = np.ascontiguousarray(tool_m, dtype=np.float64)
    workpiece = np.ascontiguousarray(workpiece_m, dtype=np.float64)
    origin = np.ascontiguousarray(start_m, dtype=np.float64)
    sign = np.ascontiguousarray(sign, dtype=np.float64)

    def fill(begin: int) -> None:
        _invert_points(target, sign, check, chain.rotary, chain.axis, chain.forward, chain.origin, chain.square,
                       chain.offset, chain.first_row, chain.rows, chain.start, chain.end, chain.inverse_step,
                       chain.first_bin, chain.inverse_bin, chain.bins, chain.periodic, chain.position, chain.values,
                       chain.slopes, tool, workpiece, origin, float(tolerance_m), int(max_iterations), _TURN, begin,
                       min(begin + CHUNK, n), command, status, link, miss)

    workers = workers or os.cpu_count() or 1
    if workers == 1 or n <= CHUNK:
        for begin in range(0, n, CHUNK):
            fill(begin)
    else:
        with ThreadPoolExecutor(min(workers, -(-n // CHUNK))) as pool:
            list(pool.map(fill, range(0, n, CHUNK)))
    return command, status, link, miss


@njit(cache=True, nogil=True)
def _invert_points(target, sign, check, rotary, axis, forward, origin, square, offset, first_row, rows, start, end,
                   inverse_step, first_bin, inverse_bin, bins, periodic, table_position, table_values, table_slopes,
                   tool, workpiece, zero_point, tolerance, max_iterations, turn, begin, stop, command, status, link,
                   miss):
    """Points ``begin`` to ``stop`` of :func:`invert_chain`."""
    links = rotary.size
    q = np.empty(links)
    v = np.empty((links, 7))
    cs = np.zeros((links, 2))
    m = np.empty(3)
    for i in range(begin, stop):
        for k in range(links):
            q[k] = sign[k] * (target[i, axis[k]] - zero_point[axis[k]])
        state = STUCK
        worst = 0.0
        for _ in range(max_iterations):
            outside = -1
            for k in range(links):
                if check[k] and not (start[k] <= q[k] <= end[k]):
                    outside = k
                    break
            if outside >= 0:
                state = OUTSIDE
                link[i] = outside
                break
            for k in range(links):
                # the table's segment and arithmetic, as chain_kernel._carry_points has them (written out:
                # called as a function of these many arrays, numba's code took five times as long)
                x = q[k]
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
                if not forward[k]:
                    v[k, 6] = _scale(v[k, 3], v[k, 4], v[k, 5])
            ax, ay, az = _carry(tool[0], tool[1], tool[2], True, True, q, v, cs, rotary, axis, forward, origin, square,
                                offset)
            m[0] = ax - workpiece[0] - target[i, 0]
            m[1] = ay - workpiece[1] - target[i, 1]
            m[2] = az - workpiece[2] - target[i, 2]
            worst = 0.0
            for k in range(links):
                worst = max(worst, abs(m[axis[k]]))
            if worst <= tolerance:
                state = DONE
                break
            for k in range(links):
                q[k] -= sign[k] * m[axis[k]]
        for k in range(links):
            command[k, i] = q[k]
        status[i] = state
        miss[i] = worst
