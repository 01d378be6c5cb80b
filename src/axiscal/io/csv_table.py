"""A parsed CSV file: the header, the rows and their line numbers, the columns converted on demand.

:func:`axiscal.io.read_csv` and :func:`axiscal.io.parse_csv` make it; a column becomes finite floats
(:meth:`CsvTable.numeric`) or stripped text (:meth:`CsvTable.text`) when asked for, and a cell that
is not what was asked is refused naming the file, the column, the cell and its line.
"""

from __future__ import annotations

import os
from collections.abc import Iterable, Sequence
from dataclasses import dataclass

import numpy as np

from axiscal.errors import AxiscalError
from axiscal.io.cells import MAX_MAGNITUDE, NOT_FINITE, beyond, numbers, shown

__all__ = ["CsvTable"]


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
    >>> from axiscal.io import parse_csv
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
                cell = shown(self._column_text(i)[k])
                raise AxiscalError(f"column '{name}': {cell} {beyond(values[k])}", path=self.path, line=self.line_of(k))
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
        _, values = numbers(self._column_text(self._index[name]), decimal_comma=self.decimal_comma)
        with np.errstate(invalid="ignore"):
            values[~(np.abs(values) <= MAX_MAGNITUDE)] = np.nan
        return values

    def _convert(self, i: int, allow_empty: bool) -> np.ndarray:
        """The strict grammar over the column's text: the first cell (in file order) that is not a
        number, or a number too large for a float, is refused."""
        cells = self._column_text(i)
        empty = cells == ""
        number, values = numbers(cells, decimal_comma=self.decimal_comma)
        with np.errstate(invalid="ignore"):
            huge = np.abs(values) > MAX_MAGNITUDE
        bad = (~number & ~(empty & allow_empty)) | huge
        if bad.any():
            k = int(np.argmax(bad))
            cell = cells[k]
            if number[k]:
                raise AxiscalError(f"column '{self.header[i]}': {shown(cell)} {beyond(values[k])}", path=self.path,
                                   line=self.line_of(k))
            problem = "is not a finite number" if NOT_FINITE.fullmatch(cell) else "is not a number"
            quoted = shown(cell) if problem == "is not a finite number" else f"'{shown(cell)}'"
            raise AxiscalError(f"column '{self.header[i]}': {quoted} {problem}", path=self.path, line=self.line_of(k))
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
