"""Calibration campaigns: a folder of test data described by campaign.toml, run as one job."""

from __future__ import annotations

from axiscal.campaign.config import (
    CAMPAIGN_FILE,
    CONTROLLERS,
    KINDS,
    Campaign,
    TestSpec,
    load_campaign,
)
from axiscal.campaign.results import (
    CampaignResults,
    Check,
    TestResult,
    overall_verdict,
    results_payload,
)
from axiscal.campaign.runner import run_campaign, run_test

__all__ = [
    "CAMPAIGN_FILE",
    "CONTROLLERS",
    "KINDS",
    "Campaign",
    "TestSpec",
    "load_campaign",
    "CampaignResults",
    "Check",
    "TestResult",
    "overall_verdict",
    "results_payload",
    "run_campaign",
    "run_test",
]
