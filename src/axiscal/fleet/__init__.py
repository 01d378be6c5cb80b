"""Fleets: many campaigns reported in parallel on Dask, and one page ranking the machines for a visit.

Each machine's row holds its last verdict, its worst figure against its tolerance, its drift and
its next due date (ILAC-G24 / OIML D 10 intervals from :mod:`axiscal.history`).
"""

from __future__ import annotations

from axiscal.fleet.generate import generated_fleet
from axiscal.fleet.page import (
    FLEET_SCHEMA,
    MachineRow,
    figure_title,
    fleet_payload,
    machine_rows,
    render_fleet_html,
)
from axiscal.fleet.report import FleetReport, fleet_report
from axiscal.fleet.runner import (
    SCHEDULER_TIMEOUT_S,
    CampaignOutcome,
    FleetRun,
    find_campaigns,
    report_one,
    run_fleet,
)

__all__ = [
    "generated_fleet",
    "FLEET_SCHEMA",
    "MachineRow",
    "figure_title",
    "fleet_payload",
    "machine_rows",
    "render_fleet_html",
    "FleetReport",
    "fleet_report",
    "SCHEDULER_TIMEOUT_S",
    "CampaignOutcome",
    "FleetRun",
    "find_campaigns",
    "report_one",
    "run_fleet",
]
