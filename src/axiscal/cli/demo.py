"""``axiscal demo``: the main job on the built-in example (paper 000's XZ module); :func:`axiscal.report.run_demo` does it."""

from __future__ import annotations

import click

from axiscal.report.demo import run_demo

__all__ = ["demo_command", "register"]


@click.command("demo")
@click.option("--output", type=click.Path(file_okay=False), default="axiscal-demo", show_default=True, help="Folder to write to.")
def demo_command(output):
    """Run the volumetric model of paper 000's XZ module and write a report.

    Writes the error motions plot, the volumetric error map (CSV and PNG) over the XZ plane, the
    diagonal check against the (simulated) interferometer readings (CSV and PNG), paper 000's
    diagonal experiment with the virtual module (0 and 2 kg), summary.json and report.md.
    """
    click.echo(run_demo(output).text(), nl=False)


def register(group: click.Group) -> None:
    group.add_command(demo_command)
