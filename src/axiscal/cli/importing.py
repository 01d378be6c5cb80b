"""``axiscal import``: instrument files into axiscal's CSV (a column map for any export, Renishaw ``.rtx``)."""

from __future__ import annotations

import click

from axiscal.cli.choices import IMPORT_UNITS

__all__ = ["import_group", "import_map_command", "import_rtx_command"]


@click.group("import")
def import_group() -> None:
    """Read an instrument's file into axiscal's CSV (see docs/importing.md)."""


@import_group.command("map")
@click.argument("map_toml", type=click.Path(dir_okay=False))
@click.argument("export_file", type=click.Path(dir_okay=False))
@click.option("-o", "--output", type=click.Path(dir_okay=False),
              help="Write the positioning CSV (and its NAME.json sidecar) here instead of stdout.")
def import_map_command(map_toml, export_file, output):
    """Positioning readings from any CSV or text export, as a column map TOML describes it.

    Writes target_mm,run,direction,deviation_um (deviation = position reached - target).
    """
    from axiscal.io.importers import import_readings, positioning_csv, read_column_map, write_positioning_csv

    readings = import_readings(read_column_map(map_toml), export_file)
    if output:
        write_positioning_csv(readings, output, map_path=map_toml)
        click.echo(f"axiscal: note: {len(readings.targets_m)} readings of {len(set(readings.runs))} runs written to {output}",
                   err=True)
    else:
        click.echo(positioning_csv(readings), nl=False)


@import_group.command("rtx")
@click.argument("rtx_file", type=click.Path(dir_okay=False))
@click.option("--unit", type=click.Choice(IMPORT_UNITS), required=True,
              help="Unit of the stored samples (the file does not record it).")
@click.option("-o", "--output", type=click.Path(dir_okay=False),
              help="Write the time series CSV (and its NAME.json sidecar) here instead of stdout.")
def import_rtx_command(rtx_file, unit, output):
    """A Renishaw dynamic capture (.rtx) as a time series: time_s, reading_<unit>."""
    from axiscal.io.importers import read_rtx, rtx_csv, write_rtx_csv

    capture = read_rtx(rtx_file, unit=unit)
    if output:
        write_rtx_csv(capture, output)
    else:
        click.echo(rtx_csv(capture), nl=False)
