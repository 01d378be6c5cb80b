"""The CSV reader's strict path: every physical line located, every row's cells counted, quoted cells split.

What :mod:`axiscal.io.plain_csv` declines comes here (see docs/formats.md, "What a reader accepts"):
the bytes are checked (NUL, UTF-8), blank and comment lines are skipped by
:class:`~axiscal.io.lines.Lines`, the delimiter is counted on every data row at once (a row with
another number of cells than the header is refused on its line), and pandas' C parser then splits
a file without quotes; quoted cells go through the ``csv`` module line by line. The table's cells
are held to the number grammar (:mod:`axiscal.io.cells`) when a column is asked for.
"""

from __future__ import annotations

import csv
import io
import warnings
from collections.abc import Sequence
from pathlib import Path

import numpy as np

from axiscal.errors import AxiscalError
from axiscal.io.cells import BLANKS
from axiscal.io.csv_table import CsvTable
from axiscal.io.lines import Lines
from axiscal.io.plain_csv import pandas_options
from axiscal.io.plain_csv import stamp as _stamp

__all__: list[str] = []

_MICRO = ("\u00b5", "\u03bc")  # micro sign and Greek mu, as in "µm"


def parse_bytes(data: bytes, path: str, min_rows: int, *, file: Path | None = None, stamp: tuple | None = None) -> CsvTable:
    """The table of a file's bytes, every problem refused naming its line.

    ``file`` and ``stamp`` (the file's :func:`~axiscal.io.plain_csv.stamp` taken before ``data`` was
    read) let pandas read the rows from the file itself while it is unchanged.
    """
    if data.startswith(b"\xef\xbb\xbf"):
        data = data[3:]
    lines = Lines(data)
    nul = data.find(b"\0")
    if nul >= 0:
        raise AxiscalError("NUL character: this is not a text file", path=path, line=lines.number_at(nul))
    try:
        if not data.isascii():
            data.decode("utf-8")
    except UnicodeDecodeError as exc:
        raise AxiscalError(f"not UTF-8 text (byte 0x{data[exc.start]:02x})", path=path, line=lines.number_at(exc.start)) from None
    kept = lines.content()
    if len(kept) == 0:
        raise AxiscalError("empty file: expected a header row", path=path, line=1)
    header_text = lines.text(kept[0])
    delimiter = next((d for d in (",", ";", "\t") if d in header_text), ",")
    header_line = int(kept[0]) + 1
    quoted = b'"' in data[lines.starts[kept[0]] :]
    if quoted:
        header = _split_quoted(lines, kept[:1], delimiter, path)[0]
    else:
        header = [cell.strip(BLANKS) for cell in header_text.split(delimiter)]
    table = CsvTable._parsed(path, checked_header(header, path, header_line), kept[1:] + 1, header_line, comma=delimiter != ",")
    if len(kept) > 1:
        cells = _split_quoted(lines, kept[1:], delimiter, path, width=len(header)) if quoted else _read_frame(table, lines, kept, delimiter, file, stamp)
        if cells is not None:
            table._set(_rows=tuple(tuple(row) for row in cells))
    if len(table) < min_rows:
        raise AxiscalError(f"{len(table)} data rows; at least {min_rows} needed", path=path, line=header_line)
    return table


def checked_header(header: list[str], path: str, line: int) -> tuple[str, ...]:
    """The header's names, a unit spelled ``µm`` or ``μm`` read as ``um``; an empty or repeated name refused."""
    seen: set[str] = set()
    out = []
    for name in header:
        stem, sep, unit = name.rpartition("_")
        if sep and unit[:1] in _MICRO:
            name = f"{stem}_u{unit[1:]}"
        if not name:
            raise AxiscalError("empty column name in header", path=path, line=line)
        if name in seen:
            raise AxiscalError(f"column '{name}' appears twice", path=path, line=line)
        seen.add(name)
        out.append(name)
    return tuple(out)


def _read_frame(
    table: CsvTable, lines: Lines, kept: np.ndarray, delimiter: str, file: Path | None, stamp: tuple | None
) -> list[list[str]] | None:
    """Give ``table`` pandas' columns of the data rows ``kept[1:]`` (in a file without quotes).

    When the rows run to the end of ``file``, pandas reads the file itself, skipping the lines
    above them (its own buffered reading is faster than from memory). Returns None, or the rows'
    cells split here when pandas saw the rows differently (or the file changed meanwhile).
    """
    import pandas as pd

    rows = kept[1:]
    width = len(table.header)
    sep = delimiter.encode()
    contiguous = rows[-1] - rows[0] + 1 == len(rows)
    arr = np.frombuffer(lines.data, dtype=np.uint8)
    start, end = int(lines.starts[rows[0]]), int(lines.ends[rows[-1]])
    seps = arr[start:end] if contiguous else np.frombuffer(lines.join(rows), dtype=np.uint8)
    first = lines.data.count(sep, start, int(lines.ends[rows[0]]))
    if first != width - 1 or np.count_nonzero(seps == ord(sep)) != (width - 1) * len(rows):
        _check_cell_counts(table, lines.count(sep, rows) + 1)
    options = pandas_options(width, delimiter, table.decimal_comma)
    try:
        with warnings.catch_warnings():
            # parsed in chunks, a column may mix numbers and text: numeric() then reads its text
            warnings.simplefilter("ignore", pd.errors.DtypeWarning)
            frame = None
            if file is not None and contiguous and rows[-1] == len(lines) - 1:
                frame = pd.read_csv(file, skiprows=int(rows[0]), **options)
                if _stamp(file) != stamp or len(frame) != len(rows):  # changed since it was read, or
                    frame = None  # pandas counted lines otherwise: parse the bytes that were read
            if frame is None:
                frame = pd.read_csv(io.BytesIO(lines.join(rows)), **options)
    except (pd.errors.ParserError, ValueError, OSError):
        frame = None
    if frame is None or len(frame) != len(rows):
        return _split_quoted(lines, rows, delimiter, table.path, width=width)

    def reread(i: int) -> np.ndarray:
        column = pd.read_csv(io.BytesIO(lines.join(rows)), usecols=[i], dtype=str, **options)[i]
        return column.str.strip(BLANKS).to_numpy(dtype=object)

    table._set(_frame=frame, _reread=reread)
    return None


def _check_cell_counts(table: CsvTable, counts: Sequence[int] | np.ndarray) -> None:
    """Refuse the first row whose number of cells is not the header's."""
    counts = np.asarray(counts)
    wrong = np.flatnonzero(counts != len(table.header))
    if len(wrong):
        k = int(wrong[0])
        raise AxiscalError(f"{counts[k]} cells where the header has {len(table.header)}", path=table.path, line=table.line_of(k))


def _split_quoted(lines: Lines, indices: np.ndarray, delimiter: str, path: str, *, width: int | None = None) -> list[list[str]]:
    """The stripped cells of the lines ``indices``, with quoted cells (which may not span lines).

    With ``width``, a line with another number of cells is refused.
    """
    out = []
    for index in indices:
        text = lines.text(index)
        if len(text) >= csv.field_size_limit():  # a cell may be as long as its line (the csv module stops at 128 kB)
            csv.field_size_limit(len(text) + 1)
        try:
            cells = next(csv.reader([text], delimiter=delimiter, strict=True), [""])
        except csv.Error as exc:
            raise AxiscalError(f"cannot split into cells ({exc})", path=path, line=int(index) + 1) from None
        if width is not None and len(cells) != width:
            raise AxiscalError(f"{len(cells)} cells where the header has {width}", path=path, line=int(index) + 1)
        out.append([cell.strip(BLANKS) for cell in cells])
    return out
