"""``axiscal ballbar``: ISO 230-4 circular test evaluation and diagnostics; ``simulate ballbar``: the trace of a virtual machine."""

from __future__ import annotations

import math

import click

from axiscal.cli.choices import DIRECTIONS, PLANES
from axiscal.cli.common import FINITE, echo_json, finite
from axiscal.units import ANGLE_UNITS, MM, UM

__all__ = ["ballbar_command", "simulate_ballbar_command"]

_URAD = ANGLE_UNITS["urad"]
MM_PER_MIN = MM / 60.0
MS = 1e-3
PPM = 1e-6


@click.command("ballbar")
@click.argument("run_csv", metavar="RUN.csv", type=click.Path(dir_okay=False))
@click.option("--radius-mm", type=FINITE, required=True, help="Nominal radius of the test (the ballbar's length), mm.")
@click.option("--plane", type=click.Choice(PLANES, case_sensitive=False), required=True,
              help="First and second axis; angles run from the first towards the second.")
@click.option("--feed-mm-min", type=finite(min=0, min_open=True), default=None,
              help="Feed of the test (mm/min); with both directions it gives the servo mismatch.")
@click.option("--json", "as_json", is_flag=True, help="Print one JSON object (figures in um).")
@click.option("--plot", "plot_path", type=click.Path(dir_okay=False), help="Write the polar plot to this file (.png, .svg, .pdf).")
def ballbar_command(run_csv, radius_mm, plane, feed_mm_min, as_json, plot_path):
    """Evaluate a ballbar test (RUN.csv: angle_deg, direction ccw/cw, radius_deviation_um) to ISO 230-4, with diagnostics."""
    from axiscal.circular.report import ballbar_payload, evaluate_ballbar_file, render_report

    feed = None if feed_mm_min is None else feed_mm_min * MM_PER_MIN
    result = evaluate_ballbar_file(run_csv, radius=radius_mm * MM, plane=plane, feed=feed)
    for warning in result.diagnostics.warnings:
        click.echo(f"axiscal: warning: {run_csv}: {warning}", err=True)
    if plot_path:
        from axiscal.circular.plot import plot_ballbar

        plot_ballbar(result, plot_path)
    if as_json:
        echo_json(ballbar_payload(result))
    else:
        click.echo(render_report(result))


def _per_axis(ctx, param, values) -> dict[str, float]:
    """``X=4`` given once per axis, as a mapping of axis letter to value."""
    out: dict[str, float] = {}
    for text in values:
        letter, sep, number = text.partition("=")
        try:
            value = float(number)
        except ValueError:
            value = math.nan
        if not sep or letter.strip().upper() not in ("X", "Y", "Z") or not math.isfinite(value):
            raise click.BadParameter(f"'{text}': give an axis and a number, e.g. X=4", ctx=ctx, param=param)
        out[letter.strip().upper()] = value
    return out


def _scaled(values: dict[str, float], factor: float) -> dict[str, float]:
    return {axis: value * factor for axis, value in values.items()}


@click.command("ballbar")
@click.option("--radius-mm", type=finite(min=0, min_open=True), default=100.0, show_default=True, help="Nominal radius, mm.")
@click.option("--plane", type=click.Choice(PLANES, case_sensitive=False), default="XY", show_default=True, help="First and second axis.")
@click.option("--feed-mm-min", type=finite(min=0, min_open=True), default=1000.0, show_default=True, help="Feed, mm/min.")
@click.option("--squareness-urad", type=FINITE, default=0.0, show_default=True, help="Included angle of the axes minus 90 deg, urad.")
@click.option("--scale-ppm", multiple=True, callback=_per_axis, metavar="AXIS=PPM", help="Scale error of an axis, e.g. X=12 (repeat per axis).")
@click.option("--backlash-um", multiple=True, callback=_per_axis, metavar="AXIS=UM", help="Backlash (lost motion) of an axis, um.")
@click.option("--servo-mismatch-ms", type=FINITE, default=0.0, show_default=True, help="Lag of the first axis minus lag of the second, ms.")
@click.option("--reversal-spike-um", multiple=True, callback=_per_axis, metavar="AXIS=UM", help="Spike height after an axis reverses, um.")
@click.option("--cyclic-error-um", multiple=True, callback=_per_axis, metavar="AXIS=UM", help="Amplitude of an axis' cyclic error, um.")
@click.option("--cyclic-pitch-mm", multiple=True, callback=_per_axis, metavar="AXIS=MM", help="Pitch of that cyclic error, mm.")
@click.option("--centre-um", multiple=True, callback=_per_axis, metavar="AXIS=UM", help="Centre of the path relative to the table ball, um.")
@click.option("--direction", "directions", type=click.Choice(DIRECTIONS + ("both",)), default="both", show_default=True,
              help="Directions run (both: ccw, then cw).")
@click.option("--step-deg", type=finite(min=0, min_open=True, max=1.0), default=0.1, show_default=True, help="Angle between readings, deg.")
@click.option("--noise-um", type=finite(min=0), default=0.0, show_default=True, help="Standard deviation of the reading noise, um.")
@click.option("--seed", type=int, default=0, show_default=True, help="Seed of the noise.")
@click.option("-o", "--output", type=click.Path(dir_okay=False), help="Write the CSV (and its JSON sidecar) here (default: standard output).")
def simulate_ballbar_command(radius_mm, plane, feed_mm_min, squareness_urad, scale_ppm, backlash_um, servo_mismatch_ms,
                             reversal_spike_um, cyclic_error_um, cyclic_pitch_mm, centre_um, directions, step_deg, noise_um,
                             seed, output):
    """Write the ballbar trace (angle_deg, direction, radius_deviation_um) of a virtual machine with the errors given."""
    from axiscal.circular.simulation import simulate_ballbar, trace_csv, write_trace

    trace = simulate_ballbar(
        radius=radius_mm * MM,
        plane=plane,
        feed=feed_mm_min * MM_PER_MIN,
        squareness=squareness_urad * _URAD,
        scale=_scaled(scale_ppm, PPM),
        backlash=_scaled(backlash_um, UM),
        servo_mismatch=servo_mismatch_ms * MS,
        reversal_spike=_scaled(reversal_spike_um, UM),
        cyclic_error=_scaled(cyclic_error_um, UM),
        cyclic_pitch=_scaled(cyclic_pitch_mm, MM),
        centre_offset=_scaled(centre_um, UM),
        directions=DIRECTIONS if directions == "both" else (directions,),
        step=math.radians(step_deg),
        noise=noise_um * UM,
        seed=seed,
    )
    if output is None:
        click.echo(trace_csv(trace), nl=False)
        return
    write_trace(
        output,
        trace,
        simulated={
            "feed_mm_min": feed_mm_min,
            "squareness_urad": squareness_urad,
            "scale_ppm": scale_ppm,
            "backlash_um": backlash_um,
            "servo_mismatch_ms": servo_mismatch_ms,
            "reversal_spike_um": reversal_spike_um,
            "cyclic_error_um": cyclic_error_um,
            "cyclic_pitch_mm": cyclic_pitch_mm,
            "centre_um": centre_um,
            "noise_um": noise_um,
            "seed": seed,
        },
    )
