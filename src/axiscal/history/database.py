"""Opening the history database: its URL, the engine, and the schema brought up to date on open.

No standard clause. The database is SQLite by default (one file in the user's data folder, made on
first use) or any server SQLAlchemy 2 reaches, PostgreSQL through psycopg 3 in particular. Writers
are serialised by the database itself: every SQLite transaction begins ``IMMEDIATE`` (write-ahead
log, a busy timeout), and on PostgreSQL the schema is migrated under an advisory lock and a
campaign is inserted once by its unique hash. The alembic migrations shipped in
``axiscal/history/migrations`` run on open; a database of a newer schema is refused.

An SQLite file is checked (``PRAGMA quick_check``) before anything is read or written: a damaged
file, an empty one or one that is not a database is refused in one line and left as it was.
Read-only opens (``readonly=True``: list, show, export, trend, check) never make, migrate or change
a database: a missing file, an empty one or a database without the history's tables is refused.
"""

from __future__ import annotations

import os
import sqlite3
from collections.abc import Iterator
from contextlib import contextmanager
from pathlib import Path
from typing import Any
from urllib.parse import quote

from axiscal.errors import AxiscalError
from axiscal.io.arguments import check_instance

__all__ = ["DB_ENVIRONMENT", "MIGRATIONS", "default_url", "resolve_url", "shown_url", "open_engine", "schema_revision",
           "database_errors", "sqlite_file"]

#: the environment variable naming the database when no URL is given
DB_ENVIRONMENT = "AXISCAL_DB"
#: the alembic scripts shipped with axiscal
MIGRATIONS = Path(__file__).resolve().parent / "migrations"
# any number that no other application of the server uses for its advisory lock ("axiscal")
_LOCK_KEY = 0x61786973636C
# the first 16 bytes of every SQLite 3 file
_MAGIC = b"SQLite format 3\x00"


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


def sqlite_file(url: str) -> Path | None:
    """The file of an SQLite URL; None for another database or an in-memory one.

    Parameters
    ----------
    url : str
        A URL as :func:`resolve_url` gives it.

    Returns
    -------
    Path or None
    """
    if not url.startswith("sqlite"):
        return None
    from sqlalchemy.engine import make_url
    from sqlalchemy.exc import ArgumentError

    try:
        parsed = make_url(url)
    except ArgumentError:
        return None
    if not parsed.database or parsed.database == ":memory:" or parsed.query.get("uri"):
        return None
    return Path(parsed.database)


def _text(exc: BaseException) -> str:
    orig = getattr(exc, "orig", None) or exc
    return " ".join(str(orig).split()) or type(orig).__name__


def _failure(exc: BaseException, url: str) -> AxiscalError:
    """One line for a database error met on ``url``."""
    text = _text(exc)
    file = sqlite_file(url)
    if file is not None or url.startswith("sqlite"):
        where = file if file is not None else url
        if "file is not a database" in text:
            return AxiscalError("not an SQLite database (file is not a database)", path=where)
        if "malformed" in text or "corrupt" in text:
            return AxiscalError(f"the history database is damaged ({text}): {CHECK_HINT}restore it from a backup",
                                path=where)
        return AxiscalError(f"cannot use the history database: {text}", path=where)
    return AxiscalError(f"cannot reach the history database {shown_url(url)}: {text}")


@contextmanager
def database_errors(url: str) -> Iterator[None]:
    """Turn a database error met inside the block into one line naming the database.

    Parameters
    ----------
    url : str
        The database, as :func:`resolve_url` gives it.

    Returns
    -------
    contextlib.AbstractContextManager
        The block's guard (it yields nothing).

    Raises
    ------
    AxiscalError
        For an SQLAlchemy or SQLite error raised in the block (a damaged page met by a query, a
        lost server); an AxiscalError raised in the block passes as it is.
    """
    from sqlalchemy.exc import SQLAlchemyError

    try:
        yield
    except (SQLAlchemyError, sqlite3.Error) as exc:
        raise _failure(exc, url) from None


def _file_uri(file: Path, mode: str) -> str:
    return f"file:{quote(str(file.resolve()))}?mode={mode}"


#: where a command that met a damaged database sends the user (never said by ``history check`` itself)
CHECK_HINT = "`axiscal history check` lists the problems; "


def _refuse_unusable(file: Path, *, readonly: bool) -> bool:
    """Refuse a missing (when read-only) or empty SQLite file, or a folder; True when the file exists."""
    if not file.exists():
        if readonly:
            raise AxiscalError("no history database here (a command that only reads makes none; "
                               "`axiscal history add` makes it)", path=file)
        return False
    if not file.is_file():
        raise AxiscalError("is not a file: an SQLite history database is one file", path=file)
    size = file.stat().st_size
    if size == 0:
        raise AxiscalError("an empty file, not a history database (it is left as it is; remove it to make a new "
                           "history there)", path=file)
    try:
        with open(file, "rb") as handle:
            header = handle.read(100)
    except OSError as exc:
        raise AxiscalError(f"cannot read the history database: {exc.strerror or exc}", path=file) from None
    if not header.startswith(_MAGIC[:len(header)]) or (len(header) >= len(_MAGIC) and header[:len(_MAGIC)] != _MAGIC):
        raise AxiscalError("not an SQLite database (file is not a database)", path=file)
    page = int.from_bytes(header[16:18], "big") if len(header) >= 18 else 0
    page = 65536 if page == 1 else page
    if size < 100 or page < 512 or size % page:
        raise AxiscalError(f"the history database is damaged (truncated: {size} bytes, not whole pages of "
                           f"{page or 'its'} bytes): restore it from a backup", path=file)
    return True


def _quick_check(file: Path) -> None:
    """Refuse an SQLite file that is not a database or is damaged, reading it only."""
    try:
        connection = sqlite3.connect(_file_uri(file, "rw"), uri=True)
    except sqlite3.Error:
        connection = None
    if connection is None:
        try:
            connection = sqlite3.connect(_file_uri(file, "ro"), uri=True)
        except sqlite3.Error as exc:
            raise AxiscalError(f"cannot open the history database: {_text(exc)}", path=file) from None
    try:
        connection.execute("PRAGMA busy_timeout = 120000")
        connection.execute("PRAGMA query_only = 1")
        rows = [row[0] for row in connection.execute("PRAGMA quick_check")]
    except sqlite3.Error as exc:
        raise _failure(exc, f"sqlite:///{file}") from None
    finally:
        connection.close()
    if rows != ["ok"]:
        more = f" and {len(rows) - 1} more problems" if len(rows) > 1 else ""
        first = " ".join(str(rows[0]).split()) if rows else "no answer"
        raise AxiscalError(f"the history database is damaged ({first}{more}): {CHECK_HINT}restore it from a backup",
                           path=file)


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


def _sqlite_readonly(file: Path) -> Any:
    """An engine that reads ``file`` and can neither make it nor write to it."""
    from sqlalchemy import create_engine, event
    from sqlalchemy.pool import NullPool

    uri = _file_uri(file, "rw")  # rw: the file is never made; query_only: nothing is written

    def connect() -> sqlite3.Connection:
        try:
            return sqlite3.connect(uri, uri=True, check_same_thread=False)
        except sqlite3.OperationalError:
            return sqlite3.connect(_file_uri(file, "ro"), uri=True, check_same_thread=False)

    engine = create_engine("sqlite://", creator=connect, poolclass=NullPool)

    @event.listens_for(engine, "connect")
    def _connect(dbapi_connection: Any, record: Any) -> None:  # noqa: ARG001
        dbapi_connection.isolation_level = None
        cursor = dbapi_connection.cursor()
        cursor.execute("PRAGMA busy_timeout = 120000")
        cursor.execute("PRAGMA query_only = 1")
        cursor.close()

    @event.listens_for(engine, "begin")
    def _begin(connection: Any) -> None:
        connection.exec_driver_sql("BEGIN")

    return engine


def open_engine(url: str | None = None, *, migrate: bool = True, readonly: bool = False):
    """An engine on the history database, its schema brought to this axiscal's (alembic, on open).

    Parameters
    ----------
    url : str or None
        See :func:`resolve_url`.
    migrate : bool, keyword-only
        Run the shipped migrations up to the newest (default); False only checks the database is
        not of a newer schema.
    readonly : bool, keyword-only
        Only read: the database is neither made nor migrated nor written to (SQLite connections
        are ``query_only``, PostgreSQL transactions read-only); a missing or empty SQLite file, a
        database without the history's tables or of an older schema is refused.

    Returns
    -------
    sqlalchemy.engine.Engine

    Raises
    ------
    AxiscalError
        One line for a URL SQLAlchemy does not read, a driver that is not installed, a file that
        is not a database, an empty or damaged SQLite file (checked before anything is read or
        written; the file is left as it was), a server that cannot be reached, or a database of a
        newer schema than this axiscal knows (or that holds another application's tables).
    """
    check_instance("migrate", migrate, bool)
    check_instance("readonly", readonly, bool)
    return _engine(resolve_url(url), migrate=migrate and not readonly, readonly=readonly)


def _engine(url: str, *, migrate: bool, readonly: bool, quick_check: bool = True, schema: bool = True):
    """:func:`open_engine` on a resolved URL; ``quick_check`` and ``schema`` False for ``history check``."""
    from sqlalchemy import create_engine
    from sqlalchemy.exc import ArgumentError, NoSuchModuleError, SQLAlchemyError
    from sqlalchemy.pool import NullPool

    file = sqlite_file(url)
    if file is not None and _refuse_unusable(file, readonly=readonly) and quick_check:
        _quick_check(file)
    try:
        if file is not None and readonly:
            engine = _sqlite_readonly(file)
        elif url.startswith("sqlite"):
            engine = create_engine(url, poolclass=NullPool)
            _sqlite_setup(engine)
        else:
            connect_args: dict[str, Any] = {"connect_timeout": 10} if url.startswith("postgresql") else {}
            if readonly and url.startswith("postgresql"):
                connect_args["options"] = "-c default_transaction_read_only=on"
            engine = create_engine(url, poolclass=NullPool, connect_args=connect_args)
    except (ArgumentError, NoSuchModuleError) as exc:
        raise AxiscalError(f"cannot use the database URL {shown_url(url)}: {' '.join(str(exc).split())}") from None
    except ImportError as exc:
        raise AxiscalError(f"the database driver for {shown_url(url)} is not installed ({exc.name}); "
                           "for PostgreSQL: pip install 'psycopg[binary]'") from None
    if not schema:
        return engine
    try:
        _bring_up_to_date(engine, url, migrate=migrate, readonly=readonly)
    except AxiscalError:
        engine.dispose()
        raise
    except (SQLAlchemyError, sqlite3.Error, OSError) as exc:
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


def _bring_up_to_date(engine: Any, url: str, *, migrate: bool, readonly: bool = False) -> None:
    from alembic import command
    from alembic.config import Config
    from alembic.runtime.migration import MigrationContext
    from sqlalchemy import inspect, text

    script = _script()
    head = script.get_current_head()
    known = {rev.revision for rev in script.walk_revisions()}
    with engine.begin() as connection:
        if connection.dialect.name == "postgresql" and not readonly:
            connection.execute(text("SELECT pg_advisory_xact_lock(:key)"), {"key": _LOCK_KEY})
        current = MigrationContext.configure(connection).get_current_revision()
        if current == head:
            return
        where = shown_url(url)
        if current is not None and current not in known:
            raise AxiscalError(f"the history database {where} has schema revision {current}, newer than this "
                               f"axiscal knows ({head}): use a newer axiscal")
        if current is None:
            tables = set(inspect(connection).get_table_names())
            if tables - {"alembic_version"}:
                raise AxiscalError(f"the database {where} holds tables that are not an axiscal history "
                                   f"({', '.join(sorted(tables)[:3])} ...); give another database")
            if readonly:
                raise AxiscalError(f"the database {where} holds no axiscal history yet (a command that only reads "
                                   "sets none up; `axiscal history add` does)")
        if readonly:
            raise AxiscalError(f"the history database {where} has schema revision {current}, older than this "
                               f"axiscal's ({head}): `axiscal history upgrade` brings it up to date")
        if not migrate:
            return
        config = Config()
        config.set_main_option("script_location", str(MIGRATIONS))
        config.attributes["connection"] = connection
        command.upgrade(config, "head")
