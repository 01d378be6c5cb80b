"""The one tabular reader and writer: CSV files with units in column names, read with pandas' C parser.

RFC 4180 CSV with the relaxations of docs/formats.md ("What a reader accepts"): UTF-8 with or
without a byte-order mark; LF, CRLF or CR line ends; blank lines and lines whose first non-blank
character is ``#`` skipped; ``,`` or, when the header says so, ``;`` or tab between cells (with a
decimal comma allowed); cells stripped of blanks (space, tab, vertical tab, form feed). Readers validate once, at the boundary: every
value a caller gets back is a finite float (or a stripped string for text columns), and every error
names the file and the physical line as an editor numbers it (the header is line 1 when it is the
first line).

A file of plain numbers is read by :mod:`axiscal.io.plain_csv` in one pass; anything else by
:mod:`axiscal.io.strict_csv`, which names the line of what is wrong. The table is
:class:`~axiscal.io.csv_table.CsvTable`, the cell grammar :mod:`axiscal.io.cells`; the text and TOML
readers (:mod:`axiscal.io.text_files`) are importable from here too.
"""

from __future__ import annotations

import contextlib
import io
import os
from collections.abc import Iterable, Mapping, Sequence
from pathlib import Path

import numpy as np

from axiscal.errors import AxiscalError
from axiscal.io.arguments import check_count, check_mapping, check_path, check_same_length
from axiscal.io.atomic import write_text
from axiscal.io.cells import BLANKS, MAX_MAGNITUDE, parse_number
from axiscal.io.csv_table import CsvTable
from axiscal.io.plain_csv import HEAD, pandas_options, read_body, read_plain
from axiscal.io.plain_csv import stamp as _stamp
from axiscal.io.strict_csv import checked_header
from axiscal.io.strict_csv import parse_bytes as _parse
from axiscal.io.text_files import parse_toml, read_checked_text, read_text, read_toml

__all__ = [
    "MAX_MAGNITUDE",
    "BLANKS",
    "CsvTable",
    "read_csv",
    "read_text",
    "read_checked_text",
    "parse_csv",
    "write_csv",
    "read_toml",
    "parse_toml",
    "parse_number",
]


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
        header = checked_header(plain.header, path, plain.header_line)
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
