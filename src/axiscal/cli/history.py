"""``axiscal history``: the calibration history database: add, list, show, export, remove, upgrade, trend, check."""

from __future__ import annotations

import click

from axiscal.cli.common import FINITE, echo_json
from axiscal.cli.choices import DB_ENVIRONMENT

__all__ = ["history_group"]

_DB_HELP = (f"Database URL (sqlite:///FILE, postgresql+psycopg://USER@HOST/DB) or an SQLite file name "
            f"[${DB_ENVIRONMENT}, else history.sqlite in the user's data folder].")


def _db_option(command):
    return click.option("--db", "db", envvar=DB_ENVIRONMENT, help=_DB_HELP)(command)


@click.group("history")
def history_group() -> None:
    """Calibration history of machines in a database: drift and calibration intervals (docs/history.md)."""


@history_group.command("add")
@click.argument("results", nargs=-1, required=True, type=click.Path(dir_okay=False))
@_db_option
def add_command(results: tuple[str, ...], db: str | None) -> None:
    """Store campaigns from their results.json files (a file already stored is stored once)."""
    from axiscal.history.store import add_results

    def progress(added) -> None:
        state = "stored" if added.new else "already stored"
        click.echo(f"{state} campaign {added.campaign_id}: {added.machine}, {added.date.isoformat()} ({added.source})")

    add_results(list(results), url=db, progress=progress)


@history_group.command("list")
@click.option("--machine", help="Only this machine (name, serial, 'name (serial)' or id).")
@_db_option
def list_command(machine: str | None, db: str | None) -> None:
    """List the stored campaigns: id, date, machine, verdict, title."""
    from axiscal.history.store import list_campaigns

    for c in list_campaigns(machine, url=db):
        serial = f" ({c.serial})" if c.serial else ""
        click.echo(f"{c.id:>6}  {c.date.isoformat()}  {c.machine}{serial}  {c.verdict}  {c.title}")


@history_group.command("show")
@click.argument("machine")
@_db_option
def show_command(machine: str, db: str | None) -> None:
    """Show every campaign of MACHINE with its toleranced figures."""
    from axiscal.history.store import machine_history

    history = machine_history(machine, url=db)
    click.echo(f"{history.label}: {len(history.campaigns)} campaigns")
    for c in history.campaigns:
        click.echo(f"campaign {c.id}  {c.date.isoformat()}  {c.verdict}  {c.title}")
        for f in c.figures:
            if f.tolerance is None:
                continue
            value = "n/a" if f.value is None else f"{f.value:.3f}"
            U = "" if f.U is None else f" U={f.U:.3f}"
            click.echo(f"    {f.key:<40} {value:>10} / {f.tolerance:g} {f.unit}{U}  {f.result}")


@history_group.command("export")
@click.argument("machine")
@click.option("-o", "--output", required=True, type=click.Path(dir_okay=False), help="The CSV to write (and its JSON sidecar).")
@_db_option
def export_command(machine: str, output: str, db: str | None) -> None:
    """Write MACHINE's history as a plain CSV, one row per campaign and figure."""
    from axiscal.history.store import export_history

    click.echo(f"wrote {export_history(machine, output, url=db)}")


@history_group.command("remove")
@click.argument("campaign_id", type=int)
@_db_option
def remove_command(campaign_id: int, db: str | None) -> None:
    """Remove the campaign CAMPAIGN_ID (as `history list` shows it) and its figures."""
    from axiscal.history.store import remove_campaign

    c = remove_campaign(campaign_id, url=db)
    click.echo(f"removed campaign {c.id}: {c.machine}, {c.date.isoformat()}")


@history_group.command("upgrade")
@_db_option
def upgrade_command(db: str | None) -> None:
    """Bring the database's schema to this axiscal's (opening it does the same)."""
    from axiscal.history.store import upgrade_database

    where, revision = upgrade_database(db)
    click.echo(f"{where}: schema revision {revision}")


@history_group.command("trend")
@click.argument("machine")
@click.option("--figure", required=True, help="The figure, KIND.AXIS.FIGURE (e.g. positioning.X.E; see `history show`).")
@click.option("--robust", is_flag=True, help="Fit the drift with Huber weights (outlying campaigns count less).")
@click.option("--risk", type=FINITE, default=0.05, show_default=True,
              help="Accepted probability of being out of tolerance at the next calibration (fixed-risk rule).")
@click.option("--plot", type=click.Path(dir_okay=False), help="Write the trend plot (PNG, SVG, PDF).")
@click.option("--json", "as_json", is_flag=True, help="Print the trend as JSON.")
@_db_option
def trend_command(machine: str, figure: str, robust: bool, risk: float, plot: str | None, as_json: bool,
                  db: str | None) -> None:
    """A figure of MACHINE over time: drift, the date it leaves its tolerance, the next calibration date."""
    from axiscal.history.analysis import figure_trend

    trend = figure_trend(machine, figure, url=db, method="robust" if robust else "wls", risk=risk, plot=plot)
    if as_json:
        echo_json(trend.payload())
        return
    p = trend.payload()
    fit, nxt = p["fit"], p["next_calibration"]
    click.echo(f"{trend.machine}: {trend.figure} over {len(trend.dates)} campaigns, tolerance {trend.tolerance:g} {trend.unit}")
    click.echo(f"drift {fit['slope_per_year']:+.4g} {trend.unit}/year, u = {fit['u_slope_per_year']:.2g} ({fit['method']})")
    low, high = p["crossing_interval"]
    click.echo(f"reaches the tolerance {trend.crossing_text}"
               f" (k = {trend.k:g}: {low or 'unbounded'} .. {high or 'unbounded'})")
    click.echo(f"next calibration {nxt['recommended']} (fixed risk {trend.risk:.0%}: {nxt['fixed_risk'] or 'beyond the horizon'};"
               f" staircase: {nxt['staircase']})")
    if plot:
        click.echo(f"plot {plot}")


@history_group.command("check")
@_db_option
def check_command(db: str | None) -> None:
    """Check the database whole (SQLite's integrity check) and every campaign complete; exit 1 on problems.

    Only reads: a missing, empty or unreadable database is refused (exit 2), never made.
    """
    from axiscal.history.integrity import integrity_problems

    problems = integrity_problems(db)
    if not problems:
        click.echo("ok: the database and every campaign in it are whole")
        return
    for problem in problems:
        click.echo(problem)
    click.echo(f"{len(problems)} problem{'s' if len(problems) != 1 else ''}: restore the database from a backup")
    click.get_current_context().exit(1)
