"""Calibration campaigns: a folder of test data described by campaign.toml, run as one job."""

from __future__ import annotations

from axiscal.campaign.config import (
    CAMPAIGN_FILE,
    CONTROLLERS,
    KINDS,
    POSITIONING_TOLERANCE_KEYS,
    TABLE_KEYS,
    Campaign,
    TestSpec,
    load_campaign,
    read_campaign,
)
from axiscal.campaign.results import (
    SCHEMA,
    VERDICTS,
    CampaignResults,
    Check,
    Figure,
    Plot,
    TestResult,
    check_figures,
    overall_verdict,
    results_payload,
)
from axiscal.campaign.runner import (
    COMPENSATION_FILES,
    KIND_RUNNERS,
    evaluation_is_raw,
    run_campaign,
    run_test,
    svg_of,
)
from axiscal.campaign.volumetric import (
    GRID_POINTS,
    compensated_machine,
    plot_volume,
    plot_volume_change,
    read_loaded_compensation,
    same_grid,
    volumetric_section,
)
from axiscal.campaign.keys import (
    key_line,
)

__all__ = [
    "CAMPAIGN_FILE",
    "KINDS",
    "CONTROLLERS",
    "POSITIONING_TOLERANCE_KEYS",
    "TestSpec",
    "Campaign",
    "load_campaign",
    "read_campaign",
    "TABLE_KEYS",
    "SCHEMA",
    "VERDICTS",
    "Check",
    "Figure",
    "Plot",
    "TestResult",
    "CampaignResults",
    "check_figures",
    "overall_verdict",
    "results_payload",
    "COMPENSATION_FILES",
    "KIND_RUNNERS",
    "evaluation_is_raw",
    "run_campaign",
    "run_test",
    "svg_of",
    "GRID_POINTS",
    "volumetric_section",
    "plot_volume",
    "plot_volume_change",
    "same_grid",
    "compensated_machine",
    "read_loaded_compensation",
    "key_line",
]
