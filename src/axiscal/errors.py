"""The one exception type of the project.

Every mistake a user can make (a malformed file, a unit we do not know, a point outside a table)
raises :class:`AxiscalError`. The command line turns it into one line naming the file, the line
and the problem, and exits with status 2.
"""

from __future__ import annotations

import re
from decimal import Decimal
from pathlib import Path

__all__ = ["AxiscalError", "MAX_PLAIN_DIGITS", "exponent_form"]

#: the most digits a number in a message shows before its decimal point; longer ones (a count or a
#: length worked out from an input of 1e300) are shown in exponent form
MAX_PLAIN_DIGITS = 15

# a number standing alone (not part of a word, a file name or another number's decimals) whose
# whole part is longer than MAX_PLAIN_DIGITS
_LONG_NUMBER = re.compile(r"(?<![\w.])\d{%d,}(?:\.\d+)?(?![\w.])" % (MAX_PLAIN_DIGITS + 1))


def exponent_form(text: str) -> str:
    """``text`` with every number of more than :data:`MAX_PLAIN_DIGITS` whole digits in exponent form.

    A message is worked out from what the user gave; an input of 1e300 turned into a count or a
    length printed with ``{:.3f}`` or as an integer would spell out 300 digits. Every
    :class:`AxiscalError` passes its message through here, so no message does.

    Parameters
    ----------
    text : str
        The message.

    Returns
    -------
    str
        The same text, each such number with 6 significant digits (``1.00000e+300`` -> ``1e+300``).

    Examples
    --------
    >>> exponent_form("1" + "0" * 300 + ".000 mm is beyond 5 mm")
    '1e+300 mm is beyond 5 mm'
    >>> exponent_form("point 12 of run_20261126123456789.csv at 1234.5 mm")
    'point 12 of run_20261126123456789.csv at 1234.5 mm'
    """
    return _LONG_NUMBER.sub(_exponent, text)


def _exponent(found: re.Match) -> str:
    """``1.23457e+297`` for a long number (Decimal: it may be beyond a float), trailing zeros dropped as
    Python's ``{:g}`` drops them."""
    mantissa, _, power = format(Decimal(found.group(0)), ".5e").partition("e")
    return f"{mantissa.rstrip('0').rstrip('.')}e{power}"



class AxiscalError(ValueError):
    """A user-facing error: bad input, or a request the method cannot honour.

    Parameters
    ----------
    message : str
        What is wrong and, where it helps, what was expected.
    path : str or Path, optional
        The file the problem is in.
    line : int, optional
        1-based line number in that file (the header of a CSV is line 1).
    """

    def __init__(self, message: str, *, path: str | Path | None = None, line: int | None = None):
        message = exponent_form(message) if isinstance(message, str) else message
        super().__init__(message)
        self.message = message
        self.path = None if path is None else str(path)
        self.line = line

    def located(self, *, path: str | Path | None = None, line: int | None = None) -> "AxiscalError":
        """Return the same error with a file (and line) filled in where it was not yet known."""
        return AxiscalError(
            self.message,
            path=self.path if self.path is not None else path,
            line=self.line if self.line is not None else line,
        )

    def __str__(self) -> str:
        where = ""
        if self.path is not None:
            where = self.path + (f":{self.line}" if self.line is not None else "") + ": "
        elif self.line is not None:
            where = f"line {self.line}: "
        return where + self.message
