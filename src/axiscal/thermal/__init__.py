"""Thermal tests (ISO 230-3): the environmental temperature variation error and thermal drift, with their correlations."""

from __future__ import annotations

from axiscal.thermal.analysis import (
    DIRECTIONS,
    LINEAR_DIRECTIONS,
    Correlation,
    DriftResult,
    EtveResult,
    correlate,
    etve,
    fit_time_constant,
    thermal_drift,
)
from axiscal.thermal.files import (
    DISPLACEMENT_COLUMNS,
    DriftEvaluation,
    EtveEvaluation,
    ThermalRun,
    evaluate_drift,
    evaluate_etve,
    read_thermal_run,
)
from axiscal.thermal.plot import plot_drift, plot_etve, plot_thermal

__all__ = [
    "DIRECTIONS",
    "LINEAR_DIRECTIONS",
    "Correlation",
    "correlate",
    "fit_time_constant",
    "EtveResult",
    "etve",
    "DriftResult",
    "thermal_drift",
    "DISPLACEMENT_COLUMNS",
    "ThermalRun",
    "read_thermal_run",
    "EtveEvaluation",
    "evaluate_etve",
    "DriftEvaluation",
    "evaluate_drift",
    "plot_thermal",
    "plot_etve",
    "plot_drift",
]
