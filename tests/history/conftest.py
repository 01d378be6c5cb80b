"""The history's databases: each test runs on SQLite and on a real PostgreSQL server.

pytest-postgresql starts the server once per session (Debian's postgresql; ``make test`` installs
it) through ``pg_ctl.sh``, which runs it as the postgres user when the tests run as root; every
test gets a fresh database.
"""

from __future__ import annotations

import datetime as _dt
from pathlib import Path

import pytest
from pytest_postgresql import factories

from axiscal.history.synthetic import Drift, drifting_results, write_results

postgresql_server = factories.postgresql_proc(executable=str(Path(__file__).with_name("pg_ctl.sh")), port=None)
postgresql_database = factories.postgresql("postgresql_server")


@pytest.fixture(params=["sqlite", "postgresql"])
def db_url(request, tmp_path) -> str:
    """A URL of an empty history database: an SQLite file, then a PostgreSQL database."""
    if request.param == "sqlite":
        return f"sqlite:///{tmp_path / 'history.sqlite'}"
    connection = request.getfixturevalue("postgresql_database")
    info = connection.info
    return f"postgresql+psycopg://{info.user}@{info.host}:{info.port}/{info.dbname}"


@pytest.fixture
def results_files(tmp_path) -> list[Path]:
    """Two machines' generated results files: four campaigns of VMC-1, three of VMC-2."""
    first = drifting_results({"positioning.X.E": Drift(10.0, 2.0, 1.0, 20.0), "positioning.X.R": Drift(2.0, 0.1, 0.4, 5.0)},
                             machine="VMC", serial="1", campaigns=4, seed=1)
    second = drifting_results({"positioning.Y.E": Drift(15.0, -1.0, 1.5, 25.0)}, machine="VMC", serial="2",
                              campaigns=3, start=_dt.date(2021, 3, 1), seed=2)
    return write_results(tmp_path / "a", first) + write_results(tmp_path / "b", second)
