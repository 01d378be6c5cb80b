"""The calibration history: campaigns added from results files, listed, shown, exported, removed.

No standard clause: ISO/IEC 17025 7.5 asks for the records of every calibration to be kept and
retrievable; ILAC-G24 / OIML D 10 (2007) set calibration intervals from them
(:mod:`axiscal.history.trend`). Each public function opens the database (:func:`open_engine`,
which checks it and migrates it; the functions that only read open it read-only, so they never
make or change one), does one job in one transaction and closes it: a campaign is stored whole or
not at all, once however often it is added, and a writer killed mid-add leaves the database as
it was. A database error met on the way (a damaged page) ends in one line.
"""

from __future__ import annotations

import csv
import datetime as _dt
import io
from collections.abc import Callable, Sequence
from dataclasses import dataclass
from pathlib import Path
from typing import Any

from axiscal.errors import AxiscalError
from axiscal.history.database import database_errors, open_engine, resolve_url, schema_revision, shown_url
from axiscal.history.models import CampaignRow, FigureRow, MachineRow
from axiscal.history.records import CampaignRecord, FigureRecord, read_results
from axiscal.io.arguments import check_instance, check_integer, check_path
from axiscal.io.atomic import write_text
from axiscal.io.jsonio import write_sidecar
from axiscal.version import __version__

__all__ = [
    "EXPORT_COLUMNS",
    "Added",
    "StoredCampaign",
    "MachineHistory",
    "machine_label",
    "add_results",
    "add_records",
    "list_campaigns",
    "machine_history",
    "machine_histories",
    "export_history",
    "remove_campaign",
    "upgrade_database",
]

#: the columns of ``axiscal history export``, in order
EXPORT_COLUMNS = ("campaign_id", "date", "machine", "serial", "verdict", "test_id", "kind", "axis", "figure",
                  "name", "value", "unit", "tolerance", "U", "result", "software_version", "results_sha256")


@dataclass(frozen=True)
class Added:
    """What adding one results file did.

    Attributes
    ----------
    campaign_id : int
        The stored campaign's id.
    machine : str
        The machine's label (name, and serial in parentheses when it has one).
    date : datetime.date
    new : bool
        False when the same file (by its SHA-256) was stored already.
    source : str
        The file added.
    """

    campaign_id: int
    machine: str
    date: _dt.date
    new: bool
    source: str


@dataclass(frozen=True)
class StoredCampaign:
    """A campaign as the history lists it.

    Attributes
    ----------
    id : int
    machine, serial, title : str
    date : datetime.date
    verdict, software_version, results_sha256 : str
    figures : tuple of FigureRecord
        Empty in listings; the figures in :func:`machine_history`.
    """

    id: int
    machine: str
    serial: str
    title: str
    date: _dt.date
    verdict: str
    software_version: str
    results_sha256: str
    figures: tuple[FigureRecord, ...] = ()


@dataclass(frozen=True)
class MachineHistory:
    """Every stored campaign of one machine, oldest first, with its figures.

    Attributes
    ----------
    machine, serial : str
    campaigns : tuple of StoredCampaign
    """

    machine: str
    serial: str
    campaigns: tuple[StoredCampaign, ...]

    @property
    def label(self) -> str:
        """The machine's name, and its serial in parentheses when it has one."""
        return machine_label(self.machine, self.serial)

    def series(self, key: str) -> list[tuple[_dt.date, FigureRecord]]:
        """The figure ``key`` over the campaigns that have it, oldest first.

        Parameters
        ----------
        key : str
            ``KIND.AXIS.FIGURE``, e.g. ``positioning.X.E``.

        Returns
        -------
        list of (date, FigureRecord)
        """
        return [(c.date, f) for c in self.campaigns for f in c.figures if f.key == key]

    @property
    def keys(self) -> list[str]:
        """Every figure key of the machine's campaigns, in first-seen order."""
        return list(dict.fromkeys(f.key for c in self.campaigns for f in c.figures))


def machine_label(name: str, serial: str) -> str:
    """How a machine is named in listings: ``name (serial)``, or the name alone.

    Parameters
    ----------
    name, serial : str
        From the results file's ``[machine]`` table (serial ``""`` when none).

    Returns
    -------
    str

    Examples
    --------
    >>> machine_label("VMC 1", "S-42")
    'VMC 1 (S-42)'
    """
    return f"{name} ({serial})" if serial else name


def _session(engine: Any):
    from sqlalchemy.orm import Session

    return Session(engine, expire_on_commit=False)


def _machine_id(session: Any, record: CampaignRecord) -> int:
    from sqlalchemy import select

    row = session.execute(select(MachineRow.id).where(MachineRow.name == record.machine,
                                                      MachineRow.serial == record.serial)).scalar_one_or_none()
    if row is not None:
        return row
    dialect = session.get_bind().dialect.name
    if dialect == "postgresql":
        from sqlalchemy.dialects.postgresql import insert
    else:
        from sqlalchemy.dialects.sqlite import insert
    session.execute(insert(MachineRow).values(name=record.machine, serial=record.serial).on_conflict_do_nothing())
    return session.execute(select(MachineRow.id).where(MachineRow.name == record.machine,
                                                       MachineRow.serial == record.serial)).scalar_one()


def _store(engine: Any, record: CampaignRecord) -> Added:
    from sqlalchemy import select
    from sqlalchemy.exc import IntegrityError

    machine = machine_label(record.machine, record.serial)
    for attempt in range(2):
        with _session(engine) as session:
            try:
                with session.begin():
                    existing = session.execute(select(CampaignRow.id).where(
                        CampaignRow.results_sha256 == record.sha256)).scalar_one_or_none()
                    if existing is not None:
                        return Added(existing, machine, record.date, False, record.source)
                    campaign = CampaignRow(
                        machine_id=_machine_id(session, record), results_sha256=record.sha256, title=record.title,
                        date=record.date, verdict=record.verdict, decision_rule=record.decision_rule,
                        software_version=record.software_version, source=record.source,
                        added_at=_dt.datetime.now(_dt.timezone.utc), figure_count=len(record.figures))
                    session.add(campaign)
                    session.flush()
                    session.add_all(FigureRow(campaign_id=campaign.id, position=i, key=f.key, test_id=f.test_id,
                                              kind=f.kind, axis=f.axis, name=f.name, value=f.value, unit=f.unit,
                                              tolerance=f.tolerance, U=f.U, result=f.result)
                                    for i, f in enumerate(record.figures))
                return Added(campaign.id, machine, record.date, True, record.source)
            except IntegrityError:
                # another writer stored the same file (or machine) between our look and our insert
                if attempt:
                    raise
    raise AssertionError("unreachable")


def add_records(
    records: Sequence[CampaignRecord],
    *,
    url: str | None = None,
    progress: Callable[[Added], None] | None = None,
) -> list[Added]:
    """Store campaign records, each in its own transaction.

    Parameters
    ----------
    records : sequence of CampaignRecord
    url : str, keyword-only
        The database (see :func:`~axiscal.history.database.resolve_url`).
    progress : callable, keyword-only
        Called with each :class:`Added` once its campaign is committed.

    Returns
    -------
    list of Added
        In the order of ``records``.

    Raises
    ------
    AxiscalError
        For records that are not CampaignRecords, or a database that cannot be opened.
    """
    if isinstance(records, (str, bytes)) or not isinstance(records, Sequence):
        raise AxiscalError(f"records must be a sequence of CampaignRecord, not {type(records).__name__}")
    for record in records:
        check_instance("records[...]", record, CampaignRecord)
    url = resolve_url(url)
    engine = open_engine(url)
    try:
        out = []
        for record in records:
            with database_errors(url):
                added = _store(engine, record)
            out.append(added)
            if progress is not None:
                progress(added)
        return out
    finally:
        engine.dispose()


def add_results(
    paths: Sequence[str | Path],
    *,
    url: str | None = None,
    progress: Callable[[Added], None] | None = None,
) -> list[Added]:
    """Store campaigns from their results.json files: what ``axiscal history add`` does.

    Every file is read and checked before anything is stored; then each campaign is stored in one
    transaction, once (a file already stored, known by its SHA-256, is not stored again).

    Parameters
    ----------
    paths : sequence of str or Path
        results.json files.
    url : str, keyword-only
        The database; default ``$AXISCAL_DB``, else the SQLite file in the user's data folder.
    progress : callable, keyword-only
        Called with each :class:`Added` once its campaign is committed.

    Returns
    -------
    list of Added

    Raises
    ------
    AxiscalError
        For a file that is not an axiscal results file (naming the file and line; nothing is
        stored then), or a database that cannot be opened.

    Examples
    --------
    >>> added = add_results(["out/results.json"], url="sqlite:///history.sqlite")  # doctest: +SKIP
    """
    if isinstance(paths, (str, bytes, Path)) or not isinstance(paths, Sequence) or not paths:
        raise AxiscalError(f"paths must be a non-empty sequence of results.json files, not {paths!r}")
    records = [read_results(check_path("paths[...]", p)) for p in paths]
    return add_records(records, url=url, progress=progress)


def _stored(row: CampaignRow, figures: bool) -> StoredCampaign:
    return StoredCampaign(
        row.id, row.machine.name, row.machine.serial, row.title, row.date, row.verdict, row.software_version,
        row.results_sha256,
        tuple(FigureRecord(f.key, f.test_id, f.kind, f.axis, f.name, f.value, f.unit, f.tolerance, f.U, f.result)
              for f in row.figures) if figures else (),
    )


def list_campaigns(machine: str | None = None, *, url: str | None = None) -> list[StoredCampaign]:
    """The stored campaigns, by machine then date: what ``axiscal history list`` prints.

    Parameters
    ----------
    machine : str, optional
        Only this machine's (see :func:`machine_history` for how it is named).
    url : str, keyword-only
        The database.

    Returns
    -------
    list of StoredCampaign
        Without their figures.

    Raises
    ------
    AxiscalError
        For a machine the history does not hold, or a database that cannot be opened, is damaged,
        missing or empty (it only reads: it never makes or changes one).
    """
    from sqlalchemy import select
    from sqlalchemy.orm import selectinload

    url = resolve_url(url)
    engine = open_engine(url, readonly=True)
    try:
        with database_errors(url), _session(engine) as session:
            query = select(CampaignRow).join(MachineRow).options(selectinload(CampaignRow.machine))
            if machine is not None:
                query = query.where(CampaignRow.machine_id == _find_machine(session, machine).id)
            rows = session.execute(query.order_by(MachineRow.name, MachineRow.serial, CampaignRow.date,
                                                  CampaignRow.id)).scalars().all()
            return [_stored(row, False) for row in rows]
    finally:
        engine.dispose()


def _find_machine(session: Any, machine: str) -> MachineRow:
    from sqlalchemy import select

    check_instance("machine", machine, str, what="a machine's name, serial, 'name (serial)' or id")
    rows = session.execute(select(MachineRow)).scalars().all()
    text = machine.strip()
    found = [r for r in rows if text == machine_label(r.name, r.serial)]
    if not found:
        found = [r for r in rows if text in (r.name, str(r.id))]
    if not found:
        found = [r for r in rows if r.serial and text == r.serial]
    if len(found) == 1:
        return found[0]
    if not found:
        known = ", ".join(sorted(machine_label(r.name, r.serial) for r in rows)[:5]) or "none yet"
        raise AxiscalError(f"the history holds no machine '{text}' (machines: {known})")
    raise AxiscalError(f"'{text}' names {len(found)} machines ({', '.join(machine_label(r.name, r.serial) for r in found)}); "
                       "give 'name (serial)'")


def machine_history(machine: str, *, url: str | None = None) -> MachineHistory:
    """Every stored campaign of one machine with its figures: what ``axiscal history show`` prints.

    Parameters
    ----------
    machine : str
        Its name (when no other machine has it), ``name (serial)``, its serial, or its id.
    url : str, keyword-only
        The database.

    Returns
    -------
    MachineHistory

    Raises
    ------
    AxiscalError
        For a machine the history does not hold, a name several machines share, or a database
        that cannot be opened, is damaged, missing or empty (it only reads: it never makes or
        changes one).
    """
    from sqlalchemy import select
    from sqlalchemy.orm import selectinload

    url = resolve_url(url)
    engine = open_engine(url, readonly=True)
    try:
        with database_errors(url), _session(engine) as session:
            row = _find_machine(session, machine)
            campaigns = session.execute(
                select(CampaignRow).where(CampaignRow.machine_id == row.id)
                .options(selectinload(CampaignRow.figures), selectinload(CampaignRow.machine))
                .order_by(CampaignRow.date, CampaignRow.id)).scalars().all()
            return MachineHistory(row.name, row.serial, tuple(_stored(c, True) for c in campaigns))
    finally:
        engine.dispose()


def machine_histories(*, url: str | None = None) -> list[MachineHistory]:
    """Every machine's history at once, read in one session: what a page listing the machines needs.

    Parameters
    ----------
    url : str, keyword-only
        The database.

    Returns
    -------
    list of MachineHistory
        One per machine, by name then serial; each with its campaigns (oldest first) and figures.

    Raises
    ------
    AxiscalError
        For a database that cannot be opened.
    """
    from sqlalchemy import select
    from sqlalchemy.orm import selectinload

    engine = open_engine(url)
    try:
        with _session(engine) as session:
            rows = session.execute(
                select(CampaignRow).join(MachineRow)
                .options(selectinload(CampaignRow.figures), selectinload(CampaignRow.machine))
                .order_by(MachineRow.name, MachineRow.serial, MachineRow.id, CampaignRow.date, CampaignRow.id)).scalars().all()
            grouped: dict[int, list[CampaignRow]] = {}
            for row in rows:
                grouped.setdefault(row.machine_id, []).append(row)
            return [MachineHistory(c[0].machine.name, c[0].machine.serial, tuple(_stored(r, True) for r in c))
                    for c in grouped.values()]
    finally:
        engine.dispose()


def _cell(value: Any) -> str:
    if value is None:
        return ""
    if isinstance(value, float):
        return repr(value)
    return str(value)


def export_history(machine: str, path: str | Path, *, url: str | None = None) -> Path:
    """Write one machine's history as a plain CSV, one row per campaign and figure.

    The columns are :data:`EXPORT_COLUMNS` (values in the unit of the row's ``unit`` column;
    ``U`` is the expanded uncertainty, k = 2); a JSON sidecar beside it says what the file holds.
    The same adds give the same file whatever the database.

    Parameters
    ----------
    machine : str
        See :func:`machine_history`.
    path : str or Path
        The CSV to write (atomically).
    url : str, keyword-only
        The database.

    Returns
    -------
    Path
        ``path``.

    Raises
    ------
    AxiscalError
        As :func:`machine_history`, or when the file cannot be written.
    """
    path = check_path("path", path)
    history = machine_history(machine, url=url)
    buffer = io.StringIO()
    writer = csv.writer(buffer, lineterminator="\n")
    writer.writerow(EXPORT_COLUMNS)
    for c in history.campaigns:
        for f in c.figures:
            writer.writerow([_cell(v) for v in (
                c.id, c.date.isoformat(), c.machine, c.serial, c.verdict, f.test_id, f.kind, f.axis, f.key, f.name,
                f.value, f.unit, f.tolerance, f.U, f.result, c.software_version, c.results_sha256)])
    write_text(path, buffer.getvalue())
    write_sidecar(path, kind="calibration history", machine=history.machine, serial=history.serial,
                  campaigns=len(history.campaigns), axiscal=__version__,
                  columns={"value": "in the row's unit", "tolerance": "in the row's unit",
                           "U": "expanded uncertainty (k = 2) in the row's unit"})
    return path


def remove_campaign(campaign_id: int, *, url: str | None = None) -> StoredCampaign:
    """Remove one campaign and its figures (a machine left without campaigns goes too).

    Parameters
    ----------
    campaign_id : int
        As ``axiscal history list`` shows it.
    url : str, keyword-only
        The database.

    Returns
    -------
    StoredCampaign
        What was removed.

    Raises
    ------
    AxiscalError
        For an id the history does not hold, or a database that cannot be opened.
    """
    from sqlalchemy import delete, func, select

    campaign_id = check_integer("campaign_id", campaign_id)
    url = resolve_url(url)
    engine = open_engine(url)
    try:
        with database_errors(url), _session(engine) as session, session.begin():
            row = session.get(CampaignRow, campaign_id)
            if row is None:
                raise AxiscalError(f"the history holds no campaign {campaign_id}")
            removed = _stored(row, False)
            machine_id = row.machine_id
            session.execute(delete(FigureRow).where(FigureRow.campaign_id == campaign_id))
            session.execute(delete(CampaignRow).where(CampaignRow.id == campaign_id))
            left = session.execute(select(func.count()).select_from(CampaignRow)
                                   .where(CampaignRow.machine_id == machine_id)).scalar_one()
            if not left:
                session.execute(delete(MachineRow).where(MachineRow.id == machine_id))
        return removed
    finally:
        engine.dispose()


def upgrade_database(url: str | None = None) -> tuple[str, str]:
    """Bring the database's schema to this axiscal's: what ``axiscal history upgrade`` does.

    Opening the database does the same; this names the outcome.

    Parameters
    ----------
    url : str, optional
        The database.

    Returns
    -------
    (str, str)
        The database as shown (password hidden) and its schema revision.

    Raises
    ------
    AxiscalError
        For a database that cannot be opened or of a newer schema.
    """
    url = resolve_url(url)
    engine = open_engine(url)
    try:
        with database_errors(url):
            return shown_url(url), str(schema_revision(engine))
    finally:
        engine.dispose()
