"""The history store on SQLite and PostgreSQL: add once, list, show, export, remove, refusals."""

from __future__ import annotations

import json
import shutil

import pytest

from axiscal.errors import AxiscalError
from axiscal.history import (
    EXPORT_COLUMNS,
    add_results,
    export_history,
    list_campaigns,
    machine_history,
    open_engine,
    read_results,
    remove_campaign,
    upgrade_database,
)


def test_adding_the_same_file_twice_stores_it_once(db_url, results_files):
    first = add_results(results_files, url=db_url)
    again = add_results(results_files[:2], url=db_url)
    assert [a.new for a in first] == [True] * 7
    assert [a.new for a in again] == [False, False]
    assert [a.campaign_id for a in again] == [a.campaign_id for a in first[:2]]
    assert len(list_campaigns(url=db_url)) == 7


def test_a_copy_of_a_file_under_another_name_is_the_same_campaign(db_url, results_files, tmp_path):
    copy = tmp_path / "copy.json"
    shutil.copy(results_files[0], copy)
    add_results([results_files[0]], url=db_url)
    assert add_results([copy], url=db_url)[0].new is False


def test_show_gives_every_campaign_with_its_figures(db_url, results_files):
    add_results(results_files, url=db_url)
    history = machine_history("VMC (1)", url=db_url)
    assert len(history.campaigns) == 4
    assert history.keys == ["positioning.X.E", "positioning.X.R"]
    series = history.series("positioning.X.E")
    stored = read_results(results_files[2]).figures[0]
    assert series[2][1] == stored
    assert series[2][1].tolerance == 20.0 and series[2][1].U == 1.0 and series[2][1].unit == "um"
    assert [d for d, _ in series] == sorted(d for d, _ in series)


def test_a_machine_is_found_by_serial_and_id_and_a_shared_name_is_refused(db_url, results_files):
    add_results(results_files, url=db_url)
    assert machine_history("2", url=db_url).serial in ("1", "2")
    assert len(list_campaigns("VMC (2)", url=db_url)) == 3
    with pytest.raises(AxiscalError, match="names 2 machines"):
        machine_history("VMC", url=db_url)
    with pytest.raises(AxiscalError, match="no machine 'Lathe'"):
        list_campaigns("Lathe", url=db_url)


def test_remove_takes_the_campaign_and_its_figures(db_url, results_files):
    added = add_results(results_files, url=db_url)
    removed = remove_campaign(added[0].campaign_id, url=db_url)
    assert removed.date == added[0].date
    assert len(machine_history("VMC (1)", url=db_url).campaigns) == 3
    for a in added[4:]:
        remove_campaign(a.campaign_id, url=db_url)
    with pytest.raises(AxiscalError, match="no machine"):
        machine_history("VMC (2)", url=db_url)
    with pytest.raises(AxiscalError, match="no campaign 999"):
        remove_campaign(999, url=db_url)
    from sqlalchemy import text

    engine = open_engine(db_url)
    with engine.connect() as connection:
        assert connection.execute(text("SELECT count(*) FROM figures")).scalar_one() == 3 * 2
    engine.dispose()


def test_export_is_one_row_per_campaign_and_figure(db_url, results_files, tmp_path):
    import pandas as pd

    add_results(results_files, url=db_url)
    path = export_history("VMC (1)", tmp_path / "vmc1.csv", url=db_url)
    table = pd.read_csv(path)
    assert tuple(table.columns) == EXPORT_COLUMNS
    assert len(table) == 4 * 2
    assert set(table["figure"]) == {"positioning.X.E", "positioning.X.R"}
    assert json.loads(path.with_suffix(".json").read_text())["kind"] == "calibration history"


def test_sqlite_and_postgresql_give_identical_exports(results_files, tmp_path, request):
    files = {}
    for name in ("sqlite", "postgresql"):
        if name == "sqlite":
            url = f"sqlite:///{tmp_path / 'h.sqlite'}"
        else:
            info = request.getfixturevalue("postgresql_database").info
            url = f"postgresql+psycopg://{info.user}@{info.host}:{info.port}/{info.dbname}"
        add_results(results_files, url=url)
        add_results(results_files[3:], url=url)
        remove_campaign(2, url=url)
        files[name] = export_history("VMC (1)", tmp_path / f"{name}.csv", url=url).read_bytes()
    assert files["sqlite"] == files["postgresql"]
    assert files["sqlite"].count(b"\n") == 1 + 3 * 2


def test_upgrade_names_the_revision(db_url):
    where, revision = upgrade_database(db_url)
    assert revision == "0001"
    assert "@" not in where or ":" not in where.split("@")[0].split("//")[1] or "***" in where


def test_a_newer_schema_is_refused_with_one_line(db_url):
    from sqlalchemy import text

    upgrade_database(db_url)
    engine = open_engine(db_url)
    with engine.begin() as connection:
        connection.execute(text("UPDATE alembic_version SET version_num = '9999'"))
    engine.dispose()
    with pytest.raises(AxiscalError, match="schema revision 9999, newer than this axiscal knows"):
        list_campaigns(url=db_url)


def test_another_applications_database_is_refused(db_url):
    from sqlalchemy import create_engine, text

    engine = create_engine(db_url)
    with engine.begin() as connection:
        connection.execute(text("CREATE TABLE invoices (id integer)"))
    engine.dispose()
    with pytest.raises(AxiscalError, match="not an axiscal history"):
        list_campaigns(url=db_url)


def test_the_migrations_build_the_models(db_url):
    from alembic.autogenerate import compare_metadata
    from alembic.runtime.migration import MigrationContext

    from axiscal.history.models import Base

    engine = open_engine(db_url)
    with engine.connect() as connection:
        diff = compare_metadata(MigrationContext.configure(connection), Base.metadata)
    engine.dispose()
    assert diff == []
