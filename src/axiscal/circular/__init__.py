"""Circular tests of two linear axes with a ballbar: ISO 230-4 figures, diagnostics of the machine errors, the reader, a virtual machine and the polar plot."""

from __future__ import annotations

from axiscal.circular.diagnostics import (
    MIN_PITCH_M,
    SERVO_WARNING,
    SPIKE_WINDOW_DEG,
    BallbarDiagnostics,
    backlash_signature,
    diagnose,
    reversal_angles,
)
from axiscal.circular.evaluation import (
    DIRECTIONS,
    MAX_GAP_DEG,
    MIN_POINTS,
    MM_PER_MIN,
    PLANES,
    BallbarTrace,
    CircularFigures,
    check_direction,
    coverage_gap,
    iso230_4,
    lsq_circle,
    plane_axes,
    radial_deviations,
)
from axiscal.circular.plot import plot_ballbar
from axiscal.circular.reader import DEVIATION_STEM, read_ballbar
from axiscal.circular.report import (
    MS,
    PPM,
    STANDARD,
    BallbarResult,
    ballbar_payload,
    evaluate_ballbar,
    evaluate_ballbar_file,
    format_number,
    iso_squareness,
    render_report,
)
from axiscal.circular.simulation import (
    SPIKE_WIDTH_DEG,
    simulate_ballbar,
    trace_csv,
    write_trace,
)

__all__ = [
    "DIRECTIONS",
    "MAX_GAP_DEG",
    "MIN_POINTS",
    "MM_PER_MIN",
    "PLANES",
    "BallbarTrace",
    "CircularFigures",
    "coverage_gap",
    "check_direction",
    "plane_axes",
    "lsq_circle",
    "radial_deviations",
    "iso230_4",
    "SPIKE_WINDOW_DEG",
    "MIN_PITCH_M",
    "SERVO_WARNING",
    "BallbarDiagnostics",
    "reversal_angles",
    "backlash_signature",
    "diagnose",
    "DEVIATION_STEM",
    "read_ballbar",
    "PPM",
    "MS",
    "STANDARD",
    "BallbarResult",
    "iso_squareness",
    "evaluate_ballbar",
    "evaluate_ballbar_file",
    "ballbar_payload",
    "format_number",
    "render_report",
    "SPIKE_WIDTH_DEG",
    "simulate_ballbar",
    "trace_csv",
    "write_trace",
    "plot_ballbar",
]
