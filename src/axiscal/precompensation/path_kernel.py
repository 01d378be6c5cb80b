"""One compiled pass (numba) laying the samples of the path checks: points along each piece's command and programmed chord.

Sample ``s`` of ``n`` along a piece is at ``t = (s + 1) / n``, the command at ``c0 + t * (c1 - c0)`` and
the programmed point at ``p0 + t * (p1 - p0)``: the arithmetic of
:func:`axiscal.precompensation.path.settle` in NumPy, one rounding each, in the same order (numba
fuses no multiply-add without fastmath), so the samples are the same to the bit. Cached on disk.
"""

from __future__ import annotations

import numpy as np
from numba import njit

#: nothing public: the entry is :func:`axiscal.precompensation.path.settle`
__all__: list[str] = []


@njit(cache=True, nogil=True)
def samples(start, out, p0, p1, idx, counts):  # pragma: no cover - compiled; tested through settle
    """The commands and programmed points at the samples of pieces ``idx`` (``counts`` each), in order."""
    total = 0
    for i in range(idx.size):
        total += counts[i]
    k = p1.shape[1]
    c_t = np.empty((total, k))
    p_t = np.empty((total, k))
    r = 0
    for i in range(idx.size):
        o = idx[i]
        n = counts[i]
        for s in range(n):
            t = (s + 1) / n
            for j in range(k):
                c0 = start[o, j]
                c_t[r, j] = c0 + t * (out[o, j] - c0)
                q0 = p0[o, j]
                p_t[r, j] = q0 + t * (p1[o, j] - q0)
            r += 1
    return c_t, p_t
