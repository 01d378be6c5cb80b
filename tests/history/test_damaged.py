"""Damaged SQLite histories: random bytes over a page, a truncated file, an empty file.

Every history command ends in one line naming the file with exit status 2 (``history check`` lists
the problems and exits 1 when it can read the file at all), and leaves the file byte for byte as
it was, writing nothing beside it. The commands that only read (list, show, export, trend, check)
never make or change a database: a missing or empty file is refused, not set up.
"""

from __future__ import annotations

import hashlib
import random
import shutil
import sqlite3

import pytest

from axiscal.errors import AxiscalError
from axiscal.history import add_results, integrity_problems, list_campaigns

PAGE = 4096
PAGE_TRIALS = 6
TRUNCATION_TRIALS = 4


def _commands(results, out):
    return {
        "add": ["history", "add", results],
        "list": ["history", "list"],
        "show": ["history", "show", "VMC (1)"],
        "export": ["history", "export", "VMC (1)", "-o", out / "x.csv"],
        "remove": ["history", "remove", "1"],
        "upgrade": ["history", "upgrade"],
        "trend": ["history", "trend", "VMC (1)", "--figure", "positioning.X.E"],
        "check": ["history", "check"],
    }


@pytest.fixture
def healthy(results_files, tmp_path):
    db = tmp_path / "healthy.sqlite"
    add_results(results_files, url=str(db))
    assert integrity_problems(str(db)) == [] and db.stat().st_size % PAGE == 0
    return db


def _digest(path):
    return hashlib.sha256(path.read_bytes()).hexdigest()


def _damaged_copies(healthy, folder):
    """(name, bytes) of damaged copies: random bytes over a page, truncations, an empty file."""
    data = healthy.read_bytes()
    pages = len(data) // PAGE
    rng = random.Random(7)
    out = []
    for page in [1] + rng.sample(range(2, pages + 1), PAGE_TRIALS - 1):
        damaged = bytearray(data)
        damaged[(page - 1) * PAGE:page * PAGE] = rng.randbytes(PAGE)
        out.append((f"page {page} of {pages}", bytes(damaged)))
    for size in [rng.randrange(1, 100), rng.randrange(100, PAGE)] + [rng.randrange(PAGE, len(data)) for _ in range(TRUNCATION_TRIALS - 2)]:
        out.append((f"truncated to {size} of {len(data)} bytes", data[:size]))
    out.append(("empty", b""))
    return out


def test_every_command_refuses_a_damaged_database_in_one_line_and_leaves_it_as_it_was(run_cli, healthy, results_files, tmp_path):
    for name, content in _damaged_copies(healthy, tmp_path):
        folder = tmp_path / name.replace(" ", "_")
        folder.mkdir()
        db = folder / "history.sqlite"
        db.write_bytes(content)
        before = _digest(db)
        for command, argv in _commands(results_files[0], folder).items():
            status, out, err = run_cli(*argv, "--db", db)
            where = f"{command} on a database with {name}"
            assert _digest(db) == before, f"{where}: the file changed"
            assert sorted(p.name for p in folder.iterdir()) == ["history.sqlite"], f"{where}: wrote {list(folder.iterdir())}"
            assert "Traceback" not in err + out, where
            if command == "check" and status == 1:
                assert out.splitlines()[-1].endswith("problems: restore the database from a backup") or \
                    out.splitlines()[-1].endswith("problem: restore the database from a backup"), where
                assert err == "", where
                continue
            assert status == 2, f"{where}: exit {status}, {out!r} {err!r}"
            assert out == "" and err.startswith(f"axiscal: error: {db}: ") and err.count("\n") == 1, f"{where}: {err!r}"
            if name == "empty":
                assert "an empty file, not a history database" in err, err
            else:
                assert "damaged" in err or "not an SQLite database" in err, f"{where}: {err!r}"


def test_check_lists_the_problems_of_a_damaged_page_and_exits_1(run_cli, healthy, tmp_path):
    data = bytearray(healthy.read_bytes())
    data[-PAGE:] = random.Random(3).randbytes(PAGE)  # the last page: figures
    db = tmp_path / "damaged.sqlite"
    db.write_bytes(bytes(data))
    status, out, err = run_cli("history", "check", "--db", db)
    assert status == 1 and err == "" and "sqlite:" in out
    status, out, err = run_cli("history", "check", "--db", healthy)
    assert status == 0 and out == "ok: the database and every campaign in it are whole\n"


def test_check_finds_a_campaign_missing_figures(run_cli, healthy):
    with sqlite3.connect(healthy) as connection:
        connection.execute("PRAGMA foreign_keys = OFF")
        connection.execute("DELETE FROM figures WHERE id = (SELECT min(id) FROM figures)")
    connection.close()
    status, out, _ = run_cli("history", "check", "--db", healthy)
    assert status == 1 and "campaign 1 holds 1 of its 2 figures" in out and out.endswith("1 problem: restore the database from a backup\n")


def test_reading_commands_never_make_or_change_a_database(run_cli, healthy, tmp_path):
    missing = tmp_path / "missing.sqlite"
    for argv in (["list"], ["show", "VMC (1)"], ["export", "VMC (1)", "-o", "{out}"],
                 ["trend", "VMC (1)", "--figure", "positioning.X.E"], ["check"]):
        line = [str(a).format(out=tmp_path / "from_missing.csv") for a in argv]
        status, out, err = run_cli("history", *line, "--db", missing)
        assert status == 2 and out == "" and "no history database here" in err and err.count("\n") == 1, err
        assert not missing.exists() and not (tmp_path / "from_missing.csv").exists()
        before, names = _digest(healthy), sorted(p.name for p in tmp_path.iterdir())
        line = [str(a).format(out=tmp_path / "out" / "x.csv") for a in argv]
        status, _, err = run_cli("history", *line, "--db", healthy)
        assert status == 0, err
        assert _digest(healthy) == before
        assert sorted(p.name for p in tmp_path.iterdir() if p.name != "out") == [n for n in names if n != "out"]
    with pytest.raises(AxiscalError, match="no history database here"):
        list_campaigns(url=str(missing))


def test_reading_commands_refuse_a_database_without_the_history(run_cli, tmp_path):
    db = tmp_path / "plain.sqlite"
    sqlite3.connect(db).close()  # SQLite makes no file for a connection that writes nothing
    db.write_bytes(b"")
    with sqlite3.connect(db) as connection:
        connection.execute("PRAGMA user_version = 1")  # a valid database holding no table
    connection.close()
    before = _digest(db)
    status, _, err = run_cli("history", "list", "--db", db)
    assert status == 2 and "holds no axiscal history yet" in err and _digest(db) == before
    status, _, err = run_cli("history", "check", "--db", db)
    assert status == 2 and "holds no axiscal history" in err and _digest(db) == before
    assert run_cli("history", "upgrade", "--db", db)[0] == 0  # a writer sets it up
    assert run_cli("history", "list", "--db", db)[0] == 0


def test_a_new_database_is_refused_by_readers_and_checked_whole_once_written(db_url, results_files):
    # an empty SQLite file name or an empty PostgreSQL database: readers refuse it, set nothing up
    with pytest.raises(AxiscalError, match="no history database here|holds no axiscal history yet"):
        list_campaigns(url=db_url)
    with pytest.raises(AxiscalError, match="no history database here|holds no axiscal history"):
        integrity_problems(db_url)
    add_results(results_files, url=db_url)
    assert integrity_problems(db_url) == [] and len(list_campaigns(url=db_url)) == 7


def test_check_never_sends_the_user_to_itself(run_cli, healthy, tmp_path):
    # a file cut short: `history check` says what is wrong and what to do, not "`axiscal history check` lists
    # the problems"; the other commands still point to it where it has more to say
    data = healthy.read_bytes()
    for size in (50, PAGE + 100, len(data) - 1):
        db = tmp_path / f"cut_{size}.sqlite"
        db.write_bytes(data[:size])
        status, out, err = run_cli("history", "check", "--db", db)
        if status == 1:  # read at all: the problems listed
            assert "history check" not in out and out.splitlines()[-1].endswith("restore the database from a backup")
            continue
        assert status == 2 and err.count("\n") == 1 and "history check" not in err, err
        assert "restore it from a backup" in err or "not an SQLite database" in err, err
    status, out, err = run_cli("history", "check", "--db", tmp_path / f"cut_{len(data) - 1}.sqlite")
    assert status == 2 and "truncated" in err and "history check" not in err, err
