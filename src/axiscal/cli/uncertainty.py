"""``axiscal uncertainty volumetric``: the volumetric error map with its Monte Carlo uncertainty."""

from __future__ import annotations

import sys
from contextlib import contextmanager

import click

from axiscal.cli.common import FINITE, echo_json
from axiscal.errors import AxiscalError
from axiscal.cli.choices import UNCERTAINTY_SCHEDULER_TIMEOUT_S as SCHEDULER_TIMEOUT_S

__all__ = ["uncertainty_group", "volumetric_uncertainty_command"]


@contextmanager
def _draws_progress(enabled: bool):
    """A Rich progress bar over the draws on a terminal; nothing when stderr is redirected."""
    if not enabled:
        yield None
        return
    from rich.console import Console
    from rich.progress import (
        BarColumn,
        MofNCompleteColumn,
        Progress,
        TextColumn,
        TimeRemainingColumn,
    )

    with Progress(TextColumn("[bold]draws"), BarColumn(), MofNCompleteColumn(), TimeRemainingColumn(),
                  transient=True, console=Console(stderr=True)) as bar:
        task = bar.add_task("draws", total=None)
        yield lambda done, total: bar.update(task, total=total, completed=done)


@click.group("uncertainty")
def uncertainty_group() -> None:
    """Measurement uncertainty (see docs/uncertainty.md; positioning U: axiscal positioning --uncertainty)."""


@uncertainty_group.command("volumetric")
@click.option("--machine", "machine_path", required=True, type=click.Path(dir_okay=False),
              help="Machine description (TOML); error tables may carry <column>_u columns, [squareness] <key>_u keys.")
@click.option("--points", "points_path", type=click.Path(dir_okay=False), help="CSV with one <axis>_mm column per axis.")
@click.option("--grid", help='Grid of axis positions in mm, e.g. "X=0:600:100,Y=0:400:100,Z=0:300:100" (start:end:step, inclusive).')
@click.option("--draws", type=int, default=10_000, show_default=True, help="Number of Monte Carlo draws.")
@click.option("--seed", type=int, default=0, show_default=True, help="Seed of the draws (same seed, same map, here or on a cluster).")
@click.option("--scheduler", help='Run on Dask: "local" (a 2-worker LocalCluster) or a scheduler address (tcp://host:8786).')
@click.option("--scheduler-timeout-s", "timeout_s", type=FINITE, default=SCHEDULER_TIMEOUT_S, show_default=True,
              help="Seconds to wait for a scheduler given by address.")
@click.option("-o", "--output", type=click.Path(dir_okay=False), help="Write the CSV here (and its JSON sidecar) instead of standard output.")
@click.option("--plot", type=click.Path(dir_okay=False), help="Write |e| and its 95 % interval against the axis positions (PNG, SVG, PDF).")
@click.option("--json", "as_json", is_flag=True, help="Print a JSON summary instead of the CSV.")
def volumetric_uncertainty_command(machine_path, points_path, grid, draws, seed, scheduler, timeout_s, output, plot, as_json):
    """Volumetric error at given axis positions with its 95 % coverage interval (Monte Carlo, JCGM 101).

    Output columns: the axis positions (<axis>_mm), then for ex, ey, ez and the length e = |e|:
    the model's error (ex_um), the standard deviation of the draws (ex_u_um) and the interval
    (ex_low_um, ex_high_um).
    """
    from axiscal.uncertainty.volumetric_map import volumetric_uncertainty_map

    if (points_path is None) == (grid is None):
        raise AxiscalError("give exactly one of --points FILE or --grid SPEC")
    with _draws_progress(sys.stderr.isatty()) as progress:
        result = volumetric_uncertainty_map(machine_path, points=points_path, grid=grid, draws=draws, seed=seed,
                                            scheduler=scheduler, timeout_s=timeout_s, progress=progress,
                                            output=output, plot_path=plot)
    if as_json:
        echo_json(result.summary())
    elif not output:
        click.echo(result.csv(), nl=False)
