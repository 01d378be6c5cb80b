"""One compiled pass (numba) over a program's bytes: which lines are plain straight moves, and their numbers.

A plain line is, between blanks (space, tab): an optional block number (``N120``, where the
dialect has them), an optional G word numbered ``0``, ``1``, ``00`` or ``01``, axis words in the
dialect's order, each axis at most once, and an optional positive F word last; at least one axis
word. Where a number without a decimal point counts increments (FANUC), an axis word must have its
point to be plain. A number is ``[+-]?(\\d+\\.?\\d*|\\.\\d+)`` (ISO 6983's, as the block
reader's), its value its digits over a power of ten: both exact in a double for at most 15 digits
and 22 decimals, so the one rounding of the division gives the correctly rounded value ``float()``
gives. A line with a longer number is marked for ``float()`` instead. Lines end at LF, CRLF or CR,
as an editor counts them. The compiled function is cached on disk by numba.
"""

from __future__ import annotations

import numpy as np
from numba import njit

#: nothing public: the entry is :class:`axiscal.io.gcode.fast.BulkScan`
__all__: list[str] = []

_POW10 = np.array([10.0 ** k for k in range(23)])
#: what a line is found to be
PLAIN, OTHER, LONG = 0, 1, 2


@njit(cache=True, nogil=True)
def scan(data, rank, naxes, count, pow10, numbered, need_point):  # pragma: no cover - compiled; tested through BulkScan
    """Per line: status (PLAIN, OTHER, LONG), G number (-1 none), F value (NaN none), axis values
    (NaN where none, or too long) as written, in program units, which axis words the line has, and
    where the block number's digits start and stop in the line (0, 0: none).

    ``rank`` maps a byte to its word: 0 for G, 1..naxes for the axes in order, naxes + 1 for F,
    -1 for anything else. ``numbered``: a first word N is the block number; ``need_point``: an axis
    number without a decimal point makes the line another's.
    """
    status = np.full(count, OTHER, dtype=np.int8)
    g = np.full(count, -1, dtype=np.int8)
    feed = np.full(count, np.nan)
    value = np.full((count, naxes), np.nan)
    present = np.zeros((count, naxes), dtype=np.bool_)
    number_at = np.zeros((count, 2), dtype=np.int32)
    n = data.size
    pos = 0
    line = 0
    while pos < n and line < count:
        i = pos
        ok = True
        long = False
        last = -1
        axis_words = 0
        line_g = -1
        line_feed = np.nan
        n_from = 0
        n_to = 0
        first = True
        while True:
            # blanks, then a letter (or the line's end)
            while i < n and (data[i] == 32 or data[i] == 9):
                i += 1
            if i >= n or data[i] == 10 or data[i] == 13:
                break
            r = rank[data[i]]
            if first and numbered and (data[i] == 78 or data[i] == 110):
                r = -2
            elif r < 0 or r <= last:
                ok = False
                break
            if r >= 0:
                last = r
            first = False
            i += 1
            while i < n and (data[i] == 32 or data[i] == 9):
                i += 1
            # the number
            start = i
            negative = False
            if i < n and (data[i] == 43 or data[i] == 45):
                negative = data[i] == 45
                i += 1
            mantissa = 0
            digits = 0
            decimals = 0
            point = False
            while i < n:
                c = data[i]
                if 48 <= c <= 57:
                    if digits < 18:
                        mantissa = mantissa * 10 + (c - 48)
                    digits += 1
                    if point:
                        decimals += 1
                elif c == 46 and not point:
                    point = True
                else:
                    break
                i += 1
            if digits == 0:
                ok = False
                break
            if r == -2:
                number = 0.0
            elif digits > 15 or decimals > 22:
                number = np.nan
                if r == 0 or r == naxes + 1:
                    ok = False  # a G or F word that long: the block reader's
                    break
                long = True
            else:
                number = mantissa / pow10[decimals]
                if negative:
                    number = -number
            if r == -2:
                n_from = start - pos
                n_to = i - pos
            elif r == 0:
                if i - start > 2 or negative or point or data[start] == 43 or mantissa > 1:
                    ok = False
                    break
                line_g = mantissa
            elif r == naxes + 1:
                if not number > 0.0:
                    ok = False
                    break
                line_feed = number
            else:
                if need_point and not point:
                    ok = False
                    break
                value[line, r - 1] = number
                present[line, r - 1] = True
                axis_words += 1
        # to the line's end
        while i < n and data[i] != 10 and data[i] != 13:
            i += 1
        if ok and axis_words > 0:
            status[line] = LONG if long else PLAIN
            g[line] = line_g
            feed[line] = line_feed
            number_at[line, 0] = n_from
            number_at[line, 1] = n_to
        else:
            for j in range(naxes):
                value[line, j] = np.nan
                present[line, j] = False
        if i < n and data[i] == 13 and i + 1 < n and data[i + 1] == 10:
            i += 2
        elif i < n:
            i += 1
        pos = i
        line += 1
    return status, g, feed, value, present, number_at
