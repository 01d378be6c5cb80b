"""The CSV reader's fast path: a file of plain numbers handed whole to pandas' parser, then checked column by column.

Most files axiscal reads are a header and rows of numbers. For those, the strict reading of
:mod:`axiscal.io.strict_csv` (every physical line located, every cell matched against the number
grammar) gives the same table as pandas' C parser reading the file by its path, which splits a
large file across threads. Only the file's head is read here: the lines above the data must hold
no NUL byte, no quote and no line ended by a lone CR, and the header must be UTF-8. The grammar
is then checked on the parsed columns instead of the text: every column must come out numeric,
finite and within :data:`~axiscal.io.cells.MAX_MAGNITUDE`. With no quote, no escape, no comment
character and blank lines kept, pandas makes exactly one row of each physical line of the data
(ended by LF, CRLF or a lone CR, as an editor counts them), so row k is line
``header_line + 1 + k``; a blank, comment, short or long line, a cell holding text, a NUL, a
quote or a byte that is not ASCII, or an odd number, leaves a column that is not all plain
numbers (or fails the parse), and :func:`read_plain` then answers None: the strict reader reads
the file and names the line of what is wrong. A row with a trailing empty cell, which pandas drops
silently, shows in the count of delimiters (:func:`count_byte`), taken over the same mapped pages
the parse has just read.
"""

from __future__ import annotations

import csv
import mmap
import os
import warnings
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from axiscal.errors import AxiscalError
from axiscal.io.lines import Lines

#: nothing public: the entry is :func:`axiscal.io.read_csv`, which tries this path first
__all__: list[str] = []

#: bytes of the file's start searched for the header (a header further down takes the strict reader)
HEAD = 1 << 16
#: bytes counted at a time by :func:`count_byte`
_BLOCK = 1 << 16


@dataclass(frozen=True)
class PlainCsv:
    """A file of plain numbers as pandas parsed it.

    Parameters
    ----------
    header : list of str
        The header's cells, stripped (not yet checked for empty or repeated names).
    header_line : int
        The 1-based line of the header.
    delimiter : str
        ``,``, ``;`` or tab.
    frame : pandas.DataFrame
        One numeric column per header cell (named 0, 1, ...), one row per line after the header,
        every value finite and within the magnitude limit.
    body_start : int
        Where the data lines start in the file, for reading a column again as text.
    """

    header: list[str]
    header_line: int
    delimiter: str
    frame: object
    body_start: int


def stamp(path: Path) -> tuple[int, int, int]:
    """Size, modification time and inode of a file: a change means it was rewritten."""
    found = os.stat(path)
    return found.st_size, found.st_mtime_ns, found.st_ino


def pandas_options(width: int, delimiter: str, decimal_comma: bool) -> dict:
    """The options of ``pandas.read_csv`` for data rows of ``width`` cells with no header line."""
    return dict(
        sep=delimiter,
        header=None,
        names=list(range(width)),
        index_col=False,
        na_filter=False,
        quoting=csv.QUOTE_NONE,
        skip_blank_lines=False,
        decimal="," if decimal_comma else ".",
        engine="c",
        encoding="utf-8",
    )


def read_plain(head: bytes, file: Path, file_stamp: tuple, max_magnitude: float) -> PlainCsv | None:
    """The file's header and its numeric columns, or None when it is not a file of plain numbers.

    Parameters
    ----------
    head : bytes
        The file's first :data:`HEAD` bytes (all of it when shorter), a byte-order mark included.
    file : Path
        The file, which pandas reads by its path (in threads, for a large file).
    file_stamp : tuple
        :func:`stamp` of the file before ``head`` was read: pandas' columns are used only when the
        file is still the one read.
    max_magnitude : float
        The largest magnitude a cell may hold.

    Returns
    -------
    PlainCsv or None
        None when anything is not plain (see the module): the caller then reads the file strictly.
    """
    bom = 3 if head.startswith(b"\xef\xbb\xbf") else 0
    lines = Lines(head[bom:])
    kept = lines.content()
    # the first data line must start within the head, and end there when the head is cut (so the
    # header's line end, CRLF included, is whole)
    last = len(lines) - (2 if len(head) < file_stamp[0] else 1)
    if len(kept) == 0 or kept[0] >= last:
        return None
    first = int(kept[0])
    body_start = bom + int(lines.starts[first + 1])
    above = head[:body_start]  # the lines pandas skips, and the header
    # a lone CR there: pandas would skip another number of lines than an editor counts
    if b"\0" in above or b'"' in above or b"\r" in above.replace(b"\r\n", b""):
        return None
    try:
        header_text = head[bom + int(lines.starts[first]) : bom + int(lines.ends[first])].decode("utf-8")
        above.decode("utf-8")
    except UnicodeDecodeError:
        return None
    delimiter = next((d for d in (",", ";", "\t") if d in header_text), ",")
    header = [cell.strip(" \t\v\f") for cell in header_text.split(delimiter)]
    import pandas as pd

    options = pandas_options(len(header), delimiter, delimiter != ",")
    try:
        with warnings.catch_warnings():
            warnings.simplefilter("error", pd.errors.ParserWarning)
            warnings.simplefilter("ignore", pd.errors.DtypeWarning)
            frame = pd.read_csv(file, skiprows=first + 1, **options)
    except (pd.errors.ParserError, pd.errors.ParserWarning, ValueError, OSError, UnicodeDecodeError):
        return None
    if len(frame) == 0:
        return None
    # pandas drops a row's trailing empty cells past the header's width ("1,2,"): the body holds one
    # delimiter fewer than cells in every row, or a row has more cells than the header
    try:
        delimiters = count_byte(file, body_start, delimiter)
    except (OSError, ValueError):
        return None
    if delimiters != len(frame) * (len(header) - 1) or stamp(file) != file_stamp:
        return None
    for i in range(len(header)):
        column = frame[i]
        if column.dtype.kind not in "iuf":
            return None
        values = column.to_numpy()
        # min and max carry a NaN through, so one comparison each refuses NaN, inf and the huge
        if not (-max_magnitude <= values.min() and values.max() <= max_magnitude):
            return None
    return PlainCsv(header, first + 1, delimiter, frame, body_start)


def count_byte(file: Path, start: int, byte: str) -> int:
    """How often the ASCII character ``byte`` occurs in ``file`` from offset ``start`` on.

    The file is mapped, not read (pandas has just mapped the same pages), and counted in blocks that
    stay in the processor's cache: a few milliseconds for 20 MB, against the tens that reading the
    bytes again and counting them took.
    """
    code = ord(byte)
    with open(file, "rb") as handle:
        size = os.fstat(handle.fileno()).st_size
        if size <= start:
            return 0
        with mmap.mmap(handle.fileno(), 0, access=mmap.ACCESS_READ) as mapped:
            data = np.frombuffer(mapped, dtype=np.uint8)
            hit = np.empty(_BLOCK, dtype=bool)
            found = 0
            for at in range(start, size, _BLOCK):
                piece = data[at : at + _BLOCK]
                np.equal(piece, code, out=hit[: len(piece)])
                found += int(np.count_nonzero(hit[: len(piece)]))
            del data, piece  # the map closes only when no array holds it
    return found


def read_body(file: Path, file_stamp: tuple, body_start: int) -> bytes:
    """The bytes of the data lines of a file read by :func:`read_plain`, read again.

    Raises
    ------
    AxiscalError
        When the file has changed since it was read.
    """
    data = file.read_bytes()
    if stamp(file) != file_stamp:
        raise AxiscalError("the file changed while it was being read", path=file)
    return data[body_start:]
