"""The fleet's page and file: one row per machine (last verdict, worst figure, drift, next due date).

No standard clause: the machines of a plant ranked for a visit, from each machine's latest
campaign and its trends (weighted drift fit and ILAC-G24 / OIML D 10 intervals,
:mod:`axiscal.history.trend`). ``fleet.html`` is one self-contained page (styles and the sorting
script inline); ``fleet.json`` holds the same rows (schema ``axiscal-fleet/1``).
"""

from __future__ import annotations

import datetime as _dt
import hashlib
from collections.abc import Sequence
from dataclasses import dataclass
from pathlib import Path
from typing import Any

from axiscal.errors import AxiscalError
from axiscal.fleet.runner import CampaignOutcome, FleetRun
from axiscal.history.analysis import machine_trends
from axiscal.history.records import CampaignRecord, campaign_record
from axiscal.history.store import MachineHistory, StoredCampaign, machine_history, machine_label
from axiscal.io.arguments import check_instance
from axiscal.io.jsonio import dumps
from axiscal.version import __version__

__all__ = ["FLEET_SCHEMA", "MachineRow", "figure_title", "machine_rows", "fleet_payload", "render_fleet_html"]

FLEET_SCHEMA = "axiscal-fleet/1"


@dataclass(frozen=True)
class MachineRow:
    """One machine of the fleet page.

    Attributes
    ----------
    machine : str
        Name (serial).
    campaigns : int
        Campaigns its trends were drawn from.
    last_date : datetime.date
    last_verdict : str
    report : str
        The report folder of its latest campaign in this run ("" when from the history only).
    worst_figure, unit : str
        The toleranced figure nearest its tolerance in the latest campaign ("" when none).
    worst_value, worst_tolerance : float or None
    drift_figure : str
        The figure whose drift is shown: the worst one when it has a trend.
    drift_per_year, u_drift_per_year : float or None
    next_due : datetime.date or None
        The earliest recommended next calibration over the machine's trends.
    error : str
        The one-line error when its drift and next due date could not be worked out ("" when
        they were); the row then holds its latest campaign only.
    trend_note : str
        Why there is no drift or next due date ("2 visits; 3 needed"), "" when there is.
    """

    machine: str
    campaigns: int
    last_date: _dt.date
    last_verdict: str
    report: str
    worst_figure: str
    unit: str
    worst_value: float | None
    worst_tolerance: float | None
    drift_figure: str
    drift_per_year: float | None
    u_drift_per_year: float | None
    next_due: _dt.date | None
    error: str = ""
    trend_note: str = ""

    @property
    def worst_ratio(self) -> float | None:
        """``|worst_value| / worst_tolerance`` (1 at the limit), None without one."""
        if self.worst_value is None or not self.worst_tolerance:
            return None
        return abs(self.worst_value) / self.worst_tolerance


#: unit suffixes of the figures' keys, as the page names them
_UNITS = {"um": "µm", "nm": "nm", "mm": "mm", "arcsec": "arcsec", "urad": "µrad", "deg": "deg", "pct": "%"}


def figure_title(key: str) -> str:
    """A figure's key as a person reads it: ``diagonal.diagonal-0kg.diagonal_error_um`` -> ``diagonal-0kg: diagonal error``.

    Parameters
    ----------
    key : str
        ``KIND.TEST.FIGURE`` as the history names figures.

    Returns
    -------
    str
        The test (axis, plane or id) and the figure's name in words, without the unit.

    Examples
    --------
    >>> figure_title("positioning.X.E"), figure_title("straightness.X.straightness_um")
    ('X: positioning E', 'X: straightness')
    """
    check_instance("key", key, str)
    parts = key.split(".", 2)
    if len(parts) != 3:
        return key
    kind, test, name = parts
    stem, _, unit = name.rpartition("_")
    if stem and unit in _UNITS:
        name = stem
    words = name.replace("_", " ")
    if not words.startswith(kind):
        words = f"{kind} {words}"
    return f"{test}: {words}"


def _trend_note(campaigns: int, trends: dict) -> str:
    if campaigns < 3:
        return f"{campaigns} visit{'' if campaigns == 1 else 's'}; 3 needed"
    if not trends:
        return "no figure with a tolerance in 3 visits"
    return ""


def _in_memory(records: list[CampaignRecord]) -> MachineHistory:
    records = sorted(records, key=lambda r: r.date)
    campaigns = tuple(StoredCampaign(i + 1, r.machine, r.serial, r.title, r.date, r.verdict, r.software_version,
                                     r.sha256, r.figures) for i, r in enumerate(records))
    return MachineHistory(records[0].machine, records[0].serial, campaigns)


def machine_rows(run: FleetRun, *, history: bool = False, db: str | None = None) -> list[MachineRow]:
    """The rows of the fleet page, most urgent first (earliest next due date, then nearest its tolerance).

    Parameters
    ----------
    run : FleetRun
    history : bool, keyword-only
        Draw the trends from the history database (which holds the run's campaigns and earlier
        ones) rather than from the run's campaigns alone.
    db : str, keyword-only
        The history database.

    Returns
    -------
    list of MachineRow
        A machine whose history or trends fail keeps its row with the one-line error (and no
        drift or next due date); the others are worked out as usual.

    Raises
    ------
    AxiscalError
        For a ``run`` that is not a FleetRun.
    """
    check_instance("run", run, FleetRun)
    by_machine: dict[str, list[tuple[CampaignRecord, CampaignOutcome]]] = {}
    for outcome in run.outcomes:
        if outcome.error:
            continue
        sha = hashlib.sha256(dumps(outcome.payload).encode("utf-8")).hexdigest()
        record = campaign_record(outcome.payload, sha256=sha, source=outcome.folder)
        by_machine.setdefault(machine_label(record.machine, record.serial), []).append((record, outcome))
    rows = []
    for label, entries in by_machine.items():
        entries.sort(key=lambda e: e[0].date)
        latest, outcome = entries[-1]
        campaigns, trends, error = len(entries), {}, ""
        try:
            past = machine_history(label, url=db) if history else _in_memory([r for r, _ in entries])
            campaigns = len(past.campaigns)
            trends = {t.figure: t for t in machine_trends(past)}
        except AxiscalError as exc:
            error = " ".join(str(exc).split())
        except Exception as exc:  # one machine's failure must not stop the page: it is listed
            error = f"{type(exc).__name__}: {' '.join(str(exc).split())}"[:500]
        toleranced = [f for f in latest.figures if f.tolerance and f.value is not None]
        worst = max(toleranced, key=lambda f: abs(f.value) / f.tolerance, default=None)
        drift = trends.get(worst.key) if worst is not None else None
        if drift is None and trends:
            drift = max(trends.values(), key=lambda t: abs(t.fit.b) / t.tolerance)
        rows.append(MachineRow(
            label, campaigns, latest.date, latest.verdict, outcome.report,
            worst.key if worst else "", worst.unit if worst else "", worst.value if worst else None,
            worst.tolerance if worst else None, drift.figure if drift else "", drift.fit.b if drift else None,
            drift.fit.u_b if drift else None, min((t.next_date for t in trends.values()), default=None), error,
            _trend_note(len(past.campaigns), trends),
        ))
    rows.sort(key=lambda r: (r.next_due or _dt.date.max, -(r.worst_ratio or 0.0), r.machine))
    return rows


def fleet_payload(run: FleetRun, rows: Sequence[MachineRow]) -> dict[str, Any]:
    """The fleet.json object (schema ``axiscal-fleet/1``).

    Parameters
    ----------
    run : FleetRun
    rows : sequence of MachineRow

    Returns
    -------
    dict

    Raises
    ------
    AxiscalError
        For a ``run`` that is not a FleetRun.
    """
    check_instance("run", run, FleetRun)
    iso = lambda d: None if d is None else d.isoformat()  # noqa: E731
    return {
        "schema": FLEET_SCHEMA,
        "software": {"name": "axiscal", "version": __version__},
        "scheduler": run.scheduler,
        "seconds": run.seconds,
        "campaigns": [{"folder": o.folder, "report": o.report, "verdict": o.payload.get("verdict"),
                       "error": o.error or None} for o in run.outcomes],
        "machines": [{
            "machine": r.machine, "campaigns": r.campaigns, "last_date": iso(r.last_date),
            "last_verdict": r.last_verdict, "report": r.report,
            "worst": {"figure": r.worst_figure, "value": r.worst_value, "tolerance": r.worst_tolerance,
                      "unit": r.unit, "ratio": r.worst_ratio} if r.worst_figure else None,
            "drift": {"figure": r.drift_figure, "per_year": r.drift_per_year, "u_per_year": r.u_drift_per_year}
            if r.drift_figure else None,
            "next_due": iso(r.next_due),
            "error": r.error or None,
        } for r in rows],
        "errors": [{"folder": o.folder, "error": o.error} for o in run.outcomes if o.error],
    }


def _drift_text(row: MachineRow) -> str:
    """The drift cell: the slope with its u, "no drift" when it is within 2 u of none."""
    unit = _UNITS.get(row.unit, row.unit)
    name = figure_title(row.drift_figure) if row.drift_figure else ""
    if row.u_drift_per_year is not None and abs(row.drift_per_year) <= 2 * row.u_drift_per_year:
        return f"no drift ({row.drift_per_year:+.3g} ± {row.u_drift_per_year:.2g} {unit}/year, {name})"
    return f"{row.drift_per_year:+.3g} ± {row.u_drift_per_year:.2g} {unit}/year ({name})"


def render_fleet_html(run: FleetRun, rows: Sequence[MachineRow], *, out_dir: str | Path | None = None,
                      generated: str | None = None) -> str:
    """The fleet page.

    Parameters
    ----------
    run : FleetRun
    rows : sequence of MachineRow
    out_dir : str or Path, keyword-only
        The fleet's folder: report links are made relative to it.
    generated : str, keyword-only
        When the page was made (default: now, UTC, to the minute).

    Returns
    -------
    str
        One self-contained HTML page: a table sortable by any column.

    Raises
    ------
    AxiscalError
        For a ``run`` that is not a FleetRun.
    """
    from axiscal.report.html import format_number, template_environment

    check_instance("run", run, FleetRun)

    def link(report: str) -> str:
        if not report:
            return ""
        path = Path(report) / "report.html"
        if out_dir is not None:
            try:
                return path.resolve().relative_to(Path(out_dir).resolve()).as_posix()
            except ValueError:
                return path.resolve().as_uri()
        return path.as_posix()

    table = [{
        "machine": r.machine, "link": link(r.report), "date": r.last_date.isoformat(), "verdict": r.last_verdict,
        "campaigns": r.campaigns, "worst": figure_title(r.worst_figure) if r.worst_figure else "",
        "worst_text": "" if r.worst_value is None else
        f"{format_number(abs(r.worst_value))} / {format_number(r.worst_tolerance)} {r.unit}",
        "ratio": "" if r.worst_ratio is None else f"{100 * r.worst_ratio:.0f}",
        "ratio_sort": "" if r.worst_ratio is None else f"{r.worst_ratio:.9g}",
        "drift": r.trend_note if r.drift_per_year is None else _drift_text(r),
        "drift_sort": "" if r.drift_per_year is None else f"{r.drift_per_year:.6g}",
        "next": "" if r.next_due is None else r.next_due.isoformat(),
        "next_note": r.trend_note or "not predicted",
    } for r in rows]
    return template_environment().get_template("fleet/fleet.html.j2").render(
        version=__version__,
        generated=generated or _dt.datetime.now(_dt.timezone.utc).strftime("%Y-%m-%d %H:%M UTC"),
        rows=table,
        errors=[o for o in run.outcomes if o.error],
        machine_errors=[r for r in rows if r.error],
        count=len(run.outcomes),
        scheduler=run.scheduler,
        seconds=run.seconds,
    )
