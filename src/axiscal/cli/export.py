"""``axiscal export``: corrections for firmware and controllers (skew correction lines)."""

from __future__ import annotations

import click

from axiscal.cli.common import echo_json
from axiscal.compensation.skew import FIRMWARES, SKEW_CONVENTIONS, skew_correction, squareness_from_results
from axiscal.errors import AxiscalError
from axiscal.units import ARCSEC, MM

__all__ = ["export_group", "export_skew_command", "register"]


@click.group("export")
def export_group() -> None:
    """Write corrections in a firmware's or controller's own format (see docs/compensation.md)."""


@export_group.command("skew")
@click.option("--firmware", type=click.Choice(FIRMWARES), required=True, help="Klipper, Marlin or RepRapFirmware.")
@click.option("--xy-arcsec", type=float, default=None, help="XY squareness (see --convention).")
@click.option("--xz-arcsec", type=float, default=None, help="XZ squareness.")
@click.option("--yz-arcsec", type=float, default=None, help="YZ squareness.")
@click.option("--square-mm", type=float, default=100.0, show_default=True,
              help="Side of the square the Klipper lengths and the RRF deviations refer to.")
@click.option("--convention", type=click.Choice(SKEW_CONVENTIONS), default="included-angle", show_default=True,
              help="included-angle: included angle of the positive axes - 90 deg (axiscal squareness); "
              "iso: EC0Y, EB0Z, EA0Z of ISO 230-1.")
@click.option("--from", "results", multiple=True, type=click.Path(dir_okay=False),
              help="A result of 'axiscal squareness --json' (one per plane; may be repeated) instead of the angles.")
@click.option("--json", "as_json", is_flag=True, help="Print one JSON object (lines, notes, factors).")
def export_skew_command(firmware, xy_arcsec, xz_arcsec, yz_arcsec, square_mm, convention, results, as_json):
    """Skew correction line(s) of a firmware for measured squareness, on standard output."""
    given = {"xy_rad": xy_arcsec, "xz_rad": xz_arcsec, "yz_rad": yz_arcsec}
    if results:
        if any(v is not None for v in given.values()):
            raise AxiscalError("give the squareness either with --from or with --xy/--xz/--yz-arcsec, not both")
        planes = squareness_from_results(results)
        angles = {f"{p.lower()}_rad": v for p, v in planes.items()}
        convention = "included-angle"
    else:
        angles = {k: v * ARCSEC for k, v in given.items() if v is not None}
    correction = skew_correction(firmware, square_m=square_mm * MM, convention=convention, **angles)
    if as_json:
        echo_json({
            "firmware": correction.firmware,
            "squareness_arcsec": {p: v / ARCSEC for p, v in correction.squareness_rad.items()},
            "convention": "included-angle",
            "factors": correction.factors,
            "square_mm": correction.square_m / MM,
            "lines": list(correction.lines),
            "notes": list(correction.notes),
        })
    else:
        click.echo(correction.text(), nl=False)


def register(group: click.Group) -> None:
    group.add_command(export_group)
