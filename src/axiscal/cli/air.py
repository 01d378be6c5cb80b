"""``axiscal air`` and ``axiscal fringes``: refractive index of air, and lengths from fringe counts.

Thin wrappers over :func:`axiscal.instruments.air.refractive_index` and :mod:`axiscal.instruments.interferometer`;
flags carry their units in their names.
"""

from __future__ import annotations

import click

from axiscal.cli.common import echo_json
from axiscal.instruments.air import METHODS, refractive_index
from axiscal.instruments.interferometer import (
    HENE_WAVELENGTH_NM,
    compensated_length,
    length_from_fringes,
)
from axiscal.materials import STEEL_EXPANSION_PER_K
from axiscal.units import MM

__all__ = ["air_command", "fringes_command", "register"]

_AIR_OPTIONS = [
    click.option("--temperature-c", type=float, required=True, help="Air temperature, degC."),
    click.option("--pressure-pa", type=float, required=True, help="Air pressure, Pa (101325 at sea level)."),
    click.option("--humidity-pct", type=float, required=True, help="Relative humidity, percent."),
    click.option(
        "--wavelength-nm", type=float, default=HENE_WAVELENGTH_NM, show_default=True, help="Vacuum wavelength, nm."
    ),
    click.option("--co2-ppm", type=float, default=450.0, show_default=True, help="CO2 content, umol/mol."),
    click.option(
        "--method", type=click.Choice(METHODS), default="ciddor", show_default=True, help="Refractive-index equation."
    ),
]


def _air_options(command):
    for option in reversed(_AIR_OPTIONS):
        command = option(command)
    return command


def _inputs(temperature_c, pressure_pa, humidity_pct, wavelength_nm, co2_ppm, method) -> dict:
    return {
        "method": method,
        "temperature_c": temperature_c,
        "pressure_pa": pressure_pa,
        "humidity_pct": humidity_pct,
        "wavelength_nm": wavelength_nm,
        "co2_ppm": co2_ppm,
    }


def _rows(pairs: list[tuple[str, str]]) -> None:
    width = max(len(label) for label, _ in pairs)
    for label, value in pairs:
        click.echo(f"{label:<{width}}  {value}")


@click.command("air")
@_air_options
@click.option("--json", "as_json", is_flag=True, help="Print one JSON object instead of text.")
def air_command(temperature_c, pressure_pa, humidity_pct, wavelength_nm, co2_ppm, method, as_json):
    """Refractive index of air (Ciddor 1996, modified Edlen, Edlen 1966 or NIST shop-floor).

    Prints the index, (n - 1) in ppm and the wavelength in air.
    """
    n = refractive_index(temperature_c, pressure_pa, humidity_pct, wavelength_nm, co2_ppm=co2_ppm, method=method)
    body = {
        "refractive_index": n,
        "n_minus_1_ppm": (n - 1.0) * 1e6,
        "wavelength_in_air_nm": wavelength_nm / n,
        **_inputs(temperature_c, pressure_pa, humidity_pct, wavelength_nm, co2_ppm, method),
    }
    if as_json:
        echo_json(body)
        return
    _rows(
        [
            ("method", method),
            ("refractive index", f"{n:.9f}"),
            ("n - 1", f"{body['n_minus_1_ppm']:.3f} ppm"),
            ("wavelength in air", f"{body['wavelength_in_air_nm']:.6f} nm (vacuum {wavelength_nm:g} nm)"),
        ]
    )


@click.command("fringes")
@click.option("--counts", type=float, required=True, help="Counter value N (fringes times --interpolation).")
@click.option("--optical-fold", type=click.IntRange(min=1), default=1, show_default=True, help="Passes m of the measuring beam (2: plane mirror).")
@click.option("--interpolation", type=click.IntRange(min=1), default=1, show_default=True, help="Counts per fringe.")
@_air_options
@click.option("--material-temperature-c", type=float, multiple=True, help="Material temperature, degC; repeat for several sensors (averaged).")
@click.option("--expansion-per-k", type=float, default=STEEL_EXPANSION_PER_K, show_default=True, help="Material expansion coefficient, 1/K.")
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
    vacuum = float(length_from_fringes(counts, wavelength_nm=wavelength_nm, optical_fold=optical_fold, interpolation=interpolation))
    common = dict(
        air_temperature_c=temperature_c,
        pressure_pa=pressure_pa,
        humidity_pct=humidity_pct,
        wavelength_nm=wavelength_nm,
        co2_ppm=co2_ppm,
        method=method,
    )
    in_air = float(compensated_length(vacuum, **common))
    material = list(material_temperature_c)
    at_20c = (
        float(compensated_length(vacuum, material_temperature_c=[material], expansion_per_k=expansion_per_k, **common)[0])
        if material
        else None
    )
    n = refractive_index(temperature_c, pressure_pa, humidity_pct, wavelength_nm, co2_ppm=co2_ppm, method=method)
    body = {
        "counts": counts,
        "optical_fold": optical_fold,
        "interpolation": interpolation,
        "refractive_index": n,
        "vacuum_length_mm": vacuum / MM,
        "length_in_air_mm": in_air / MM,
        "length_at_20c_mm": None if at_20c is None else at_20c / MM,
        "material_temperature_c": material,
        "expansion_per_k": expansion_per_k,
        **_inputs(temperature_c, pressure_pa, humidity_pct, wavelength_nm, co2_ppm, method),
    }
    if as_json:
        echo_json(body)
        return
    rows = [
        ("refractive index", f"{n:.9f} ({method})"),
        ("length, index 1", f"{vacuum / MM:.6f} mm"),
        ("length in air", f"{in_air / MM:.6f} mm"),
    ]
    if at_20c is not None:
        mean = sum(material) / len(material)
        rows.append(("length at 20 degC", f"{at_20c / MM:.6f} mm (material {mean:.3f} degC, alpha {expansion_per_k:g}/K)"))
    _rows(rows)


def register(group: click.Group) -> None:
    group.add_command(air_command)
    group.add_command(fringes_command)
