"""``axiscal demo``: a whole campaign on the virtual XZ module of paper 000, reported; :func:`axiscal.report.run_demo` does it."""

from __future__ import annotations

import click


__all__ = ["demo_command"]


@click.command("demo")
@click.option("-o", "--output", type=click.Path(file_okay=False), default="axiscal-demo", show_default=True, help="Folder to write to.")
def demo_command(output):
    """Simulate a whole calibration campaign of paper 000's XZ module and report it.

    The virtual instrument (seeded, so every run is the same) calibrates the sensors, records the
    6-DOF sensors, runs ISO 230-2 laser tests of X and Z with air and material sensors, separates
    the straightness of X, measures the XZ squareness with a pentaprism and checks the diagonal
    unloaded and with 2 kg. Writes OUTPUT/campaign/ (campaign.toml and its data),
    OUTPUT/report/ (report.html, results.json, compensation files) and OUTPUT/summary.json.
    """
    from axiscal.report.demo import run_demo

    click.echo(run_demo(output).text(), nl=False)
