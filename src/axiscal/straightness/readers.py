"""The straightness room's files: the one profile reader, probe readings and reversal runs read into SI, and a data CSV written with its sidecar.

Files are in the units their column names spell; everything returned is SI. Data CSVs are written
plain (header first, no comment lines) with a JSON sidecar holding their metadata. The commands'
file-level calls (:mod:`axiscal.straightness.files`) and the simulated readings
(:mod:`axiscal.straightness.simulated`) build on these.
"""

from __future__ import annotations

from dataclasses import dataclass
from pathlib import Path
from typing import Any

import numpy as np

from axiscal.errors import AxiscalError
from axiscal.io.arguments import check_array, check_instance, check_number, check_path, check_same_length
from axiscal.io.atomic import write_text
from axiscal.io.jsonio import write_sidecar
from axiscal.io.tabular import CsvTable, read_csv
from axiscal.straightness.probes import ProbeReadings, uneven_step
from axiscal.units import ANGLE_UNITS, MM, UM, length_factor

__all__ = [
    "Profile",
    "read_profile",
    "read_probe_readings",
    "read_reversal_runs",
]

URAD = ANGLE_UNITS["urad"]
#: units accepted in the name of a profile's position and deviation columns
POSITION_UNITS = ("mm", "m", "um")
DEVIATION_UNITS = ("um", "nm", "mm")
#: a profile's deviation column: ``deviation_<unit>``, or ``profile_<unit>`` as ``axiscal separate`` writes it
DEVIATION_STEMS = ("deviation", "profile")


@dataclass(frozen=True)
class Profile:
    """A straightness profile read from a file, SI units.

    Attributes
    ----------
    position_m : ndarray, shape (n,)
        Positions along the axis, metres.
    deviation_m : ndarray, shape (n,)
        Deviations across the axis, metres.
    yaw_rad : ndarray, shape (n,) or None
        Yaw from a ``yaw_urad`` column, radians (NaN for an empty cell); None when the file has none.
    path : str
        The file.
    lines : tuple of int
        Line number of each row in the file (for error messages).
    """

    position_m: np.ndarray
    deviation_m: np.ndarray
    yaw_rad: np.ndarray | None
    path: str
    lines: tuple[int, ...]

    def __post_init__(self) -> None:
        object.__setattr__(self, "position_m", check_array("position_m", self.position_m, ndim=1))
        object.__setattr__(self, "deviation_m", check_array("deviation_m", self.deviation_m, ndim=1))
        if self.yaw_rad is not None:  # NaN: a yaw not resolved (an empty cell)
            object.__setattr__(self, "yaw_rad", check_array("yaw_rad", self.yaw_rad, ndim=1, finite=False))
        check_same_length(position_m=self.position_m, deviation_m=self.deviation_m, yaw_rad=self.yaw_rad)
        check_path("path", self.path)


def _bool(name: str, value: Any) -> bool:
    if not isinstance(value, (bool, np.bool_)):
        raise AxiscalError(f"{name} must be True or False, not {value!r}")
    return bool(value)


def _column(table: CsvTable, stems: tuple[str, ...], allowed: tuple[str, ...]) -> tuple[str, float]:
    """The one column named ``<stem>_<unit>`` (first stem that has one) and its factor to metres."""
    for stem in stems:
        names = [name for name in table.header if name.rpartition("_")[0] == stem]
        if len(names) > 1:
            raise AxiscalError(
                f"more than one column {stem}_<unit> ({', '.join(names)})", path=table.path, line=table.header_line
            )
        if names:
            unit = names[0].rpartition("_")[2]
            try:
                return names[0], length_factor(unit, allowed=allowed, what=names[0])
            except AxiscalError as exc:
                raise exc.located(path=table.path, line=table.header_line) from None
    wanted = " or ".join(f"{stems[0]}_{unit}" for unit in allowed)
    raise AxiscalError(f"missing column {wanted} (columns are: {', '.join(table.header)})", path=table.path, line=table.header_line)


def read_profile(path: str | Path, *, increasing: bool = False) -> Profile:
    """Read a straightness profile: positions and deviations, in the units the column names spell.

    The position column is ``position_mm`` (or ``_m``, ``_um``); the deviation column is
    ``deviation_um`` (or ``_nm``, ``_mm``), or ``profile_um`` as ``axiscal separate`` writes it. A
    ``yaw_urad`` column, when present, is read too (an empty cell, a yaw not resolved, is NaN).
    Other columns are ignored.

    Parameters
    ----------
    path : str or Path
        The CSV file.
    increasing : bool, keyword-only
        Require strictly increasing positions (a profile that is interpolated).

    Returns
    -------
    Profile
        Positions and deviations in metres, yaw in radians.

    Raises
    ------
    AxiscalError
        Missing file or column, an unknown unit, a cell that is not a finite number, fewer than 2
        rows, all rows at one position, or (``increasing``) a position not above the one before;
        each naming the file and, where there is one, the line.

    Examples
    --------
    >>> import pathlib, tempfile
    >>> path = pathlib.Path(tempfile.mkdtemp()) / "run.csv"
    >>> _ = path.write_text("position_mm,deviation_um\\n0,1\\n100,2\\n")
    >>> read_profile(path).deviation_m.tolist()
    [1e-06, 2e-06]
    """
    increasing = _bool("increasing", increasing)
    table = read_csv(check_path("path", path), min_rows=2)
    position_name, position_factor = _column(table, ("position",), POSITION_UNITS)
    deviation_name, deviation_factor = _column(table, DEVIATION_STEMS, DEVIATION_UNITS)
    position = table.numeric(position_name) * position_factor
    deviation = table.numeric(deviation_name) * deviation_factor
    yaw = table.numeric("yaw_urad", allow_empty=True) * URAD if table.has("yaw_urad") else None
    if np.ptp(position) == 0.0:
        raise AxiscalError(
            "all rows are at one position: a profile needs at least 2 distinct positions",
            path=table.path,
            line=table.lines[0],
        )
    if increasing and np.any(np.diff(position) <= 0):
        k = int(np.flatnonzero(np.diff(position) <= 0)[0]) + 1
        raise AxiscalError("positions must increase", path=table.path, line=table.lines[k])
    return Profile(position, deviation, yaw, table.path, table.lines)


def read_probe_readings(path: str | Path, *, spacing_ab_m: float, spacing_bc_m: float | None = None) -> ProbeReadings:
    """Read probe readings (``position_mm, a_um, b_um[, c_um]``, position of probe A).

    Parameters
    ----------
    path : str or Path
        The CSV file.
    spacing_ab_m : float, keyword-only
        Probe spacing A-B, metres.
    spacing_bc_m : float, optional, keyword-only
        Probe spacing B-C, metres (default: the A-B spacing); used when the file has ``c_um``.

    Returns
    -------
    ProbeReadings
        Positions and readings in metres.

    Raises
    ------
    AxiscalError
        Missing file or column, a cell that is not a finite number, fewer than 2 rows, or
        positions that do not increase in even steps (every method but reversal needs them):
        the first row that breaks the step is named by its line.
    """
    check_number("spacing_ab_m", spacing_ab_m, positive=True)
    if spacing_bc_m is not None:
        check_number("spacing_bc_m", spacing_bc_m, positive=True)
    table = read_csv(check_path("path", path), min_rows=2)
    table.require("position_mm", "a_um", "b_um")
    position = table.numeric("position_mm")
    k = uneven_step(position)
    if k is not None:
        first = position[1] - position[0]
        problem = (
            f"positions must increase (the first step is {first:g} mm)"
            if not first > 0
            else f"the step from {position[k]:g} mm is {position[k + 1] - position[k]:g} mm where the first step is {first:g} mm"
        )
        raise AxiscalError(
            f"error separation needs evenly stepped positions: {problem}", path=table.path, line=table.lines[k + 1]
        )
    c = table.numeric("c_um") * UM if table.has("c_um") else None
    spacing_bc = None if c is None else (spacing_ab_m if spacing_bc_m is None else spacing_bc_m)
    return ProbeReadings(position * MM, table.numeric("a_um") * UM, table.numeric("b_um") * UM, c, spacing_ab_m, spacing_bc)


def read_reversal_runs(normal_path: str | Path, reversed_path: str | Path) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Read the two runs of a reversal (``position_mm, a_um`` each, at the same positions).

    Parameters
    ----------
    normal_path, reversed_path : str or Path
        The run as mounted and the run with the workpiece turned over.

    Returns
    -------
    position_m, normal_m, reversed_m : ndarray, shape (n,)
        Positions and the two runs' readings, metres.

    Raises
    ------
    AxiscalError
        Missing file or column, a bad cell, fewer than 2 rows, or runs whose positions differ
        (naming the reversed run's line).
    """
    normal = read_csv(check_path("normal_path", normal_path), min_rows=2)
    turned = read_csv(check_path("reversed_path", reversed_path), min_rows=2)
    normal.require("position_mm", "a_um")
    turned.require("position_mm", "a_um")
    x1, x2 = normal.numeric("position_mm"), turned.numeric("position_mm")
    if x1.shape != x2.shape:
        raise AxiscalError(
            f"{len(x2)} readings where the normal run has {len(x1)}: reversal needs the same positions", path=reversed_path
        )
    bad = np.flatnonzero(np.abs(x1 - x2) > 1e-9 * max(1.0, float(np.max(np.abs(x1)))))
    if bad.size:
        k = int(bad[0])
        raise AxiscalError(
            f"position {x2[k]:g} mm where the normal run has {x1[k]:g} mm: reversal needs the same positions",
            path=reversed_path,
            line=turned.lines[k],
        )
    return x1 * MM, normal.numeric("a_um") * UM, turned.numeric("a_um") * UM


def _write_data(path: str | Path, text: str, **sidecar: Any) -> None:
    """A plain data CSV and its JSON sidecar, each written atomically."""
    write_text(path, text)
    write_sidecar(path, **sidecar)


def _text_and_metadata(csv_text: str, metadata: dict[str, Any]) -> None:
    check_instance("csv_text", csv_text, str, what="the CSV text")
    check_instance("metadata", metadata, dict, what="a dict")
