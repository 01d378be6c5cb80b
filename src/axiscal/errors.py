"""The one exception type of the project.

Every mistake a user can make (a malformed file, a unit we do not know, a point outside a table)
raises :class:`AxiscalError`. The command line turns it into one line naming the file, the line
and the problem, and exits with status 2.
"""

from __future__ import annotations

from pathlib import Path

__all__ = ["AxiscalError"]


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
