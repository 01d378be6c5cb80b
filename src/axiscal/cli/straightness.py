"""``axiscal straightness``: straightness of a profile about a least-squares, end-point or minimum-zone line."""

from __future__ import annotations

import click

from axiscal.cli.common import echo_json
from axiscal.cli.choices import REFERENCES

__all__ = ["straightness_command"]


@click.command("straightness")
@click.argument("profile", type=click.Path(dir_okay=False))
@click.option(
    "--reference",
    type=click.Choice(REFERENCES),
    default="least-squares",
    show_default=True,
    help="Reference straight line (ISO 230-1).",
)
@click.option("--json", "as_json", is_flag=True, help="Print JSON: straightness_um, slope_urad, intercept_um, reference.")
@click.option("--plot", "plot_path", type=click.Path(dir_okay=False), help="Write a plot of the profile and its zone.")
def straightness_command(profile: str, reference: str, as_json: bool, plot_path: str | None) -> None:
    """Straightness of PROFILE (CSV with position_mm, deviation_um): the zone's width about a reference line."""
    from axiscal.straightness.files import evaluate_straightness_file

    result = evaluate_straightness_file(profile, reference=reference, plot_path=plot_path)
    if as_json:
        echo_json(result.payload())
    else:
        click.echo(result.report())
