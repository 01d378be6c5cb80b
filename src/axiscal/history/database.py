"""Opening the history database: its URL, the engine, and the schema brought up to date on open.

No standard clause. The database is SQLite by default (one file in the user's data folder, made on
first use) or any server SQLAlchemy 2 reaches, PostgreSQL through psycopg 3 in particular. Writers
are serialised by the database itself: every SQLite transaction begins ``IMMEDIATE`` (write-ahead
log, a busy timeout), and on PostgreSQL the schema is migrated under an advisory lock and a
campaign is inserted once by its unique hash. The alembic migrations shipped in
``axiscal/history/migrations`` run on open; a database of a newer schema is refused.
"""

from __future__ import annotations

import os
from pathlib import Path
from typing import Any

from axiscal.errors import AxiscalError
from axiscal.io.arguments import check_instance

__all__ = ["DB_ENVIRONMENT", "MIGRATIONS", "default_url", "resolve_url", "shown_url", "open_engine", "schema_revision"]

#: the environment variable naming the database when no URL is given
DB_ENVIRONMENT = "AXISCAL_DB"
#: the alembic scripts shipped with axiscal
MIGRATIONS = Path(__file__).resolve().parent / "migrations"
# any number that no other application of the server uses for its advisory lock ("axiscal")
_LOCK_KEY = 0x61786973636C


def default_url() -> str:
    """The SQLite file in the user's data folder (platformdirs), its folder made when missing.

    Parameters
    ----------
    (none)

    Returns
    -------
    str
        ``sqlite:///.../axiscal/history.sqlite``.
    """
    import platformdirs

    folder = Path(platformdirs.user_data_dir("axiscal", appauthor=False, ensure_exists=True))
    return f"sqlite:///{folder / 'history.sqlite'}"


def resolve_url(url: str | None = None) -> str:
    """The database URL to use: ``url``, else ``$AXISCAL_DB``, else :func:`default_url`.

    Parameters
    ----------
    url : str or None
        A SQLAlchemy URL (``sqlite:///history.sqlite``, ``postgresql+psycopg://user@host/db``); a
        ``postgresql://`` URL is read as psycopg 3's, and a plain file name as an SQLite file.

    Returns
    -------
    str
        A SQLAlchemy URL.

    Raises
    ------
    AxiscalError
        For a ``url`` that is not a text.
    """
    if url is None:
        url = os.environ.get(DB_ENVIRONMENT) or None
    if url is None:
        return default_url()
    check_instance("url", url, str, what="a database URL (a str)")
    url = url.strip()
    if not url:
        raise AxiscalError("url must be a database URL or an SQLite file name, not an empty text")
    if "://" not in url:
        return f"sqlite:///{Path(url).expanduser()}"
    for plain in ("postgresql://", "postgres://"):
        if url.startswith(plain):
            return "postgresql+psycopg://" + url[len(plain):]
    return url


def shown_url(url: str) -> str:
    """``url`` with its password hidden, as messages show it.

    Parameters
    ----------
    url : str

    Returns
    -------
    str
    """
    from sqlalchemy.engine import make_url
    from sqlalchemy.exc import ArgumentError

    try:
        return make_url(url).render_as_string(hide_password=True)
    except ArgumentError:
        return url


def _failure(exc: BaseException, url: str) -> AxiscalError:
    """One line for a database error met while opening ``url``."""
    orig = getattr(exc, "orig", None) or exc
    text = " ".join(str(orig).split()) or type(orig).__name__
    if url.startswith("sqlite"):
        file = url.split("///", 1)[-1]
        if "file is not a database" in text:
            return AxiscalError("not an SQLite database (file is not a database)", path=file)
        return AxiscalError(f"cannot open the history database: {text}", path=file)
    return AxiscalError(f"cannot reach the history database {shown_url(url)}: {text}")


def _sqlite_setup(engine: Any) -> None:
    from sqlalchemy import event

    @event.listens_for(engine, "connect")
    def _connect(dbapi_connection: Any, record: Any) -> None:  # noqa: ARG001
        dbapi_connection.isolation_level = None  # transactions begun below, not by the driver
        cursor = dbapi_connection.cursor()
        cursor.execute("PRAGMA busy_timeout = 120000")
        cursor.execute("PRAGMA foreign_keys = ON")
        cursor.execute("PRAGMA journal_mode = WAL")
        cursor.close()

    @event.listens_for(engine, "begin")
    def _begin(connection: Any) -> None:
        connection.exec_driver_sql("BEGIN IMMEDIATE")


def open_engine(url: str | None = None, *, migrate: bool = True):
    """An engine on the history database, its schema brought to this axiscal's (alembic, on open).

    Parameters
    ----------
    url : str or None
        See :func:`resolve_url`.
    migrate : bool, keyword-only
        Run the shipped migrations up to the newest (default); False only checks the database is
        not of a newer schema.

    Returns
    -------
    sqlalchemy.engine.Engine

    Raises
    ------
    AxiscalError
        One line for a URL SQLAlchemy does not read, a driver that is not installed, a file that
        is not a database, a server that cannot be reached, or a database of a newer schema than
        this axiscal knows (or that holds another application's tables).
    """
    from sqlalchemy import create_engine
    from sqlalchemy.exc import ArgumentError, NoSuchModuleError, SQLAlchemyError
    from sqlalchemy.pool import NullPool

    url = resolve_url(url)
    check_instance("migrate", migrate, bool)
    try:
        if url.startswith("sqlite"):
            engine = create_engine(url, poolclass=NullPool)
            _sqlite_setup(engine)
        else:
            connect_args = {"connect_timeout": 10} if url.startswith("postgresql") else {}
            engine = create_engine(url, poolclass=NullPool, connect_args=connect_args)
    except (ArgumentError, NoSuchModuleError) as exc:
        raise AxiscalError(f"cannot use the database URL {shown_url(url)}: {' '.join(str(exc).split())}") from None
    except ImportError as exc:
        raise AxiscalError(f"the database driver for {shown_url(url)} is not installed ({exc.name}); "
                           "for PostgreSQL: pip install 'psycopg[binary]'") from None
    try:
        _bring_up_to_date(engine, migrate=migrate)
    except AxiscalError:
        engine.dispose()
        raise
    except (SQLAlchemyError, OSError) as exc:
        engine.dispose()
        raise _failure(exc, url) from None
    return engine


def _script():
    from alembic.script import ScriptDirectory

    return ScriptDirectory(str(MIGRATIONS))


def schema_revision(engine: Any) -> str | None:
    """The alembic revision the database is at.

    Parameters
    ----------
    engine : sqlalchemy.engine.Engine

    Returns
    -------
    str or None
        None for a database axiscal has not yet made its tables in.
    """
    from alembic.runtime.migration import MigrationContext

    with engine.connect() as connection:
        return MigrationContext.configure(connection).get_current_revision()


def _bring_up_to_date(engine: Any, *, migrate: bool) -> None:
    from alembic import command
    from alembic.config import Config
    from alembic.runtime.migration import MigrationContext
    from sqlalchemy import inspect, text

    script = _script()
    head = script.get_current_head()
    known = {rev.revision for rev in script.walk_revisions()}
    with engine.begin() as connection:
        if connection.dialect.name == "postgresql":
            connection.execute(text("SELECT pg_advisory_xact_lock(:key)"), {"key": _LOCK_KEY})
        current = MigrationContext.configure(connection).get_current_revision()
        if current == head:
            return
        where = shown_url(str(engine.url))
        if current is not None and current not in known:
            raise AxiscalError(f"the history database {where} has schema revision {current}, newer than this "
                               f"axiscal knows ({head}): use a newer axiscal")
        if current is None:
            tables = set(inspect(connection).get_table_names())
            if tables - {"alembic_version"}:
                raise AxiscalError(f"the database {where} holds tables that are not an axiscal history "
                                   f"({', '.join(sorted(tables)[:3])} ...); give another database")
        if not migrate:
            return
        config = Config()
        config.set_main_option("script_location", str(MIGRATIONS))
        config.attributes["connection"] = connection
        command.upgrade(config, "head")
