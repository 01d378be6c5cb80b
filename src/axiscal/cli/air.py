"""``axiscal air`` and ``axiscal fringes``: refractive index of air, and lengths from fringe counts.

Thin wrappers over :func:`axiscal.instruments.air.air_report` and
:func:`axiscal.instruments.interferometer.fringe_report`; flags carry their units in their names.
"""

from __future__ import annotations

import click

from axiscal.cli.common import FINITE, echo_json
from axiscal.cli.choices import AIR_METHODS as METHODS
from axiscal.cli.choices import HENE_WAVELENGTH_NM
from axiscal.materials import STEEL_EXPANSION_PER_K

__all__ = ["air_command", "fringes_command"]

_AIR_OPTIONS = [
    click.option("--temperature-c", type=FINITE, required=True, help="Air temperature, degC."),
    click.option("--pressure-pa", type=FINITE, required=True, help="Air pressure, Pa (101325 at sea level)."),
    click.option("--humidity-pct", type=FINITE, required=True, help="Relative humidity, percent."),
    click.option(
        "--wavelength-nm", type=FINITE, default=HENE_WAVELENGTH_NM, show_default=True, help="Vacuum wavelength, nm."
    ),
    click.option("--co2-ppm", type=FINITE, default=450.0, show_default=True, help="CO2 content, umol/mol."),
    click.option(
        "--method", type=click.Choice(METHODS), default="ciddor", show_default=True, help="Refractive-index equation."
    ),
]


def _air_options(command):
    for option in reversed(_AIR_OPTIONS):
        command = option(command)
    return command


@click.command("air")
@_air_options
@click.option("--json", "as_json", is_flag=True, help="Print one JSON object instead of text.")
def air_command(temperature_c, pressure_pa, humidity_pct, wavelength_nm, co2_ppm, method, as_json):
    """Refractive index of air (Ciddor 1996, modified Edlen, Edlen 1966 or NIST shop-floor).

    Prints the index, (n - 1) in ppm and the wavelength in air.
    """
    from axiscal.instruments.air import air_report, air_text

    report = air_report(temperature_c, pressure_pa, humidity_pct, wavelength_nm, co2_ppm=co2_ppm, method=method)
    if as_json:
        echo_json(report)
    else:
        click.echo(air_text(report), nl=False)


@click.command("fringes")
@click.option("--counts", type=FINITE, required=True, help="Counter value N (fringes times --interpolation).")
@click.option("--optical-fold", type=click.IntRange(min=1), default=1, show_default=True, help="Passes m of the measuring beam (2: plane mirror).")
@click.option("--interpolation", type=click.IntRange(min=1), default=1, show_default=True, help="Counts per fringe.")
@_air_options
@click.option("--material-temperature-c", type=FINITE, multiple=True, help="Material temperature, degC; repeat for several sensors (averaged).")
@click.option("--expansion-per-k", type=FINITE, default=STEEL_EXPANSION_PER_K, show_default=True, help="Material expansion coefficient, 1/K.")
@click.option("--json", "as_json", is_flag=True, help="Print one JSON object instead of text.")
def fringes_command(
    counts,
    optical_fold,
    interpolation,
    temperature_c,
    pressure_pa,
    humidity_pct,
    wavelength_nm,
    co2_ppm,
    method,
    material_temperature_c,
    expansion_per_k,
    as_json,
):
    """Length from a fringe count (paper 003 eq 1), compensated for the air and normalised to 20 degC."""
    from axiscal.instruments.interferometer import fringe_report, fringe_text

    report = fringe_report(
        counts,
        optical_fold=optical_fold,
        interpolation=interpolation,
        temperature_c=temperature_c,
        pressure_pa=pressure_pa,
        humidity_pct=humidity_pct,
        wavelength_nm=wavelength_nm,
        co2_ppm=co2_ppm,
        method=method,
        material_temperature_c=material_temperature_c,
        expansion_per_k=expansion_per_k,
    )
    if as_json:
        echo_json(report)
    else:
        click.echo(fringe_text(report), nl=False)
