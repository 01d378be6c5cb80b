"""``axiscal measure``, ``axiscal calibrate``, ``axiscal simulate``, ``axiscal experiment``: the 6-DOF measurement system.

See docs/measurement.md. ``measure`` runs recorded raw frames through the same pipeline the live
dashboard uses; ``calibrate`` fits channel sensitivities and the plane-mirror map into a
calibration file; ``simulate`` writes frames of the virtual module; ``experiment diagonal``
reproduces paper 000's diagonal comparison (section 5, eq 13) in simulation.
"""

from __future__ import annotations

import math
from pathlib import Path

import click
import numpy as np

from axiscal.cli.common import echo_json, write_output
from axiscal.errors import AxiscalError
from axiscal.io.tabular import CsvTable, parse_csv, read_csv, read_text
from axiscal.measurement.virtual import PATHS

__all__ = [
    "read_frames",
    "write_columns",
    "measure_command",
    "calibrate_group",
    "sensitivity_command",
    "mirror_command",
    "simulate_group",
    "simulate_frames_command",
    "simulate_laser_command",
    "experiment_group",
    "diagonal_command",
    "register",
]



def _system(machine: str | None, *, seed: int = 0, load_kg: float = 0.0):
    """The measurement system of a machine TOML, or of the built-in virtual module."""
    from axiscal.measurement.pipeline import MeasurementSystem
    from axiscal.measurement.virtual import VirtualModule

    if machine is None:
        return VirtualModule(seed=seed, load_kg=load_kg).measurement_system()
    return MeasurementSystem.from_toml(machine)


def _cells(table: CsvTable, name: str) -> np.ndarray:
    """Column ``name`` as floats; an empty, ``nan`` or unreadable cell is a missing value (NaN)."""
    table.require(name)
    index = table.header.index(name)
    out = np.empty(len(table.rows))
    for k, row in enumerate(table.rows):
        try:
            out[k] = float(row[index])
        except ValueError:
            out[k] = math.nan
    out[~np.isfinite(out)] = math.nan
    return out


def read_frames(path: str | Path, channels: tuple[str, ...]) -> dict[str, np.ndarray]:
    """Raw frames from a CSV with ``t_s`` and every channel (other columns are ignored).

    A cell that is empty, ``nan`` or not a number is a missing reading: the frame is flagged by the
    pipeline, not refused. In a live record, a last line without its newline (cut short by a
    crash) is dropped; in any other file it is a frame. A missing column or a bad time stamp is an
    error naming the file.
    """
    from axiscal.live.recorder import drop_cut_line

    text, _ = drop_cut_line(read_text(path))
    table = parse_csv(text.split("\n"), path=str(path))
    table.require("t_s", *channels)
    frames = {"t_s": table.numeric("t_s")}
    for name in channels:
        frames[name] = _cells(table, name)
    return frames


def write_columns(path: str | Path | None, columns: dict[str, np.ndarray], *, comments: tuple[str, ...] = ()) -> str:
    """Write equal-length numeric columns as CSV (``%.9g``, NaN as ``nan``, integers as integers)."""
    names = list(columns)
    lines = [f"# {c}" for c in comments] + [",".join(names)]
    formats = ["%d" if np.issubdtype(np.asarray(columns[n]).dtype, np.integer) else "%.9g" for n in names]
    n = len(columns[names[0]]) if names else 0
    stacked = [np.asarray(columns[name]) for name in names]
    row_format = ",".join(formats)
    lines += [row_format % tuple(col[k] for col in stacked) for k in range(n)]
    text = "\n".join(lines) + "\n"
    if path is not None:
        write_output(path, lambda target: target.write_text(text, encoding="utf-8"))
    return text


@click.command("measure")
@click.argument("frames_path", metavar="FRAMES.csv", type=click.Path(dir_okay=False))
@click.option("--machine", type=click.Path(dir_okay=False), help="Machine TOML with [axes.<L>.sensors] (default: the built-in virtual module).")
@click.option("-o", "--output", type=click.Path(dir_okay=False), help="Write the results CSV here (default: standard output).")
@click.option("--json", "as_json", is_flag=True, help="Print a JSON summary instead of the results CSV.")
def measure_command(frames_path, machine, output, as_json):
    """Process recorded raw frames offline: six errors per axis, spatial error, corrected position.

    FRAMES.csv has a column t_s and one column per raw channel (the names of the machine's sensor
    sections, e.g. x_cmd_mm, x_scale_mm, x_psd_y_um ...); other columns are ignored, so a live
    record can be processed again. Output: t_s, fault (0 = good; 1 missing channel, 2 out of
    range, 4 position outside the model), the axis positions, the six errors per axis, ex_um,
    ey_um, ez_um, e_um and px_mm, py_mm, pz_mm. Faulty frames are kept, with empty results (nan).
    """
    system = _system(machine)
    frames = read_frames(frames_path, system.channels)
    result = system.process(frames)
    columns = {"t_s": result["t_s"], "fault": result["fault"]}
    columns.update({k: v for k, v in result.items() if k not in columns})
    faults = result["fault"] != 0
    if as_json:
        good = ~faults
        summary = {
            "frames": int(faults.size),
            "faulty_frames": int(np.count_nonzero(faults)),
            "faults": {system.fault_text(bit): int(np.count_nonzero(result["fault"] & bit)) for bit in (1, 2, 4)},
            "max_e_um": float(np.max(result["e_um"][good])) if np.any(good) else None,
            "mean_e_um": float(np.mean(result["e_um"][good])) if np.any(good) else None,
        }
        if output:
            write_columns(output, columns)
            summary["output"] = str(output)
        echo_json(summary)
        return
    text = write_columns(output, columns, comments=(f"axiscal measure {Path(frames_path).name}: {np.count_nonzero(faults)} faulty frames of {faults.size}",))
    if output is None:
        click.echo(text, nl=False)
    else:
        click.echo(f"{faults.size} frames, {np.count_nonzero(faults)} faulty -> {output}")


@click.group("calibrate")
def calibrate_group():
    """Fit sensor calibrations against reference instruments into a calibration file (JSON)."""


def _channel_role(system, channel: str):
    for letter, head in system.heads.items():
        for role, name in head.channels.items():
            if name == channel:
                return letter, head, role
    raise AxiscalError(f"unknown channel '{channel}'; channels are: {', '.join(system.channels)}")


def _reference_column(table: CsvTable, kinds: tuple[str, ...]) -> tuple[str, str]:
    from axiscal.units import split_unit

    for column in table.header:
        if column.startswith("reference_"):
            _, unit = split_unit(column)
            if unit not in kinds:
                raise AxiscalError(f"column '{column}': reference unit must be one of {', '.join(kinds)}", path=table.path, line=table.header_line)
            return column, unit
    raise AxiscalError(f"missing column 'reference_<unit>' (unit one of {', '.join(kinds)})", path=table.path, line=table.header_line)


def _save(calibration, output: str | None, as_json: bool, report: dict) -> None:
    from axiscal.instruments.calibration import load_calibration, save_calibration

    if output is not None:
        merged = load_calibration(output).merged(calibration) if Path(output).exists() else calibration
        write_output(output, lambda target: save_calibration(merged, target))
        report["output"] = str(output)
    if as_json:
        echo_json(report)
    else:
        for key, value in report.items():
            click.echo(f"{key}: {value}")


@calibrate_group.command("sensitivity")
@click.argument("run_path", metavar="RUN.csv", type=click.Path(dir_okay=False))
@click.option("--channel", required=True, help="The raw channel calibrated, e.g. x_psd_y_um (a column of RUN.csv).")
@click.option("--machine", type=click.Path(dir_okay=False), help="Machine TOML with the sensor geometry (default: the built-in virtual module).")
@click.option("--reference-offset-mm", default=None, help="Sensor point minus reference point 'dx,dy,dz' (mm) to transfer the reference (needs the axis' angle columns).")
@click.option("-o", "--output", type=click.Path(dir_okay=False), help="Calibration file to create or update (JSON).")
@click.option("--json", "as_json", is_flag=True, help="Print the result as JSON.")
def sensitivity_command(run_path, channel, machine, reference_offset_mm, output, as_json):
    """Gain and offset of one channel by least squares against a reference instrument.

    RUN.csv holds the raw channel column and a reference column: reference_um / reference_mm for
    the scale and PSD channels, reference_arcsec / reference_urad (the angle an autocollimator or
    level read) for the quadrant and roll detectors. With --reference-offset-mm the reference of a
    translation is first moved to the sensor's point (paper 000 section 4.2) with the angle
    columns E<A,B,C><axis>_urad or _arcsec of the run.
    """
    from axiscal.instruments.calibration import (
        Calibration,
        fit_sensitivity,
        transfer_reference,
    )
    from axiscal.units import angle_factor, length_factor

    system = _system(machine)
    letter, head, role = _channel_role(system, channel)
    table = read_csv(run_path, min_rows=3)
    raw = table.numeric(channel)
    kind = role.split("_")[0]
    angular = kind in ("qd", "roll")
    column, unit = _reference_column(table, ("arcsec", "urad") if angular else ("nm", "um", "mm"))
    reference = table.numeric(column)
    channel_unit = 1e-3 if kind == "scale" else 1e-6
    if angular:
        component = {"qd_u": head.qd_u, "qd_v": head.qd_v, "roll": head.roll}[role]
        focal = head.qd_focal_m if kind == "qd" else 2.0 * head.roll_focal_m
        reference = component.sign * reference * angle_factor(unit) * focal / channel_unit
        if reference_offset_mm is not None:
            raise AxiscalError("--reference-offset-mm applies to translation channels (scale, PSD), not to angles")
    else:
        reference = reference * length_factor(unit, allowed=("nm", "um", "mm")) / channel_unit
        if reference_offset_mm is not None:
            offset = _vector_mm(reference_offset_mm, "--reference-offset-mm")
            eps = np.column_stack([_angle_column(table, f"E{r}{letter}") for r in "ABC"])
            component = head.index if kind == "scale" else "xyz".index(role.split("_")[1])
            reference = transfer_reference(reference * channel_unit, eps, offset, component) / channel_unit
    fit = fit_sensitivity(channel, raw, reference)
    unit_name = "mm" if kind == "scale" else "um"
    report = {
        "channel": channel,
        "gain": fit.gain,
        "offset_" + unit_name: fit.offset,
        "residual_max_" + unit_name: fit.residual_max,
        "residual_rms_" + unit_name: fit.residual_rms,
        "points": fit.points,
    }
    if angular:
        from axiscal.units import ARCSEC

        report["residual_max_arcsec"] = fit.residual_max * channel_unit / focal / ARCSEC
    _save(Calibration({channel: fit}), output, as_json, report)


def _vector_mm(text: str, option: str) -> np.ndarray:
    try:
        values = [float(v) for v in text.split(",")]
    except ValueError:
        values = []
    if len(values) != 3 or not all(math.isfinite(v) for v in values):
        raise AxiscalError(f"{option} '{text}': expected three numbers in mm, e.g. '0,45,20'")
    return np.array(values) * 1e-3


def _angle_column(table: CsvTable, stem: str) -> np.ndarray:
    from axiscal.units import angle_factor

    for unit in ("urad", "arcsec"):
        if table.has(f"{stem}_{unit}"):
            return table.numeric(f"{stem}_{unit}") * angle_factor(unit)
    raise AxiscalError(f"missing column '{stem}_urad' (or _arcsec), needed to transfer the reference", path=table.path, line=table.header_line)


@calibrate_group.command("mirror")
@click.argument("run_path", metavar="RUN.csv", type=click.Path(dir_okay=False))
@click.option("--axis", "letter", required=True, type=click.Choice(["X", "Y", "Z"], case_sensitive=False), help="The axis whose roll mirror was mapped.")
@click.option("--machine", type=click.Path(dir_okay=False), help="Machine TOML with the sensor geometry (default: the built-in virtual module).")
@click.option("--max-order", type=click.IntRange(0, 30), default=12, show_default=True, help="Highest polynomial order tried by the cross-validation.")
@click.option("-o", "--output", type=click.Path(dir_okay=False), help="Calibration file to create or update (JSON).")
@click.option("--json", "as_json", is_flag=True, help="Print the result as JSON.")
def mirror_command(run_path, letter, machine, max_order, output, as_json):
    """Map the roll detector's plane mirror against a level (paper 000 eqs 11-12).

    RUN.csv: position_mm, the raw roll channel (e.g. x_roll_um) and level_arcsec or level_urad at
    the same positions. The roll channel's sensitivity calibration (from the machine's calibration
    file, then from --output if it exists) is applied first; the form error module - level is
    fitted by a Legendre polynomial whose order leave-one-out cross-validation picks.
    """
    from axiscal.instruments.calibration import (
        Calibration,
        fit_mirror,
        load_calibration,
    )
    from axiscal.instruments.sensors import roll_from_autocollimation
    from axiscal.units import ARCSEC

    letter = letter.upper()
    system = _system(machine)
    if output is not None and Path(output).exists():
        system = system.with_calibration(load_calibration(output))
    if letter not in system.heads:
        raise AxiscalError(f"axis {letter} has no sensors in this machine (axes: {', '.join(system.axes)})")
    head = system.heads[letter]
    channel = head.channels["roll"]
    table = read_csv(run_path, min_rows=4)
    position = table.numeric("position_mm") * 1e-3
    shift = system.calibration.channel(channel).apply(table.numeric(channel)) * 1e-6
    module_roll = head.roll.sign * roll_from_autocollimation(shift, head.roll_focal_m)
    level = _angle_column(table, "level")
    mirror = fit_mirror(letter, position, module_roll, level, max_order=max_order)
    report = {
        "axis": letter,
        "order": mirror.order,
        "residual_max_arcsec": mirror.residual_max_rad / ARCSEC,
        "residual_rms_arcsec": mirror.residual_rms_rad / ARCSEC,
        "form_error_range_arcsec": float(np.ptp(mirror.evaluate(np.linspace(mirror.start_m, mirror.end_m, 200)))) / ARCSEC,
        "cv_rms_arcsec": [v / ARCSEC for v in mirror.cv_rms_rad],
        "points": mirror.points,
    }
    if not as_json:
        report["cv_rms_arcsec"] = " ".join(f"{v:.3f}" for v in report["cv_rms_arcsec"])
    _save(Calibration({}, {letter: mirror}), output, as_json, report)


@click.group("simulate")
def simulate_group():
    """Data from the virtual XZ module of paper 000 (docs/measurement.md)."""


@simulate_group.command("frames")
@click.option("--path", "motion", type=click.Choice(PATHS), default="diagonal", show_default=True, help="Motion of the module.")
@click.option("--rate", "rate_hz", type=click.FloatRange(min=0, min_open=True), default=1000.0, show_default=True, help="Frames per second (Hz).")
@click.option("--duration", "duration_s", type=click.FloatRange(min=0, min_open=True), default=1.0, show_default=True, help="Length of the run (s).")
@click.option("--load-kg", type=click.FloatRange(min=0), default=0.0, show_default=True, help="Mass on the Z slide (kg).")
@click.option("--seed", type=int, default=0, show_default=True, help="Seed of the sensors and the noise.")
@click.option("--truth", is_flag=True, help="Add the true values as truth_<name> columns.")
@click.option("-o", "--output", type=click.Path(dir_okay=False), help="Write the CSV here (default: standard output).")
def simulate_frames_command(motion, rate_hz, duration_s, load_kg, seed, truth, output):
    """Raw frames of the virtual module: t_s and every channel, ready for `axiscal measure`."""
    from axiscal.measurement.virtual import VirtualModule

    count = int(round(duration_s * rate_hz))
    if count < 1 or count > 10_000_000:
        raise AxiscalError(f"--rate x --duration gives {count} frames; allowed 1 to 10000000")
    module = VirtualModule(seed=seed, load_kg=load_kg)
    frames, true = module.frames(np.arange(count) / rate_hz, path=motion)
    columns = dict(frames)
    if truth:
        columns.update({f"truth_{k}": v for k, v in true.items() if k != "t_s"})
    comment = f"virtual XZ module (paper 000), seed {seed}, load {load_kg:g} kg, path {motion}, {rate_hz:g} Hz"
    text = write_columns(output, columns, comments=(comment,))
    if output is None:
        click.echo(text, nl=False)
    else:
        click.echo(f"{count} frames -> {output}")


@simulate_group.command("laser")
@click.option("--steps", type=click.IntRange(min=1), default=19, show_default=True, help="Steps from the start (0, 0).")
@click.option("--step-mm", type=click.FloatRange(min=0, min_open=True), default=10.0, show_default=True, help="Move of each axis per step (mm).")
@click.option("--load-kg", type=click.FloatRange(min=0), default=0.0, show_default=True, help="Mass on the Z slide (kg).")
@click.option("--seed", type=int, default=0, show_default=True, help="Seed of the noise.")
@click.option("-o", "--output", type=click.Path(dir_okay=False), help="Write the CSV here (default: standard output).")
def simulate_laser_command(steps, step_mm, load_kg, seed, output):
    """Laser interferometer readings on the XZ diagonal of the virtual module.

    Columns nominal_mm, measured_mm (the format `axiscal diagonal --interferometer` reads): the
    nominal displacement along the diagonal and the reading, zeroed at the start.
    """
    from axiscal.measurement.virtual import STROKE_M, VirtualModule

    if steps * step_mm * 1e-3 > STROKE_M + 1e-12:
        raise AxiscalError(f"{steps} steps of {step_mm:g} mm leave the 190 mm travel")
    module = VirtualModule(seed=seed, load_kg=load_kg)
    q = np.arange(steps + 1) * step_mm * 1e-3
    positions = {"X": q, "Z": q.copy()}
    reading = module.laser_diagonal(positions)
    comment = f"simulated interferometer on the XZ diagonal of the virtual module, seed {seed}, load {load_kg:g} kg"
    text = write_columns(output, {"nominal_mm": np.hypot(q, q) * 1e3, "measured_mm": reading * 1e3}, comments=(comment,))
    if output is None:
        click.echo(text, nl=False)
    else:
        click.echo(f"{steps + 1} readings -> {output}")


@click.group("experiment")
def experiment_group():
    """Paper experiments reproduced in simulation."""


@experiment_group.command("diagonal")
@click.option("--load-kg", type=click.FloatRange(min=0), default=0.0, show_default=True, help="Mass on the Z slide (kg); the paper's second run uses 2.")
@click.option("--seed", type=int, default=0, show_default=True, help="Seed of the sensors and the noise.")
@click.option("--samples", type=click.IntRange(min=1), default=1, show_default=True, help="Frames averaged at each stop.")
@click.option("--squareness-error-arcsec", type=float, default=0.0, show_default=True, help="Error of the squareness in the model (arcsec), e.g. 8.18 for the paper's marble square.")
@click.option("--plot", type=click.Path(dir_okay=False), help="Write the figure (PNG), like paper 000 Fig. 22.")
@click.option("--json", "as_json", is_flag=True, help="Print the result as JSON.")
def diagonal_command(load_kg, seed, samples, squareness_error_arcsec, plot, as_json):
    """Paper 000 section 5: the XZ diagonal against a laser interferometer, before and after the model.

    The virtual module steps both axes 10 mm at a time over 19 points; eq (13) gives the diagonal
    error without the model (E_BD) and with the measured spatial error (E_AD). The paper reports
    68 -> 13 um (no load) and 56 -> 14 um (2 kg); docs/measurement.md says why the simulation
    leaves less.
    """
    from axiscal.measurement.virtual import VirtualModule, diagonal_experiment
    from axiscal.units import ARCSEC

    result = diagonal_experiment(
        VirtualModule(seed=seed, load_kg=load_kg), samples=samples, squareness_error_rad=squareness_error_arcsec * ARCSEC
    )
    if plot:
        from axiscal.model.plot import plot_diagonal_experiment

        write_output(plot, lambda target: plot_diagonal_experiment(result, target))
    if as_json:
        echo_json(
            {
                "load_kg": result.load_kg,
                "before_max_um": result.before_max_um,
                "after_max_um": result.after_max_um,
                "scales_only_max_um": result.scales_only_max_um,
                "paper_um": {"before": 56.0, "after": 14.0} if load_kg == 2.0 else {"before": 68.0, "after": 13.0} if load_kg == 0.0 else None,
                "points": [
                    {"x_mm": x, "z_mm": z, "laser_mm": p, "before_um": b, "after_um": a, "scales_only_um": s}
                    for x, z, p, b, a, s in zip(result.x_mm, result.z_mm, result.laser_mm, result.before_um, result.after_um, result.scales_only_um)
                ],
            }
        )
        return
    click.echo(f"XZ diagonal of the virtual module, load {load_kg:g} kg, {result.x_mm.size - 1} steps of 10 mm (paper 000 eq 13)")
    click.echo(f"{'x_mm':>7} {'z_mm':>7} {'laser_mm':>11} {'E_BD_um':>9} {'E_AD_um':>9} {'scales_um':>9}")
    for x, z, p, b, a, s in zip(result.x_mm, result.z_mm, result.laser_mm, result.before_um, result.after_um, result.scales_only_um):
        click.echo(f"{x:7.1f} {z:7.1f} {p:11.6f} {b:9.2f} {a:9.2f} {s:9.2f}")
    click.echo(f"before the model: {result.before_max_um:.1f} um; after: {result.after_max_um:.2f} um; scales only: {result.scales_only_max_um:.1f} um")
    if load_kg in (0.0, 2.0):
        paper = "56 -> 14" if load_kg == 2.0 else "68 -> 13"
        click.echo(f"paper 000: {paper} um")
    if plot:
        click.echo(f"figure -> {plot}")


def register(group: click.Group) -> None:
    group.add_command(measure_command)
    group.add_command(calibrate_group)
    group.add_command(simulate_group)
    group.add_command(experiment_group)
