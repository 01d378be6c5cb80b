"""``axiscal flatness``: flatness of a surface from its measured lines (Union Jack or grid, ISO 230-1)."""

from __future__ import annotations

import click

from axiscal.cli.common import echo_json
from axiscal.cli.choices import EVALUATIONS

__all__ = ["flatness_command"]


@click.command("flatness")
@click.argument("lines", type=click.Path(dir_okay=False))
@click.option("--evaluation", type=click.Choice(EVALUATIONS), default="least-squares", show_default=True,
              help="Join the lines by least squares (any layout) or by Moody's method (a Union Jack).")
@click.option("--json", "as_json", is_flag=True,
              help="Print JSON: flatness_um (minimum zone), flatness_least_squares_um, closure_max_um, closures ...")
@click.option("-o", "--output", type=click.Path(dir_okay=False),
              help="Write the surface (x_mm, y_mm, height_um) and its JSON sidecar here.")
@click.option("--plot", "plot_path", type=click.Path(dir_okay=False), help="Write a contour map and a 3-D view of the surface.")
def flatness_command(lines: str, evaluation: str, as_json: bool, output: str | None, plot_path: str | None) -> None:
    """Flatness of the surface measured along the lines of LINES (TOML: [[lines]] with ends and readings or profiles)."""
    from axiscal.flatness.files import evaluate_flatness

    result = evaluate_flatness(lines, evaluation=evaluation, output=output, plot_path=plot_path)
    if as_json:
        echo_json(result.payload())
    else:
        click.echo(result.report())
