"""``axiscal workbench --db``: a history that cannot be used is refused at start, in one line, as the history commands do.

Before, the server started and served its page; the error was swallowed in the thread that read the history first.
"""

from __future__ import annotations

import random
import sqlite3

import pytest

from axiscal.errors import AxiscalError
from axiscal.history import Drift, add_results, drifting_results, write_results
from axiscal.workbench import serve_workbench


@pytest.fixture
def healthy(tmp_path):
    """A history database holding one machine's three campaigns."""
    db = tmp_path / "healthy.sqlite"
    payloads = drifting_results({"positioning.X.E": Drift(12.0, 4.0, 0.5, 40.0)}, machine="Lathe 7", serial="L7", campaigns=3)
    add_results(write_results(tmp_path / "results", payloads), url=str(db))
    return db


def _text_file(tmp_path, healthy):
    path = tmp_path / "notes.sqlite"
    path.write_text("these are my notes, not a database\n" * 100)
    return str(path), "not an SQLite database"


def _cut_short(tmp_path, healthy):
    path = tmp_path / "cut.sqlite"
    data = healthy.read_bytes()
    path.write_bytes(data[: len(data) - 1000])
    return str(path), "damaged (truncated"


def _damaged(tmp_path, healthy):
    path = tmp_path / "damaged.sqlite"
    data = bytearray(healthy.read_bytes())
    data[4096:8192] = random.Random(7).randbytes(4096)  # the second page: random bytes
    path.write_bytes(bytes(data))
    return str(path), "damaged"


def _newer_schema(tmp_path, healthy):
    with sqlite3.connect(healthy) as connection:
        connection.execute("UPDATE alembic_version SET version_num = '0042'")
    connection.close()
    return str(healthy), "schema revision 0042, newer than this axiscal knows"


def _another_application(tmp_path, healthy):
    path = tmp_path / "shop.sqlite"
    with sqlite3.connect(path) as connection:
        connection.execute("CREATE TABLE customers (id INTEGER PRIMARY KEY, name TEXT)")
        connection.execute("INSERT INTO customers (name) VALUES ('ACME')")
    connection.close()
    return str(path), "holds tables that are not an axiscal history (customers"


def _folder(tmp_path, healthy):
    path = tmp_path / "a-folder"
    path.mkdir()
    return str(path), "is not a file"


def _mysql(tmp_path, healthy):
    return "mysql://cal:secret@127.0.0.1:1/history", "mysql://cal:***@127.0.0.1:1/history"


def _unreachable_postgresql(tmp_path, healthy):
    return "postgresql://cal:secret@127.0.0.1:1/history", "cannot reach the history database postgresql+psycopg://cal:***@127.0.0.1:1"


CASES = {"a text file": _text_file, "cut short": _cut_short, "damaged": _damaged, "a newer schema": _newer_schema,
         "another application's": _another_application, "a folder": _folder, "mysql://": _mysql,
         "an unreachable PostgreSQL": _unreachable_postgresql}


@pytest.mark.parametrize("case", CASES)
def test_the_library_refuses_the_history_before_it_serves(tmp_path, healthy, case):
    db, expected = CASES[case](tmp_path, healthy)
    server = None
    try:
        with pytest.raises(AxiscalError) as refused:
            server = serve_workbench(tmp_path / "data", db=db, port=0)
    finally:
        if server is not None:
            server.stop()
    assert expected in str(refused.value) and "\n" not in str(refused.value)
    assert "secret" not in str(refused.value)


@pytest.mark.parametrize("case", CASES)
def test_the_command_says_it_in_one_line_and_exits_2(run_cli, tmp_path, healthy, case):
    db, expected = CASES[case](tmp_path, healthy)
    # a file that is no usable SQLite history is refused before it is opened: left byte for byte as it was
    unopened = case in ("a text file", "cut short", "damaged")
    before = (tmp_path / db).read_bytes() if unopened else None
    status, out, err = run_cli("workbench", "--db", db, "--data", tmp_path / "data", "--port", "0")
    assert status == 2 and out == "", err
    assert len(err.splitlines()) == 1 and err.startswith("axiscal: error: ") and expected in err
    assert "Traceback" not in err and "secret" not in err and "workbench: http" not in err
    if before is not None:
        assert (tmp_path / db).read_bytes() == before  # left as it was


def test_a_healthy_history_and_a_new_one_are_served(tmp_path, healthy):
    for db, machines in ((str(healthy), ["Lathe 7 (L7)"]), (str(tmp_path / "new.sqlite"), [])):
        server = serve_workbench(tmp_path / "data", db=db, port=0)
        try:
            assert [m["machine"] for m in server.bench.machines()] == machines
        finally:
            server.stop()
