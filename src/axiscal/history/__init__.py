"""The calibration history: every campaign kept in a database, its figures' drift, and the next date.

Campaigns are stored from their results.json (SQLite in the user's data folder by default,
PostgreSQL or any SQLAlchemy 2 database by URL), listed, shown, exported, removed; a figure's
trend over the campaigns gives its drift, the date it is expected to leave its tolerance and the
next calibration date by the methods of ILAC-G24 / OIML D 10 (2007).
"""

from __future__ import annotations

from axiscal.history.analysis import (
    figure_trend,
    history_trend,
    machine_trends,
)
from axiscal.history.database import (
    DB_ENVIRONMENT,
    MIGRATIONS,
    database_errors,
    default_url,
    open_engine,
    resolve_url,
    schema_revision,
    shown_url,
    sqlite_file,
)
from axiscal.history.integrity import integrity_problems
from axiscal.history.models import (
    Base,
    CampaignRow,
    FigureRow,
    MachineRow,
)
from axiscal.history.records import (
    CampaignRecord,
    FigureRecord,
    campaign_record,
    read_results,
)
from axiscal.history.store import (
    EXPORT_COLUMNS,
    Added,
    MachineHistory,
    StoredCampaign,
    add_records,
    add_results,
    export_history,
    list_campaigns,
    machine_histories,
    machine_history,
    machine_label,
    remove_campaign,
    upgrade_database,
)
from axiscal.history.plot import plot_trend
from axiscal.history.synthetic import (
    Drift,
    drifting_results,
    write_results,
)
from axiscal.history.trend import (
    CROSSING_HORIZON_YEARS,
    ONE_SIDED_FIGURES,
    TREND_METHODS,
    DriftFit,
    Trend,
    crossing,
    fit_drift,
    one_sided_figure,
    staircase,
    trend_of,
)

__all__ = [
    "figure_trend",
    "history_trend",
    "machine_trends",
    "DB_ENVIRONMENT",
    "MIGRATIONS",
    "database_errors",
    "default_url",
    "open_engine",
    "resolve_url",
    "schema_revision",
    "shown_url",
    "sqlite_file",
    "integrity_problems",
    "Base",
    "CampaignRow",
    "FigureRow",
    "MachineRow",
    "CampaignRecord",
    "FigureRecord",
    "campaign_record",
    "read_results",
    "EXPORT_COLUMNS",
    "Added",
    "MachineHistory",
    "StoredCampaign",
    "add_records",
    "add_results",
    "export_history",
    "list_campaigns",
    "machine_history",
    "machine_histories",
    "machine_label",
    "remove_campaign",
    "upgrade_database",
    "plot_trend",
    "Drift",
    "drifting_results",
    "write_results",
    "CROSSING_HORIZON_YEARS",
    "TREND_METHODS",
    "ONE_SIDED_FIGURES",
    "one_sided_figure",
    "DriftFit",
    "Trend",
    "crossing",
    "fit_drift",
    "staircase",
    "trend_of",
]
