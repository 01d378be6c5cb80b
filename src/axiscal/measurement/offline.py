"""Offline work with the 6-DOF measurement system on files: what ``axiscal measure``, ``calibrate``, ``simulate`` and ``experiment`` do.

Each command is one call here (paper 000: sections 2-3 for :func:`measure_file`, section 5 and eq 13
for :func:`run_diagonal_experiment`; section 4, the calibrations with eqs 11-12, is in
:mod:`axiscal.measurement.calibrate`). The data CSVs written are plain (the header is the first line)
with their metadata in a JSON sidecar (``<name>.json``); every write is atomic.
"""

from __future__ import annotations

from collections.abc import Mapping, Sequence
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

import numpy as np

from axiscal.errors import AxiscalError
from axiscal.instruments.reports import render_report
from axiscal.io.arguments import check_count, check_instance, check_mapping, check_number, check_path, check_same_length
from axiscal.io.atomic import write_text
from axiscal.io.jsonio import read_json, sidecar_path, write_sidecar
from axiscal.io.tabular import CsvTable, parse_csv, read_text, write_csv
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
from axiscal.units import MM, UM

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


# the calibrations (axiscal calibrate) live in calibrate.py; the names stay importable from here
from axiscal.measurement.calibrate import calibrate_mirror, calibrate_sensitivity, calibration_text  # noqa: E402,F401
