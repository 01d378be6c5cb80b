"""Straightness files: the one profile reader, probe readings, and the file-level calls of the commands.

ISO 230-1 straightness of a profile file (``axiscal straightness``) and paper 001's multi-probe
error separation from a readings file (``axiscal separate``); the simulated set-up of
``axiscal simulate probes`` is in :mod:`axiscal.straightness.simulated`. Files are in the units their column names spell; everything
returned is SI. Data CSVs are written plain (header first, no comment lines) with a JSON sidecar
holding their metadata.
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
from axiscal.io.tabular import CsvTable, read_csv, write_csv
from axiscal.straightness.reference import ReferenceLine, reference_line
from axiscal.straightness.report import render_report
from axiscal.straightness.separation import (
    METHODS,
    ProbeReadings,
    Separation,
    reversal,
    separate,
    uneven_step,
)
from axiscal.units import ANGLE_UNITS, MM, UM, length_factor

__all__ = [
    "SEPARATION_METHODS",
    "Profile",
    "read_profile",
    "read_probe_readings",
    "read_reversal_runs",
    "StraightnessEvaluation",
    "evaluate_straightness_file",
    "separation_columns",
    "SeparationRun",
    "separate_file",
]

#: every method ``separate_file`` takes: those of :func:`separate` and ``"reversal"``
SEPARATION_METHODS = (*METHODS, "reversal")

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


# ---------------------------------------------------------------------------------------------
# axiscal straightness


@dataclass(frozen=True)
class StraightnessEvaluation:
    """The straightness of one profile file about its reference line.

    Attributes
    ----------
    profile : Profile
        The profile as read, metres.
    line : ReferenceLine
        The reference line and the straightness, SI.
    """

    profile: Profile
    line: ReferenceLine

    def __post_init__(self) -> None:
        check_instance("profile", self.profile, Profile, what="a Profile (read_profile)")
        check_instance("line", self.line, ReferenceLine, what="a ReferenceLine (reference_line)")

    def payload(self) -> dict[str, Any]:
        """The JSON object: ``straightness_um``, ``slope_urad``, ``intercept_um``, ``reference``."""
        return {
            "straightness_um": self.line.straightness_m / UM,
            "slope_urad": self.line.slope / URAD,
            "intercept_um": self.line.intercept_m / UM,
            "reference": self.line.reference,
        }

    def report(self) -> str:
        """The readable summary (three lines, um and urad)."""
        return render_report("straightness.txt.j2", **self.payload())


def evaluate_straightness_file(
    path: str | Path, *, reference: str = "least-squares", plot_path: str | Path | None = None
) -> StraightnessEvaluation:
    """Straightness of a profile file about a reference line (ISO 230-1), optionally plotted.

    Parameters
    ----------
    path : str or Path
        Profile CSV, read by :func:`read_profile`.
    reference : {"least-squares", "end-points", "minimum-zone"}, keyword-only
        Reference line (default least squares).
    plot_path : str or Path, optional, keyword-only
        Write the profile, its line and zone to this image (format from the suffix).

    Returns
    -------
    StraightnessEvaluation

    Raises
    ------
    AxiscalError
        A bad file (see :func:`read_profile`), an unknown reference, or a line that is not defined
        (end points: a repeated end position), naming the file.

    Examples
    --------
    >>> import pathlib, tempfile
    >>> path = pathlib.Path(tempfile.mkdtemp()) / "p.csv"
    >>> _ = path.write_text("position_mm,deviation_um\\n0,0\\n50,1\\n100,0\\n")
    >>> round(evaluate_straightness_file(path, reference="end-points").payload()["straightness_um"], 6)
    1.0
    """
    profile = read_profile(path)
    try:
        line = reference_line(profile.position_m, profile.deviation_m, reference=reference)
    except AxiscalError as exc:
        raise exc.located(path=path) from None
    if plot_path is not None:
        from axiscal.straightness.plot import plot_straightness

        plot_straightness(plot_path, profile.position_m, profile.deviation_m, line)
    return StraightnessEvaluation(profile, line)


# ---------------------------------------------------------------------------------------------
# axiscal separate


def _cells(values: np.ndarray, scale: float, fmt: str) -> list[str]:
    return ["" if not np.isfinite(v) else fmt.format(v / scale) for v in values]


def _separation(result: Separation, name: str) -> Separation:
    check_instance(name, result, Separation, what="a Separation (separate or reversal)")
    return result


def separation_columns(result: Separation) -> dict[str, list[str]]:
    """The columns a separation is written as.

    Parameters
    ----------
    result : Separation

    Returns
    -------
    dict of str to list of str
        ``position_mm``, ``profile_um``, ``motion_um`` and, when the method resolves yaw,
        ``yaw_urad``; an empty cell where a value is not resolved.
    """
    _separation(result, "result")
    columns = {
        "position_mm": _cells(result.position_m, MM, "{:.4f}"),
        "profile_um": _cells(result.profile_m, UM, "{:.5f}"),
        "motion_um": _cells(result.motion_m, UM, "{:.5f}"),
    }
    if np.any(np.isfinite(result.yaw_rad)):
        columns["yaw_urad"] = _cells(result.yaw_rad, URAD, "{:.5f}")
    return columns


def _write_data(path: str | Path, text: str, **sidecar: Any) -> None:
    """A plain data CSV and its JSON sidecar, each written atomically."""
    write_text(path, text)
    write_sidecar(path, **sidecar)


def _text_and_metadata(csv_text: str, metadata: dict[str, Any]) -> None:
    check_instance("csv_text", csv_text, str, what="the CSV text")
    check_instance("metadata", metadata, dict, what="a dict")


@dataclass(frozen=True)
class SeparationRun:
    """A separation computed from files.

    Attributes
    ----------
    separation : Separation
        The result, SI.
    csv_text : str
        The CSV as written (header first, no comment lines).
    metadata : dict
        What the sidecar holds besides kind, units and sources: method, lost wavelengths (mm).
    """

    separation: Separation
    csv_text: str
    metadata: dict[str, Any]

    def __post_init__(self) -> None:
        _separation(self.separation, "separation")
        _text_and_metadata(self.csv_text, self.metadata)


def separate_file(
    readings_path: str | Path,
    *,
    method: str = "combined",
    spacing_ab_m: float | None = None,
    spacing_bc_m: float | None = None,
    reversed_path: str | Path | None = None,
    probes: int | None = None,
    min_gain: float = 0.05,
    parabola: bool = True,
    calibration_m: tuple[float, float] | None = None,
    output: str | Path | None = None,
    plot_path: str | Path | None = None,
) -> SeparationRun:
    """Separate workpiece profile and slide motion from a readings file (paper 001).

    Parameters
    ----------
    readings_path : str or Path
        Readings (``position_mm, a_um, b_um[, c_um]``); for ``method="reversal"`` the normal run
        (``position_mm, a_um``).
    method : str, keyword-only
        One of :data:`SEPARATION_METHODS` (default ``"combined"``).
    spacing_ab_m, spacing_bc_m : float, keyword-only
        Probe spacings A-B and B-C, metres (B-C defaults to A-B); needed by every method but
        reversal.
    reversed_path : str or Path, keyword-only
        Reversal: the run with the workpiece turned over.
    probes, min_gain, parabola, calibration_m : keyword-only
        Passed to :func:`axiscal.straightness.separation.separate`.
    output : str or Path, optional, keyword-only
        Write the CSV (``position_mm, profile_um, motion_um[, yaw_urad]``) here, with its JSON
        sidecar beside it. The CSV is a valid input of :func:`evaluate_straightness_file`.
    plot_path : str or Path, optional, keyword-only
        Write a plot of the separated profile and motion.

    Returns
    -------
    SeparationRun

    Raises
    ------
    AxiscalError
        A bad file, a missing spacing or reversed run, or readings the method cannot separate
        (naming the file).
    """
    check_path("readings_path", readings_path)
    if not isinstance(method, str) or method not in SEPARATION_METHODS:
        raise AxiscalError(f"unknown separation method {method!r}; use one of {', '.join(SEPARATION_METHODS)}")
    if method == "reversal":
        if reversed_path is None:
            raise AxiscalError("the reversal method needs reversed_path: the run with the workpiece turned over")
        result = reversal(*read_reversal_runs(readings_path, reversed_path))
        sources = [readings_path, reversed_path]
    else:
        if spacing_ab_m is None:
            raise AxiscalError(f"the {method} method needs spacing_ab_m, the probe spacing A-B")
        data = read_probe_readings(readings_path, spacing_ab_m=spacing_ab_m, spacing_bc_m=spacing_bc_m)
        try:
            result = separate(
                data, method=method, probes=probes, min_gain=min_gain, parabola=parabola, calibration_m=calibration_m
            )
        except AxiscalError as exc:
            raise exc.located(path=readings_path) from None
        sources = [readings_path]
    metadata: dict[str, Any] = {
        "method": result.method,
        "note": "profile and motion up to a common straight line",
        "lost_wavelength_mm": (np.sort(result.lost_wavelength_m)[::-1] / MM).tolist(),
    }
    text = write_csv(None, separation_columns(result))
    if output is not None:
        _write_data(output, text, kind="separation", sources=sources, **metadata)
    if plot_path is not None:
        from axiscal.straightness.plot import plot_separation

        plot_separation(plot_path, result)
    return SeparationRun(result, text, metadata)


# ---------------------------------------------------------------------------------------------


# simulated probe readings (axiscal simulate probes) live in simulated.py; the names stay importable from here
from axiscal.straightness.simulated import MAX_READINGS, SimulatedReadings, simulate_probe_readings  # noqa: E402,F401
