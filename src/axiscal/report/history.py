"""The report's history section: the campaign stored in the history, and each figure's trend.

No standard clause: the stored campaigns of the machine fed to :mod:`axiscal.history.trend`
(drift fit, Fieller's crossing interval, ILAC-G24 / OIML D 10 next calibration), one plot per
toleranced figure.
"""

from __future__ import annotations

import hashlib
from typing import Any

from axiscal.campaign.results import CampaignResults, results_payload
from axiscal.campaign.runner import svg_of
from axiscal.history.analysis import machine_trends
from axiscal.history.records import campaign_record
from axiscal.history.store import add_records, machine_history, machine_label
from axiscal.io.arguments import check_instance
from axiscal.io.jsonio import dumps

__all__ = ["history_section"]


def history_section(results: CampaignResults, *, url: str | None = None, source: str = "") -> dict[str, Any]:
    """Store the campaign in the history and make the report's history section.

    Parameters
    ----------
    results : CampaignResults
        The campaign just run; stored under the hash of the results.json the report writes.
    url : str, keyword-only
        The history database (default ``$AXISCAL_DB``, else the user's SQLite file).
    source : str, keyword-only
        Where its results.json goes, kept with the campaign.

    Returns
    -------
    dict
        ``campaign_id``, ``database`` (where it was stored, password hidden), ``machine``,
        ``campaigns`` (how many the machine has), ``trends`` (one dict per
        figure with three campaigns and a tolerance: ``figure``, ``unit``, ``slope``, ``u_slope``,
        ``crossing``, ``interval``, ``next``, ``svg``) and ``method``.

    Raises
    ------
    AxiscalError
        For a database that cannot be opened.
    """
    check_instance("results", results, CampaignResults)
    payload = results_payload(results)
    data = dumps(payload).encode("utf-8")
    record = campaign_record(payload, sha256=hashlib.sha256(data).hexdigest(), source=source)
    added = add_records([record], url=url)[0]
    from axiscal.history.plot import plot_trend

    history = machine_history(machine_label(record.machine, record.serial), url=url)
    trends = []
    for trend in machine_trends(history):
        low, high = trend.crossing_interval
        trends.append({
            "figure": trend.figure, "unit": trend.unit, "slope": trend.fit.b, "u_slope": trend.fit.u_b,
            "crossing": trend.crossing_text,
            "interval": f"{low.isoformat() if low else 'unbounded'} .. {high.isoformat() if high else 'unbounded'}",
            "next": trend.next_date.isoformat(),
            "svg": svg_of(lambda path, t=trend: plot_trend(t, path)),
        })
    from axiscal.history.database import resolve_url, shown_url

    return {
        "campaign_id": added.campaign_id,
        "database": shown_url(resolve_url(url)),
        "machine": machine_label(record.machine, record.serial),
        "campaigns": len(history.campaigns),
        "trends": trends,
        "method": ("Drift: straight line by weighted least squares (weights 1/u^2, u = U/2); crossing date where "
                   "the line reaches the tolerance, with Fieller's interval (k = 2); next calibration by ILAC-G24 / "
                   "OIML D 10: the earlier of the fixed-risk date (5 %) and the staircase."),
    }
