"""``axiscal import``: instrument files into axiscal's CSV (a column map for any export, Renishaw ``.rtx``)."""

from __future__ import annotations

import click

from axiscal.io.importers import (
    IMPORT_UNITS,
    import_readings,
    positioning_csv,
    read_column_map,
    read_rtx,
    rtx_csv,
    write_positioning_csv,
    write_rtx_csv,
)

__all__ = ["import_group", "import_map_command", "import_rtx_command", "register"]


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
    readings = import_readings(read_column_map(map_toml), export_file)
    if output:
        write_positioning_csv(readings, output, map_path=map_toml)
    else:
        click.echo(positioning_csv(readings), nl=False)


@import_group.command("rtx")
@click.argument("rtx_file", type=click.Path(dir_okay=False))
@click.option("--unit", type=click.Choice(tuple(IMPORT_UNITS)), required=True,
              help="Unit of the stored samples (the file does not record it).")
@click.option("-o", "--output", type=click.Path(dir_okay=False),
              help="Write the time series CSV (and its NAME.json sidecar) here instead of stdout.")
def import_rtx_command(rtx_file, unit, output):
    """A Renishaw dynamic capture (.rtx) as a time series: time_s, reading_<unit>."""
    capture = read_rtx(rtx_file, unit=unit)
    if output:
        write_rtx_csv(capture, output)
    else:
        click.echo(rtx_csv(capture), nl=False)


def register(group: click.Group) -> None:
    group.add_command(import_group)
