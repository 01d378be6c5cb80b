"""Coordinate measuring machines: ISO 10360-2 length measurement tests (E0, E150, R0) and ISO 10360-5 probing tests on a sphere, decided by ISO 14253-1."""

from __future__ import annotations

from axiscal.cmm.acceptance import (
    RAM_OFFSET_M,
    AcceptanceResult,
    LengthMeasurements,
    LengthSet,
    combined_verdict,
    evaluate_acceptance,
    length_acceptance,
    read_length_measurements,
)
from axiscal.cmm.mpe import K_RANGE, LIMIT_M, Mpe
from axiscal.cmm.plot import plot_acceptance, plot_probing
from axiscal.cmm.probing import (
    PROBING_FIGURES,
    SPREAD_LIMIT,
    ProbingResult,
    SphereFit,
    SpherePoints,
    evaluate_probing,
    fit_sphere,
    fit_spread,
    probing_test,
    read_sphere_points,
)

__all__ = [
    "LIMIT_M",
    "K_RANGE",
    "Mpe",
    "RAM_OFFSET_M",
    "LengthMeasurements",
    "read_length_measurements",
    "LengthSet",
    "AcceptanceResult",
    "length_acceptance",
    "evaluate_acceptance",
    "combined_verdict",
    "PROBING_FIGURES",
    "SphereFit",
    "fit_sphere",
    "SPREAD_LIMIT",
    "fit_spread",
    "SpherePoints",
    "read_sphere_points",
    "ProbingResult",
    "probing_test",
    "evaluate_probing",
    "plot_acceptance",
    "plot_probing",
]
