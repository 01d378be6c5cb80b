"""A cell of a CSV file: what it is stripped of, the number grammar, the largest magnitude, how an error quotes it.

The grammar of docs/formats.md ("What a reader accepts"): a number is
``[+-]digits[.digits][e[+-]digits]``, with a decimal comma allowed when ``;`` or tab separates the
cells; a cell is stripped of ASCII blanks (space, tab, vertical tab, form feed) only. Both readers
of :mod:`axiscal.io.tabular` (the plain-number path and the strict one) and :class:`CsvTable` hold
cells to it.
"""

from __future__ import annotations

import math
import re

import numpy as np

__all__ = ["BLANKS", "MAX_MAGNITUDE", "parse_number"]

#: the largest magnitude a numeric cell may hold, in its column's unit (1e12 mm is 1e9 m)
MAX_MAGNITUDE = 1e12

#: what a cell is stripped of: ASCII white space within a line (space, tab, vertical tab, form
#: feed), not the other control characters and separators ``str.strip`` also removes (a cell
#: "\x1d.5" is not the number 0.5)
BLANKS = " \t\v\f"

#: a number as a file may spell it: optional sign, decimal digits with an optional point, optional exponent
# (the digits before and after the point are separate groups, so a long cell that is not a number
# is refused in linear time: "[0-9]+\.?[0-9]*" would try every split of a run of digits)
NUMBER = re.compile(r"[+-]?(?:[0-9]+(?:\.[0-9]*)?|\.[0-9]+)(?:[eE][+-]?[0-9]+)?")
NUMBER_COMMA = re.compile(r"[+-]?(?:[0-9]+(?:[.,][0-9]*)?|[.,][0-9]+)(?:[eE][+-]?[0-9]+)?")
NOT_FINITE = re.compile(r"[+-]?(?:nan|inf|infinity)", re.IGNORECASE)
_SHOWN = 40  # characters of a cell quoted in an error message


def numbers(cells: np.ndarray, *, decimal_comma: bool) -> tuple[np.ndarray, np.ndarray]:
    """Which stripped cells are numbers by the grammar, and their values (NaN for the others).

    Parameters
    ----------
    cells : numpy.ndarray of str (object), shape (n,)
    decimal_comma : bool, keyword-only
        Whether a decimal comma is accepted.

    Returns
    -------
    number : numpy.ndarray of bool, shape (n,)
    values : numpy.ndarray of float, shape (n,)
        Not yet checked for magnitude (a long run of digits may give inf).
    """
    match = (NUMBER_COMMA if decimal_comma else NUMBER).fullmatch
    number = np.fromiter((match(cell) is not None for cell in cells), dtype=bool, count=len(cells))
    values = np.full(len(cells), np.nan)
    texts = cells[number]
    if decimal_comma:
        texts = [cell.replace(",", ".") for cell in texts]
    values[number] = np.fromiter((float(cell) for cell in texts), dtype=np.float64, count=len(texts))
    return number, values


def beyond(value: float) -> str:
    """Why a number that parsed is refused: not finite, or beyond any physical magnitude."""
    if not np.isfinite(value):
        return "is not a finite number"
    return f"is beyond any physical value (more than {MAX_MAGNITUDE:g} in the column's unit)"


def shown(cell: str) -> str:
    """The cell as an error message quotes it: shortened, control characters escaped (``\\x1d``)."""
    cell = cell if len(cell) <= _SHOWN else cell[: _SHOWN - 3] + "..."
    return cell if cell.isprintable() else cell.encode("unicode_escape").decode("ascii")


def parse_number(text: str) -> float | None:
    """A number as a file spells it (the grammar of :meth:`CsvTable.numeric`), or None.

    Plain decimals with an optional sign and exponent, surrounding blanks allowed; not ``1_000``,
    full-width digits, ``nan``, ``inf`` or a value beyond :data:`MAX_MAGNITUDE`, which Python's
    ``float()`` would take.

    Parameters
    ----------
    text : str

    Returns
    -------
    float or None
        None when the text is not such a number.

    Examples
    --------
    >>> parse_number(" 1.5e3 "), parse_number("1_000"), parse_number("inf")
    (1500.0, None, None)
    """
    cell = text.strip(BLANKS)
    if not NUMBER.fullmatch(cell):
        return None
    value = float(cell)
    return value if math.isfinite(value) and abs(value) <= MAX_MAGNITUDE else None
