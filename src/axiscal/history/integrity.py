"""The integrity check of a history database: the store whole, every campaign complete.

No standard clause: ISO/IEC 17025 7.11.3 asks that stored data be protected and its integrity
checked. The database's own check (SQLite ``PRAGMA integrity_check`` and ``foreign_key_check``;
PostgreSQL keeps its pages checked itself), its schema revision, and the history's: every campaign
holds as many figures as it was stored with, belongs to a machine, and no results file is stored
twice. The check only reads: it never makes, migrates or changes a database.
"""

from __future__ import annotations

import sqlite3

from axiscal.errors import AxiscalError
from axiscal.history.database import (
    CHECK_HINT,
    _engine,
    _failure,
    _script,
    _text,
    resolve_url,
    shown_url,
    sqlite_file,
)

__all__ = ["integrity_problems"]


def integrity_problems(url: str | None = None) -> list[str]:
    """What is wrong with the history database; an empty list when nothing is: ``axiscal history check``.

    Parameters
    ----------
    url : str, optional
        The database (see :func:`~axiscal.history.database.resolve_url`).

    Returns
    -------
    list of str
        One line per problem: the database's own check (a damaged page, an index that does not
        match its table), a schema that is not this axiscal's, and the history's own checks
        (a campaign missing figures, a campaign without its machine, a file stored twice).

    Raises
    ------
    AxiscalError
        For a database that cannot be checked at all: a missing or empty SQLite file, a file that
        is not a database, or a server that cannot be reached.
    """
    try:
        return _problems(resolve_url(url))
    except AxiscalError as exc:  # said by this command: it does not send the user to itself
        raise AxiscalError(exc.message.replace(CHECK_HINT, ""), path=exc.path, line=exc.line) from None


def _problems(url: str) -> list[str]:
    """:func:`integrity_problems` of a resolved URL."""
    from alembic.runtime.migration import MigrationContext
    from sqlalchemy import inspect, text
    from sqlalchemy.exc import SQLAlchemyError

    engine = _engine(url, migrate=False, readonly=True, quick_check=False, schema=False)
    problems: list[str] = []
    try:
        try:
            connection = engine.connect()
        except (SQLAlchemyError, sqlite3.Error) as exc:
            raise _failure(exc, url) from None
        with connection:
            if connection.dialect.name == "sqlite":
                try:
                    problems += [f"sqlite: {' '.join(str(row[0]).split())}"
                                 for row in connection.exec_driver_sql("PRAGMA integrity_check") if row[0] != "ok"]
                    problems += [f"foreign key: {tuple(row)}"
                                 for row in connection.exec_driver_sql("PRAGMA foreign_key_check")]
                except (SQLAlchemyError, sqlite3.Error) as exc:
                    if "file is not a database" in _text(exc):
                        raise _failure(exc, url) from None
                    problems.append(f"sqlite: {_text(exc)}")
                    connection.rollback()
            try:
                head = _script().get_current_head()
                current = MigrationContext.configure(connection).get_current_revision()
                if current is None:
                    tables = set(inspect(connection).get_table_names())
                    raise AxiscalError("holds no axiscal history (no schema revision"
                                       + (f"; tables {', '.join(sorted(tables)[:3])}" if tables else "") + ")")
                if current != head:
                    problems.append(f"schema revision {current}, not this axiscal's ({head})")
                partial = connection.execute(text(
                    "SELECT c.id, c.figure_count, count(f.id) FROM campaigns c LEFT JOIN figures f ON f.campaign_id = c.id "
                    "GROUP BY c.id, c.figure_count HAVING count(f.id) <> c.figure_count")).all()
                problems += [f"campaign {cid} holds {n} of its {expected} figures" for cid, expected, n in partial]
                orphans = connection.execute(text(
                    "SELECT count(*) FROM campaigns c LEFT JOIN machines m ON m.id = c.machine_id WHERE m.id IS NULL")).scalar_one()
                if orphans:
                    problems.append(f"{orphans} campaigns without their machine")
                twice = connection.execute(text(
                    "SELECT results_sha256 FROM campaigns GROUP BY results_sha256 HAVING count(*) > 1")).all()
                problems += [f"results file {sha[:12]}... stored twice" for (sha,) in twice]
            except AxiscalError as exc:
                if problems:  # the damage the database's own check found hides the tables
                    problems.append(f"the history's own checks could not run: {exc.message}")
                else:
                    file = sqlite_file(url)
                    raise (AxiscalError(exc.message, path=file) if file is not None else
                           AxiscalError(f"the database {shown_url(url)} {exc.message}")) from None
            except (SQLAlchemyError, sqlite3.Error) as exc:
                if "file is not a database" in _text(exc):
                    raise _failure(exc, url) from None
                problems.append(f"the history's own checks could not run: {_text(exc)}")
    finally:
        engine.dispose()
    return problems
