"""Squareness between two axes from straightness runs, the pentaprism's correction, and CMM squareness compensation (papers 002 and 004)."""

from __future__ import annotations

from axiscal.squareness.cmm import (
    CmmSquareness,
    GaugeBlockCheck,
    Plane,
    compensate,
    gauge_block_length,
    least_squares_plane,
    psd_squareness,
    readings_for,
    simulate_gauge_block,
    squareness_from_psd_runs,
)
from axiscal.squareness.evaluation import (
    CONVENTIONS,
    PLANES,
    ReversalResult,
    SquarenessResult,
    included_angle_from_iso,
    iso_from_included_angle,
    iso_term,
    prism_deviation_from_wedge,
    prism_reversal,
    psd_angular_resolution,
    read_straightness_run,
    squareness,
    squareness_from_slopes,
)

__all__ = [
    "PLANES",
    "CONVENTIONS",
    "iso_term",
    "iso_from_included_angle",
    "included_angle_from_iso",
    "SquarenessResult",
    "squareness_from_slopes",
    "squareness",
    "ReversalResult",
    "prism_reversal",
    "prism_deviation_from_wedge",
    "psd_angular_resolution",
    "read_straightness_run",
    "CmmSquareness",
    "compensate",
    "readings_for",
    "psd_squareness",
    "squareness_from_psd_runs",
    "Plane",
    "least_squares_plane",
    "gauge_block_length",
    "GaugeBlockCheck",
    "simulate_gauge_block",
]
