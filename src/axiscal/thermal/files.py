"""Thermal test files: the run reader and the evaluations behind ``axiscal thermal etve`` and ``drift``.

ISO 230-3 runs (see :mod:`axiscal.thermal.analysis`): ``time_s`` or ``time_h``; the displacements
``x_um``, ``y_um``, ``z_um`` (those measured, one at least: the ETVE and the drift are displacements
of the functional point) and the tilts ``a_urad``, ``b_urad`` beside them;
temperatures ``temperature_<place>_c``; for a distortion test optionally ``running`` (1 while the
spindle rotates or the axis moves, 0 while it stands). Other columns are ignored.
"""

from __future__ import annotations

import re
from dataclasses import dataclass
from pathlib import Path
from typing import Any

import numpy as np

from axiscal.errors import AxiscalError
from axiscal.io.arguments import check_array, check_instance, check_mapping, check_number, check_path, render_checked
from axiscal.io.tabular import read_csv
from axiscal.io.templates import render_template
from axiscal.thermal.analysis import LINEAR_DIRECTIONS, DriftResult, EtveResult, etve, thermal_drift
from axiscal.units import UM, URAD

__all__ = ["DISPLACEMENT_COLUMNS", "ThermalRun", "read_thermal_run", "EtveEvaluation", "evaluate_etve",
           "DriftEvaluation", "evaluate_drift"]

#: column -> (direction, SI per unit)
DISPLACEMENT_COLUMNS = {"x_um": ("X", UM), "y_um": ("Y", UM), "z_um": ("Z", UM), "a_urad": ("A", URAD), "b_urad": ("B", URAD)}
_TEMPERATURE = re.compile(r"temperature_(.+)_c")
HOUR = 3600.0


@dataclass(frozen=True)
class ThermalRun:
    """A thermal test run read from a file, SI.

    Attributes
    ----------
    time_s : ndarray, shape (n,)
        Sample times, seconds.
    displacements : dict of str to ndarray
        Direction (X, Y, Z in metres; A, B in radians) to displacement.
    temperatures_c : dict of str to ndarray
        Sensor place to temperature, degC.
    running : ndarray of float, shape (n,), or None
        1 while heating, 0 while cooling; None without a ``running`` column.
    path : str
        The file.
    """

    time_s: np.ndarray
    displacements: dict[str, np.ndarray]
    temperatures_c: dict[str, np.ndarray]
    running: np.ndarray | None
    path: str

    def __post_init__(self) -> None:
        object.__setattr__(self, "time_s", check_array("time_s", self.time_s, ndim=1))
        check_mapping("displacements", self.displacements)
        check_mapping("temperatures_c", self.temperatures_c)
        if self.running is not None:
            object.__setattr__(self, "running", check_array("running", self.running, ndim=1))
        check_path("path", self.path)


def read_thermal_run(path: str | Path) -> ThermalRun:
    """Read a thermal test run (``time_s`` or ``time_h``, displacements, temperatures, ``running``).

    Parameters
    ----------
    path : str or Path
        The CSV file.

    Returns
    -------
    ThermalRun

    Raises
    ------
    AxiscalError
        A missing file, no time column or both, no displacement column (x_um, y_um or z_um: tilts
        alone are refused), a cell that is not a
        finite number, fewer than 3 rows, a time not after the one before, a ``running`` cell other
        than 0 or 1; naming the file and, where there is one, the line.

    Examples
    --------
    >>> import pathlib, tempfile
    >>> path = pathlib.Path(tempfile.mkdtemp()) / "run.csv"
    >>> _ = path.write_text("time_h,z_um,temperature_air_c\\n0,0,20\\n1,-2,21\\n2,-3,21.5\\n")
    >>> run = read_thermal_run(path)
    >>> run.time_s.tolist(), sorted(run.temperatures_c)
    ([0.0, 3600.0, 7200.0], ['air'])
    """
    table = read_csv(check_path("path", path), min_rows=3)
    times = [name for name in ("time_s", "time_h") if table.has(name)]
    if len(times) != 1:
        problem = "no time column" if not times else "both time_s and time_h"
        raise AxiscalError(f"{problem}: give time_s or time_h", path=table.path, line=table.header_line)
    time = table.numeric(times[0]) * (HOUR if times[0] == "time_h" else 1.0)
    steps = np.diff(time)
    if np.any(steps <= 0.0):
        k = int(np.flatnonzero(steps <= 0.0)[0]) + 1
        raise AxiscalError("times must increase", path=table.path, line=table.lines[k])
    displacements = {d: table.numeric(c) * f for c, (d, f) in DISPLACEMENT_COLUMNS.items() if table.has(c)}
    if not set(displacements) & set(LINEAR_DIRECTIONS):
        linear = [c for c, (d, _) in DISPLACEMENT_COLUMNS.items() if d in LINEAR_DIRECTIONS]
        tilts = [c for c, (d, _) in DISPLACEMENT_COLUMNS.items() if d not in LINEAR_DIRECTIONS]
        raise AxiscalError(f"no displacement column: give one of {', '.join(linear)} (the tilts {', '.join(tilts)} are"
                           " read beside one, never alone)", path=table.path, line=table.header_line)
    temperatures = {}
    for name in table.header:
        found = _TEMPERATURE.fullmatch(name)
        if found:
            temperatures[found.group(1)] = table.numeric(name)
    running = None
    if table.has("running"):
        running = table.numeric("running")
        bad = np.flatnonzero((running != 0) & (running != 1))
        if bad.size:
            raise AxiscalError("column 'running' holds 1 (heating) or 0 (cooling)", path=table.path, line=table.lines[bad[0]])
    return ThermalRun(time, displacements, temperatures, running, table.path)


def _scaled(values: dict[str, float]) -> tuple[dict[str, float], dict[str, float]]:
    """Per-direction SI values split into um (X, Y, Z) and urad (A, B)."""
    return ({k: v / UM for k, v in values.items() if k in "XYZ"}, {k: v / URAD for k, v in values.items() if k in "AB"})


def _finite(value: float) -> float | None:
    return float(value) if np.isfinite(value) else None


@dataclass(frozen=True)
class EtveEvaluation:
    """An ETVE run file evaluated.

    Attributes
    ----------
    run : ThermalRun
    result : EtveResult
    """

    run: ThermalRun
    result: EtveResult

    def __post_init__(self) -> None:
        check_instance("run", self.run, ThermalRun, what="a ThermalRun (read_thermal_run)")
        check_instance("result", self.result, EtveResult, what="an EtveResult (etve)")

    def payload(self) -> dict[str, Any]:
        """The JSON object: ``etve_um`` (and ``etve_urad`` for tilts) per direction, ``temperature_range_c``,
        ``correlations`` (``direction``, ``sensor``, ``r``, ``lag_h``, ``r_at_lag``, ``sensitivity_um_per_k``
        or ``sensitivity_urad_per_k``), ``duration_h``, ``samples``."""
        um, urad = _scaled(self.result.etve)
        out: dict[str, Any] = {"etve_um": um}
        if urad:
            out["etve_urad"] = urad
        out["temperature_range_c"] = dict(self.result.temperature_range_c)
        correlations = []
        for c in self.result.correlations:
            unit, factor = ("urad", URAD) if c.direction in "AB" else ("um", UM)
            correlations.append({"direction": c.direction, "sensor": c.sensor, "r": _finite(c.r), "lag_h": c.lag_s / HOUR,
                                 "r_at_lag": _finite(c.r_at_lag), f"sensitivity_{unit}_per_k": _finite(c.sensitivity / factor)})
        out["correlations"] = correlations
        out["duration_h"] = self.result.duration_s / HOUR
        out["samples"] = int(self.run.time_s.size)
        return out

    def report(self) -> str:
        """The readable summary."""
        return render_checked(render_template, "thermal_etve.txt.j2", **self.payload()).rstrip("\n")


def evaluate_etve(path: str | Path, *, max_lag_s: float | None = None) -> EtveEvaluation:
    """The ETVE of a run file (what ``axiscal thermal etve`` does).

    Parameters
    ----------
    path : str or Path
        The run, read by :func:`read_thermal_run`; it needs a temperature column.
    max_lag_s : float, optional, keyword-only
        The largest lag of the correlations, seconds (default a quarter of the duration).

    Returns
    -------
    EtveEvaluation

    Raises
    ------
    AxiscalError
        A bad file (see :func:`read_thermal_run`), no temperature column, a negative lag; naming the file.
    """
    if max_lag_s is not None:
        max_lag_s = check_number("max_lag_s", max_lag_s, nonnegative=True)
    run = read_thermal_run(path)
    if not run.temperatures_c:
        raise AxiscalError("no temperature column temperature_<place>_c: the ETVE is read against the temperatures", path=path)
    try:
        result = etve(run.time_s, run.displacements, run.temperatures_c, max_lag_s=max_lag_s)
    except AxiscalError as exc:
        raise exc.located(path=path) from None
    return EtveEvaluation(run, result)


@dataclass(frozen=True)
class DriftEvaluation:
    """A thermal distortion run file evaluated.

    Attributes
    ----------
    run : ThermalRun
    result : DriftResult
    """

    run: ThermalRun
    result: DriftResult

    def __post_init__(self) -> None:
        check_instance("run", self.run, ThermalRun, what="a ThermalRun (read_thermal_run)")
        check_instance("result", self.result, DriftResult, what="a DriftResult (thermal_drift)")

    def payload(self) -> dict[str, Any]:
        """The JSON object: per direction ``drift_max_um``, ``drift_range_um``, ``drift_end_um``,
        ``drift_heating_end_um`` (with phases), ``time_constant_h`` (tilts under ``..._urad``),
        and ``temperature_range_c``, ``heating_phases``, ``duration_h``, ``samples``."""
        r = self.result
        out: dict[str, Any] = {}
        for key, values in (("drift_max", r.drift_max), ("drift_range", r.drift_range), ("drift_end", r.drift_end),
                            ("drift_heating_end", r.drift_heating_end)):
            um, urad = _scaled(values)
            if um:
                out[f"{key}_um"] = um
            if urad:
                out[f"{key}_urad"] = urad
        out["time_constant_h"] = {k: _finite(v / HOUR) for k, v in r.time_constant_s.items()}
        out["temperature_range_c"] = dict(r.temperature_range_c)
        out["heating_phases"] = r.heating_phases
        out["duration_h"] = r.duration_s / HOUR
        out["samples"] = int(self.run.time_s.size)
        return out

    def report(self) -> str:
        """The readable summary: one row per direction."""
        payload = self.payload()
        rows = []
        for direction in self.result.drift_max:
            unit = "urad" if direction in "AB" else "um"
            rows.append({"direction": direction, "unit": unit, "max": payload[f"drift_max_{unit}"][direction],
                         "range": payload[f"drift_range_{unit}"][direction], "end": payload[f"drift_end_{unit}"][direction],
                         "heating_end": payload.get(f"drift_heating_end_{unit}", {}).get(direction),
                         "tau_h": payload["time_constant_h"][direction]})
        return render_checked(render_template, "thermal_drift.txt.j2", rows=rows, duration_h=payload["duration_h"],
                              samples=payload["samples"], heating_phases=payload["heating_phases"],
                              temperature_range_c=payload["temperature_range_c"]).rstrip("\n")


def evaluate_drift(path: str | Path) -> DriftEvaluation:
    """The thermal drift of a distortion run file (what ``axiscal thermal drift`` does).

    Parameters
    ----------
    path : str or Path
        The run, read by :func:`read_thermal_run`.

    Returns
    -------
    DriftEvaluation

    Raises
    ------
    AxiscalError
        A bad file (see :func:`read_thermal_run`), naming the file.
    """
    run = read_thermal_run(path)
    try:
        result = thermal_drift(run.time_s, run.displacements, run.temperatures_c, running=run.running)
    except AxiscalError as exc:
        raise exc.located(path=path) from None
    return DriftEvaluation(run, result)
