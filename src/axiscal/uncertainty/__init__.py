"""Measurement uncertainty: the budget file, U of the ISO 230-2 figures (GTC), Monte Carlo (GUM Supplement 1) and decision rules (ISO 14253-1), straightness and squareness, the volumetric map with uncertainty, the U and verdict of a campaign test's figures."""

from __future__ import annotations

from axiscal.uncertainty.budget import (
    BUDGET_KEYS,
    BUDGET_RANGES,
    COMPONENTS,
    HE_NE_WAVELENGTH_NM,
    Budget,
    air_sensitivities,
    budget_from_dict,
    budget_from_tables,
    length_components,
    length_model,
    read_budget,
)
from axiscal.uncertainty.decision import DECISION_RULES, Decision, decide
from axiscal.uncertainty.figures import (
    UNCERTAINTY_KINDS,
    figure_uncertainties,
    figure_verdicts,
)
from axiscal.uncertainty.montecarlo import CoverageInterval, coverage_interval
from axiscal.uncertainty.plot import plot_volumetric_uncertainty
from axiscal.uncertainty.positioning import (
    COVERAGE_FACTOR,
    FIGURE_COMPONENTS,
    FIGURES,
    MAX_POSITIONING_DRAWS,
    PositioningUncertainty,
    PositioningWithUncertainty,
    budget_report,
    evaluate_positioning_with_uncertainty,
    positioning_decisions,
    positioning_monte_carlo,
    positioning_uncertainty,
    uncertainty_payload,
)
from axiscal.uncertainty.straightness import (
    LineUncertainty,
    squareness_uncertainty,
    straightness_uncertainty,
)
from axiscal.uncertainty.volumetric import (
    MAX_DRAW_POINTS,
    SCHEDULER_TIMEOUT_S,
    MachineUncertainty,
    VolumetricUncertainty,
    load_machine_uncertainty,
    volumetric_monte_carlo,
    volumetric_uncertainty_columns,
    write_volumetric_uncertainty,
)
from axiscal.uncertainty.volumetric_map import (
    VolumetricUncertaintyMap,
    volumetric_uncertainty_map,
)

__all__ = [
    "COMPONENTS",
    "BUDGET_KEYS",
    "BUDGET_RANGES",
    "HE_NE_WAVELENGTH_NM",
    "Budget",
    "budget_from_dict",
    "budget_from_tables",
    "read_budget",
    "air_sensitivities",
    "length_model",
    "length_components",
    "DECISION_RULES",
    "Decision",
    "decide",
    "UNCERTAINTY_KINDS",
    "figure_uncertainties",
    "figure_verdicts",
    "CoverageInterval",
    "coverage_interval",
    "FIGURES",
    "FIGURE_COMPONENTS",
    "COVERAGE_FACTOR",
    "MAX_POSITIONING_DRAWS",
    "PositioningUncertainty",
    "PositioningWithUncertainty",
    "evaluate_positioning_with_uncertainty",
    "positioning_uncertainty",
    "positioning_monte_carlo",
    "uncertainty_payload",
    "budget_report",
    "positioning_decisions",
    "LineUncertainty",
    "straightness_uncertainty",
    "squareness_uncertainty",
    "MachineUncertainty",
    "VolumetricUncertainty",
    "load_machine_uncertainty",
    "volumetric_monte_carlo",
    "write_volumetric_uncertainty",
    "volumetric_uncertainty_columns",
    "MAX_DRAW_POINTS",
    "SCHEDULER_TIMEOUT_S",
    "VolumetricUncertaintyMap",
    "volumetric_uncertainty_map",
    "plot_volumetric_uncertainty",
]
