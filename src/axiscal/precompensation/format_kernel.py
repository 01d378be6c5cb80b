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
def _write_number(out, at, count, places, pow10):  # pragma: no cover - compiled; tested through program_lines
    """Write ``count / 10**places`` at ``out[at]``; return the position after it."""
    value = np.uint64(np.int64(count)) if count >= 0 else np.uint64(-np.int64(count))
    if count < 0 and value != 0:
        out[at] = 45
        at += 1
    digits = places + 1  # at least one whole digit
    while digits < 20 and value >= pow10[digits]:
        digits += 1
    end = at + digits + (1 if places > 0 else 0)
    k = end - 1
    ten = np.uint64(10)
    zero = np.uint64(48)
    for d in range(digits):
        if places > 0 and d == places:
            out[k] = 46
            k -= 1
        q = value // ten
        out[k] = np.uint8(zero + (value - q * ten))
        value = q
        k -= 1
    return end


@njit(cache=True, nogil=True)
def piece_text(word_code, words, word_length, letters, counts, places, e_show, e_counts, prefix, prefix_at,
               prefix_length):  # pragma: no cover
    """The rows' text, each ended by a LF, as bytes: ``N<prefix[prefix_at[i]:][:prefix_length[i]]> `` where
    ``prefix_at[i] >= 0`` (a block number), ``words[word_code[i], :word_length[...]]``, then
    `` <letter><number>`` per column of ``counts`` (``places[i]`` decimals), then `` E<number>`` with 5
    decimals where ``e_show[i]``."""
    n, k = counts.shape
    widest = 0
    for w in range(word_length.size):
        widest = max(widest, word_length[w])
    extra = 0
    for i in range(n):
        if prefix_at[i] >= 0:
            extra += prefix_length[i] + 2
    out = np.empty(n * (widest + 1 + k * 24 + 24) + extra, dtype=np.uint8)
    pow10 = np.empty(20, dtype=np.uint64)
    pow10[0] = 1
    for d in range(1, 20):
        pow10[d] = pow10[d - 1] * np.uint64(10)
    at = 0
    for i in range(n):
        if prefix_at[i] >= 0:
            out[at] = 78
            at += 1
            for c in range(prefix_length[i]):
                out[at] = prefix[prefix_at[i] + c]
                at += 1
            out[at] = 32
            at += 1
        w = word_code[i]
        for c in range(word_length[w]):
            out[at] = words[w, c]
            at += 1
        for j in range(k):
            out[at] = 32
            out[at + 1] = letters[j]
            at = _write_number(out, at + 2, counts[i, j], places[i], pow10)
        if e_show[i]:
            out[at] = 32
            out[at + 1] = 69
            at = _write_number(out, at + 2, e_counts[i], 5, pow10)
        out[at] = 10
        at += 1
    return out[:at]
