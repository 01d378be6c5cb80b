"""The one tabular reader and writer: CSV files with units in column names, read with pandas' C parser.

RFC 4180 CSV with the relaxations of docs/formats.md ("What a reader accepts"): UTF-8 with or
without a byte-order mark; LF, CRLF or CR line ends; blank lines and lines whose first non-blank
character is ``#`` skipped; ``,`` or, when the header says so, ``;`` or tab between cells (with a
decimal comma allowed); cells stripped of blanks (space, tab, vertical tab, form feed). Readers validate once, at the boundary: every
value a caller gets back is a finite float (or a stripped string for text columns), and every error
names the file and the physical line as an editor numbers it (the header is line 1 when it is the
first line).
"""

from __future__ import annotations

import contextlib
import csv
import io
import math
import os
import re
import warnings
from collections.abc import Iterable, Mapping, Sequence
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from axiscal.errors import AxiscalError
from axiscal.io.arguments import check_count, check_instance, check_mapping, check_path, check_same_length
from axiscal.io.atomic import write_text
from axiscal.io.lines import Lines
from axiscal.io.plain_csv import HEAD, pandas_options, read_body, read_plain
from axiscal.io.plain_csv import stamp as _stamp

#: the largest magnitude a numeric cell may hold, in its column's unit (1e12 mm is 1e9 m)
MAX_MAGNITUDE = 1e12

__all__ = [
    "MAX_MAGNITUDE",
    "CsvTable",
    "read_csv",
    "read_text",
    "parse_csv",
    "write_csv",
    "read_toml",
    "parse_toml",
    "parse_number",
]

#: a number as a file may spell it: optional sign, decimal digits with an optional point, optional exponent
# (the digits before and after the point are separate groups, so a long cell that is not a number
# is refused in linear time: "[0-9]+\.?[0-9]*" would try every split of a run of digits)
_NUMBER = re.compile(r"[+-]?(?:[0-9]+(?:\.[0-9]*)?|\.[0-9]+)(?:[eE][+-]?[0-9]+)?")
_NUMBER_COMMA = re.compile(r"[+-]?(?:[0-9]+(?:[.,][0-9]*)?|[.,][0-9]+)(?:[eE][+-]?[0-9]+)?")
_NOT_FINITE = re.compile(r"[+-]?(?:nan|inf|infinity)", re.IGNORECASE)
_MICRO = ("\u00b5", "\u03bc")  # micro sign and Greek mu, as in "µm"
_SHOWN = 40  # characters of a cell quoted in an error message
#: what a cell is stripped of: ASCII white space within a line (space, tab, vertical tab, form
#: feed), not the other control characters and separators ``str.strip`` also removes (a cell
#: "\x1d.5" is not the number 0.5)
BLANKS = " \t\v\f"


class _Lazy:
    """A field of :class:`CsvTable` that a table read from a file builds on first use."""

    def __set_name__(self, owner: type, name: str) -> None:
        self.slot = f"_{name}"
        self.build = f"_build_{name}"

    def __get__(self, table: CsvTable | None, owner: type | None = None):
        if table is None:
            return ()  # the field's default
        value = table.__dict__.get(self.slot)
        if value is None:
            value = getattr(table, self.build)()
            table.__dict__[self.slot] = value
        return value

    def __set__(self, table: CsvTable, value) -> None:
        table.__dict__[self.slot] = value


@dataclass(frozen=True, repr=False)
class CsvTable:
    """A parsed CSV file: the header, the cells of each data row, and each row's line number.

    Made by :func:`read_csv` or :func:`parse_csv`; columns are converted when asked for. A
    dataclass: ``dataclasses.replace(table, rows=..., lines=...)`` gives a table of chosen rows.

    Parameters
    ----------
    path : str
        The file's name, for error messages.
    header : tuple of str
        Column names (stripped; a unit spelled ``µm`` or ``μm`` is ``um``).
    rows : tuple of tuple of str
        The stripped cells of each data row (built on first use for a table read from a file).
    lines : tuple of int
        The 1-based line number of each data row (built on first use likewise).
    decimal_comma : bool
        Whether numbers may have a decimal comma (``;`` or tab between cells).

    Attributes
    ----------
    header_line : int
        The line number of the header.

    Raises
    ------
    AxiscalError
        For a ``path`` that is not a name, a ``header`` that is not a sequence of names,
        rows and lines of different lengths.

    Examples
    --------
    >>> table = parse_csv(["# note", "position_mm, EXX_µm", "0, 1.5", "10, -2"])
    >>> table.header, table.lines, table.header_line
    (('position_mm', 'EXX_um'), (3, 4), 2)
    >>> table.numeric("EXX_um")
    array([ 1.5, -2. ])
    """

    path: str
    header: tuple[str, ...]
    rows: tuple[tuple[str, ...], ...] = _Lazy()  # type: ignore[assignment]
    lines: tuple[int, ...] = _Lazy()  # type: ignore[assignment]
    decimal_comma: bool = False

    def __post_init__(self) -> None:
        if not isinstance(self.path, (str, os.PathLike)):
            raise AxiscalError(f"path must be the file's name (a str), not {self.path!r}")
        if isinstance(self.header, (str, bytes)) or not isinstance(self.header, Iterable):
            raise AxiscalError(f"header must be a sequence of column names, not {self.header!r}")
        if not all(isinstance(name, str) for name in self.header):
            raise AxiscalError(f"header must be a sequence of column names (str), not {tuple(self.header)!r}")
        rows, lines = self.__dict__["_rows"], self.__dict__["_lines"]
        if rows is not None and (lines is None or len(tuple(lines)) != len(tuple(rows))):
            raise AxiscalError("rows and lines must have the same length (one line number per row)")
        if rows is not None:
            self.__dict__["_rows"] = tuple(tuple(row) for row in rows)
            self.__dict__["_lines"] = lines = tuple(lines)
        self._set(
            header=tuple(self.header),
            _index={name: i for i, name in enumerate(self.header)},
            _n=0 if rows is None else len(rows),
            _row_lines=None if lines is None else np.asarray(lines, dtype=np.int64),
            _header_line=lines[0] - 1 if lines else 1,
            _frame=None,  # pandas' columns, with the dtypes its parser inferred
            _reread=None,  # reads one column as text from the same bytes
            _strings={},
            _checked=frozenset(),  # columns of _frame known to be finite numbers within MAX_MAGNITUDE
        )

    def _set(self, **values) -> None:
        self.__dict__.update(values)

    @classmethod
    def _parsed(cls, path: str, header: Sequence[str], row_lines: np.ndarray, header_line: int, *, comma: bool) -> CsvTable:
        table = cls(path, tuple(header), rows=None, lines=None, decimal_comma=comma)  # type: ignore[arg-type]
        table._set(_row_lines=row_lines, _header_line=header_line, _n=len(row_lines))
        return table

    def __len__(self) -> int:
        return self._n

    def __repr__(self) -> str:
        return f"CsvTable(path={self.path!r}, header={self.header!r}, {self._n} rows)"

    def _build_rows(self) -> tuple[tuple[str, ...], ...]:
        columns = [self._column_text(i) for i in range(len(self.header))]
        return tuple(zip(*columns)) if columns and self._n else ()

    def _build_lines(self) -> tuple[int, ...]:
        return tuple(self._row_lines) if isinstance(self._row_lines, range) else tuple(self._row_lines.tolist())

    @property
    def header_line(self) -> int:
        """The 1-based line number of the header row."""
        return self._header_line

    def line_of(self, row: int) -> int:
        """The 1-based line number of data row ``row`` (0-based)."""
        return int(self._row_lines[row])

    def has(self, name: str) -> bool:
        """Whether the header has a column ``name``."""
        return name in self._index

    def require(self, *names: str) -> None:
        """Raise naming the first of ``names`` that is not a column.

        Raises
        ------
        AxiscalError
            Naming the missing column, the columns there are, the file and the header line.
        """
        for name in names:
            if name not in self._index:
                raise AxiscalError(
                    f"missing column '{name}' (columns are: {', '.join(self.header)})", path=self.path, line=self.header_line
                )

    def text(self, name: str) -> list[str]:
        """The stripped cells of column ``name``.

        Raises
        ------
        AxiscalError
            If there is no such column.
        """
        self.require(name)
        return self._column_text(self._index[name]).tolist()

    def numeric(self, name: str, *, allow_empty: bool = False) -> np.ndarray:
        """Column ``name`` as finite floats.

        Parameters
        ----------
        name : str
            The column.
        allow_empty : bool, keyword-only
            Read an empty cell as NaN instead of refusing it.

        Returns
        -------
        numpy.ndarray of float, shape (len(self),)
            A new array, in the file's unit (the caller converts to SI).

        Raises
        ------
        AxiscalError
            If the column is missing, or a cell is not a number (``1_000``, ``0x1F``, ``nan``,
            ``inf``, full-width digits, an empty cell unless ``allow_empty``), naming the column,
            the cell and its line. Numbers are ``[+-]digits[.digits][e[+-]digits]`` (``-1.5``,
            ``+.5``, ``1.``, ``2E-3``); with ``;`` or tab between cells a decimal comma is accepted.
            A magnitude above :data:`MAX_MAGNITUDE` (in the column's own unit) is refused too: no
            length, angle, time or air condition axiscal reads comes near it, and such a value
            would overflow the arithmetic that follows.
        """
        self.require(name)
        i = self._index[name]
        if i in self._checked:
            return self._frame[i].to_numpy(dtype=np.float64, copy=True)
        if self._frame is not None and self._frame[i].dtype.kind in "iuf":
            values = self._frame[i].to_numpy(dtype=np.float64, copy=True)
            with np.errstate(invalid="ignore"):
                bad = ~(np.abs(values) <= MAX_MAGNITUDE)
            if bad.any():
                k = int(np.argmax(bad))
                cell = _shown(self._column_text(i)[k])
                raise AxiscalError(f"column '{name}': {cell} {_beyond(values[k])}", path=self.path, line=self.line_of(k))
            return values
        return self._convert(i, allow_empty)

    def numeric_or_missing(self, name: str) -> np.ndarray:
        """Column ``name`` as floats, a cell that is not a number read as a missing value (NaN).

        For channels where a bad reading is flagged downstream rather than refused (a sensor
        that dropped out writes an empty cell or ``nan``).

        Parameters
        ----------
        name : str
            The column.

        Returns
        -------
        numpy.ndarray of float, shape (len(self),)
            The numbers; NaN where a cell is empty, not a number by the grammar of
            :meth:`numeric`, not finite, or beyond :data:`MAX_MAGNITUDE`.

        Raises
        ------
        AxiscalError
            If the column is missing.
        """
        self.require(name)
        cells = self._column_text(self._index[name])
        match = (_NUMBER_COMMA if self.decimal_comma else _NUMBER).fullmatch
        number = np.fromiter((match(cell) is not None for cell in cells), dtype=bool, count=len(cells))
        values = np.full(len(cells), np.nan)
        texts = cells[number]
        if self.decimal_comma:
            texts = [cell.replace(",", ".") for cell in texts]
        values[number] = np.fromiter((float(cell) for cell in texts), dtype=np.float64, count=len(texts))
        with np.errstate(invalid="ignore"):
            values[~(np.abs(values) <= MAX_MAGNITUDE)] = np.nan
        return values

    def _convert(self, i: int, allow_empty: bool) -> np.ndarray:
        """The strict grammar over the column's text: the first cell (in file order) that is not a
        number, or a number too large for a float, is refused."""
        cells = self._column_text(i)
        empty = cells == ""
        match = (_NUMBER_COMMA if self.decimal_comma else _NUMBER).fullmatch
        number = np.fromiter((match(cell) is not None for cell in cells), dtype=bool, count=len(cells))
        values = np.full(len(cells), np.nan)
        texts = cells[number]
        if self.decimal_comma:
            texts = [cell.replace(",", ".") for cell in texts]
        values[number] = np.fromiter((float(cell) for cell in texts), dtype=np.float64, count=len(texts))
        with np.errstate(invalid="ignore"):
            huge = np.abs(values) > MAX_MAGNITUDE
        bad = (~number & ~(empty & allow_empty)) | huge
        if bad.any():
            k = int(np.argmax(bad))
            cell = cells[k]
            if number[k]:
                raise AxiscalError(f"column '{self.header[i]}': {_shown(cell)} {_beyond(values[k])}", path=self.path,
                                   line=self.line_of(k))
            problem = "is not a finite number" if _NOT_FINITE.fullmatch(cell) else "is not a number"
            shown = _shown(cell) if problem == "is not a finite number" else f"'{_shown(cell)}'"
            raise AxiscalError(f"column '{self.header[i]}': {shown} {problem}", path=self.path, line=self.line_of(k))
        return values

    def _column_text(self, i: int) -> np.ndarray:
        found = self._strings.get(i)
        if found is None:
            if self._reread is not None:
                found = self._reread(i)
            else:
                found = np.array([row[i] for row in self._rows or ()], dtype=object)
            self._strings[i] = found
        return found


def _beyond(value: float) -> str:
    """Why a number that parsed is refused: not finite, or beyond any physical magnitude."""
    if not np.isfinite(value):
        return "is not a finite number"
    return f"is beyond any physical value (more than {MAX_MAGNITUDE:g} in the column's unit)"


def _shown(cell: str) -> str:
    """The cell as an error message quotes it: shortened, control characters escaped (``\\x1d``)."""
    cell = cell if len(cell) <= _SHOWN else cell[: _SHOWN - 3] + "..."
    return cell if cell.isprintable() else cell.encode("unicode_escape").decode("ascii")


def read_csv(path: str | Path, *, min_rows: int = 1) -> CsvTable:
    """Read a CSV file with a header row (see docs/formats.md, "What a reader accepts").

    Parameters
    ----------
    path : str or Path
        The file.
    min_rows : int, keyword-only
        The fewest data rows accepted.

    Returns
    -------
    CsvTable
        The header and the rows; convert columns with :meth:`CsvTable.numeric` or :meth:`CsvTable.text`.

    Raises
    ------
    AxiscalError
        If the file is missing or unreadable, is not UTF-8 text, has no header, an empty or repeated
        column name, a row with a different number of cells than the header, or fewer than
        ``min_rows`` data rows; it names the file and line.

    Examples
    --------
    >>> import tempfile, pathlib
    >>> path = pathlib.Path(tempfile.mkdtemp()) / "p.csv"
    >>> _ = path.write_text("position_mm;deviation_µm\\n0;1,5\\n10;-2\\n")
    >>> read_csv(path).numeric("deviation_um")
    array([ 1.5, -2. ])
    """
    path = check_path("path", path)
    with _reading(path):
        stamp = _stamp(path)  # before any read: a later change of the file shows against it
        with open(path, "rb") as handle:
            head = handle.read(HEAD)
    table = _read_plain(head, str(path), min_rows, path, stamp)
    if table is not None:
        return table
    with _reading(path):
        data = path.read_bytes()
    return _parse(data, str(path), min_rows, file=path, stamp=stamp)


@contextlib.contextmanager
def _reading(path: Path):
    """Reading ``path``: a missing, unreadable or folder path raises AxiscalError naming it."""
    try:
        yield
    except FileNotFoundError:
        raise AxiscalError("file not found", path=path) from None
    except IsADirectoryError:
        raise AxiscalError("is a folder, not a file", path=path) from None
    except OSError as exc:
        raise AxiscalError(f"cannot read file ({exc.strerror or exc})", path=path) from None


def _read_plain(head: bytes, path: str, min_rows: int, file: Path, stamp: tuple) -> CsvTable | None:
    """The table of a file of plain numbers, read by pandas in one pass; None for any other file
    (the strict reading of :func:`_parse` then reads it and names what is wrong)."""
    plain = read_plain(head, file, stamp, MAX_MAGNITUDE)
    if plain is None or len(plain.frame) < min_rows:
        return None
    try:
        header = _checked_header(plain.header, path, plain.header_line)
    except AxiscalError:
        return None
    first = plain.header_line + 1
    rows = range(first, first + len(plain.frame))
    table = CsvTable._parsed(path, header, rows, plain.header_line, comma=plain.delimiter != ",")  # type: ignore[arg-type]
    options = pandas_options(len(header), plain.delimiter, plain.delimiter != ",")

    def reread(i: int) -> np.ndarray:
        import pandas as pd

        body = read_body(file, stamp, plain.body_start)
        column = pd.read_csv(io.BytesIO(body), usecols=[i], dtype=str, **options)[i]
        return column.str.strip(BLANKS).to_numpy(dtype=object)

    table._set(_frame=plain.frame, _reread=reread, _checked=frozenset(range(len(header))))
    return table


def parse_csv(lines: Iterable[str], *, path: str = "<input>", min_rows: int = 1) -> CsvTable:
    """Parse CSV text given as lines, numbered from 1 (see :func:`read_csv`).

    Parameters
    ----------
    lines : iterable of str
        The lines, without or with their line ends.
    path : str, keyword-only
        The name errors give.
    min_rows : int, keyword-only
        The fewest data rows accepted.

    Returns
    -------
    CsvTable

    Raises
    ------
    AxiscalError
        As :func:`read_csv`.
    """
    if isinstance(lines, (str, bytes)) or not isinstance(lines, Iterable):
        raise AxiscalError(f"lines must be an iterable of str (the lines of the text), not {type(lines).__name__}")
    lines = list(lines)
    if not all(isinstance(line, str) for line in lines):
        raise AxiscalError("lines must be an iterable of str (the lines of the text), not of other things")
    if not isinstance(path, (str, os.PathLike)):
        raise AxiscalError(f"path must be the name errors give (a str), not {path!r}")
    min_rows = check_count("min_rows", min_rows, minimum=0)
    text = "\n".join(line[:-1] if line.endswith("\n") else line for line in lines)
    return _parse(text.encode("utf-8", errors="surrogatepass"), path, min_rows)


def _parse(data: bytes, path: str, min_rows: int, *, file: Path | None = None, stamp: tuple | None = None) -> CsvTable:
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
    table = CsvTable._parsed(path, _checked_header(header, path, header_line), kept[1:] + 1, header_line, comma=delimiter != ",")
    if len(kept) > 1:
        cells = _split_quoted(lines, kept[1:], delimiter, path, width=len(header)) if quoted else _read_frame(table, lines, kept, delimiter, file, stamp)
        if cells is not None:
            table._set(_rows=tuple(tuple(row) for row in cells))
    if len(table) < min_rows:
        raise AxiscalError(f"{len(table)} data rows; at least {min_rows} needed", path=path, line=header_line)
    return table


def _checked_header(header: list[str], path: str, line: int) -> tuple[str, ...]:
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
    if not _NUMBER.fullmatch(cell):
        return None
    value = float(cell)
    return value if math.isfinite(value) and abs(value) <= MAX_MAGNITUDE else None


def read_text(path: str | Path) -> str:
    """The text of a UTF-8 file (a byte-order mark is dropped).

    Raises
    ------
    AxiscalError
        If the file is missing or unreadable, naming it; if it is not UTF-8, naming the line of the
        first byte that is not.
    """
    return read_checked_text(check_path("path", path))


def read_checked_text(path: Path) -> str:
    """:func:`read_text` of a path a public entry has already checked (a file a checked file names).

    Parameters
    ----------
    path : Path

    Returns
    -------
    str
    """
    try:
        data = path.read_bytes()
    except FileNotFoundError:
        raise AxiscalError("file not found", path=path) from None
    except OSError as exc:
        raise AxiscalError(f"cannot read file ({exc})", path=path) from None
    try:
        return data.decode("utf-8-sig")
    except UnicodeDecodeError as exc:
        before = data[: exc.start]
        line = before.count(b"\n") + before.count(b"\r") - before.count(b"\r\n") + 1
        raise AxiscalError(f"not UTF-8 text (byte 0x{data[exc.start]:02x})", path=path, line=line) from None


def write_csv(
    path: str | Path | None,
    columns: Mapping[str, Sequence[float] | np.ndarray],
    *,
    fmt: str | Mapping[str, str] = "{:.6f}",
) -> str:
    """Write columns (all the same length) as a plain CSV, atomically; return the text.

    The header is the first line and there are no comment lines, so ``pandas.read_csv(path)``,
    spreadsheets and ``csv.DictReader`` read the file as it is; what describes the data belongs in
    a JSON sidecar (:func:`axiscal.io.write_sidecar`).

    Parameters
    ----------
    path : str, Path or None
        The file; ``None`` only returns the text.
    columns : mapping of str to sequence
        Column name (with its unit) to values; strings are written as they are.
    fmt : str or mapping of str to str, keyword-only
        One format for every float column, or a format per column name (default ``{:.6f}``).

    Returns
    -------
    str
        The CSV text.

    Raises
    ------
    AxiscalError
        If the file cannot be written (the file that was there is left as it was); for columns
        that are not a mapping of names to sequences of one length, or a format that is not one.
    """
    check_mapping("columns", columns, what="a mapping of column names to values")
    for name, values in columns.items():
        if not isinstance(name, str) or isinstance(values, (str, bytes)) or not hasattr(values, "__len__") or not hasattr(values, "__getitem__"):
            raise AxiscalError(f"columns must map column names to sequences of values, not {name!r}: {type(values).__name__}")
    check_same_length(**{str(k): v for k, v in columns.items()})
    if not isinstance(fmt, (str, Mapping)) or isinstance(fmt, Mapping) and not all(isinstance(f, str) for f in fmt.values()):
        raise AxiscalError(f"fmt must be a format string or a mapping of them, not {fmt!r}")
    names = list(columns)
    n = len(next(iter(columns.values()))) if names else 0
    out = [",".join(names)]
    formats = [fmt.get(name, "{:.6f}") if isinstance(fmt, Mapping) else fmt for name in names]
    for k in range(n):
        cells = []
        for name, f in zip(names, formats):
            value = columns[name][k]
            try:
                cells.append(value if isinstance(value, str) else f.format(float(value)))
            except (TypeError, ValueError, IndexError, KeyError) as exc:
                raise AxiscalError(f"fmt {f!r} cannot write {value!r} (columns['{name}'] row {k}: {exc})") from None
        out.append(",".join(cells))
    text = "\n".join(out) + "\n"
    if path is not None:
        write_text(path, text)
    return text


def read_toml(path: str | Path) -> dict:
    """Parse a TOML file.

    Raises
    ------
    AxiscalError
        If the file is missing, unreadable or malformed, naming the file and line.
    """
    return parse_toml(read_text(path), path=path)


def parse_toml(text: str, *, path: str | Path | None = None) -> dict:
    """Parse TOML text, a malformed text refused naming its line.

    Parameters
    ----------
    text : str
        The TOML text (as :func:`read_text` returns it).
    path : str or Path, optional, keyword-only
        The file's name, for messages.

    Returns
    -------
    dict

    Raises
    ------
    AxiscalError
        For malformed TOML, naming the line (the last line for a text cut short).

    Examples
    --------
    >>> parse_toml("a = 1")
    {'a': 1}
    """
    import tomllib

    check_instance("text", text, str, what="the TOML text (a str)")
    try:
        return tomllib.loads(text)
    except tomllib.TOMLDecodeError as exc:
        # Python 3.11 has no lineno attribute: the line is only in the message
        found = re.search(r"\(at line (\d+)", str(exc))
        message = re.split(r" \(at (?:line|end of document)", str(exc))[0]
        if found:
            line = int(found.group(1))
        else:  # "at end of document": the last line
            line = len(re.split(r"\r\n|\r|\n", text.rstrip("\r\n"))) if "end of document" in str(exc) else None
        raise AxiscalError(f"malformed TOML: {message}", path=path, line=line) from None
