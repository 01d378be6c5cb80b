"""``axiscal separate`` and ``axiscal simulate probes``: multi-probe straightness error separation (paper 001)."""

from __future__ import annotations

import math

import click

from axiscal.cli.common import FINITE, hidden_alias
from axiscal.errors import AxiscalError
from axiscal.cli.choices import SEPARATION_METHODS
from axiscal.units import MM, UM

__all__ = ["separate_command", "simulate_probes_command", "simulate_probes_alias"]


def _positive(**flags: float | None) -> None:
    """Refuse a flag that is given but not a positive, finite number (``spacing_mm=...`` names ``--spacing-mm``)."""
    for name, value in flags.items():
        if value is not None and not (math.isfinite(value) and value > 0):
            raise AxiscalError(f"--{name.replace('_', '-')} must be a positive number, got {value:g}")


def _mm(value: float | None) -> float | None:
    return None if value is None else value * MM


@click.command("separate")
@click.argument("readings", type=click.Path(dir_okay=False))
@click.option("--method", type=click.Choice(SEPARATION_METHODS), default="combined", show_default=True, help="Separation method.")
@click.option("--spacing-mm", type=FINITE, help="Probe spacing A-B, mm (every method but reversal).")
@click.option("--spacing-bc-mm", type=FINITE, help="Probe spacing B-C, mm (default: the A-B spacing).")
@click.option(
    "--reversed",
    "reversed_run",
    type=click.Path(dir_okay=False),
    help="Reversal: the run with the workpiece turned over (position_mm, a_um).",
)
@click.option("--two-probe", is_flag=True, help="Frequency method: use probes A and B only (default: all probes in the file).")
@click.option(
    "--min-gain",
    type=FINITE,
    default=0.05,
    show_default=True,
    help="Frequency method: harmonics below this fraction of the gain envelope are left out.",
)
@click.option(
    "--periodic", is_flag=True, help="Frequency method: treat the profile as periodic over the record (no bow taken out)."
)
@click.option("--calibration-mm", type=FINITE, nargs=2, help="Combined method: START END of the smooth region joining the groups.")
@click.option("-o", "--output", type=click.Path(dir_okay=False), help="Write the CSV (and its JSON sidecar) here instead of standard output.")
@click.option("--plot", "plot_path", type=click.Path(dir_okay=False), help="Write a plot of the separated profile and motion.")
def separate_command(
    readings: str,
    method: str,
    spacing_mm: float | None,
    spacing_bc_mm: float | None,
    reversed_run: str | None,
    two_probe: bool,
    min_gain: float,
    periodic: bool,
    calibration_mm: tuple[float, float] | None,
    output: str | None,
    plot_path: str | None,
) -> None:
    """Separate workpiece profile and slide motion from READINGS (position_mm, a_um, b_um[, c_um]).

    Writes position_mm, profile_um, motion_um[, yaw_urad] for every position the method
    resolves; profile and motion share an undetermined straight line.
    """
    from axiscal.straightness.files import separate_file

    if method == "reversal":
        if reversed_run is None:
            raise AxiscalError("the reversal method needs --reversed RUN.csv: the run with the workpiece turned over")
    else:
        if spacing_mm is None:
            raise AxiscalError(f"--spacing-mm (a positive probe spacing A-B in mm) is needed for the {method} method")
        _positive(spacing_mm=spacing_mm, spacing_bc_mm=spacing_bc_mm)
        if not 0.0 <= min_gain < 1.0:
            raise AxiscalError(f"--min-gain must be at least 0 and below 1, got {min_gain:g}")
        if calibration_mm is not None and not calibration_mm[0] < calibration_mm[1]:
            raise AxiscalError(f"--calibration-mm needs START < END, got {calibration_mm[0]:g} {calibration_mm[1]:g}")
    run = separate_file(
        readings,
        method=method,
        spacing_ab_m=_mm(spacing_mm),
        spacing_bc_m=_mm(spacing_bc_mm),
        reversed_path=reversed_run,
        probes=2 if two_probe else None,
        min_gain=min_gain,
        parabola=not periodic,
        calibration_m=None if calibration_mm is None else (calibration_mm[0] * MM, calibration_mm[1] * MM),
        output=output,
        plot_path=plot_path,
    )
    if output is None:
        click.echo(run.csv_text, nl=False)


@click.command("probes")
@click.option(
    "--profile",
    "profile_path",
    required=True,
    type=click.Path(dir_okay=False),
    help="Workpiece profile R: position_mm, deviation_um.",
)
@click.option(
    "--motion",
    "motion_path",
    required=True,
    type=click.Path(dir_okay=False),
    help="Slide motion S: position_mm, deviation_um[, yaw_urad].",
)
@click.option("--spacing-mm", type=FINITE, required=True, help="Probe spacing A-B, mm.")
@click.option("--spacing-bc-mm", type=FINITE, help="Probe spacing B-C, mm (default: the A-B spacing).")
@click.option("--probes", type=click.IntRange(2, 3), default=3, show_default=True, help="Number of probes.")
@click.option("--step-mm", type=FINITE, required=True, help="Sampling step of the carriage, mm.")
@click.option("--noise-um", type=FINITE, default=0.0, show_default=True, help="Standard deviation of the probe noise, um.")
@click.option(
    "--offsets-um",
    type=FINITE,
    nargs=3,
    default=(0.0, 0.0, 0.0),
    show_default=True,
    help="Zero offsets of probes A B C, um (paper 001 eq 8).",
)
@click.option("--seed", type=int, default=0, show_default=True, help="Seed of the noise.")
@click.option("-o", "--output", type=click.Path(dir_okay=False), help="Write the CSV (and its JSON sidecar) here instead of standard output.")
def simulate_probes_command(
    profile_path: str,
    motion_path: str,
    spacing_mm: float,
    spacing_bc_mm: float | None,
    probes: int,
    step_mm: float,
    noise_um: float,
    offsets_um: tuple[float, float, float],
    seed: int,
    output: str | None,
) -> None:
    """Write the readings (position_mm, a_um, b_um[, c_um]) a probe set-up would give on a profile and a slide.

    Readings follow paper 001 eq (1): a = R(x) - S(x), b = R(x + d1) - S(x) - d1 yaw(x),
    c = R(x + d1 + d2) - S(x) - (d1 + d2) yaw(x), minus the zero offsets, plus Gaussian noise.
    Probe A runs from the profile's first position in steps of --step-mm as far as the last
    probe stays on the profile.
    """
    from axiscal.straightness.files import simulate_probe_readings

    _positive(spacing_mm=spacing_mm, spacing_bc_mm=spacing_bc_mm, step_mm=step_mm)
    if not (math.isfinite(noise_um) and noise_um >= 0):
        raise AxiscalError(f"--noise-um must be a number >= 0, got {noise_um:g}")
    if not all(math.isfinite(o) for o in offsets_um):
        raise AxiscalError("--offsets-um must be three finite numbers")
    simulated = simulate_probe_readings(
        profile_path,
        motion_path,
        spacing_ab_m=spacing_mm * MM,
        spacing_bc_m=_mm(spacing_bc_mm),
        probes=probes,
        step_m=step_mm * MM,
        noise_m=noise_um * UM,
        offsets_m=(offsets_um[0] * UM, offsets_um[1] * UM, offsets_um[2] * UM),
        seed=seed,
        output=output,
    )
    if output is None:
        click.echo(simulated.csv_text, nl=False)


simulate_probes_alias = hidden_alias(simulate_probes_command, "simulate-probes", "simulate probes")
