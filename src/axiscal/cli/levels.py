"""``axiscal levels``: straightness profile and angular error motion from electronic level readings (ISO 230-1)."""

from __future__ import annotations

import math

import click

from axiscal.cli.common import FINITE, echo_json
from axiscal.errors import AxiscalError
from axiscal.cli.choices import REFERENCES
from axiscal.units import MM

__all__ = ["levels_command"]


@click.command("levels")
@click.argument("run", type=click.Path(dir_okay=False))
@click.option("--foot-mm", type=FINITE, required=True, help="The level's foot spacing, mm.")
@click.option("--reference", type=click.Choice(REFERENCES), default="least-squares", show_default=True,
              help="Reference straight line of the straightness (ISO 230-1).")
@click.option("--json", "as_json", is_flag=True,
              help="Print JSON: straightness_um, slope_urad, angular_error_urad, angular_error_arcsec ...")
@click.option("-o", "--output", type=click.Path(dir_okay=False),
              help="Write the profile (position_mm, deviation_um) and its JSON sidecar here.")
@click.option("--plot", "plot_path", type=click.Path(dir_okay=False), help="Write a plot of the profile and the readings.")
def levels_command(run: str, foot_mm: float, reference: str, as_json: bool, output: str | None, plot_path: str | None) -> None:
    """Straightness and pitch (or roll) of RUN (CSV: position_mm and angle_arcsec, angle_urad or angle_um_per_m)."""
    from axiscal.levels.files import evaluate_levels

    if not (math.isfinite(foot_mm) and foot_mm > 0):
        raise AxiscalError(f"--foot-mm must be a positive number, got {foot_mm:g}")
    result = evaluate_levels(run, foot_m=foot_mm * MM, reference=reference, output=output)
    if plot_path:
        from axiscal.levels.plot import plot_levels

        plot_levels(plot_path, result)
    if as_json:
        echo_json(result.payload())
    else:
        click.echo(result.report())
