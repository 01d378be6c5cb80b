"""``axiscal compensate``: controller compensation tables from a positioning run."""

from __future__ import annotations

import click
import numpy as np

from axiscal.cli.common import write_output
from axiscal.compensation import (
    error_curve,
    fanuc_table,
    heidenhain_table,
    linuxcnc_table,
    residuals,
    siemens_table,
)
from axiscal.errors import AxiscalError
from axiscal.positioning.evaluation import target_statistics
from axiscal.positioning.reader import read_positioning_run
from axiscal.units import MM, UM

__all__ = ["FORMATS", "FORMAT_OPTIONS", "compensate_command", "register"]

FORMATS = ("linuxcnc", "fanuc", "siemens", "heidenhain")
#: the format-specific options each format reads; giving another format's option is an error, not ignored
FORMAT_OPTIONS = {
    "comp_type": ("linuxcnc",),
    "interval_mm": ("fanuc", "siemens"),
    "magnification": ("fanuc",),
    "detection_unit_um": ("fanuc",),
    "reference_position_mm": ("fanuc", "siemens"),
    "reference_point": ("fanuc",),
    "bidirectional": ("fanuc",),
    "axis": ("siemens", "heidenhain"),
    "axis_number": ("fanuc",),
    "no_backlash": ("heidenhain",),
}


def _refuse_options_of_other_formats(fmt: str) -> None:
    ctx = click.get_current_context()
    for name, formats in FORMAT_OPTIONS.items():
        if fmt not in formats and ctx.get_parameter_source(name) == click.core.ParameterSource.COMMANDLINE:
            flag = "--" + name.replace("_", "-")
            raise AxiscalError(f"{flag} applies to --format {' or '.join(formats)}, not {fmt}")


@click.command("compensate")
@click.argument("run_csv", type=click.Path(dir_okay=False))
@click.option("--format", "fmt", type=click.Choice(FORMATS), required=True, help="Controller table format.")
@click.option("-o", "--output", type=click.Path(dir_okay=False), help="Write the table here instead of stdout.")
@click.option("--comp-type", type=click.IntRange(0, 1), default=1, show_default=True,
              help="linuxcnc: COMP_FILE_TYPE, 0 = positions reached, 1 = corrections.")
@click.option("--interval-mm", type=float, default=None,
              help="fanuc/siemens: spacing of the compensation points [mean target spacing, whole mm].")
@click.option("--magnification", type=int, default=1, show_default=True, help="fanuc: parameter 3623 (1..100).")
@click.option("--detection-unit-um", type=float, default=1.0, show_default=True, help="fanuc: detection unit.")
@click.option("--reference-position-mm", type=float, default=None,
              help="fanuc: machine position of the reference position [first target]; siemens: value zero here.")
@click.option("--reference-point", type=int, default=None, help="fanuc: compensation point number of the reference (3620).")
@click.option("--bidirectional", is_flag=True, help="fanuc: separate table for travel in the - direction (3605#0).")
@click.option("--axis", default=None, help="Axis name: siemens machine axis [X1], heidenhain axis [X].")
@click.option("--axis-number", type=int, default=1, show_default=True, help="fanuc: axis number on the parameter tape.")
@click.option("--no-backlash", is_flag=True, help="heidenhain: one mean column, no BACKLASH column.")
def compensate_command(run_csv, fmt, output, comp_type, interval_mm, magnification, detection_unit_um,
                       reference_position_mm, reference_point, bidirectional, axis, axis_number, no_backlash):
    """Write a compensation table for the controller from the mean deviations of RUN_CSV."""
    _refuse_options_of_other_formats(fmt)
    data = read_positioning_run(run_csv)
    curve = error_curve(target_statistics(data.run))
    targets = data.run.targets
    interval = (interval_mm * MM) if interval_mm is not None else max(1.0, round(np.ptp(targets) / (targets.size - 1) / MM)) * MM
    reference = targets[0] if reference_position_mm is None else reference_position_mm * MM
    offset = 0.0
    if fmt == "linuxcnc":
        table = linuxcnc_table(curve, comp_type=comp_type)
        directions = ("+", "-")
        what = f"LinuxCNC COMP_FILE_TYPE = {comp_type}, {table.nominal.size} entries"
    elif fmt == "fanuc":
        table = fanuc_table(curve, interval_m=interval, reference_position_m=reference, reference_point=reference_point,
                            magnification=magnification, detection_unit_m=detection_unit_um * UM,
                            bidirectional=bidirectional, axis_number=axis_number)
        directions = ("+", "-") if bidirectional else ("mean",)
        offset = table.reference_deviation_m
        what = (f"FANUC pitch error compensation, points {table.points[0]}..{table.points[-1]}, reference point"
                f" {table.reference_point}, interval {interval / MM:g} mm, unit {table.resolution / UM:g} um")
    elif fmt == "siemens":
        zero = None if reference_position_mm is None else reference
        table = siemens_table(curve, step_m=interval, axis=axis or "X1", zero_at_m=zero)
        directions = ("mean",)
        offset = 0.0 if zero is None else float(curve.at(zero, "mean"))
        what = f"SINUMERIK $AA_ENC_COMP, {table.values_mm.size} points, step {interval / MM:g} mm"
    else:
        table = heidenhain_table(curve, axis=axis or "X", backlash=not no_backlash)
        directions = ("+", "-") if not no_backlash else ("mean",)
        what = f"HEIDENHAIN {table.axis}.COM, {table.positions_mm.size} rows"
    text = table.text()
    if output:
        write_output(output, lambda target: target.write_text(text, encoding="utf-8"))
    else:
        click.echo(text, nl=False)
    left = max(float(np.abs(residuals(table, curve, targets, d, offset=offset)).max()) for d in directions)
    zero_point = (
        f"; the table is zero at the reference position, whose own deviation {offset / UM:+.3f} um is left"
        f" to the reference position setting" if offset else ""
    )
    click.echo(
        f"axiscal: note: {what}; largest error left at the measured targets {left / UM:.3f} um"
        f" (table resolution {table.resolution / UM:g} um){zero_point}",
        err=True,
    )


def register(group: click.Group) -> None:
    group.add_command(compensate_command)
