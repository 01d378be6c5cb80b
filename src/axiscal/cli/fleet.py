"""``axiscal fleet report``: every campaign of a folder reported in parallel on Dask, and the fleet's page."""

from __future__ import annotations

import click

from axiscal.cli.common import FINITE
from axiscal.errors import AxiscalError
from axiscal.cli.choices import FLEET_SCHEDULER_TIMEOUT_S as SCHEDULER_TIMEOUT_S

__all__ = ["fleet_group", "fleet_report_command"]


@click.group("fleet")
def fleet_group() -> None:
    """Many machines at once: campaigns reported in parallel, one page ranking the machines (docs/history.md)."""


@fleet_group.command("report")
@click.argument("campaigns_dir", type=click.Path(file_okay=False))
@click.option("-o", "--output", "out_dir", required=True, type=click.Path(file_okay=False),
              help="Where each campaign's report, fleet.html and fleet.json go.")
@click.option("--scheduler", default="local", show_default=True,
              help='"local" (a Dask LocalCluster), "threads" (this process) or a scheduler address (tcp://host:8786).')
@click.option("--workers", type=int, default=2, show_default=True, help="Workers of the LocalCluster, or threads.")
@click.option("--scheduler-timeout-s", "timeout_s", type=FINITE, default=SCHEDULER_TIMEOUT_S, show_default=True,
              help="Seconds to wait for a scheduler given by address.")
@click.option("--history", is_flag=True, help="Store every campaign in the calibration history; trends use all stored campaigns.")
@click.option("--db", help="With --history: the database URL or SQLite file [$AXISCAL_DB, else the user's data folder].")
def fleet_report_command(campaigns_dir: str, out_dir: str, scheduler: str, workers: int, timeout_s: float,
                         history: bool, db: str | None) -> None:
    """Report every campaign under CAMPAIGNS_DIR (folders with campaign.toml); exit 1 when any could not be.

    OUT is replaced as a whole once everything is written (an existing OUT must be empty or an
    earlier fleet report).
    """
    from axiscal.fleet.report import fleet_report

    if db is not None and not history:
        raise AxiscalError("--db applies only with --history")
    fleet = fleet_report(campaigns_dir, out_dir, scheduler=scheduler, workers=workers, timeout_s=timeout_s,
                         history=history, db=db)
    run = fleet.run
    click.echo(f"{len(run.outcomes)} campaigns of {len(fleet.machines)} machines in {run.seconds:.1f} s "
               f"({run.scheduler}); {fleet.failed} failed")
    for outcome in run.outcomes:
        if outcome.error:
            click.echo(f"failed {outcome.folder}: {outcome.error}")
    for row in fleet.machines:
        if row.error:
            click.echo(f"failed machine {row.machine}: {row.error}")
    click.echo(f"fleet {fleet.html}")
    click.echo(f"json {fleet.json}")
    if fleet.failed or fleet.failed_machines:
        click.get_current_context().exit(1)
