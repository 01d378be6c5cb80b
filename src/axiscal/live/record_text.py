"""The live record's lines written in one compiled pass (numba): numbers as C's ``%.Nf``, ``%.Ng`` and ``%d`` print them.

The recorder writes a row of some 40 numbers for every frame, ten thousand times a second: in
Python each number costs a call of the float formatter (0.2-0.4 us), some 15-25 us a frame, the
largest part of the live loop's time. :func:`format_rows` writes the whole batch into one byte
buffer in a compiled function that holds no interpreter lock.

Each column has a kind: ``FIXED`` (``%.{digits}f``), ``GENERAL`` (``%.{digits}g``) or ``INTEGER``
(``%d``). The text is the one Python's ``%`` gives, except that a number whose digits are a tie
at the last one printed (or within a unit in the 16th significant digit of one) may end one unit
apart in that digit: the decimal digits are found in double precision, not from the exact binary
value. A value read back differs from Python's by at most that unit. NaN is written ``nan``,
infinities ``inf`` and ``-inf``. A column ``FIXED`` or ``INTEGER`` whose magnitude is 2**53 / 10**digits
or more (or 2**53) cannot be written this way: :func:`format_rows` returns None and the caller
formats the batch in Python.
"""

from __future__ import annotations

import math

import numpy as np
from numba import njit

__all__ = ["FIXED", "GENERAL", "INTEGER", "format_rows", "python_format"]

FIXED = 0
GENERAL = 1
INTEGER = 2
_CODES = {FIXED: "f", GENERAL: "g", INTEGER: "d"}
#: largest whole number a double holds exactly
_EXACT = 2.0**53


def _check_columns(kinds, digits, columns: int | None = None) -> tuple[np.ndarray, np.ndarray]:
    """``kinds`` and ``digits`` as int64 arrays of one length (``columns`` when given), of known kinds and 1-15 digits."""
    from axiscal.errors import AxiscalError

    try:
        kinds, digits = np.asarray(kinds, dtype=np.int64), np.asarray(digits, dtype=np.int64)
    except (TypeError, ValueError):
        raise AxiscalError("kinds and digits must be whole numbers, one per column") from None
    if kinds.ndim != 1 or digits.shape != kinds.shape or (columns is not None and kinds.size != columns):
        raise AxiscalError(f"kinds and digits must hold one whole number per column, not shapes {kinds.shape} and "
                           f"{digits.shape}")
    if not np.isin(kinds, (FIXED, GENERAL, INTEGER)).all() or ((digits < 1) | (digits > 15))[kinds != INTEGER].any():
        raise AxiscalError("kinds must be FIXED, GENERAL or INTEGER and digits 1 to 15")
    return kinds, digits


def python_format(kinds: np.ndarray, digits: np.ndarray) -> str:
    """The ``%`` format of one line for columns of these kinds and digits (what :func:`format_rows` matches).

    Parameters
    ----------
    kinds, digits : ndarray of int64, shape (M,)
        Kind (:data:`FIXED`, :data:`GENERAL`, :data:`INTEGER`) and digits of each column.

    Returns
    -------
    str
        E.g. ``"%.9f,%.15g,%d\\n"``.
    """
    kinds, digits = _check_columns(kinds, digits)
    return ",".join("%d" if kind == INTEGER else f"%.{int(d)}{_CODES[int(kind)]}" for kind, d in zip(kinds, digits)) + "\n"


@njit(cache=True, nogil=True)
def _put_digits(out, at, value, width):
    """Write the whole number ``value`` >= 0 with at least ``width`` digits (zero-padded); return the new end."""
    count = 1
    probe = value
    while probe >= 10:
        probe //= 10
        count += 1
    if count < width:
        count = width
    for k in range(count - 1, -1, -1):
        out[at + k] = 48 + value % 10
        value //= 10
    return at + count


@njit(cache=True, nogil=True)
def _put_text(out, at, text):
    for k in range(len(text)):
        out[at + k] = text[k]
    return at + len(text)


@njit(cache=True, nogil=True)
def _general(out, at, x, precision, nan_text, inf_text, digits, pow10):
    """``%.{precision}g`` of ``x``; return the new end."""
    if math.isnan(x):
        return _put_text(out, at, nan_text)
    if math.copysign(1.0, x) < 0:
        out[at] = 45  # '-'
        at += 1
        x = -x
    if math.isinf(x):
        return _put_text(out, at, inf_text)
    if x == 0.0:
        out[at] = 48
        return at + 1
    exponent = int(math.floor(math.log10(x)))
    top = np.int64(pow10[precision])
    mantissa = 0
    for _ in range(3):  # log10 may miss by one: the mantissa must have exactly `precision` digits
        shift = precision - 1 - exponent
        if shift > 300:  # near the subnormal range: scale in two steps
            scaled = (x * 1e300) * pow10[shift - 300]
        elif shift >= 0:
            scaled = x * pow10[shift]
        else:
            scaled = x / pow10[-shift]
        mantissa = int(np.rint(scaled))
        if mantissa >= top:
            exponent += 1
        elif mantissa < top // 10:
            exponent -= 1
        else:
            break
    if mantissa >= top:  # 9.99...95 rounded up to 10.0...0
        mantissa = top // 10
        exponent += 1
    for k in range(precision - 1, -1, -1):
        digits[k] = mantissa % 10
        mantissa //= 10
    last = precision - 1  # trailing zeros are not written (%g)
    while last > 0 and digits[last] == 0:
        last -= 1
    if -4 <= exponent < precision:
        if exponent >= 0:
            for k in range(exponent + 1):
                out[at] = 48 + digits[k]
                at += 1
            if last > exponent:
                out[at] = 46  # '.'
                at += 1
                for k in range(exponent + 1, last + 1):
                    out[at] = 48 + digits[k]
                    at += 1
        else:
            out[at] = 48
            out[at + 1] = 46
            at += 2
            for _ in range(-exponent - 1):
                out[at] = 48
                at += 1
            for k in range(last + 1):
                out[at] = 48 + digits[k]
                at += 1
        return at
    out[at] = 48 + digits[0]
    at += 1
    if last > 0:
        out[at] = 46
        at += 1
        for k in range(1, last + 1):
            out[at] = 48 + digits[k]
            at += 1
    out[at] = 101  # 'e'
    out[at + 1] = 45 if exponent < 0 else 43
    return _put_digits(out, at + 2, abs(exponent), 2)


@njit(cache=True, nogil=True)
def _fixed(out, at, x, decimals, nan_text, inf_text, pow10):
    """``%.{decimals}f`` of ``x`` (|x| * 10**decimals below 2**53); return the new end."""
    if math.isnan(x):
        return _put_text(out, at, nan_text)
    if math.copysign(1.0, x) < 0:
        out[at] = 45
        at += 1
        x = -x
    if math.isinf(x):
        return _put_text(out, at, inf_text)
    scale = np.int64(pow10[decimals])
    units = int(np.rint(x * pow10[decimals]))
    at = _put_digits(out, at, units // scale, 1)
    if decimals > 0:
        out[at] = 46
        at = _put_digits(out, at + 1, units % scale, decimals)
    return at


@njit(cache=True, nogil=True)
def _format_rows(table, kinds, digits, out, nan_text, inf_text, pow10):
    scratch = np.empty(20, np.int64)
    at = 0
    rows, columns = table.shape
    for i in range(rows):
        for j in range(columns):
            if j:
                out[at] = 44  # ','
                at += 1
            x = table[i, j]
            kind = kinds[j]
            if kind == 1:
                at = _general(out, at, x, digits[j], nan_text, inf_text, scratch, pow10)
            elif kind == 0:
                at = _fixed(out, at, x, digits[j], nan_text, inf_text, pow10)
            elif math.isnan(x) or math.isinf(x):
                at = _general(out, at, x, 1, nan_text, inf_text, scratch, pow10)
            else:
                value = int(x)
                if value < 0:
                    out[at] = 45
                    at += 1
                    value = -value
                at = _put_digits(out, at, value, 1)
        out[at] = 10  # '\n'
        at += 1
    return at


_NAN = np.frombuffer(b"nan", dtype=np.uint8)
_INF = np.frombuffer(b"inf", dtype=np.uint8)
#: 10**k, k = 0 ... 308, each the double nearest to it
_POW10 = np.array([float(f"1e{k}") for k in range(309)])


def format_rows(table: np.ndarray, kinds: np.ndarray, digits: np.ndarray) -> bytes | None:
    """The CSV lines of ``table``, each column as its kind and digits say; None when a value cannot be written so.

    Parameters
    ----------
    table : ndarray of float64, shape (N, M)
        One row per line.
    kinds, digits : ndarray of int64, shape (M,)
        Kind and digits of each column (digits 1-15, what a double holds; ignored for
        :data:`INTEGER`).

    Returns
    -------
    bytes or None
        ASCII lines, each ended by ``\\n``; None when a ``FIXED`` or ``INTEGER`` value is too
        large to be written exactly here (then format with :func:`python_format`).
    """
    from axiscal.errors import AxiscalError

    try:
        table = np.ascontiguousarray(table, dtype=np.float64)
    except (TypeError, ValueError):
        raise AxiscalError("table must be numbers, one row per line") from None
    if table.ndim != 2:
        raise AxiscalError(f"table must be two-dimensional (rows, columns), not of shape {table.shape}")
    kinds, digits = _check_columns(kinds, digits, table.shape[1])
    if not table.size:
        return b"\n" * table.shape[0]
    exact = kinds != GENERAL
    if exact.any():
        bound = np.where(kinds[exact] == FIXED, _EXACT / 10.0 ** digits[exact], _EXACT)
        magnitude = np.abs(table[:, exact])
        if (magnitude[np.isfinite(magnitude)] >= np.broadcast_to(bound, magnitude.shape)[np.isfinite(magnitude)]).any():
            return None
    # widest cell: sign, 17 digits, point, 'e-308'; or a fixed value below 2**53 with its decimals
    width = int(np.max(np.where(kinds == FIXED, 18 + digits, 26))) + 1
    out = np.empty(table.shape[0] * (table.shape[1] * width + 1), dtype=np.uint8)
    end = _format_rows(table, kinds, digits, out, _NAN, _INF, _POW10)
    return out[:end].tobytes()
