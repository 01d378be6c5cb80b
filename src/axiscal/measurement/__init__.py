"""From raw sensor frames to the error of the functional point (paper 000), and the virtual instrument that simulates them."""

from __future__ import annotations

from axiscal.measurement.faults import FAULT_TEXT, Fault, fault_legend, fault_text
from axiscal.measurement.pipeline import (
    MeasurementSystem,
    diagonal_errors,
    spatial_error,
)
from axiscal.measurement.virtual import (
    INTERFEROMETER_BEAM_M,
    NOISE,
    PATHS,
    QD_FOCAL_M,
    REFERENCE_NOISE,
    ROLL_FOCAL_M,
    SQUARENESS_EB0Z_RAD,
    STROKE_M,
    TOOL_M,
    Z_ORIGIN_M,
    DiagonalExperiment,
    Truth,
    VirtualModule,
    diagonal_experiment,
)

__all__ = [
    "Fault",
    "FAULT_TEXT",
    "fault_text",
    "fault_legend",
    "MeasurementSystem",
    "spatial_error",
    "diagonal_errors",
    "STROKE_M",
    "SQUARENESS_EB0Z_RAD",
    "TOOL_M",
    "Z_ORIGIN_M",
    "PATHS",
    "INTERFEROMETER_BEAM_M",
    "QD_FOCAL_M",
    "ROLL_FOCAL_M",
    "NOISE",
    "REFERENCE_NOISE",
    "Truth",
    "VirtualModule",
    "DiagonalExperiment",
    "diagonal_experiment",
]
