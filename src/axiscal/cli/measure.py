"""``axiscal measure``, ``axiscal calibrate``, ``axiscal simulate``, ``axiscal experiment``: the 6-DOF measurement system.

See docs/measurement.md. Each command is one call of :mod:`axiscal.measurement.offline`:
``measure`` runs recorded raw frames through the same pipeline the live dashboard uses;
``calibrate`` fits channel sensitivities and the plane-mirror map into a calibration file;
``simulate`` writes frames of the virtual module; ``experiment diagonal`` reproduces paper 000's
diagonal comparison (section 5, eq 13) in simulation.
"""

from __future__ import annotations

import math
from typing import Any

import click

from axiscal.cli.common import FINITE, echo_json, finite, flags_named
from axiscal.errors import AxiscalError
from axiscal.cli.choices import PATHS
from axiscal.units import ARCSEC, MM

__all__ = [
    "measure_command",
    "calibrate_group",
    "sensitivity_command",
    "mirror_command",
    "simulate_frames_command",
    "simulate_laser_command",
    "experiment_group",
    "diagonal_command",
]


def _echo_report(report: dict[str, Any], as_json: bool) -> None:
    from axiscal.measurement import offline

    if as_json:
        echo_json(report)
        return
    click.echo(offline.calibration_text(report), nl=False)


@click.command("measure")
@click.argument("frames_path", metavar="FRAMES.csv", type=click.Path(dir_okay=False))
@click.option("--machine", type=click.Path(dir_okay=False), help="Machine TOML with [axes.<L>.sensors] (default: the built-in virtual module).")
@click.option("-o", "--output", type=click.Path(dir_okay=False), help="Write the results CSV (and its .json sidecar) here (default: standard output).")
@click.option("--json", "as_json", is_flag=True, help="Print a JSON summary instead of the results CSV.")
def measure_command(frames_path, machine, output, as_json):
    """Process recorded raw frames offline: six errors per axis, spatial error, corrected position.

    FRAMES.csv has a column t_s and one column per raw channel (the names of the machine's sensor
    sections, e.g. x_cmd_mm, x_scale_mm, x_psd_y_um ...); other columns are ignored, so a live
    record can be processed again. Output: t_s, fault (0 = good; 1 missing channel, 2 out of
    range, 4 position outside the model), the axis positions, the six errors per axis, ex_um,
    ey_um, ez_um, e_um and px_mm, py_mm, pz_mm. Faulty frames are kept, with empty results (nan).
    """
    from axiscal.measurement import offline

    result = offline.measure_file(frames_path, machine=machine, output=output)
    if as_json:
        summary = result.summary()
        if output:
            summary["output"] = str(output)
        echo_json(summary)
    elif output is None:
        click.echo(result.csv_text(), nl=False)
    else:
        click.echo(f"{result.fault.size} frames, {result.faulty_frames} faulty -> {output}")


@click.group("calibrate")
def calibrate_group():
    """Fit sensor calibrations against reference instruments into a calibration file (JSON)."""


def _vector_mm(text: str | None, option: str) -> tuple[float, float, float] | None:
    """Parse 'dx,dy,dz' (mm) into metres."""
    if text is None:
        return None
    try:
        values = [float(v) for v in text.split(",")]
    except ValueError:
        values = []
    if len(values) != 3 or not all(math.isfinite(v) for v in values):
        raise AxiscalError(f"{option} '{text}': expected three numbers in mm, e.g. '0,45,20'")
    return tuple(v * MM for v in values)  # type: ignore[return-value]


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
    from axiscal.measurement import offline

    offset = _vector_mm(reference_offset_mm, "--reference-offset-mm")
    with flags_named({"reference_offset_m": "--reference-offset-mm"}):
        report = offline.calibrate_sensitivity(run_path, channel, machine=machine, reference_offset_m=offset, output=output)
    _echo_report(report, as_json)


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
    from axiscal.measurement import offline

    report = offline.calibrate_mirror(run_path, letter, machine=machine, max_order=max_order, output=output)
    _echo_report(report, as_json)


@click.command("frames")
@click.option("--path", "motion", type=click.Choice(PATHS), default="diagonal", show_default=True, help="Motion of the module.")
@click.option("--rate", "rate_hz", type=finite(min=0, min_open=True), default=1000.0, show_default=True, help="Frames per second (Hz).")
@click.option("--duration", "duration_s", type=finite(min=0, min_open=True), default=1.0, show_default=True, help="Length of the run (s).")
@click.option("--load-kg", type=finite(min=0), default=0.0, show_default=True, help="Mass on the Z slide (kg).")
@click.option("--seed", type=int, default=0, show_default=True, help="Seed of the sensors and the noise.")
@click.option("--truth", is_flag=True, help="Add the true values as truth_<name> columns.")
@click.option("-o", "--output", type=click.Path(dir_okay=False), help="Write the CSV (and its .json sidecar) here (default: standard output).")
def simulate_frames_command(motion, rate_hz, duration_s, load_kg, seed, truth, output):
    """Raw frames of the virtual module: t_s and every channel, ready for `axiscal measure`."""
    from axiscal.measurement import offline

    with flags_named({"rate_hz": "--rate", "duration_s": "--duration"}):
        made = offline.simulate_frames(path=motion, rate_hz=rate_hz, duration_s=duration_s, load_kg=load_kg, seed=seed,
                                       truth=truth, output=output)
    if output is None:
        click.echo(made.text, nl=False)
    else:
        click.echo(f"{made.rows} frames -> {output}")


@click.command("laser")
@click.option("--steps", type=click.IntRange(min=1), default=19, show_default=True, help="Steps from the start (0, 0).")
@click.option("--step-mm", type=finite(min=0, min_open=True), default=10.0, show_default=True, help="Move of each axis per step (mm).")
@click.option("--load-kg", type=finite(min=0), default=0.0, show_default=True, help="Mass on the Z slide (kg).")
@click.option("--seed", type=int, default=0, show_default=True, help="Seed of the noise.")
@click.option("-o", "--output", type=click.Path(dir_okay=False), help="Write the CSV (and its .json sidecar) here (default: standard output).")
def simulate_laser_command(steps, step_mm, load_kg, seed, output):
    """Laser interferometer readings on the XZ diagonal of the virtual module.

    Columns nominal_mm, measured_mm (the format `axiscal diagonal --interferometer` reads): the
    nominal displacement along the diagonal and the reading, zeroed at the start.
    """
    from axiscal.measurement import offline

    made = offline.simulate_laser(steps=steps, step_m=step_mm * MM, load_kg=load_kg, seed=seed, output=output)
    if output is None:
        click.echo(made.text, nl=False)
    else:
        click.echo(f"{made.rows} readings -> {output}")


@click.group("experiment")
def experiment_group():
    """Paper experiments reproduced in simulation."""


@experiment_group.command("diagonal")
@click.option("--load-kg", type=finite(min=0), default=0.0, show_default=True, help="Mass on the Z slide (kg); the paper's second run uses 2.")
@click.option("--seed", type=int, default=0, show_default=True, help="Seed of the sensors and the noise.")
@click.option("--samples", type=click.IntRange(min=1), default=1, show_default=True, help="Frames averaged at each stop.")
@click.option("--squareness-error-arcsec", type=FINITE, default=0.0, show_default=True, help="Error of the squareness in the model (arcsec), e.g. 8.18 for the paper's marble square.")
@click.option("--plot", type=click.Path(dir_okay=False), help="Write the figure (PNG), like paper 000 Fig. 22.")
@click.option("--json", "as_json", is_flag=True, help="Print the result as JSON.")
def diagonal_command(load_kg, seed, samples, squareness_error_arcsec, plot, as_json):
    """Paper 000 section 5: the XZ diagonal against a laser interferometer, before and after the model.

    The virtual module steps both axes 10 mm at a time over 19 points; eq (13) gives the diagonal
    error without the model (E_BD) and with the measured spatial error (E_AD). The paper reports
    68 -> 13 um (no load) and 56 -> 14 um (2 kg); docs/measurement.md says why the simulation
    leaves less.
    """
    from axiscal.measurement import offline

    report = offline.run_diagonal_experiment(
        load_kg=load_kg, seed=seed, samples=samples, squareness_error_rad=squareness_error_arcsec * ARCSEC, plot=plot
    )
    if as_json:
        echo_json(report.to_dict())
        return
    click.echo(report.text(), nl=False)
    if plot:
        click.echo(f"figure -> {plot}")
