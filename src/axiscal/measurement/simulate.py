"""Files simulated on the virtual module: raw frames and a laser interferometer's readings on the XZ diagonal (``axiscal simulate``)."""

from __future__ import annotations

from pathlib import Path

import numpy as np

from axiscal.errors import AxiscalError
from axiscal.io.arguments import check_count, check_number
from axiscal.measurement.display import to_display
from axiscal.measurement.frames import CsvOutput, columns_csv, write_data_csv
from axiscal.measurement.virtual import PATHS, STROKE_M, VirtualModule
from axiscal.units import MM

__all__ = ["MAX_SIMULATED_FRAMES", "simulate_frames", "simulate_laser"]

#: most frames :func:`simulate_frames` makes in one call
MAX_SIMULATED_FRAMES = 10_000_000


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
