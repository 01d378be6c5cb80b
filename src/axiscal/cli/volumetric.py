"""``axiscal volumetric``, ``axiscal diagonal``, ``axiscal inverse``: the machine model at the command line."""

from __future__ import annotations

import click

from axiscal.cli.common import echo_json
from axiscal.errors import AxiscalError
from axiscal.cli.choices import MEASURES

__all__ = ["volumetric_command", "diagonal_command", "inverse_command"]


@click.command("volumetric")
@click.option("--machine", "machine_path", required=True, type=click.Path(dir_okay=False), help="Machine description (TOML).")
@click.option("--points", "points_path", type=click.Path(dir_okay=False), help="CSV with one <axis>_mm column per linear axis, <axis>_deg per rotary axis.")
@click.option("--grid", help='Grid of axis positions in mm (deg for A, B, C), e.g. "X=0:190:10,C=0:360:15" (start:end:step, inclusive).')
@click.option("-o", "--output", type=click.Path(dir_okay=False), help="Write the CSV here (and its JSON sidecar) instead of standard output.")
@click.option("--plot", type=click.Path(dir_okay=False), help="Write a map of the volumetric error (PNG).")
def volumetric_command(machine_path, points_path, grid, output, plot):
    """Volumetric error of the functional point at given axis positions.

    Output columns: the axis positions (<axis>_mm, <axis>_deg), then ex_um, ey_um, ez_um (tool
    point relative to the workpiece, actual minus nominal, in the workpiece frame) and e_um = |e|;
    with rotary axes also ei_urad, ej_urad (orientation error of the tool axis).
    """
    from axiscal.model.volumetric import volumetric_map

    if (points_path is None) == (grid is None):
        raise AxiscalError("give exactly one of --points FILE or --grid SPEC")
    result = volumetric_map(machine_path, points=points_path, grid=grid)
    if output:
        result.write_csv(output)
    else:
        click.echo(result.csv(), nl=False)
    if plot:
        result.plot(plot)


@click.command("diagonal")
@click.option("--machine", "machine_path", required=True, type=click.Path(dir_okay=False), help="Machine description (TOML).")
@click.option("--from", "start", required=True, help='Axis positions of the first point in mm, e.g. "X=0,Z=0".')
@click.option("--to", "end", required=True, help='Axis positions of the last point in mm, e.g. "X=190,Z=190".')
@click.option("--steps", type=click.IntRange(min=1), help="Number of intervals (default: from the readings, else 10).")
@click.option("--interferometer", type=click.Path(dir_okay=False), help="Readings CSV: nominal_mm, measured_mm.")
@click.option("--measure", type=click.Choice(MEASURES), default="projection", show_default=True,
              help="Reading as displacement along the diagonal (ISO 230-6) or as point distance (paper 000 eq 13).")
@click.option("-o", "--output", type=click.Path(dir_okay=False), help="Write the per-point CSV here (and its JSON sidecar).")
@click.option("--json", "as_json", is_flag=True, help="Print one JSON object.")
@click.option("--plot", type=click.Path(dir_okay=False), help="Write the before/after plot (PNG).")
def diagonal_command(machine_path, start, end, steps, interferometer, measure, output, as_json, plot):
    """Diagonal displacement test predicted by the model (ISO 230-6), and compared with an
    interferometer (paper 000 eq 13: E_BD before the model, E_AD after).

    Every error is actual minus nominal along the diagonal: model_error = predicted - nominal,
    E_BD = measured - nominal, E_AD = measured - predicted (paper 000 writes E_BD and E_AD with the
    opposite sign).
    """
    from axiscal.model.diagonal import diagonal_test
    from axiscal.model.inputs import parse_point

    result = diagonal_test(
        machine_path, parse_point(start, "--from"), parse_point(end, "--to"), steps=steps, readings=interferometer, measure=measure
    )
    if output:
        result.write_csv(output)
    if as_json:
        echo_json(result.summary())
    else:
        click.echo(result.text(), nl=False)
    if plot:
        from axiscal.model.plot import plot_diagonal

        plot_diagonal(result, plot)


@click.command("inverse")
@click.option("--machine", "machine_path", required=True, type=click.Path(dir_okay=False), help="Machine description (TOML).")
@click.option("--points", "points_path", required=True, type=click.Path(dir_okay=False),
              help="CSV of wanted tool points: x_mm, y_mm, z_mm (relative to the workpiece point, workpiece frame).")
@click.option("-o", "--output", type=click.Path(dir_okay=False), help="Write the CSV here (and its JSON sidecar) instead of standard output.")
def inverse_command(machine_path, points_path, output):
    """Axis commands that put the tool point on wanted points (compensated commands, to < 1 nm)."""
    from axiscal.model.inverse import inverse_commands

    result = inverse_commands(machine_path, points_path)
    if output:
        result.write_csv(output)
    else:
        click.echo(result.csv(), nl=False)
