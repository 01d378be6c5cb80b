"""The integrity check of a history database: the store whole, every campaign complete.

No standard clause: ISO/IEC 17025 7.11.3 asks that stored data be protected and its integrity
checked. The database's own check (SQLite ``PRAGMA integrity_check``; PostgreSQL keeps its pages
checked itself) and the history's: every campaign holds as many figures as it was stored with,
belongs to a machine, and no results file is stored twice.
"""

from __future__ import annotations

from axiscal.history.database import open_engine

__all__ = ["integrity_problems"]


def integrity_problems(url: str | None = None) -> list[str]:
    """What is wrong with the history database; an empty list when nothing is.

    Parameters
    ----------
    url : str, optional
        The database.

    Returns
    -------
    list of str
        One line per problem.

    Raises
    ------
    AxiscalError
        For a database that cannot be opened.
    """
    from sqlalchemy import text

    engine = open_engine(url)
    problems: list[str] = []
    try:
        with engine.connect() as connection:
            if connection.dialect.name == "sqlite":
                problems += [f"sqlite: {row[0]}" for row in connection.exec_driver_sql("PRAGMA integrity_check")
                             if row[0] != "ok"]
                problems += [f"foreign key: {tuple(row)}" for row in connection.exec_driver_sql("PRAGMA foreign_key_check")]
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
    finally:
        engine.dispose()
    return problems
