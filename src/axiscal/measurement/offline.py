"""Offline work with the 6-DOF measurement system on files: what ``axiscal measure``, ``calibrate``, ``simulate`` and ``experiment`` do.

Each command is one call here (paper 000: sections 2-3 for :func:`measure_file`; section 4, the
calibrations with eqs 11-12, from :mod:`axiscal.measurement.calibrate`; section 5 and eq 13, the
diagonal experiment, from :mod:`axiscal.measurement.experiment`; the simulated files from
:mod:`axiscal.measurement.simulate`). This module is the top of the room's file work: the frames
files it reads and writes are :mod:`axiscal.measurement.frames`, which the others use too.
"""

from __future__ import annotations

from dataclasses import dataclass
from pathlib import Path
from typing import Any

import numpy as np

from axiscal.errors import AxiscalError
from axiscal.io.arguments import check_mapping, check_path
from axiscal.measurement.calibrate import calibrate_mirror, calibrate_sensitivity, calibration_text
from axiscal.measurement.display import to_display
from axiscal.measurement.experiment import DiagonalReport, run_diagonal_experiment
from axiscal.measurement.faults import Fault, fault_legend, fault_text, mark_malformed
from axiscal.measurement.frames import (
    RECORD_KIND,
    CsvOutput,
    columns_csv,
    drop_cut_line,
    is_live_record,
    numeric_columns,
    read_frames,
    read_frames_table,
    write_data_csv,
)
from axiscal.measurement.simulate import MAX_SIMULATED_FRAMES, simulate_frames, simulate_laser
from axiscal.measurement.system import load_system
from axiscal.units import UM

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
