"""``axiscal dynamics``, ``axiscal periodic`` and ``axiscal on-the-fly``: an axis in motion, its periodic error, readings taken in passing."""

from __future__ import annotations

import click

from axiscal.cli.choices import READING_UNITS
from axiscal.cli.common import FINITE, echo_json, flags_named
from axiscal.units import MM, UM

__all__ = ["dynamics_command", "periodic_command", "on_the_fly_command"]


@click.command("dynamics")
@click.argument("recording", type=click.Path(dir_okay=False))
@click.option("--plan", "plan_csv", type=click.Path(dir_okay=False), default=None, help="The plan the program ran: its steps name the stops.")
@click.option("--unit", type=click.Choice(tuple(READING_UNITS)), default=None, help="Unit of the readings (an .rtx file needs it).")
@click.option("--channel", default=None, help="The column holding the laser reading [the only length column].")
@click.option("--window-ms", type=FINITE, default=20.0, show_default=True, help="Savitzky-Golay window (at least degree + 2 samples).")
@click.option("--polyorder", type=int, default=3, show_default=True, help="Degree of the Savitzky-Golay polynomial (3 to 7).")
@click.option("--moving-mm-s", type=FINITE, default=1.0, show_default=True, help="Speed above which the axis is moving.")
@click.option("--band-um", type=FINITE, default=1.0, show_default=True, help="Half-width of the settling band.")
@click.option("--final-window-s", type=FINITE, default=0.5, show_default=True, help="A stop's final value: the mean over its last window.")
@click.option("--segment-s", type=FINITE, default=1.0, show_default=True, help="Length of Welch's segments.")
@click.option("--json", "as_json", is_flag=True, help="Print every move and stop as JSON.")
@click.option("--plot", "plot_path", type=click.Path(dir_okay=False), default=None, help="Draw position, velocity, acceleration and the spectrum.")
def dynamics_command(recording, plan_csv, unit, channel, window_ms, polyorder, moving_mm_s, band_um, final_window_s, segment_s,
                     as_json, plot_path):
    """Dynamics of an axis from a timebase RECORDING: velocity, acceleration, jerk, spectrum, settling at each stop."""
    from axiscal.dynamics.analysis import DynamicsSettings, dynamics_from_file

    with flags_named({"window_s": "--window-ms", "polyorder": "--polyorder", "moving_m_s": "--moving-mm-s",
                      "band_m": "--band-um", "final_window_s": "--final-window-s", "segment_s": "--segment-s"}):
        settings = DynamicsSettings(window_s=window_ms * 1e-3, polyorder=polyorder, moving_m_s=moving_mm_s * MM,
                                    band_m=band_um * UM, final_window_s=final_window_s, segment_s=segment_s)
    result = dynamics_from_file(recording, plan_csv, unit=unit, channel=channel, settings=settings)
    if plot_path:
        from axiscal.dynamics.plot import plot_dynamics

        plot_dynamics(plot_path, result)
    if as_json:
        echo_json(result.payload())
    else:
        click.echo(result.report())


@click.command("periodic")
@click.argument("run_csv", type=click.Path(dir_okay=False))
@click.option("--period-mm", type=FINITE, default=None, help="The period when known (the screw's pitch): the fit keeps it [found].")
@click.option("--json", "as_json", is_flag=True, help="Print the figures of every direction as JSON.")
@click.option("--plot", "plot_path", type=click.Path(dir_okay=False), default=None, help="Draw the deviations with the fit, and the spectrum.")
def periodic_command(run_csv, period_mm, as_json, plot_path):
    """Periodic positioning error of RUN_CSV (a step cycle's run): amplitude and period by fit and by spectrum."""
    from axiscal.dynamics.periodic import periodic_from_file

    with flags_named({"period_m": "--period-mm"}):
        result = periodic_from_file(run_csv, period_m=None if period_mm is None else period_mm * MM)
    if plot_path:
        from axiscal.dynamics.plot import plot_periodic

        plot_periodic(plot_path, result)
    if as_json:
        echo_json(result.payload())
    else:
        click.echo(result.report())


@click.command("on-the-fly")
@click.argument("plan_csv", type=click.Path(dir_okay=False))
@click.option("--from", "recording", required=True, type=click.Path(dir_okay=False), help="A recording with time_s, the reading and position_mm.")
@click.option("-o", "--output", required=True, type=click.Path(dir_okay=False), help="The positioning run CSV to write.")
@click.option("--unit", type=click.Choice(tuple(READING_UNITS)), default=None, help="Unit of a reading column whose name has none.")
@click.option("--channel", default=None, help="The column holding the laser reading.")
@click.option("--delay-ms", type=FINITE, default=None, help="The position stream's delay behind the laser, when known [estimated].")
@click.option("--max-delay-ms", type=FINITE, default=500.0, show_default=True, help="Largest delay looked for.")
@click.option("--window-ms", type=FINITE, default=10.0, show_default=True, help="The reading's line is fitted over this window about each crossing.")
@click.option("--offset-mm", type=FINITE, default=0.0, show_default=True, help="The reading at the datum, when the laser was not zeroed there.")
@click.option("--json", "as_json", is_flag=True, help="Print the delay and every crossing as JSON.")
@click.option("--plot", "plot_path", type=click.Path(dir_okay=False), default=None, help="Draw the deviations and the speed at each crossing.")
def on_the_fly_command(plan_csv, recording, output, unit, channel, delay_ms, max_delay_ms, window_ms, offset_mm, as_json, plot_path):
    """Capture a positioning run on the fly: each target's reading where the position stream crosses it.

    The delay of the position stream behind the laser is estimated from the two streams' velocities
    (or given with --delay-ms) and removed. The run is what `axiscal positioning` reads.
    """
    from axiscal.capture.on_the_fly import on_the_fly_to_file

    with flags_named({"delay_s": "--delay-ms", "max_delay_s": "--max-delay-ms", "window_s": "--window-ms",
                      "offset_m": "--offset-mm"}):
        result, run_csv, _ = on_the_fly_to_file(
            plan_csv, recording, output, unit=unit, channel=channel, delay_s=None if delay_ms is None else delay_ms * 1e-3,
            max_delay_s=max_delay_ms * 1e-3, window_s=window_ms * 1e-3, offset_m=offset_mm * MM)
    if plot_path:
        from axiscal.capture.on_the_fly_plot import plot_on_the_fly

        plot_on_the_fly(plot_path, result)
    payload = result.payload()
    if as_json:
        echo_json({"run_csv": str(run_csv), **payload})
    click.echo(f"axiscal: note: {payload['readings']} readings taken on the fly at {payload['speed_mm_min']:.5g} mm/min,"
               f" delay {payload['delay_ms']:.4f} ms {'estimated' if payload['delay_estimated'] else 'given'}, into {run_csv}",
               err=True)
