"""Recordings a positioning test is captured from: a Renishaw ``.rtx`` dynamic capture or a time-series CSV.

A recording is a laser's reading over time, with the air and material sensors when they were
recorded beside it. Two file kinds are read:

- ``.rtx``: equally spaced float64 samples (:func:`axiscal.io.importers.rtx.read_rtx`); the file
  does not state its unit, so it must be given.
- CSV: a time column ``time_s`` (``t_s`` as a live record names it) and the reading column: the
  one named by ``channel``, else the only column whose name ends in a length unit (``reading_mm``
  as ``axiscal import rtx`` writes it, ``x_laser_um`` ...). The unit is the column name's; a name
  without one takes the ``unit`` given. The environment columns ``air_temperature_c``,
  ``pressure_pa``, ``humidity_pct`` and ``material_temperature*_c`` are kept beside the reading.
"""

from __future__ import annotations

from collections.abc import Callable, Mapping
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np

from axiscal.errors import AxiscalError
from axiscal.io.arguments import check_array, check_instance, check_mapping, check_path
from axiscal.io.importers.columnmap import IMPORT_UNITS
from axiscal.io.importers.rtx import read_rtx
from axiscal.io.tabular import read_csv

__all__ = ["READING_UNITS", "ENVIRONMENT_COLUMNS", "Recording", "environment_columns", "read_recording"]

#: units a reading may be given in, and metres per unit
READING_UNITS: Mapping[str, float] = IMPORT_UNITS
#: the environment columns of a positioning run, in the order they are written
ENVIRONMENT_COLUMNS = ("air_temperature_c", "pressure_pa", "humidity_pct", "material_temperature_c")
_TIME_COLUMNS = ("time_s", "t_s")


def environment_columns(names) -> tuple[str, ...]:
    """The names among ``names`` that are air or material sensor columns of a positioning run.

    Parameters
    ----------
    names : iterable of str
        Column or channel names.

    Returns
    -------
    tuple of str
        ``air_temperature_c``, ``pressure_pa``, ``humidity_pct`` and every ``material_temperature*_c``,
        in the order given.

    Raises
    ------
    AxiscalError
        For ``names`` that are not a sequence of names.
    """
    if isinstance(names, str) or not hasattr(names, "__iter__"):
        raise AxiscalError(f"names must be a sequence of column names, not {names!r}")
    return tuple(
        n for n in names
        if isinstance(n, str) and (n in ENVIRONMENT_COLUMNS[:3] or (n.startswith("material_temperature") and n.endswith("_c")))
    )


@dataclass(frozen=True)
class Recording:
    """A laser reading over time, with the sensors recorded beside it.

    Attributes
    ----------
    time_s : ndarray, shape (n,), seconds
        Sample times, increasing.
    reading_m : ndarray, shape (n,), metres
        The reading at each time.
    channels : dict of str to ndarray, shape (n,)
        Environment columns (air and material sensors), each in the unit its name ends in.
    source : str
        The file read (or a description of the stream).
    header : dict of str to str
        The capture's header (an ``.rtx`` file's ``Key: value`` lines), empty for a CSV.
    locate : callable or None
        Line of the file that holds sample k (a CSV), None where samples have no lines (``.rtx``).
    """

    time_s: np.ndarray
    reading_m: np.ndarray
    channels: Mapping[str, np.ndarray] = field(default_factory=dict)
    source: str = "<recording>"
    header: Mapping[str, str] = field(default_factory=dict)
    locate: Callable[[int], int] | None = None

    def __post_init__(self) -> None:
        time_s = check_array("time_s", self.time_s, ndim=1, unit="s")
        reading = check_array("reading_m", self.reading_m, ndim=1, finite=False, unit="m")
        if reading.shape != time_s.shape:
            raise AxiscalError(f"reading_m must hold one reading per time ({time_s.size}), not {reading.size}")
        check_mapping("channels", self.channels, what="a mapping of sensor columns to arrays")
        for name, values in self.channels.items():
            if not isinstance(name, str) or np.shape(values) != time_s.shape:
                raise AxiscalError(f"channels must map names to arrays of {time_s.size} values, not {name!r}")
        check_instance("source", self.source, str)
        if self.locate is not None and not callable(self.locate):
            raise AxiscalError(f"locate must be a function of the sample index, not {self.locate!r}")

    def line_of(self, index: int) -> int | None:
        """Line of the file holding sample ``index`` (None for a file without lines)."""
        return None if self.locate is None else self.locate(int(index))


def _unit_of(name: str) -> str | None:
    unit = name.rpartition("_")[2]
    return unit if "_" in name and unit in READING_UNITS else None


def read_recording(path: str | Path, *, unit: str | None = None, channel: str | None = None) -> Recording:
    """Read a recording: an ``.rtx`` capture or a CSV with ``time_s`` and a reading column.

    Parameters
    ----------
    path : str or Path
        The file; ``.rtx`` (any case) is read as a Renishaw capture, anything else as CSV.
    unit : str, optional, keyword-only
        Unit of the readings (``nm``, ``um``, ``mm``, ``m``, ``in``): needed for an ``.rtx`` file
        and for a CSV column whose name has no unit; where the column name has one, it must agree.
    channel : str, optional, keyword-only
        The CSV column holding the reading (default: the only column named with a length unit).

    Returns
    -------
    Recording

    Raises
    ------
    AxiscalError
        Naming the file: an unknown unit, no unit for an ``.rtx`` file or a unitless column, a
        unit that contradicts the column's name, no time column, no reading column or more than
        one candidate, a channel that is not a column; and whatever the readers refuse.

    Examples
    --------
    >>> rec = read_recording("examples/capture/recording_x.csv")  # doctest: +SKIP
    >>> rec.time_s.size > 0  # doctest: +SKIP
    True
    """
    path = check_path("path", path)
    if unit is not None and unit not in READING_UNITS:
        raise AxiscalError(f"unknown unit '{unit}' for the readings; use one of {', '.join(READING_UNITS)}")
    if path.suffix.lower() == ".rtx":
        if unit is None:
            raise AxiscalError("unit must be given (mm, um, nm, m or in): an .rtx capture does not say the unit of its samples",
                               path=path)
        capture = read_rtx(path, unit=unit)
        return Recording(capture.time_s, capture.samples_m, {}, str(path), dict(capture.header), None)
    table = read_csv(path, min_rows=1)
    time_name = next((name for name in _TIME_COLUMNS if table.has(name)), None)
    if time_name is None:
        raise AxiscalError("no time column: a recording needs time_s (seconds)", path=path, line=table.header_line)
    environment = environment_columns(table.header)
    if channel is not None:
        if not table.has(channel):
            raise AxiscalError(f"no column '{channel}' (the reading's channel); the columns are {', '.join(table.header)}",
                               path=path, line=table.header_line)
        name = channel
    else:
        candidates = [n for n in table.header if _unit_of(n) is not None and n not in environment and n != time_name]
        if not candidates:  # one column besides the time and the sensors: the reading, its unit given apart
            candidates = [n for n in table.header if n not in environment and n != time_name][:2]
        if len(candidates) != 1:
            found = ", ".join(candidates) if candidates else "none"
            raise AxiscalError(
                f"channel must name the column that holds the reading: columns named with a length unit: {found}",
                path=path, line=table.header_line,
            )
        name = candidates[0]
    named = _unit_of(name)
    if named is not None and unit is not None and unit != named:
        raise AxiscalError(f"column {name} is in {named}, not in {unit} as the unit given says", path=path, line=table.header_line)
    used = named or unit
    if used is None:
        raise AxiscalError(f"unit must be given (mm, um, nm, m or in): column {name} does not say its unit", path=path,
                           line=table.header_line)
    time_s = table.numeric(time_name)
    if np.any(np.diff(time_s) < 0):
        k = int(np.flatnonzero(np.diff(time_s) < 0)[0]) + 1
        raise AxiscalError(f"{time_name} goes back ({time_s[k - 1]:g} s, then {time_s[k]:g} s)", path=path, line=table.line_of(k))
    reading = table.numeric(name) * READING_UNITS[used]
    channels = {c: table.numeric(c) for c in environment}
    return Recording(time_s, reading, channels, str(path), {}, table.line_of)
