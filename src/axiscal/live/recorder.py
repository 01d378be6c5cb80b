"""The crash-safe live record: every frame received and every result computed, appended as CSV.

Format (docs/live.md, "Record format"): a plain CSV, the header first, then one line per frame::

    t_s,<raw channels...>,fault,ex_um,ey_um,ez_um,e_um,px_mm,py_mm,pz_mm,<positions>,<six errors per axis>

Its metadata (what the record is, source, machine, start time, the fault bits) is in the JSON
sidecar ``<record>.json``, written when the record opens. ``pandas.read_csv(record)`` reads the
record with no options. Records of the earlier format (``#`` lines before the header) are still
read by :func:`read_record`.

``t_s`` to the nanosecond, raw channels to 15 significant digits (a replay reproduces the results
to about 1e-12 relative), results to 9 significant digits, ``fault`` as an integer, ``nan`` where
a value is missing.

Durability: each batch is written with one ``os.write`` on a file opened ``O_APPEND`` (no buffer in
the process, so a crash of the process loses nothing that was written); a background thread
``fsync`` s the file every ``sync_interval_s`` and only then counts the frames as *acknowledged*
(:attr:`Recorder.frames_acknowledged`): those survive even a crash of the operating system. After a
kill the last line may be cut short; :func:`read_record` drops it (in a live record only: in any
other CSV a last line without its newline is a complete frame), and pandas reads it as a row with
missing cells at its end.
"""

from __future__ import annotations

import contextlib
import os
import threading
from collections.abc import Mapping, Sequence
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np

from axiscal.errors import AxiscalError
from axiscal.io.arguments import check_mapping, check_number, check_path
from axiscal.io.arguments import check_instance
from axiscal.io.jsonio import read_json, sidecar_path, write_sidecar
from axiscal.live.protocol import _checked_channels
from axiscal.live.record_text import FIXED, GENERAL, INTEGER, format_rows
from axiscal.measurement.faults import fault_legend
from axiscal.measurement.offline import RECORD_KIND, numeric_columns, read_frames_table

__all__ = ["FORMAT_LINE", "RECORD_KIND", "Recorder", "Record", "read_record"]

#: first line of a record in the earlier format (comment lines before the header); still read
FORMAT_LINE = "# axiscal live record, format 1 (docs/live.md)"
#: the record format written now: plain CSV with a JSON sidecar
FORMAT_VERSION = 2


class Recorder:
    """Append frames and results to a CSV file that survives a crash of the process.

    Parameters
    ----------
    path : str or Path
        The record file; created when the recorder opens (an existing one is emptied when
        ``overwrite``, else refused).
    channels : sequence of str
        Raw channel names, in frame order.
    result_columns : sequence of str
        Result columns to write after ``fault`` (names as ``MeasurementSystem.process`` returns them).
    sync_interval_s : float
        How often the background thread makes the written frames durable (``fsync``), seconds.
    metadata : mapping, optional
        Entries of the record's JSON sidecar besides its kind, format, columns and fault bits
        (source, machine, start time).
    overwrite : bool
        Replace an existing file (False: refuse it, atomically with the creation).

    Raises
    ------
    AxiscalError
        If the record or its sidecar cannot be created or written, or the record exists and not
        ``overwrite`` (naming the file).
    """

    def __init__(
        self,
        path: str | Path,
        channels: Sequence[str],
        result_columns: Sequence[str],
        *,
        sync_interval_s: float = 0.1,
        metadata: Mapping[str, object] | None = None,
        overwrite: bool = True,
    ):
        check_number("sync_interval_s", sync_interval_s, positive=True)
        if metadata is not None:
            check_mapping("metadata", metadata)
        check_instance("overwrite", overwrite, bool)
        self.path = check_path("path", path)
        self.channels = _checked_channels(channels)
        self.result_columns = _checked_channels(result_columns, "result_columns")
        self.columns = ("t_s",) + self.channels + ("fault",) + self.result_columns
        self.sync_interval_s = float(sync_interval_s)
        self._row_format = ",".join(["%.9f"] + ["%.15g"] * len(self.channels) + ["%d"] + ["%.9g"] * len(self.result_columns)) + "\n"
        # the same columns for the compiled writer (live/record_text.py), compiled or loaded now, not on the first batch
        self._kinds = np.array([FIXED] + [GENERAL] * len(self.channels) + [INTEGER] + [GENERAL] * len(self.result_columns), dtype=np.int64)
        self._digits = np.array([9] + [15] * len(self.channels) + [0] + [9] * len(self.result_columns), dtype=np.int64)
        format_rows(np.zeros((1, len(self._kinds))), self._kinds, self._digits)
        try:
            self._fd = os.open(self.path, os.O_WRONLY | os.O_CREAT | os.O_APPEND | (os.O_TRUNC if overwrite else os.O_EXCL), 0o644)
        except FileExistsError:
            raise AxiscalError("the record file exists; choose another file, or give overwrite=True to replace it", path=self.path) from None
        except OSError as exc:
            raise AxiscalError(f"cannot open the record file ({exc.strerror})", path=self.path) from None
        try:
            os.write(self._fd, (",".join(self.columns) + "\n").encode("utf-8"))
            os.fsync(self._fd)
        except OSError as exc:
            os.close(self._fd)
            raise AxiscalError(f"cannot write the record file ({exc.strerror})", path=self.path) from None
        _sync_folder(self.path)
        try:
            write_sidecar(
                self.path,
                kind=RECORD_KIND,
                format=FORMAT_VERSION,
                channels=list(self.channels),
                results=list(self.result_columns),
                fault_bits=fault_legend(),
                **dict(metadata or {}),
            )
        except AxiscalError:
            os.close(self._fd)
            raise
        self._lock = threading.Lock()
        self._written = 0
        self._acknowledged = 0
        self._closed = threading.Event()
        self._syncer = threading.Thread(target=self._sync_loop, name="axiscal-record-sync", daemon=True)
        self._syncer.start()

    @property
    def frames_written(self) -> int:
        """Frames handed to the operating system (survive a crash of this process)."""
        return self._written

    @property
    def frames_acknowledged(self) -> int:
        """Frames made durable by ``fsync`` (survive a crash of the operating system too)."""
        return self._acknowledged

    def append(self, t_s: np.ndarray, values: np.ndarray, fault: np.ndarray, results: Mapping[str, np.ndarray]) -> None:
        """Append N frames: times (N,), raw values (N, C), fault bits (N,) and result columns (N,) each.

        A result column missing from ``results`` is written as ``nan``.
        """
        n = len(t_s)
        if n == 0:
            return
        nan = np.full(n, np.nan)
        table = np.column_stack([t_s, values, fault] + [results.get(name, nan) for name in self.result_columns])
        data = format_rows(table, self._kinds, self._digits)
        if data is None:  # a time stamp or fault too large for the compiled writer: Python's formatting
            fmt = self._row_format
            data = "".join([fmt % row for row in map(tuple, table.tolist())]).encode("ascii")
        with self._lock:
            if self._closed.is_set():
                raise AxiscalError("the record file is closed", path=self.path)
            view = memoryview(data)
            try:
                while view:
                    view = view[os.write(self._fd, view) :]
            except OSError as exc:
                raise AxiscalError(
                    f"cannot write the record file ({exc.strerror}); {self._acknowledged} frames were acknowledged", path=self.path
                ) from None
            self._written += n

    def sync(self) -> int:
        """Make everything written so far durable now; return the acknowledged frame count."""
        with self._lock:
            if self._closed.is_set():
                return self._acknowledged
            written = self._written
            fd = self._fd
        os.fsync(fd)
        with self._lock:
            self._acknowledged = max(self._acknowledged, written)
        return self._acknowledged

    def _sync_loop(self) -> None:
        while not self._closed.wait(self.sync_interval_s):
            if self._written != self._acknowledged:
                try:
                    self.sync()
                except OSError:
                    return

    def close(self) -> None:
        """Sync and close; every frame written is acknowledged afterwards (unless the disk refuses the sync)."""
        if self._closed.is_set():
            return
        with contextlib.suppress(OSError):
            self.sync()
        with self._lock:
            self._closed.set()
            os.close(self._fd)
        self._syncer.join(timeout=5.0)

    def __enter__(self) -> "Recorder":
        return self

    def __exit__(self, *exc: object) -> None:
        self.close()


def _sync_folder(path: Path) -> None:
    """Make the file's entry in its folder durable (a new file's name is not covered by fsync of the file)."""
    try:
        folder = os.open(path.parent, os.O_RDONLY)
    except OSError:
        return
    with contextlib.suppress(OSError):
        os.fsync(folder)
    os.close(folder)


@dataclass(frozen=True)
class Record:
    """A record read back.

    Attributes
    ----------
    path : str
        The record file.
    comments : tuple of str
        Comment lines of a record in the earlier format (empty for a plain record).
    columns : dict of str to ndarray
        Every column as floats (NaN where missing), display units as named.
    truncated : bool
        Whether a last line cut short by a crash was dropped.
    metadata : dict
        The JSON sidecar (empty when there is none).
    """

    path: str
    comments: tuple[str, ...]
    columns: dict[str, np.ndarray]
    truncated: bool
    metadata: dict = field(default_factory=dict)

    def __len__(self) -> int:
        return len(self.columns["t_s"])


def read_record(path: str | Path) -> Record:
    """Read a live record (or any CSV with a ``t_s`` column): a cell that is empty, ``nan`` or not a number is NaN.

    Cells are read as ``axiscal measure`` reads frames
    (:func:`~axiscal.measurement.offline.numeric_columns`); lines may end with LF, CRLF or CR.

    In a live record (its sidecar says so, its columns are a record's, or it is in the earlier
    format), a last line without its newline (the process was killed while writing it) is dropped
    and :attr:`Record.truncated` is set; every complete line is returned.

    Parameters
    ----------
    path : str or Path
        The record (or CSV) file.

    Returns
    -------
    Record

    Raises
    ------
    AxiscalError
        If the file is missing, has no header with ``t_s``, or a complete line has a wrong number of
        cells (naming the file and line).
    """
    path = check_path("path", path)
    table, truncated = read_frames_table(path, min_rows=0)
    if "t_s" not in table.header:
        raise AxiscalError(f"no 't_s' column (columns are: {', '.join(table.header)})", path=path, line=table.header_line)
    comments = []
    with open(path, encoding="utf-8-sig", errors="replace") as handle:
        for line in handle:  # the earlier format's comment lines come before the header
            if line.strip() and not line.startswith("#"):
                break
            if line.startswith("#"):
                comments.append(line.strip()[1:].strip())
    columns = numeric_columns(table, table.header)
    side = sidecar_path(path)
    metadata = read_json(side) if side.is_file() else {}
    return Record(str(path), tuple(comments), columns, truncated, metadata if isinstance(metadata, dict) else {})

