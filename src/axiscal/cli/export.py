"""``axiscal export``: corrections for firmware and controllers (skew lines, backlash, screw maps, sag tables, grids)."""

from __future__ import annotations

import click

from axiscal.cli.common import FINITE, echo_json, flags_named
from axiscal.cli.choices import (
    BACKLASH_CONTROLLERS,
    BACKLASH_METHODS,
    FIRMWARES,
    SAG_CONTROLLERS,
    SAG_REFERENCES,
    SCREWMAP_CONTROLLERS,
    SKEW_CONVENTIONS,
)
from axiscal.errors import AxiscalError
from axiscal.units import ARCSEC, MM, UM

#: what ``axiscal export grid`` writes
GRID_FORMATS = ("csv", "isg", "isg-axis")

__all__ = ["export_group", "export_skew_command", "export_backlash_command", "export_screwmap_command", "export_sag_command", "export_grid_command"]


@click.group("export")
def export_group() -> None:
    """Write corrections in a firmware's or controller's own format (see docs/compensation.md)."""


@export_group.command("skew")
@click.option("--firmware", type=click.Choice(FIRMWARES), required=True, help="Klipper, Marlin or RepRapFirmware.")
@click.option("--xy-arcsec", type=FINITE, default=None, help="XY squareness (see --convention).")
@click.option("--xz-arcsec", type=FINITE, default=None, help="XZ squareness.")
@click.option("--yz-arcsec", type=FINITE, default=None, help="YZ squareness.")
@click.option("--square-mm", type=FINITE, default=100.0, show_default=True,
              help="Side of the square the Klipper lengths and the RRF deviations refer to.")
@click.option("--convention", type=click.Choice(SKEW_CONVENTIONS), default="included-angle", show_default=True,
              help="included-angle: included angle of the positive axes - 90 deg (axiscal squareness); "
              "iso: EC0Y, EB0Z, EA0Z of ISO 230-1.")
@click.option("--from", "results", multiple=True, type=click.Path(dir_okay=False),
              help="A result of 'axiscal squareness --json' (one per plane; may be repeated) instead of the angles.")
@click.option("--json", "as_json", is_flag=True, help="Print one JSON object (lines, notes, factors).")
def export_skew_command(firmware, xy_arcsec, xz_arcsec, yz_arcsec, square_mm, convention, results, as_json):
    """Skew correction line(s) of a firmware for measured squareness, on standard output."""
    from axiscal.compensation.skew import skew_correction, squareness_from_results

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


@export_group.command("backlash")
@click.argument("run_csv", required=False, type=click.Path(dir_okay=False))
@click.option("--controller", type=click.Choice(BACKLASH_CONTROLLERS), required=True,
              help="The controller whose backlash parameter to write.")
@click.option("--axis", default="X", show_default=True, help="Axis letter.")
@click.option("--axis-number", type=int, default=None, help="1-based axis number (LinuxCNC joint + 1, SINUMERIK AXn) [X=1, Y=2, ...].")
@click.option("--method", type=click.Choice(BACKLASH_METHODS), default="mean", show_default=True,
              help="mean: -B_mean of ISO 230-2; max: -B_i where |B_i| is largest; target: -B_i at --target-mm.")
@click.option("--target-mm", type=FINITE, default=None, help="The target for --method target.")
@click.option("--backlash-um", type=FINITE, default=None, help="A backlash measured otherwise, instead of RUN_CSV.")
@click.option("--json", "as_json", is_flag=True, help="Print one JSON object.")
def export_backlash_command(run_csv, controller, axis, axis_number, method, target_mm, backlash_um, as_json):
    """A controller's backlash parameter from a positioning test (RUN_CSV) or a value."""
    from axiscal.compensation.backlash import backlash_from_run, backlash_setting

    if (run_csv is None) == (backlash_um is None):
        raise AxiscalError("give either a positioning run CSV or --backlash-um")
    if backlash_um is not None:
        setting = backlash_setting(controller, backlash_um * UM, axis=axis, axis_number=axis_number)
    else:
        target_m = None if target_mm is None else target_mm * MM
        setting = backlash_from_run(controller, run_csv, method=method, target_m=target_m, axis=axis, axis_number=axis_number)
    if as_json:
        echo_json({
            "controller": setting.controller,
            "axis": setting.axis,
            "parameter": setting.parameter,
            "backlash_um": setting.backlash_m / UM,
            "written_um": setting.written_m / UM,
            "lines": list(setting.lines),
            "notes": list(setting.notes),
        })
    else:
        click.echo(setting.text(), nl=False)


@export_group.command("screwmap")
@click.argument("run_csv", type=click.Path(dir_okay=False))
@click.option("--controller", type=click.Choice(SCREWMAP_CONTROLLERS), required=True,
              help="twincat: TwinCAT CNC leadscrew error compensation list (kw.ssfk); "
              "mach4: the values of a Mach4 screw map (Machine Calibration plugin).")
@click.option("--axis", default="X", show_default=True, help="Axis name (TwinCAT: kopf.log_achs_name).")
@click.option("--axis-number", type=int, default=1, show_default=True, help="twincat: logical axis number (kopf.achs_nr).")
@click.option("--interval-mm", type=FINITE, default=None,
              help="twincat: equidistant points this far apart (resampled) [the measured targets, listed].")
@click.option("--points", type=int, default=None,
              help="mach4: number of evenly spaced points, both ends included [the number of targets].")
@click.option("--unit", type=click.Choice(("mm", "in")), default="mm", show_default=True,
              help="mach4: machine units of the profile.")
@click.option("--unilateral", is_flag=True, help="One table of the bidirectional mean instead of one per direction.")
@click.option("--max-points", type=int, default=None, help="twincat: table entries the control reserves (P-COMP-00059).")
@click.option("-o", "--output", type=click.Path(dir_okay=False), help="Write the table here instead of stdout.")
def export_screwmap_command(run_csv, controller, axis, axis_number, interval_mm, points, unit, unilateral, max_points,
                            output):
    """A lead-screw error table from a positioning test (RUN_CSV) in a controller's own format."""
    from axiscal.compensation.screwmaps import screwmap_file

    table = screwmap_file(
        run_csv,
        controller=controller,
        axis=axis,
        axis_number=axis_number,
        interval_m=None if interval_mm is None else interval_mm * MM,
        points=points,
        bidirectional=not unilateral,
        max_points=max_points,
        unit=unit,
    )
    _write_table(table, output)


@export_group.command("sag")
@click.argument("run_csv", type=click.Path(dir_okay=False))
@click.option("--controller", type=click.Choice(SAG_CONTROLLERS), required=True,
              help="siemens: SINUMERIK sag compensation table ($AN_CEC, %_N_NC_CEC_INI); "
              "heidenhain: .COM table of a dependent axis (compensation axis = F(base axis)).")
@click.option("--base-axis", required=True,
              help="Axis the run moves: $AN_CEC_INPUT_AXIS (e.g. AX2) or the .CMA column (e.g. Y).")
@click.option("--compensation-axis", required=True,
              help="Axis the deviation is along: $AN_CEC_OUTPUT_AXIS (e.g. AX3) or the .COM column (e.g. Z).")
@click.option("--step-mm", type=FINITE, default=None,
              help="Spacing of the table's points, the run resampled on it: $AN_CEC_STEP (required for siemens); "
              "for heidenhain, default one row per measured position.")
@click.option("--table", "table_index", type=int, default=0, show_default=True, help="siemens: table index t.")
@click.option("--reference", type=click.Choice(SAG_REFERENCES), default="none", show_default=True,
              help="none: the whole deviation; least-squares / end-points: the deviation about that line.")
@click.option("--direction", type=click.IntRange(-1, 1), default=0, show_default=True,
              help="siemens: $AN_CEC_DIRECTION: 0 both, 1 positive, -1 negative direction of the base axis.")
@click.option("--max-points", type=int, default=None, help="siemens: MD18342 $MN_MM_CEC_MAX_POINTS of the table (200 on an 828D).")
@click.option("--name", default=None, help="heidenhain: the .COM file's name without extension (default BASE+COMPENSATION, e.g. YZ).")
@click.option("-o", "--output", type=click.Path(dir_okay=False), help="Write the table here instead of stdout.")
def export_sag_command(run_csv, controller, base_axis, compensation_axis, step_mm, table_index, reference, direction,
                       max_points, name, output):
    """A cross-axis (sag) table from a straightness run (position_mm, deviation_um) of the base axis."""
    from axiscal.compensation.sag import sag_table_file

    table = sag_table_file(
        run_csv,
        controller=controller,
        base_axis=base_axis,
        compensation_axis=compensation_axis,
        step_m=None if step_mm is None else step_mm * MM,
        table=table_index,
        reference=reference,
        direction=direction,
        max_points=max_points,
        name=name,
    )
    _write_table(table, output)


def _write_table(table, output) -> None:
    from axiscal.io.atomic import write_text

    if output:
        write_text(output, table.text())
    else:
        click.echo(table.text(), nl=False)
    if table.note:
        click.echo(f"axiscal: note: {table.note}", err=True)


@export_group.command("grid")
@click.option("--machine", required=True, type=click.Path(dir_okay=False), help="The machine model (TOML).")
@click.option("--grid", required=True, help='Programmed points: "X=0:800:50,Y=0:500:50,Z=0:300:50" (mm; start:end:step or one value; rotary axes one angle in deg).')
@click.option("--format", "file_format", type=click.Choice(GRID_FORMATS), default="csv", show_default=True,
              help="csv: the pre-compensation correction as a plain CSV; isg: the model's volumetric error for a TwinCAT CNC /"
              " ISG kernel (ISG CSV parameter file, its NAME.lis list); isg-axis: each linear axis's positioning error"
              " as a TwinCAT CNC leadscrew list (STEM_X.lis, ...).")
@click.option("--axis-numbers", default=None, help="isg, isg-axis: logical axis numbers, e.g. X=1,Y=2,Z=3 [X=1,Y=2,Z=3].")
@click.option("-o", "--output", required=True, type=click.Path(dir_okay=False),
              help="The grid CSV (its sidecar NAME.json beside it), or the ISG parameter file (isg) or the stem of the lists (isg-axis).")
def export_grid_command(machine, grid, file_format, axis_numbers, output):
    """The model on a regular grid: the pre-compensation correction (CSV) or a TwinCAT CNC / ISG compensation."""
    if file_format == "csv":
        if axis_numbers is not None:
            raise AxiscalError("--axis-numbers applies to --format isg and isg-axis")
        from axiscal.precompensation.grid import export_correction_grid

        result = export_correction_grid(machine, grid, output)
        largest = float(abs(result.correction_m).max()) / UM
        click.echo(f"axiscal: {output}: {len(result.programmed_m)} grid points, largest correction {largest:.3f} um", err=True)
        return
    from axiscal.precompensation.isg import export_isg, parse_axis_numbers

    with flags_named({"axis_numbers": "--axis-numbers", "grid": "--grid"}):
        numbers = parse_axis_numbers(axis_numbers)
        written = export_isg(machine, grid, output, kind="axis" if file_format == "isg-axis" else "volumetric",
                             axis_numbers=numbers)
    if written.volumetric is not None:
        what = (f"{written.volumetric.parameter_si.shape[0]} grid nodes, largest error {written.largest_m / UM:.3f} um;"
                f" list: chain {written.chain}, workpiece_axes {written.workpiece_axes}")
    else:
        what = f"{len(written.axes)} axis lists, largest positioning error {written.largest_m / UM:.1f} um"
    click.echo(f"axiscal: {', '.join(str(f) for f in written.files)}: {what}", err=True)
