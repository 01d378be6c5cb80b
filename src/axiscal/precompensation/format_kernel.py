"""One compiled pass (numba) writing the pieces' text: the motion word, then each axis's number, to the byte.

A number is written from its count of the last decimal written (an integer held exactly in a
double, below 10^15): a minus for a negative count, the whole digits (at least one), the point and
``places`` decimals, as ``f"{count / 10**places:.{places}f}"`` writes it for such counts, never
``-0``. The text of :func:`axiscal.precompensation.text._piece_rows`; cached on disk by numba.
"""

from __future__ import annotations

import numpy as np
from numba import njit

#: nothing public: the entry is :func:`axiscal.precompensation.text.program_lines`
__all__: list[str] = []


@njit(cache=True, nogil=True)
def _write_number(out, at, count, places):  # pragma: no cover - compiled; tested through program_lines
    """Write ``count / 10**places`` at ``out[at]``; return the position after it."""
    value = np.int64(count)
    if value < 0:
        out[at] = 45
        at += 1
        value = -value
    digits = 0
    probe = value
    while True:  # the number of digits of value, at least places + 1
        digits += 1
        probe //= 10
        if probe == 0 and digits > places:
            break
    # digits of value from the last, the point before the last `places`
    total = digits + (1 if places > 0 else 0)
    end = at + total
    k = end - 1
    for d in range(digits):
        if places > 0 and d == places:
            out[k] = 46
            k -= 1
        out[k] = 48 + value % 10
        value //= 10
        k -= 1
    return end


@njit(cache=True, nogil=True)
def piece_text(word_code, words, word_length, letters, counts, places, e_show, e_counts):  # pragma: no cover
    """The rows' text, each ended by a LF, as bytes: ``words[word_code[i], :word_length[...]]``, then
    `` <letter><number>`` per column of ``counts`` (``places[i]`` decimals), then `` E<number>`` with 5
    decimals where ``e_show[i]``."""
    n, k = counts.shape
    size = 0
    widest = 0
    for w in range(word_length.size):
        widest = max(widest, word_length[w])
    out = np.empty(n * (widest + 1 + k * 24 + 24), dtype=np.uint8)
    at = 0
    for i in range(n):
        w = word_code[i]
        for c in range(word_length[w]):
            out[at] = words[w, c]
            at += 1
        for j in range(k):
            out[at] = 32
            out[at + 1] = letters[j]
            at = _write_number(out, at + 2, counts[i, j], places[i])
        if e_show[i]:
            out[at] = 32
            out[at + 1] = 69
            at = _write_number(out, at + 2, e_counts[i], 5)
        out[at] = 10
        at += 1
    size = at
    return out[:size]
