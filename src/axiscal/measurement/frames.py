"""Frames files: raw sensor frames and live records read from CSV, plain data CSVs written with their JSON sidecar.

The one reading of a frames file (``axiscal measure``, the replay source of ``axiscal live``,
:func:`axiscal.live.recorder.read_record`): an unreadable cell is a missing reading, a live record's
last line cut short by a crash is dropped. The data CSVs written are plain (the header is the first
line) with their metadata in a JSON sidecar (``<name>.json``); every write is atomic.
"""

from __future__ import annotations

from collections.abc import Mapping, Sequence
from dataclasses import dataclass
from pathlib import Path
from typing import Any

import numpy as np

from axiscal.errors import AxiscalError
from axiscal.io.arguments import check_count, check_instance, check_mapping, check_path, check_same_length
from axiscal.io.atomic import write_text
from axiscal.io.jsonio import read_json, sidecar_path, write_sidecar
from axiscal.io.tabular import CsvTable, parse_csv, read_text, write_csv

__all__ = [
    "RECORD_KIND",
    "is_live_record",
    "drop_cut_line",
    "numeric_columns",
    "read_frames_table",
    "read_frames",
    "columns_csv",
    "write_data_csv",
    "CsvOutput",
]

#: the ``kind`` of a live record's JSON sidecar
RECORD_KIND = "live record"


def is_live_record(path: str | Path, header: Sequence[str] = ()) -> bool:
    """Whether ``path`` is a live record: its sidecar says so, or (sidecar not copied along) its columns do.

    Parameters
    ----------
    path : str or Path
        The CSV file.
    header : sequence of str
        Its column names, if already read (a record has ``fault`` and ``e_um`` besides ``t_s``).

    Returns
    -------
    bool
    """
    side = sidecar_path(check_path("path", path))
    header = _names("header", header)
    if side.is_file():
        try:
            data = read_json(side)
        except AxiscalError:
            data = None
        if isinstance(data, Mapping) and data.get("kind") == RECORD_KIND:
            return True
    return {"t_s", "fault", "e_um"} <= set(header)


def drop_cut_line(text: str) -> str:
    """A live record's text without a last line cut short by a crash (one without its newline).

    Only for live records (:func:`is_live_record`): in any other CSV a last line without its
    newline is a complete row.

    Parameters
    ----------
    text : str
        The record's text.

    Returns
    -------
    str
        The text up to and including its last newline (unchanged when it ends with one).
    """
    check_instance("text", text, str, what="the record's text (str)")
    if text and not text.endswith("\n"):
        return text[: text.rfind("\n") + 1]
    return text


def numeric_columns(table: CsvTable, names: Sequence[str]) -> dict[str, np.ndarray]:
    """Columns of a frames table as floats: a cell that is empty, ``nan``, infinite or not a number is NaN.

    The one rule for raw frames read from files (``axiscal measure``, the replay source of
    ``axiscal live``, :func:`axiscal.live.recorder.read_record`), the same as the line protocol's:
    an unreadable channel cell is a missing reading, an unreadable ``t_s`` a frame without a time
    stamp; neither stops the reading.

    Parameters
    ----------
    table : CsvTable
        The parsed file.
    names : sequence of str
        Columns wanted (each must be in ``table.header``).

    Returns
    -------
    dict of str to ndarray, shape (N,)
        Each column, NaN where the cell is not a number by the grammar of
        :meth:`axiscal.io.CsvTable.numeric`, not finite, or beyond its physical magnitude limit.

    Examples
    --------
    >>> table = parse_csv(["t_s,a", "0.1,oops", "0.2,"])
    >>> numeric_columns(table, ["a"])["a"].tolist()
    [nan, nan]
    """
    check_instance("table", table, CsvTable, what="a CsvTable (read_csv, parse_csv)")
    return {name: table.numeric_or_missing(name) for name in _names("names", names)}



def read_frames_table(path: str | Path, *, min_rows: int = 1) -> tuple[CsvTable, bool]:
    """A frames CSV parsed: line ends ``\\n``, ``\\r\\n`` or ``\\r``; in a live record a cut last line dropped.

    Parameters
    ----------
    path : str or Path
        The file (``#`` comment lines before the header are allowed).
    min_rows : int
        Fewest data rows accepted.

    Returns
    -------
    table : CsvTable
        Header and raw cells.
    truncated : bool
        Whether a live record's last line, cut short by a crash, was dropped.

    Raises
    ------
    AxiscalError
        If the file is missing or unreadable, or a line has a different number of cells than the
        header (naming file and line).
    """
    min_rows = check_count("min_rows", min_rows, minimum=0)
    text = read_text(check_path("path", path))  # universal newlines: CR-only and CRLF files read as LF
    first = text[: text.find("\n")] if "\n" in text else text
    header = [c.strip() for c in first.split(",")]
    truncated = False
    if is_live_record(path, header) or text.startswith("# axiscal live record"):
        kept = drop_cut_line(text)
        truncated, text = kept != text, kept
    return parse_csv(text.split("\n"), path=str(path), min_rows=min_rows), truncated


def read_frames(path: str | Path, channels: Sequence[str]) -> dict[str, np.ndarray]:
    """Raw frames from a CSV with ``t_s`` and every channel (other columns are ignored).

    A cell that is empty, ``nan`` or not a number is a missing reading (:func:`numeric_columns`):
    the frame is flagged by the pipeline, not refused; a ``t_s`` that cannot be read is NaN (the
    frame is malformed, :data:`~axiscal.measurement.faults.Fault.MALFORMED`). In a live record
    (:func:`is_live_record`) a last line without its newline (cut short by a crash) is dropped; in
    any other file it is a frame.

    Parameters
    ----------
    path : str or Path
        The frames file (``#`` comment lines before the header are allowed; lines end with LF,
        CRLF or CR).
    channels : sequence of str
        The raw channels wanted (``MeasurementSystem.channels``).

    Returns
    -------
    dict of str to ndarray, shape (N,)
        ``"t_s"`` and every channel, in the channel's own unit.

    Raises
    ------
    AxiscalError
        For a missing file or column or a line with a wrong number of cells (naming file and line).
    """
    channels = _names("channels", channels)
    table, _ = read_frames_table(path)
    table.require("t_s", *channels)
    return numeric_columns(table, ["t_s", *channels])


def columns_csv(columns: Mapping[str, np.ndarray]) -> str:
    """Equal-length numeric columns as plain CSV text (9 significant digits, ``nan`` for NaN).

    Parameters
    ----------
    columns : mapping of str to ndarray, shape (N,)
        Column name to values (display units, named with them).

    Returns
    -------
    str
        The header line and one line per row.
    """
    check_mapping("columns", columns, what="a mapping of column names to values")
    for name, value in columns.items():
        if not isinstance(name, str) or isinstance(value, (str, bytes)) or np.ndim(value) != 1:
            raise AxiscalError(f"columns must map names to one-dimensional columns; columns[{name!r}] is not one")
    check_same_length(**{str(name): value for name, value in columns.items()})
    return write_csv(None, dict(columns), fmt="{:.9g}")


def write_data_csv(path: str | Path, columns: Mapping[str, np.ndarray], *, kind: str, sources: Sequence[str | Path] = (), **metadata: Any) -> str:
    """Write a plain data CSV and its JSON sidecar, both atomically; return the CSV text.

    Parameters
    ----------
    path : str or Path
        The CSV file.
    columns : mapping of str to ndarray
        The columns (display units in their names).
    kind : str
        What the file holds (the sidecar's ``kind``).
    sources : sequence of paths
        Input files it was computed from.
    **metadata
        Further sidecar entries.

    Returns
    -------
    str
        The CSV text written.

    Raises
    ------
    AxiscalError
        If a file cannot be written (naming it).
    """
    path = check_path("path", path)
    if not isinstance(kind, str) or not kind:
        raise AxiscalError(f"kind must name what the file holds, not {kind!r}")
    text = columns_csv(columns)
    write_text(path, text)
    write_sidecar(path, kind=kind, sources=sources, **metadata)
    return text


@dataclass(frozen=True)
class CsvOutput:
    """A data CSV made by a command.

    Attributes
    ----------
    text : str
        The CSV text.
    rows : int
        Its number of data rows.
    """

    text: str
    rows: int

    def __post_init__(self) -> None:
        check_instance("text", self.text, str, what="the CSV text")
        check_count("rows", self.rows, minimum=0)


def _names(name: str, values: Sequence[str]) -> tuple[str, ...]:
    """A sequence of names (column or channel names), refused when it is a single string or not names."""
    if isinstance(values, (str, bytes)) or not hasattr(values, "__iter__"):
        raise AxiscalError(f"{name} must be a sequence of names (str), not {values!r}")
    values = tuple(values)
    if not all(isinstance(v, str) for v in values):
        raise AxiscalError(f"{name} must be a sequence of names (str), not {values!r}"[:200])
    return values
