"""``axiscal separate`` and ``axiscal simulate-probes``: multi-probe straightness error separation (paper 001)."""

from __future__ import annotations

import math

import click
import numpy as np

from axiscal.cli.common import ensure_parent, pyplot
from axiscal.errors import AxiscalError
from axiscal.io.tabular import read_csv, write_csv
from axiscal.straightness.reference import reference_line
from axiscal.straightness.separation import (
    METHODS,
    ProbeReadings,
    Separation,
    reversal,
    separate,
    simulate_readings,
    uneven_step,
)
from axiscal.units import MM, UM

__all__ = [
    "CLI_METHODS",
    "MAX_READINGS",
    "read_readings",
    "separation_columns",
    "plot_separation",
    "separate_command",
    "simulate_probes_command",
    "register",
]

CLI_METHODS = (*METHODS, "reversal")
MAX_READINGS = 10**7


def _positive(**flags: float | None) -> None:
    """Refuse a flag that is given but not a positive, finite number (``spacing_mm=...`` names ``--spacing-mm``)."""
    for name, value in flags.items():
        if value is not None and not (math.isfinite(value) and value > 0):
            raise AxiscalError(f"--{name.replace('_', '-')} must be a positive number, got {value:g}")


def read_readings(path: str, *, spacing_mm: float, spacing_bc_mm: float | None) -> ProbeReadings:
    """A readings file (``position_mm, a_um, b_um[, c_um]``, position of probe A) in SI units.

    Every method but reversal needs evenly stepped, increasing positions: the first row that
    breaks the step is named by its line.
    """
    table = read_csv(path, min_rows=2)
    table.require("position_mm", "a_um", "b_um")
    position = table.numeric("position_mm")
    k = uneven_step(position)
    if k is not None:
        first = position[1] - position[0]
        problem = (
            f"positions must increase (the first step is {first:g} mm)"
            if not first > 0
            else f"the step from {position[k]:g} mm is {position[k + 1] - position[k]:g} mm where the first step is {first:g} mm"
        )
        raise AxiscalError(
            f"error separation needs evenly stepped positions: {problem}", path=path, line=table.lines[k + 1]
        )
    c = table.numeric("c_um") * UM if table.has("c_um") else None
    spacing_bc = None if c is None else (spacing_mm if spacing_bc_mm is None else spacing_bc_mm) * MM
    return ProbeReadings(position * MM, table.numeric("a_um") * UM, table.numeric("b_um") * UM, c, spacing_mm * MM, spacing_bc)


def _cells(values: np.ndarray, scale: float, fmt: str) -> list[str]:
    return ["" if not np.isfinite(v) else fmt.format(v / scale) for v in values]


def separation_columns(result: Separation) -> dict[str, list[str]]:
    """Output columns: position_mm, profile_um, motion_um and, when resolved, yaw_urad (empty cells: not resolved)."""
    columns = {
        "position_mm": _cells(result.position_m, MM, "{:.4f}"),
        "profile_um": _cells(result.profile_m, UM, "{:.5f}"),
        "motion_um": _cells(result.motion_m, UM, "{:.5f}"),
    }
    if np.any(np.isfinite(result.yaw_rad)):
        columns["yaw_urad"] = _cells(result.yaw_rad, 1e-6, "{:.5f}")
    return columns


def plot_separation(path: str, result: Separation) -> None:
    """Profile R and motion S about the profile's least-squares line (top) and the yaw when resolved (bottom).

    R and S share an undetermined straight line, so the same line (the profile's least-squares
    line) is taken from both: what is left is their shape, and S keeps its place relative to R.
    """
    plt = pyplot()
    x = result.position_m
    line = reference_line(x, result.profile_m)
    profile = line.residuals(x, result.profile_m)
    motion = line.residuals(x, result.motion_m)
    has_yaw = bool(np.any(np.isfinite(result.yaw_rad)))
    marker = "o-" if x.size <= 60 else "-"
    fig, axes = plt.subplots(2 if has_yaw else 1, 1, figsize=(8, 6 if has_yaw else 4), sharex=True, squeeze=False)
    ax = axes[0, 0]
    finite = np.isfinite(motion)
    motion_zone = np.ptp(motion[finite]) if finite.any() else np.nan
    ax.plot(x / MM, profile / UM, marker, ms=3, label=f"profile R (P-V {np.ptp(profile) / UM:.3f} um)")
    ax.plot(x / MM, motion / UM, marker, ms=3, label=f"motion S (P-V {motion_zone / UM:.3f} um)")
    ax.set_ylabel("deviation / um")
    ax.set_title(f"error separation: {result.method} (R and S less R's least-squares line)")
    ax.legend(fontsize=8)
    if has_yaw:
        yaw = axes[1, 0]
        yaw.plot(x / MM, result.yaw_rad / 1e-6, marker, ms=3, color="C2", label="yaw (up to a constant)")
        yaw.set_ylabel("yaw / urad")
        yaw.legend(fontsize=8)
    axes[-1, 0].set_xlabel("position along the workpiece / mm")
    fig.tight_layout()
    fig.savefig(ensure_parent(path), dpi=120)
    plt.close(fig)


@click.command("separate")
@click.argument("readings", type=click.Path(dir_okay=False))
@click.option("--method", type=click.Choice(CLI_METHODS), default="combined", show_default=True, help="Separation method.")
@click.option("--spacing-mm", type=float, help="Probe spacing A-B, mm (every method but reversal).")
@click.option("--spacing-bc-mm", type=float, help="Probe spacing B-C, mm (default: the A-B spacing).")
@click.option(
    "--reversed",
    "reversed_run",
    type=click.Path(dir_okay=False),
    help="Reversal: the run with the workpiece turned over (position_mm, a_um).",
)
@click.option("--two-probe", is_flag=True, help="Frequency method: use probes A and B only (default: all probes in the file).")
@click.option(
    "--min-gain",
    type=float,
    default=0.05,
    show_default=True,
    help="Frequency method: harmonics below this fraction of the gain envelope are left out.",
)
@click.option(
    "--periodic", is_flag=True, help="Frequency method: treat the profile as periodic over the record (no bow taken out)."
)
@click.option("--calibration-mm", type=float, nargs=2, help="Combined method: START END of the smooth region joining the groups.")
@click.option("-o", "--output", type=click.Path(dir_okay=False), help="Write the CSV here instead of standard output.")
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
    if method == "reversal":
        result = _reversal(readings, reversed_run)
    else:
        if spacing_mm is None:
            raise AxiscalError(f"--spacing-mm (a positive probe spacing A-B in mm) is needed for the {method} method")
        _positive(spacing_mm=spacing_mm, spacing_bc_mm=spacing_bc_mm)
        if not 0.0 <= min_gain < 1.0:
            raise AxiscalError(f"--min-gain must be at least 0 and below 1, got {min_gain:g}")
        if calibration_mm is not None and not calibration_mm[0] < calibration_mm[1]:
            raise AxiscalError(f"--calibration-mm needs START < END, got {calibration_mm[0]:g} {calibration_mm[1]:g}")
        data = read_readings(readings, spacing_mm=spacing_mm, spacing_bc_mm=spacing_bc_mm)
        calibration = None if calibration_mm is None else (calibration_mm[0] * MM, calibration_mm[1] * MM)
        try:
            result = separate(
                data,
                method=method,
                probes=2 if two_probe else None,
                min_gain=min_gain,
                parabola=not periodic,
                calibration_m=calibration,
            )
        except AxiscalError as exc:
            raise exc.located(path=readings) from None
    comments = [f"method {result.method}; profile and motion up to a common straight line"]
    if result.lost_wavelength_m.size:
        lost = ", ".join(f"{w / MM:.4g}" for w in np.sort(result.lost_wavelength_m)[::-1])
        comments.append(f"harmonics left out (wavelengths, mm): {lost}")
    text = write_csv(output, separation_columns(result), comments=comments)
    if output is None:
        click.echo(text, nl=False)
    if plot_path:
        plot_separation(plot_path, result)


def _reversal(normal_path: str, reversed_path: str | None) -> Separation:
    if reversed_path is None:
        raise AxiscalError("the reversal method needs --reversed RUN.csv: the run with the workpiece turned over")
    normal = read_csv(normal_path, min_rows=2)
    turned = read_csv(reversed_path, min_rows=2)
    normal.require("position_mm", "a_um")
    turned.require("position_mm", "a_um")
    x1, x2 = normal.numeric("position_mm"), turned.numeric("position_mm")
    if x1.shape != x2.shape:
        raise AxiscalError(
            f"{len(x2)} readings where the normal run has {len(x1)}: reversal needs the same positions", path=reversed_path
        )
    bad = np.flatnonzero(np.abs(x1 - x2) > 1e-9 * max(1.0, float(np.max(np.abs(x1)))))
    if bad.size:
        k = int(bad[0])
        raise AxiscalError(
            f"position {x2[k]:g} mm where the normal run has {x1[k]:g} mm: reversal needs the same positions",
            path=reversed_path,
            line=turned.lines[k],
        )
    return reversal(x1 * MM, normal.numeric("a_um") * UM, turned.numeric("a_um") * UM)


def _curve(path: str, column: str, unit: float, what: str):
    table = read_csv(path, min_rows=2)
    table.require("position_mm", column)
    x = table.numeric("position_mm") * MM
    v = table.numeric(column) * unit
    if np.any(np.diff(x) <= 0):
        k = int(np.flatnonzero(np.diff(x) <= 0)[0]) + 1
        raise AxiscalError(f"{what}: positions must increase", path=path, line=table.lines[k])

    def at(p: np.ndarray) -> np.ndarray:
        if p.min() < x[0] - 1e-12 or p.max() > x[-1] + 1e-12:
            raise AxiscalError(
                f"{what} covers {x[0] / MM:g}..{x[-1] / MM:g} mm but the probes reach {p.min() / MM:g}..{p.max() / MM:g} mm",
                path=path,
            )
        return np.interp(p, x, v)

    return at, x, table


@click.command("simulate-probes")
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
@click.option("--spacing-mm", type=float, required=True, help="Probe spacing A-B, mm.")
@click.option("--spacing-bc-mm", type=float, help="Probe spacing B-C, mm (default: the A-B spacing).")
@click.option("--probes", type=click.IntRange(2, 3), default=3, show_default=True, help="Number of probes.")
@click.option("--step-mm", type=float, required=True, help="Sampling step of the carriage, mm.")
@click.option("--noise-um", type=float, default=0.0, show_default=True, help="Standard deviation of the probe noise, um.")
@click.option(
    "--offsets-um",
    type=float,
    nargs=3,
    default=(0.0, 0.0, 0.0),
    show_default=True,
    help="Zero offsets of probes A B C, um (paper 001 eq 8).",
)
@click.option("--seed", type=int, default=0, show_default=True, help="Seed of the noise.")
@click.option("-o", "--output", type=click.Path(dir_okay=False), help="Write the CSV here instead of standard output.")
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
    _positive(spacing_mm=spacing_mm, spacing_bc_mm=spacing_bc_mm, step_mm=step_mm)
    if not (math.isfinite(noise_um) and noise_um >= 0):
        raise AxiscalError(f"--noise-um must be a number >= 0, got {noise_um:g}")
    if not all(math.isfinite(o) for o in offsets_um):
        raise AxiscalError("--offsets-um must be three finite numbers")
    profile, px, _ = _curve(profile_path, "deviation_um", UM, "the profile")
    motion, _, motion_table = _curve(motion_path, "deviation_um", UM, "the motion")
    yaw = _curve(motion_path, "yaw_urad", 1e-6, "the yaw")[0] if motion_table.has("yaw_urad") else None
    d1 = spacing_mm * MM
    d2 = (spacing_mm if spacing_bc_mm is None else spacing_bc_mm) * MM if probes == 3 else None
    reach = d1 + (d2 or 0.0)
    steps = (px[-1] - px[0] - reach) / (step_mm * MM)
    if steps >= MAX_READINGS:
        raise AxiscalError(f"--step-mm {step_mm:g} gives {steps:.3g} readings; at most {MAX_READINGS} are simulated")
    count = int(np.floor(steps + 1e-9)) + 1
    if count < 2:
        raise AxiscalError(
            f"the profile ({(px[-1] - px[0]) / MM:g} mm) is too short for probes {reach / MM:g} mm apart", path=profile_path
        )
    x = px[0] + step_mm * MM * np.arange(count)
    data = simulate_readings(
        x,
        profile,
        motion,
        yaw,
        spacing_ab_m=d1,
        spacing_bc_m=d2,
        offsets_m=tuple(o * UM for o in offsets_um),  # type: ignore[arg-type]
        noise_m=noise_um * UM,
        rng=np.random.default_rng(seed),
    )
    columns = {"position_mm": data.position_m / MM, "a_um": data.a_m / UM, "b_um": data.b_m / UM}
    if data.c_m is not None:
        columns["c_um"] = data.c_m / UM
    spacing_note = f"spacing A-B {spacing_mm:g} mm" + (f", B-C {d2 / MM:g} mm" if d2 is not None else "")
    comments = [f"simulated readings, paper 001 eq (1); {spacing_note}; step {step_mm:g} mm; noise {noise_um:g} um"]
    formats = {"position_mm": "{:.4f}", "a_um": "{:.6f}", "b_um": "{:.6f}", "c_um": "{:.6f}"}
    text = write_csv(output, columns, fmt=formats, comments=comments)
    if output is None:
        click.echo(text, nl=False)


def register(group: click.Group) -> None:
    group.add_command(separate_command)
    group.add_command(simulate_probes_command)
