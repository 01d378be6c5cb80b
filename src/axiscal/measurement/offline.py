"""Offline work with the 6-DOF measurement system on files: what ``axiscal measure``, ``calibrate``, ``simulate`` and ``experiment`` do.

Each command is one call here (paper 000: sections 2-3 for :func:`measure_file`, section 4 for
:func:`calibrate_sensitivity` and :func:`calibrate_mirror` with eqs 11-12, section 5 and eq 13 for
:func:`run_diagonal_experiment`). The data CSVs written are plain (the header is the first line)
with their metadata in a JSON sidecar (``<name>.json``); every write is atomic.
"""

from __future__ import annotations

import math
from collections.abc import Mapping, Sequence
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

import numpy as np

from axiscal.errors import AxiscalError
from axiscal.instruments.calibration import (
    Calibration,
    fit_mirror,
    fit_sensitivity,
    load_calibration,
    save_calibration,
    transfer_reference,
)
from axiscal.instruments.reports import render_report
from axiscal.instruments.sensors import roll_from_autocollimation
from axiscal.io.arguments import check_array, check_count, check_instance, check_mapping, check_number, check_path, check_same_length
from axiscal.io.atomic import write_text
from axiscal.io.jsonio import read_json, sidecar_path, write_sidecar
from axiscal.io.tabular import CsvTable, parse_csv, read_csv, read_text, write_csv
from axiscal.measurement.display import to_display
from axiscal.measurement.faults import Fault, fault_legend, fault_text, mark_malformed
from axiscal.measurement.pipeline import MeasurementSystem
from axiscal.measurement.virtual import (
    PATHS,
    STROKE_M,
    DiagonalExperiment,
    VirtualModule,
    diagonal_experiment,
)
from axiscal.units import ARCSEC, MM, UM, angle_factor, length_factor, split_unit

__all__ = [
    "RECORD_KIND",
    "MAX_SIMULATED_FRAMES",
    "load_system",
    "is_live_record",
    "drop_cut_line",
    "numeric_columns",
    "read_frames_table",
    "read_frames",
    "columns_csv",
    "write_data_csv",
    "CsvOutput",
    "MeasureResult",
    "measure_file",
    "calibrate_sensitivity",
    "calibrate_mirror",
    "calibration_text",
    "simulate_frames",
    "simulate_laser",
    "DiagonalReport",
    "run_diagonal_experiment",
]

#: the ``kind`` of a live record's JSON sidecar
RECORD_KIND = "live record"
#: most frames :func:`simulate_frames` makes in one call
MAX_SIMULATED_FRAMES = 10_000_000
#: the paper's published diagonal errors (paper 000 section 5, Fig. 22), um, by load in kg
PAPER_DIAGONAL_UM = {0.0: {"before": 68.0, "after": 13.0}, 2.0: {"before": 56.0, "after": 14.0}}


def load_system(machine: str | Path | None = None, *, seed: int = 0, load_kg: float = 0.0) -> MeasurementSystem:
    """The measurement system of a machine TOML, or of the built-in virtual module.

    Parameters
    ----------
    machine : str or Path, optional
        Machine TOML with ``[axes.<L>.sensors]`` sections; None: the virtual XZ module.
    seed : int
        Seed of the virtual module (only without ``machine``).
    load_kg : float
        Mass on the virtual module's Z slide, kg (only without ``machine``).

    Returns
    -------
    MeasurementSystem

    Raises
    ------
    AxiscalError
        If the machine file is missing or wrong (naming the file).
    """
    if machine is None:
        return VirtualModule(seed=seed, load_kg=load_kg).measurement_system()
    return MeasurementSystem.from_toml(check_path("machine", machine))


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


@dataclass(frozen=True)
class MeasureResult:
    """Recorded frames processed offline (``axiscal measure``).

    Attributes
    ----------
    source : str
        The frames file.
    results : dict of str to ndarray
        The SI result columns of :meth:`MeasurementSystem.process` (``t_s``, ``fault``, ...).
    """

    source: str
    results: dict[str, np.ndarray]

    def __post_init__(self) -> None:
        if not isinstance(self.source, str):
            raise AxiscalError(f"source must be the frames file's name, not {self.source!r}")
        check_mapping("results", self.results, ("t_s", "fault"), what="the results of MeasurementSystem.process with 'fault'")

    @property
    def fault(self) -> np.ndarray:
        """Fault bits of each frame (0 = good)."""
        return self.results["fault"]

    @property
    def faulty_frames(self) -> int:
        """Number of frames with a fault."""
        return int(np.count_nonzero(self.fault))

    def columns(self) -> dict[str, np.ndarray]:
        """The columns of the results CSV: ``t_s``, ``fault``, then every result in display units."""
        shown = to_display(self.results)
        return {"t_s": shown["t_s"], "fault": shown["fault"]} | {k: v for k, v in shown.items() if k not in ("t_s", "fault")}

    def csv_text(self) -> str:
        """The results as plain CSV text."""
        return columns_csv(self.columns())

    def summary(self) -> dict[str, Any]:
        """Frame and fault counts and the largest and mean spatial error of the good frames (um)."""
        good = self.fault == 0
        e_um = self.results["e_m"][good] / UM
        return {
            "frames": int(self.fault.size),
            "faulty_frames": self.faulty_frames,
            "faults": {fault_text(bit): int(np.count_nonzero(self.fault & bit)) for bit in (Fault.MISSING, Fault.RANGE, Fault.POSITION)},
            "max_e_um": float(np.max(e_um)) if e_um.size else None,
            "mean_e_um": float(np.mean(e_um)) if e_um.size else None,
        }


def measure_file(frames_path: str | Path, *, machine: str | Path | None = None, output: str | Path | None = None) -> MeasureResult:
    """Process recorded raw frames offline: six errors per axis, spatial error, corrected position.

    Parameters
    ----------
    frames_path : str or Path
        CSV with ``t_s`` and one column per raw channel (:func:`read_frames`); a live record works.
    machine : str or Path, optional
        Machine TOML with the sensor sections (default: the built-in virtual module).
    output : str or Path, optional
        Write the results CSV (:meth:`MeasureResult.columns`) and its sidecar here.

    Returns
    -------
    MeasureResult

    Raises
    ------
    AxiscalError
        For unreadable input or an output that cannot be written.
    """
    frames_path = check_path("frames_path", frames_path)
    system = load_system(machine)
    frames = read_frames(frames_path, system.channels)
    fault, results = mark_malformed(system.process(frames), ~np.isfinite(frames["t_s"]))
    result = MeasureResult(str(frames_path), results | {"fault": fault})
    if output is not None:
        write_data_csv(
            output,
            result.columns(),
            kind="measured frames",
            sources=[frames_path, *([machine] if machine else [])],
            machine=str(machine) if machine else "built-in virtual module",
            fault_bits=fault_legend(),
            frames=int(result.fault.size),
            faulty_frames=result.faulty_frames,
        )
    return result


def _names(name: str, values: Sequence[str]) -> tuple[str, ...]:
    """A sequence of names (column or channel names), refused when it is a single string or not names."""
    if isinstance(values, (str, bytes)) or not hasattr(values, "__iter__"):
        raise AxiscalError(f"{name} must be a sequence of names (str), not {values!r}")
    values = tuple(values)
    if not all(isinstance(v, str) for v in values):
        raise AxiscalError(f"{name} must be a sequence of names (str), not {values!r}"[:200])
    return values


def _channel_role(system: MeasurementSystem, channel: str):
    if not isinstance(channel, str):
        raise AxiscalError(f"channel must be a channel name, not {channel!r}")
    for letter, head in system.heads.items():
        for role, name in head.channels.items():
            if name == channel:
                return letter, head, role
    raise AxiscalError(f"unknown channel '{channel}'; channels are: {', '.join(system.channels)}")


def _reference_column(table: CsvTable, kinds: tuple[str, ...]) -> tuple[str, str]:
    for column in table.header:
        if column.startswith("reference_"):
            _, unit = split_unit(column)
            if unit not in kinds:
                raise AxiscalError(f"column '{column}': reference unit must be one of {', '.join(kinds)}", path=table.path, line=table.header_line)
            return column, unit
    raise AxiscalError(f"missing column 'reference_<unit>' (unit one of {', '.join(kinds)})", path=table.path, line=table.header_line)


def _angle_column(table: CsvTable, stem: str) -> np.ndarray:
    for unit in ("urad", "arcsec"):
        if table.has(f"{stem}_{unit}"):
            return table.numeric(f"{stem}_{unit}") * angle_factor(unit)
    raise AxiscalError(f"missing column '{stem}_urad' (or _arcsec), needed to transfer the reference", path=table.path, line=table.header_line)


def _save(calibration: Calibration, output: str | Path | None, report: dict[str, Any]) -> dict[str, Any]:
    """Merge ``calibration`` into the file ``output`` (created when missing) and note it in the report."""
    if output is not None:
        merged = load_calibration(output).merged(calibration) if Path(output).exists() else calibration
        save_calibration(merged, output)
        report["output"] = str(output)
    return report


def _line_fit_uncertainty(x: np.ndarray, residual_rms: float) -> tuple[float, float]:
    """Standard uncertainties of gain and offset of a least-squares line ``y = gain * x + offset``.

    The ordinary least-squares standard errors (those ``scipy.stats.linregress`` gives): with ``s``
    the residual standard deviation on n - 2 degrees of freedom, u(gain) = s / sqrt(Sxx) and
    u(offset) = s * sqrt(1/n + mean(x)^2 / Sxx).
    """
    x = np.asarray(x, dtype=float)
    n = len(x)
    if n <= 2:
        return math.inf, math.inf
    s = residual_rms * math.sqrt(n / (n - 2))
    sxx = float(np.sum((x - x.mean()) ** 2))
    if sxx == 0:
        return math.inf, math.inf
    return s / math.sqrt(sxx), s * math.sqrt(1.0 / n + float(x.mean()) ** 2 / sxx)


def _significant_place(scale: float, digits: int = 2) -> int:
    """Decimals that show ``digits`` significant digits of ``scale`` (0 for a zero or non-finite scale)."""
    if not (math.isfinite(scale) and scale > 0):
        return 6
    return max(0, digits - 1 - math.floor(math.log10(scale)))


def calibration_text(report: Mapping[str, Any]) -> str:
    """A calibration report (:func:`calibrate_sensitivity`, :func:`calibrate_mirror`) as text, to the digits that mean something.

    A value with a standard uncertainty (``gain`` and ``gain_u``, ``offset_<unit>`` and
    ``offset_u_<unit>``) is rounded to the second significant digit of its uncertainty; an
    uncertainty, a residual, a range and the cross-validation values are given to two significant
    digits; counts and names as they are. Full precision is in the report itself (``--json``).

    Parameters
    ----------
    report : mapping
        The report dict.

    Returns
    -------
    str
        One ``name: value`` line per entry.

    Examples
    --------
    >>> print(calibration_text({"channel": "x_psd_y_um", "gain": 0.9549890195972108, "gain_u": 0.000123456, "points": 21}), end="")
    channel: x_psd_y_um
    gain: 0.95499
    gain_u: 0.00012
    points: 21
    """
    check_mapping("report", report, what="a calibration report (calibrate_sensitivity, calibrate_mirror)")
    if not report:
        raise AxiscalError("report holds nothing to show")
    lines = []
    for key, value in report.items():
        if isinstance(value, (list, tuple)):
            shown = " ".join(f"{v:.{_significant_place(max(abs(x) for x in value))}f}" for v in value) if value else ""
        elif isinstance(value, bool) or isinstance(value, (int, str)) or value is None:
            shown = str(value)
        else:
            if key == "gain":
                u = report.get("gain_u")
            elif key.startswith("offset_") and not key.startswith("offset_u_"):
                u = report.get("offset_u_" + key.removeprefix("offset_"))
            else:
                u = None
            scale = u if isinstance(u, float) else abs(value)
            shown = f"{value:.{_significant_place(scale)}f}"
        lines.append((key, shown))
    return render_report("measurement/calibration.txt.j2", lines=lines)


def calibrate_sensitivity(
    run_path: str | Path,
    channel: str,
    *,
    machine: str | Path | None = None,
    reference_offset_m: Sequence[float] | None = None,
    output: str | Path | None = None,
) -> dict[str, Any]:
    """Gain and offset of one channel by least squares against a reference instrument (paper 000 section 4.1).

    Parameters
    ----------
    run_path : str or Path
        CSV with the raw channel column and a reference column: ``reference_um`` / ``_mm`` /
        ``_nm`` for scale and PSD channels, ``reference_arcsec`` / ``_urad`` for the quadrant and
        roll detectors.
    channel : str
        The raw channel calibrated, e.g. ``"x_psd_y_um"``.
    machine : str or Path, optional
        Machine TOML with the sensor geometry (default: the virtual module).
    reference_offset_m : sequence of 3 floats, optional
        Sensor point minus reference point, m: the reference of a translation is first moved to
        the sensor's point (section 4.2) with the run's angle columns ``E<A,B,C><axis>_urad`` or
        ``_arcsec``.
    output : str or Path, optional
        Calibration file (JSON) to create or update.

    Returns
    -------
    dict
        ``channel``, ``gain``, ``gain_u`` and ``offset_<unit>``, ``offset_u_<unit>`` (each with
        its standard uncertainty from the fit's residuals), ``residual_max_<unit>``,
        ``residual_rms_<unit>`` (the channel's unit), ``points``; for angle channels also
        ``residual_max_arcsec``; ``output`` when written.

    Raises
    ------
    AxiscalError
        For an unknown channel, missing or wrong columns, an offset on an angle channel, or an
        output that cannot be written.
    """
    run_path = check_path("run_path", run_path)
    system = load_system(machine)
    letter, head, role = _channel_role(system, channel)
    table = read_csv(run_path, min_rows=3)
    raw = table.numeric(channel)
    kind = role.split("_")[0]
    angular = kind in ("qd", "roll")
    column, unit = _reference_column(table, ("arcsec", "urad") if angular else ("nm", "um", "mm"))
    reference = table.numeric(column)
    channel_unit = MM if kind == "scale" else UM
    if angular:
        component = {"qd_u": head.qd_u, "qd_v": head.qd_v, "roll": head.roll}[role]
        focal = head.qd_focal_m if kind == "qd" else 2.0 * head.roll_focal_m
        reference = component.sign * reference * angle_factor(unit) * focal / channel_unit
        if reference_offset_m is not None:
            raise AxiscalError("reference_offset_m applies to translation channels (scale, PSD), not to angles")
    else:
        reference = reference * length_factor(unit, allowed=("nm", "um", "mm")) / channel_unit
        if reference_offset_m is not None:
            offset = check_array("reference_offset_m", reference_offset_m, ndim=1, last=3)
            eps = np.column_stack([_angle_column(table, f"E{r}{letter}") for r in "ABC"])
            component = head.index if kind == "scale" else "xyz".index(role.split("_")[1])
            reference = transfer_reference(reference * channel_unit, eps, offset, component) / channel_unit
    fit = fit_sensitivity(channel, raw, reference)
    unit_name = "mm" if kind == "scale" else "um"
    u_gain, u_offset = _line_fit_uncertainty(raw, fit.residual_rms)
    report: dict[str, Any] = {
        "channel": channel,
        "gain": fit.gain,
        "gain_u": u_gain,
        "offset_" + unit_name: fit.offset,
        "offset_u_" + unit_name: u_offset,
        "residual_max_" + unit_name: fit.residual_max,
        "residual_rms_" + unit_name: fit.residual_rms,
        "points": fit.points,
    }
    if angular:
        report["residual_max_arcsec"] = fit.residual_max * channel_unit / focal / ARCSEC
    return _save(Calibration({channel: fit}), output, report)


def calibrate_mirror(
    run_path: str | Path,
    letter: str,
    *,
    machine: str | Path | None = None,
    max_order: int = 12,
    output: str | Path | None = None,
) -> dict[str, Any]:
    """Map the roll detector's plane mirror against a level (paper 000 eqs 11-12).

    The roll channel's sensitivity calibration (from the machine's calibration file, then from
    ``output`` if it exists) is applied first; the form error module - level is fitted by a
    Legendre polynomial whose order leave-one-out cross-validation picks.

    Parameters
    ----------
    run_path : str or Path
        CSV with ``position_mm``, the raw roll channel (e.g. ``x_roll_um``) and ``level_arcsec``
        or ``level_urad``.
    letter : str
        The axis whose mirror was mapped.
    machine : str or Path, optional
        Machine TOML with the sensor geometry (default: the virtual module).
    max_order : int
        Highest polynomial order tried.
    output : str or Path, optional
        Calibration file (JSON) to create or update.

    Returns
    -------
    dict
        ``axis``, ``order``, ``residual_max_arcsec``, ``residual_rms_arcsec``,
        ``form_error_range_arcsec``, ``cv_rms_arcsec`` (list, one per order tried), ``points``;
        ``output`` when written.

    Raises
    ------
    AxiscalError
        For an axis without sensors, missing columns or an output that cannot be written.
    """
    run_path = check_path("run_path", run_path)
    if not isinstance(letter, str):
        raise AxiscalError(f"letter must be an axis letter, not {letter!r}")
    max_order = check_count("max_order", max_order, minimum=0)
    letter = letter.upper()
    system = load_system(machine)
    if output is not None and Path(output).exists():
        system = system.with_calibration(load_calibration(output))
    if letter not in system.heads:
        raise AxiscalError(f"letter: axis {letter} has no sensors in this machine (axes: {', '.join(system.axes)})")
    head = system.heads[letter]
    channel = head.channels["roll"]
    table = read_csv(run_path, min_rows=4)
    position = table.numeric("position_mm") * MM
    shift = system.calibration.channel(channel).apply(table.numeric(channel)) * UM
    module_roll = head.roll.sign * roll_from_autocollimation(shift, head.roll_focal_m)
    level = _angle_column(table, "level")
    mirror = fit_mirror(letter, position, module_roll, level, max_order=max_order)
    report: dict[str, Any] = {
        "axis": letter,
        "order": mirror.order,
        "residual_max_arcsec": mirror.residual_max_rad / ARCSEC,
        "residual_rms_arcsec": mirror.residual_rms_rad / ARCSEC,
        "form_error_range_arcsec": float(np.ptp(mirror.evaluate(np.linspace(mirror.start_m, mirror.end_m, 200)))) / ARCSEC,
        "cv_rms_arcsec": [v / ARCSEC for v in mirror.cv_rms_rad],
        "points": mirror.points,
    }
    return _save(Calibration({}, {letter: mirror}), output, report)


def simulate_frames(
    *,
    path: str = "diagonal",
    rate_hz: float = 1000.0,
    duration_s: float = 1.0,
    load_kg: float = 0.0,
    seed: int = 0,
    truth: bool = False,
    output: str | Path | None = None,
) -> CsvOutput:
    """Raw frames of the virtual module as CSV: ``t_s`` and every channel, ready for :func:`measure_file`.

    Parameters
    ----------
    path : str
        Motion, one of :data:`~axiscal.measurement.virtual.PATHS`.
    rate_hz : float
        Frames per second, Hz.
    duration_s : float
        Length of the run, s.
    load_kg : float
        Mass on the Z slide, kg.
    seed : int
        Seed of the sensors and the noise.
    truth : bool
        Add the true values as ``truth_<name>`` columns (display units).
    output : str or Path, optional
        Write the CSV and its sidecar here.

    Returns
    -------
    CsvOutput
        The CSV text and its frame count.

    Raises
    ------
    AxiscalError
        For an unknown path or a frame count outside 1 .. :data:`MAX_SIMULATED_FRAMES`.
    """
    rate_hz = check_number("rate_hz", rate_hz, positive=True)
    duration_s = check_number("duration_s", duration_s, positive=True)
    if not isinstance(truth, (bool, np.bool_)):
        raise AxiscalError(f"truth must be True or False, not {truth!r}")
    if not isinstance(path, str) or path not in PATHS:
        raise AxiscalError(f"unknown path {path!r}; use one of {', '.join(PATHS)}")
    count = int(round(duration_s * rate_hz))
    if count < 1 or count > MAX_SIMULATED_FRAMES:
        raise AxiscalError(f"rate_hz x duration_s gives {count} frames; allowed 1 to {MAX_SIMULATED_FRAMES}")
    if path not in PATHS:
        raise AxiscalError(f"unknown path '{path}'; use one of {', '.join(PATHS)}")
    module = VirtualModule(seed=seed, load_kg=load_kg)
    frames, true = module.frames(np.arange(count) / rate_hz, path=path)
    columns = dict(frames)
    if truth:
        columns.update({f"truth_{k}": v for k, v in to_display(true).items() if k != "t_s"})
    meta = dict(source="virtual XZ module (paper 000)", seed=seed, load_kg=load_kg, motion=path, rate_hz=rate_hz, frames=count)
    text = columns_csv(columns) if output is None else write_data_csv(output, columns, kind="raw frames", **meta)
    return CsvOutput(text, count)


def simulate_laser(
    *, steps: int = 19, step_m: float = 0.010, load_kg: float = 0.0, seed: int = 0, output: str | Path | None = None
) -> CsvOutput:
    """Laser interferometer readings on the XZ diagonal of the virtual module, as CSV.

    Columns ``nominal_mm`` (nominal displacement along the diagonal) and ``measured_mm`` (the
    reading, zeroed at the start): the format ``axiscal diagonal --interferometer`` reads.

    Parameters
    ----------
    steps : int
        Steps from the start (0, 0).
    step_m : float
        Move of each axis per step, m.
    load_kg : float
        Mass on the Z slide, kg.
    seed : int
        Seed of the noise.
    output : str or Path, optional
        Write the CSV and its sidecar here.

    Returns
    -------
    CsvOutput
        The CSV text and its number of readings.

    Raises
    ------
    AxiscalError
        If the steps leave the 190 mm travel.
    """
    steps = check_count("steps", steps)
    step_m = check_number("step_m", step_m, positive=True)
    if steps * step_m > STROKE_M + 1e-12:
        raise AxiscalError(f"steps x step_m: {steps} steps of {step_m / MM:g} mm leave the {STROKE_M / MM:g} mm travel")
    module = VirtualModule(seed=seed, load_kg=load_kg)
    q = np.arange(steps + 1) * step_m
    reading = module.laser_diagonal({"X": q, "Z": q.copy()})
    columns = {"nominal_mm": np.hypot(q, q) / MM, "measured_mm": reading / MM}
    meta = dict(source="simulated interferometer on the XZ diagonal of the virtual module", seed=seed, load_kg=load_kg)
    text = columns_csv(columns) if output is None else write_data_csv(output, columns, kind="interferometer readings", **meta)
    return CsvOutput(text, steps + 1)


@dataclass(frozen=True)
class DiagonalReport:
    """The diagonal experiment with what is shown of it (``axiscal experiment diagonal``).

    Attributes
    ----------
    experiment : DiagonalExperiment
        The SI result.
    paper_um : dict or None
        The paper's published before/after values for this load (um), if it published any.
    """

    experiment: DiagonalExperiment
    paper_um: dict[str, float] | None = field(default=None)

    def __post_init__(self) -> None:
        check_instance("experiment", self.experiment, DiagonalExperiment, what="a DiagonalExperiment (diagonal_experiment)")
        if self.paper_um is not None:
            check_mapping("paper_um", self.paper_um, ("before", "after"), what="the paper's before and after values in um")

    def to_dict(self) -> dict[str, Any]:
        """JSON-ready summary and points, display units (mm, um)."""
        e = self.experiment
        return {
            "load_kg": e.load_kg,
            "before_max_um": e.before_max_m / UM,
            "after_max_um": e.after_max_m / UM,
            "scales_only_max_um": e.scales_only_max_m / UM,
            "paper_um": self.paper_um,
            "points": [
                {"x_mm": x / MM, "z_mm": z / MM, "laser_mm": p / MM, "before_um": b / UM, "after_um": a / UM, "scales_only_um": s / UM}
                for x, z, p, b, a, s in zip(e.x_m, e.z_m, e.laser_m, e.before_m, e.after_m, e.scales_only_m)
            ],
        }

    def text(self) -> str:
        """The plain-text report (template ``templates/measurement/diagonal_experiment.txt.j2``)."""
        return render_report("measurement/diagonal_experiment.txt.j2", report=self.to_dict(), steps=self.experiment.x_m.size - 1)


def run_diagonal_experiment(
    *,
    load_kg: float = 0.0,
    seed: int = 0,
    samples: int = 1,
    squareness_error_rad: float = 0.0,
    plot: str | Path | None = None,
) -> DiagonalReport:
    """Paper 000 section 5 on the virtual module: the XZ diagonal against a laser, before and after the model.

    Parameters
    ----------
    load_kg : float
        Mass on the Z slide, kg (the paper's second run uses 2).
    seed : int
        Seed of the sensors and the noise.
    samples : int
        Frames averaged at each stop.
    squareness_error_rad : float
        Error of the squareness in the model, rad.
    plot : str or Path, optional
        Write the figure (like paper 000 Fig. 22) here.

    Returns
    -------
    DiagonalReport

    Raises
    ------
    AxiscalError
        For a negative load or a figure that cannot be written.
    """
    load_kg = check_number("load_kg", load_kg)
    if load_kg < 0:
        raise AxiscalError(f"load_kg must not be negative, got {load_kg:g}")
    experiment = diagonal_experiment(VirtualModule(seed=seed, load_kg=load_kg), samples=samples, squareness_error_rad=squareness_error_rad)
    if plot is not None:
        from axiscal.model.plot import plot_diagonal_experiment

        plot_diagonal_experiment(experiment, plot)
    return DiagonalReport(experiment, PAPER_DIAGONAL_UM.get(float(load_kg)))
