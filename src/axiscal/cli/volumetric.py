"""``axiscal volumetric``, ``axiscal diagonal``, ``axiscal inverse``: the machine model at the command line."""

from __future__ import annotations

from pathlib import Path

import click
import numpy as np

from axiscal.cli.common import echo_json, ensure_parent
from axiscal.errors import AxiscalError
from axiscal.io.tabular import read_csv, write_csv
from axiscal.model.diagonal import diagonal_check
from axiscal.model.machine import Machine, axis_positions_from_grid, load_machine

__all__ = [
    "read_points",
    "check_travel",
    "parse_point",
    "volumetric_command",
    "read_interferometer",
    "diagonal_command",
    "inverse_command",
    "register",
]

_XYZ = ("x", "y", "z")


def read_points(path: str | Path, machine: Machine) -> tuple[dict[str, np.ndarray], tuple[int, ...]]:
    """Axis positions from a CSV with one ``<axis>_mm`` column per axis of the machine (metres)."""
    table = read_csv(path)
    positions = {}
    for letter in machine.letters:
        column = f"{letter.lower()}_mm" if table.has(f"{letter.lower()}_mm") else f"{letter}_mm"
        if not table.has(column):
            raise AxiscalError(f"missing column '{letter.lower()}_mm' for axis {letter}", path=str(path), line=table.header_line)
        positions[letter] = table.numeric(column) * 1e-3
    check_travel(machine, positions, path=str(path), lines=table.lines)
    return positions, table.lines


def check_travel(machine: Machine, positions: dict[str, np.ndarray], *, path: str, lines: tuple[int, ...] | None = None) -> None:
    """Name the first point outside an axis' error table (and its line when the points came from a file)."""
    for letter in machine.letters:
        machine.table(letter).check_range(positions[letter], path=path, lines=lines)


def parse_point(text: str, option: str) -> dict[str, float]:
    """``"X=0,Z=190"`` (mm) -> ``{"X": 0.0, "Z": 0.19}`` (m)."""
    point: dict[str, float] = {}
    for part in text.split(","):
        letter, sep, value = part.partition("=")
        letter = letter.strip().upper()
        try:
            number = float(value)
        except ValueError:
            number = float("nan")
        if not sep or letter not in "XYZ" or not letter or not np.isfinite(number):
            raise AxiscalError(f"{option} '{text}': expected axis positions in mm like 'X=0,Z=190'")
        point[letter] = number * 1e-3
    return point


@click.command("volumetric")
@click.option("--machine", "machine_path", required=True, type=click.Path(dir_okay=False), help="Machine description (TOML).")
@click.option("--points", "points_path", type=click.Path(dir_okay=False), help="CSV with one <axis>_mm column per axis.")
@click.option("--grid", help='Grid of axis positions in mm, e.g. "X=0:190:10,Z=0:190:10" (start:end:step, inclusive).')
@click.option("-o", "--output", type=click.Path(dir_okay=False), help="Write the CSV here instead of standard output.")
@click.option("--plot", type=click.Path(dir_okay=False), help="Write a map of the volumetric error (PNG).")
def volumetric_command(machine_path, points_path, grid, output, plot):
    """Volumetric error of the functional point at given axis positions.

    Output columns: the axis positions (<axis>_mm), then ex_um, ey_um, ez_um (tool point relative
    to the workpiece, actual minus nominal, in the workpiece frame) and e_um = |e|.
    """
    if (points_path is None) == (grid is None):
        raise AxiscalError("give exactly one of --points FILE or --grid SPEC")
    machine = load_machine(machine_path)
    if points_path is not None:
        positions, _ = read_points(points_path, machine)
    else:
        positions = axis_positions_from_grid(grid)
        missing = sorted(set(machine.letters) - set(positions))
        if missing:
            raise AxiscalError(f"--grid gives no positions for axis {', '.join(missing)} of chain '{machine.chain}'")
        extra = sorted(set(positions) - set(machine.letters))
        if extra:
            raise AxiscalError(f"--grid names axis {', '.join(extra)}, which is not in chain '{machine.chain}'")
        check_travel(machine, positions, path="--grid")
    error = machine.volumetric_error(positions)
    columns = {f"{k.lower()}_mm": positions[k] * 1e3 for k in machine.letters}
    for i, name in enumerate(_XYZ):
        columns[f"e{name}_um"] = error[:, i] * 1e6
    columns["e_um"] = np.linalg.norm(error, axis=1) * 1e6
    text = write_csv(ensure_parent(output) if output else None, columns, fmt="{:.4f}")
    if output is None:
        click.echo(text, nl=False)
    if plot:
        from axiscal.model.plot import plot_volumetric

        plot_volumetric(positions, error, ensure_parent(plot), title=f"Volumetric error: {machine.name or machine.chain}")


def read_interferometer(path: str | Path, nominal_m: np.ndarray | None) -> np.ndarray:
    """Interferometer readings on a diagonal: CSV ``nominal_mm, measured_mm`` (zeroed at the start)."""
    table = read_csv(path, min_rows=2)
    table.require("nominal_mm", "measured_mm")
    nominal = table.numeric("nominal_mm") * 1e-3
    measured = table.numeric("measured_mm") * 1e-3
    if nominal_m is not None:
        if nominal.size != nominal_m.size:
            raise AxiscalError(f"{nominal.size} readings for a diagonal of {nominal_m.size} points", path=str(path))
        off = np.abs(nominal - nominal_m) > 1e-6
        if np.any(off):
            k = int(np.argmax(off))
            raise AxiscalError(
                f"nominal_mm {nominal[k] * 1e3:.6f} does not match the diagonal's point {k} at {nominal_m[k] * 1e3:.6f} mm",
                path=str(path),
                line=table.lines[k],
            )
    return measured


@click.command("diagonal")
@click.option("--machine", "machine_path", required=True, type=click.Path(dir_okay=False), help="Machine description (TOML).")
@click.option("--from", "start", required=True, help='Axis positions of the first point in mm, e.g. "X=0,Z=0".')
@click.option("--to", "end", required=True, help='Axis positions of the last point in mm, e.g. "X=190,Z=190".')
@click.option("--steps", type=int, help="Number of intervals (default: from the readings, else 10).")
@click.option("--interferometer", type=click.Path(dir_okay=False), help="Readings CSV: nominal_mm, measured_mm.")
@click.option("--measure", type=click.Choice(["projection", "length"]), default="projection", show_default=True,
              help="Reading as displacement along the diagonal (ISO 230-6) or as point distance (paper 000 eq 13).")
@click.option("-o", "--output", type=click.Path(dir_okay=False), help="Write the per-point CSV here.")
@click.option("--json", "as_json", is_flag=True, help="Print one JSON object.")
@click.option("--plot", type=click.Path(dir_okay=False), help="Write the before/after plot (PNG).")
def diagonal_command(machine_path, start, end, steps, interferometer, measure, output, as_json, plot):
    """Diagonal displacement test predicted by the model (ISO 230-6), and compared with an
    interferometer (paper 000 eq 13: E_BD before the model, E_AD after)."""
    machine = load_machine(machine_path)
    start_m, end_m = parse_point(start, "--from"), parse_point(end, "--to")
    measured = None
    if interferometer is not None and steps is None:
        steps = len(read_csv(interferometer, min_rows=2)) - 1
    steps = 10 if steps is None else steps
    positions_probe = {k: np.array([start_m[k], end_m[k]]) for k in start_m}
    if set(start_m) == set(machine.letters):
        check_travel(machine, positions_probe, path="--from/--to")
    result = diagonal_check(machine, start_m, end_m, steps, measure=measure)
    if interferometer is not None:
        measured = read_interferometer(interferometer, result.nominal_m)
        result = diagonal_check(machine, start_m, end_m, steps, measured_m=measured, measure=measure)
    columns = {f"{k.lower()}_mm": result.positions_m[k] * 1e3 for k in machine.letters}
    columns["nominal_mm"] = result.nominal_m * 1e3
    columns["model_error_um"] = result.model_error_m * 1e6
    if measured is not None:
        columns["measured_mm"] = result.measured_m * 1e3
        columns["E_BD_um"] = result.error_before_m * 1e6
        columns["E_AD_um"] = result.error_after_m * 1e6
    if output:
        write_csv(ensure_parent(output), columns, fmt="{:.6f}")
    if as_json:
        payload = {"measure": measure, "model_error_range_um": float(np.ptp(result.model_error_m)) * 1e6}
        if measured is not None:
            payload["E_BD_range_um"] = result.range_before_m * 1e6
            payload["E_AD_range_um"] = result.range_after_m * 1e6
        payload["points"] = {k: np.round(np.asarray(v), 6) for k, v in columns.items()}
        echo_json(payload)
    else:
        click.echo(f"diagonal of {machine.name or machine.chain}: {steps + 1} points, length {result.nominal_m[-1] * 1e3:.3f} mm")
        click.echo(f"  model error along the diagonal: P-V {np.ptp(result.model_error_m) * 1e6:.2f} um")
        if measured is not None:
            click.echo(f"  E_BD (before model): P-V {result.range_before_m * 1e6:.2f} um")
            click.echo(f"  E_AD (after model):  P-V {result.range_after_m * 1e6:.2f} um")
    if plot:
        from axiscal.model.plot import plot_diagonal

        plot_diagonal(result, ensure_parent(plot))


@click.command("inverse")
@click.option("--machine", "machine_path", required=True, type=click.Path(dir_okay=False), help="Machine description (TOML).")
@click.option("--points", "points_path", required=True, type=click.Path(dir_okay=False),
              help="CSV of wanted tool points: x_mm, y_mm, z_mm (relative to the workpiece point, workpiece frame).")
@click.option("-o", "--output", type=click.Path(dir_okay=False), help="Write the CSV here instead of standard output.")
def inverse_command(machine_path, points_path, output):
    """Axis commands that put the tool point on wanted points (compensated commands, to < 1 nm)."""
    machine = load_machine(machine_path)
    table = read_csv(points_path)
    table.require("x_mm", "y_mm", "z_mm")
    target = np.column_stack([table.numeric(f"{c}_mm") for c in _XYZ]) * 1e-3
    try:
        command = machine.command_for(target)
    except AxiscalError as exc:
        raise exc.located(path=points_path) from None
    columns = {f"{c}_mm": target[:, i] * 1e3 for i, c in enumerate(_XYZ)}
    columns |= {f"{k.lower()}_command_mm": command[k] * 1e3 for k in machine.letters}
    text = write_csv(ensure_parent(output) if output else None, columns, fmt="{:.7f}")
    if output is None:
        click.echo(text, nl=False)


def register(group: click.Group) -> None:
    group.add_command(volumetric_command)
    group.add_command(diagonal_command)
    group.add_command(inverse_command)
