"""``axiscal report``: run a calibration campaign and write its report, results and compensation files."""

from __future__ import annotations

import sys
from contextlib import contextmanager

import click

from axiscal.errors import AxiscalError

__all__ = ["report_command"]


@contextmanager
def _progress(enabled: bool):
    """A Rich progress bar on a terminal; nothing when output is redirected."""
    if not enabled:
        yield None
        return
    from rich.progress import (
        BarColumn,
        MofNCompleteColumn,
        Progress,
        TextColumn,
        TimeElapsedColumn,
    )

    with Progress(
        TextColumn("[bold]{task.description}"), BarColumn(), MofNCompleteColumn(), TimeElapsedColumn(), transient=True
    ) as bar:
        task = bar.add_task("tests", total=None)

        def update(done: int, total: int, spec) -> None:
            bar.update(task, total=total, completed=done, description=f"{spec.id}" if done < total else "writing")

        yield update


@click.command("report")
@click.argument("campaign_dir", type=click.Path(file_okay=True, dir_okay=True))
@click.option("-o", "--output", "out_dir", type=click.Path(file_okay=False), help="Report folder [CAMPAIGN_DIR/report].")
@click.option("--compare", type=click.Path(dir_okay=False), help="results.json of another campaign (e.g. before compensation), or the dcc.xml of its certificate: drawn "
                   "behind every plot, and each figure before, after and its change in the verdict table.")
@click.option("--pdf", is_flag=True, help="Also write report.pdf.")
@click.option("--exit-code", is_flag=True,
              help="Exit with status 1 when the verdict is fail, or inconclusive under a guard-band rule (for scripts and CI).")
@click.option("--history", "history", is_flag=True,
              help="Also store the campaign in the calibration history and add the machine's trends to the report.")
@click.option("--db", help="With --history: the database URL or SQLite file [$AXISCAL_DB, else the user's data folder].")
@click.option("--certificate", is_flag=True,
              help="Also write the calibration certificate (ISO/IEC 17025): certificate.html, certificate.pdf (PDF/A-3b, "
                   "the DCC attached) and dcc.xml. Needs [laboratory], [certificate] and [[signatory]] in campaign.toml.")
@click.option("--dcc", is_flag=True, help="Also write dcc.xml, the Digital Calibration Certificate (PTB's XML, schema 3.2.0).")
def report_command(campaign_dir: str, out_dir: str | None, compare: str | None, pdf: bool, exit_code: bool,
                   history: bool, db: str | None, certificate: bool, dcc: bool) -> None:
    """Run every test of CAMPAIGN_DIR (campaign.toml) and write report.html, results.json and the compensation files."""
    from axiscal.report.writer import report_campaign

    if db is not None and not history:
        raise AxiscalError("--db applies only with --history")
    with _progress(sys.stderr.isatty()) as progress:
        files = report_campaign(campaign_dir, out_dir, compare=compare, pdf=pdf, progress=progress,
                                history=history, db=db, certificate=certificate, dcc=dcc)
    verdict = files.results_data.verdict
    click.echo(f"{verdict.upper()}: {len(files.results_data.tests)} tests; report {files.html}")
    click.echo(f"results {files.results}")
    for path in files.compensation:
        click.echo(f"compensation {path}")
    if files.pdf is not None:
        click.echo(f"pdf {files.pdf}")
    for path in files.certificate:
        click.echo(f"certificate {path}")
    if files.dcc is not None:
        click.echo(f"dcc {files.dcc}")
    if files.history is not None:
        stored = files.history
        count = stored["campaigns"]
        click.echo(f"history: campaign {stored['campaign_id']} of {stored['machine']} stored in {stored['database']}"
                   f" ({count} campaign{'' if count == 1 else 's'} of this machine)")
    if exit_code and verdict in ("fail", "inconclusive"):
        click.get_current_context().exit(1)
