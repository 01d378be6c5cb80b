"""``axiscal history``: add, list, show, export, remove, upgrade, and one line for each refusal."""

from __future__ import annotations

import json

from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from axiscal.errors import AxiscalError
from axiscal.history import read_results


def test_add_list_show_export_remove(run_cli, results_files, tmp_path):
    db = f"sqlite:///{tmp_path / 'h.sqlite'}"
    status, out, _ = run_cli("history", "add", *results_files, "--db", db)
    assert status == 0 and out.count("stored campaign") == 7
    status, out, _ = run_cli("history", "add", results_files[0], "--db", db)
    assert status == 0 and out.startswith("already stored campaign 1")
    status, out, _ = run_cli("history", "list", "--machine", "VMC (2)", "--db", db)
    assert status == 0 and len(out.splitlines()) == 3
    status, out, _ = run_cli("history", "show", "VMC (1)", "--db", db)
    assert status == 0 and out.count("positioning.X.E") == 4
    status, out, _ = run_cli("history", "export", "VMC (1)", "-o", tmp_path / "x.csv", "--db", db)
    assert status == 0 and (tmp_path / "x.csv").read_text().count("\n") == 9
    status, out, _ = run_cli("history", "remove", "1", "--db", db)
    assert status == 0 and out.startswith("removed campaign 1")
    status, out, _ = run_cli("history", "upgrade", "--db", db)
    assert status == 0 and out.rstrip().endswith("schema revision 0001")


def test_the_database_comes_from_the_environment(run_cli, results_files, tmp_path, monkeypatch):
    monkeypatch.setenv("AXISCAL_DB", str(tmp_path / "env.sqlite"))
    assert run_cli("history", "add", results_files[0])[0] == 0
    assert (tmp_path / "env.sqlite").is_file()


def test_the_default_database_is_in_the_users_data_folder(run_cli, results_files, tmp_path, monkeypatch):
    monkeypatch.delenv("AXISCAL_DB", raising=False)
    monkeypatch.setenv("XDG_DATA_HOME", str(tmp_path / "data"))
    assert run_cli("history", "add", results_files[0])[0] == 0
    assert (tmp_path / "data" / "axiscal" / "history.sqlite").is_file()


def test_a_file_that_is_not_a_database_is_one_line(run_cli, results_files, tmp_path):
    bad = tmp_path / "notes.sqlite"
    bad.write_text("these are my notes, not a database\n" * 100)
    status, out, err = run_cli("history", "add", results_files[0], "--db", bad)
    assert status == 2 and out == ""
    assert err == f"axiscal: error: {bad}: not an SQLite database (file is not a database)\n"


def test_a_newer_schema_is_one_line(run_cli, results_files, tmp_path):
    import sqlite3

    db = tmp_path / "h.sqlite"
    assert run_cli("history", "add", results_files[0], "--db", db)[0] == 0
    with sqlite3.connect(db) as connection:
        connection.execute("UPDATE alembic_version SET version_num = '0042'")
    status, _, err = run_cli("history", "list", "--db", db)
    assert status == 2 and len(err.splitlines()) == 1
    assert "schema revision 0042, newer than this axiscal knows (0001)" in err


def test_an_unreachable_server_is_one_line(run_cli, results_files):
    status, _, err = run_cli("history", "list", "--db", "postgresql://someone:secret@127.0.0.1:1/history")
    assert status == 2 and len(err.splitlines()) == 1
    assert err.startswith("axiscal: error: cannot reach the history database postgresql+psycopg://someone:***@127.0.0.1:1")
    assert "secret" not in err


def test_a_bad_url_and_a_bad_results_file_are_one_line(run_cli, results_files, tmp_path):
    status, _, err = run_cli("history", "list", "--db", "nosuchdb://x")
    assert status == 2 and err.startswith("axiscal: error: cannot use the database URL nosuchdb://x")
    bad = tmp_path / "results.json"
    payload = json.loads(results_files[0].read_text())
    del payload["campaign"]["campaign"]["date"]
    bad.write_text(json.dumps(payload, indent=1))
    status, out, err = run_cli("history", "add", results_files[0], bad, "--db", tmp_path / "h.sqlite")
    assert status == 2 and out == ""
    assert err.startswith(f"axiscal: error: {bad}:") and "campaign.campaign.date must be a date" in err
    assert not (tmp_path / "h.sqlite").exists()


@settings(max_examples=150, suppress_health_check=[HealthCheck.function_scoped_fixture])
@given(data=st.data())
def test_a_mutated_results_file_is_read_or_refused_cleanly(results_files, tmp_path, data):
    text = results_files[0].read_bytes()
    at = data.draw(st.integers(0, len(text) - 1))
    kind = data.draw(st.sampled_from(["delete", "replace", "insert", "truncate"]))
    byte = bytes([data.draw(st.integers(0, 255))])
    mutated = {"delete": text[:at] + text[at + 1:], "replace": text[:at] + byte + text[at + 1:],
               "insert": text[:at] + byte + text[at:], "truncate": text[:at]}[kind]
    path = tmp_path / "mutated.json"
    path.write_bytes(mutated)
    try:
        record = read_results(path)
    except AxiscalError as exc:
        assert str(exc).startswith(str(path)) and "\n" not in str(exc)
    else:
        assert record.machine and record.date.year >= 1
        assert all(f.key.count(".") >= 2 for f in record.figures)


def test_the_url_forms(tmp_path, monkeypatch):
    from axiscal.history import resolve_url

    monkeypatch.delenv("AXISCAL_DB", raising=False)
    assert resolve_url(str(tmp_path / "h.sqlite")) == f"sqlite:///{tmp_path / 'h.sqlite'}"
    assert resolve_url("postgresql://cal@db.local/history") == "postgresql+psycopg://cal@db.local/history"
    assert resolve_url("postgres://cal@db.local/history") == "postgresql+psycopg://cal@db.local/history"
    assert resolve_url("sqlite:///x.sqlite") == "sqlite:///x.sqlite"
    monkeypatch.setenv("AXISCAL_DB", "postgresql+psycopg://cal@server/h")
    assert resolve_url() == "postgresql+psycopg://cal@server/h"


def test_report_db_without_history_is_refused(run_cli, examples, tmp_path):
    status, _, err = run_cli("report", examples / "campaign", "-o", tmp_path / "r", "--db", tmp_path / "h.sqlite")
    assert status == 2 and err == "axiscal: error: --db applies only with --history\n"
    assert not (tmp_path / "r").exists()
