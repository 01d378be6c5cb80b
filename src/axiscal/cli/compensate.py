"""``axiscal compensate``: controller compensation tables from a positioning run."""

from __future__ import annotations

import click

from axiscal.cli.common import FINITE, finite, flags_named, given_options, write_output
from axiscal.cli.choices import FORMATS
from axiscal.units import DEG, MM, UM

__all__ = ["compensate_command"]


def _si(value: float | None, factor: float) -> float | None:
    return None if value is None else value * factor


@click.command("compensate")
@click.argument("run_csv", type=click.Path(dir_okay=False))
@click.option("--format", "fmt", type=click.Choice(FORMATS), required=True, help="Controller table format.")
@click.option("-o", "--output", type=click.Path(dir_okay=False), help="Write the table here instead of stdout.")
@click.option("--comp-type", type=click.IntRange(0, 1), default=1, show_default=True,
              help="linuxcnc: COMP_FILE_TYPE, 0 = positions reached, 1 = corrections.")
@click.option("--interval-mm", type=FINITE, default=None,
              help="fanuc/siemens: spacing of the compensation points [mean target spacing, whole mm].")
@click.option("--interval-deg", type=FINITE, default=None,
              help="fanuc/siemens, rotary axis: spacing of the compensation points [mean target spacing, whole deg].")
@click.option("--magnification", type=int, default=1, show_default=True, help="fanuc: parameter 3623 (1..100).")
@click.option("--detection-unit-um", type=FINITE, default=1.0, show_default=True, help="fanuc: detection unit.")
@click.option("--reference-position-mm", type=FINITE, default=None,
              help="fanuc: machine position of the reference position [first target]; siemens: value zero here.")
@click.option("--detection-unit-deg", type=FINITE, default=None, help="fanuc, rotary axis: detection unit [0.001].")
@click.option("--reference-position-deg", type=FINITE, default=None,
              help="fanuc, rotary axis: position of the reference [first target]; siemens: value zero here.")
@click.option("--reference-point", type=int, default=None, help="fanuc: compensation point number of the reference (3620).")
@click.option("--bidirectional", is_flag=True, help="fanuc: separate table for travel in the - direction (3605#0).")
@click.option("--axis", default=None, help="Axis name: siemens machine axis [X1], heidenhain axis [X].")
@click.option("--axis-number", type=int, default=1, show_default=True, help="fanuc: axis number on the parameter tape.")
@click.option("--no-backlash", is_flag=True, help="heidenhain: one mean column, no BACKLASH column.")
@click.option("--max-correction-mm", type=finite(0.0, 1000.0, min_open=True), default=1.0, show_default=True,
              help="The largest mean deviation a table corrects: one beyond it is refused (a reading in the wrong unit or from"
                   " the wrong datum); raise it only for an axis truly out by more.")
@click.option("--max-correction-deg", type=finite(0.0, 360.0, min_open=True), default=1.0, show_default=True,
              help="The same for a rotary axis.")
def compensate_command(run_csv, fmt, output, comp_type, interval_mm, interval_deg, magnification, detection_unit_um,
                       reference_position_mm, detection_unit_deg, reference_position_deg, reference_point, bidirectional,
                       axis, axis_number, no_backlash, max_correction_mm, max_correction_deg):
    """Write a compensation table for the controller from the mean deviations of RUN_CSV (a linear or rotary axis)."""
    from axiscal.compensation.formats import compensation_table

    options = given_options(
        comp_type=comp_type, interval_mm=_si(interval_mm, MM), interval_deg=_si(interval_deg, DEG),
        magnification=magnification, detection_unit_um=_si(detection_unit_um, UM),
        reference_position_mm=_si(reference_position_mm, MM), detection_unit_deg=_si(detection_unit_deg, DEG),
        reference_position_deg=_si(reference_position_deg, DEG), reference_point=reference_point,
        bidirectional=bidirectional, axis=axis, axis_number=axis_number, no_backlash=not no_backlash,
    )
    keywords = {"interval_mm": "interval_m", "detection_unit_um": "detection_unit_m",
                "reference_position_mm": "reference_position_m", "interval_deg": "interval_rad",
                "detection_unit_deg": "detection_unit_rad", "reference_position_deg": "reference_position_rad",
                "no_backlash": "backlash"}
    options = {keywords.get(name, name): value for name, value in options.items()}
    with flags_named({keyword: "--" + name.replace("_", "-") for name, keyword in
                      {**{n: n for n in options}, **keywords}.items()}
                     | {"backlash": "--no-backlash", "max_correction_m": "--max-correction-mm",
                        "max_correction_rad": "--max-correction-deg"}):
        result = compensation_table(run_csv, fmt, max_correction_m=max_correction_mm * MM,
                                    max_correction_rad=max_correction_deg * DEG, **options)
    if output:
        write_output(output, lambda target: target.write_text(result.text, encoding="utf-8"))
    else:
        click.echo(result.text, nl=False)
    click.echo(f"axiscal: note: {result.note}", err=True)
