"""``axiscal plan``: uneven ISO 230-2 targets and the test cycle as CSV and G-code."""

from __future__ import annotations

import click

from axiscal.cli.common import finite, flags_named
from axiscal.cli.choices import CYCLES, DIALECT_NAMES
from axiscal.errors import AxiscalError
from axiscal.units import MM

__all__ = ["plan_command"]

#: a position a control's word holds: five whole digits of millimetres
_POSITION = finite(-99_999.999, 99_999.999)


@click.command("plan")
@click.option("--start-mm", type=_POSITION, required=True, help="First target position.")
@click.option("--end-mm", type=_POSITION, default=None, help="Last target position (needed but with --step-cycle).")
@click.option("--targets", "count", type=int, default=None, help="Number of targets (ISO 230-2: >= 5 per metre, >= 5; needed but with --step-cycle).")
@click.option("--runs", type=int, default=None, help="Runs in each direction [5; 1 with --step-cycle].")
@click.option("--overrun-mm", type=finite(0.0, 1000.0, min_open=True), default=None, help="Travel beyond a target before approaching it [5; 1 with --step-cycle].")
@click.option("--step-cycle", is_flag=True, help="ISO 230-2 Annex B/C: even steps over whole periods from --start-mm, for the periodic error (axiscal periodic).")
@click.option("--period-mm", type=finite(0.0, 1000.0, min_open=True), default=None, help="With --step-cycle: the period looked for (the screw's pitch).")
@click.option("--periods", type=int, default=None, help="With --step-cycle: periods covered [2].")
@click.option("--steps-per-period", type=int, default=None, help="With --step-cycle: targets per period [12].")
@click.option("--seed", type=int, default=None, help="Seed of the random target offsets (same seed, same targets) [a fresh one, shown in the note and recorded in the sidecar and the G-code].")
@click.option("--cycle", type=click.Choice(CYCLES), default="linear", show_default=True, help="Test cycle.")
@click.option("--gcode", "gcode_path", type=click.Path(dir_okay=False), help="Also write the cycle as a G-code program.")
@click.option("--dialect", type=click.Choice(DIALECT_NAMES), default="linuxcnc", show_default=True,
              help="The control's G-code dialect: its dwell word and unit, units, comments, start and end.")
@click.option("--axis", default="X", show_default=True, help="Axis letter in the G-code program.")
@click.option("--dwell-s", type=finite(0.0, 3600.0), default=2.0, show_default=True, help="Dwell at each target in the G-code, seconds (written in the dialect's own word and unit).")
@click.option("--feed-mm-min", type=finite(0.0, 100_000.0, min_open=True), default=2000.0, show_default=True, help="Feed of the G-code moves.")
@click.option("--on-the-fly", is_flag=True, help="The G-code for an on-the-fly capture: no dwells, a last move past the last target (axiscal on-the-fly).")
@click.option("-o", "--output", type=click.Path(dir_okay=False),
              help="Write the cycle CSV (and its JSON sidecar) here instead of stdout.")
def plan_command(start_mm, end_mm, count, runs, overrun_mm, step_cycle, period_mm, periods, steps_per_period, seed, cycle,
                 gcode_path, dialect, axis, dwell_s, feed_mm_min, on_the_fly, output):
    """Plan an ISO 230-2 positioning test: uneven targets and the test cycle (CSV to fill in; G-code with --gcode).

    With --step-cycle: evenly spaced targets, --steps-per-period to a --period-mm, over --periods
    periods from --start-mm, for the periodic error (ISO 230-2 Annexes B and C).
    """
    from axiscal.positioning.plan import cycle_csv, plan_test, write_plan
    from axiscal.positioning.step_cycle import plan_step_cycle

    with flags_named({"start_m": "--start-mm", "end_m": "--end-mm", "overrun_m": "--overrun-mm", "dwell_s": "--dwell-s",
                      "feed_mm_per_min": "--feed-mm-min", "period_m": "--period-mm", "periods": "--periods",
                      "steps_per_period": "--steps-per-period", "runs": "--runs"}):
        if step_cycle:
            if period_mm is None or end_mm is not None or count is not None:
                raise AxiscalError("--step-cycle plans from --start-mm and --period-mm (not --end-mm or --targets)")
            plan = plan_step_cycle(start_mm * MM, period_mm * MM, periods=2 if periods is None else periods,
                                   steps_per_period=12 if steps_per_period is None else steps_per_period,
                                   runs=1 if runs is None else runs, overrun_m=(1.0 if overrun_mm is None else overrun_mm) * MM)
        else:
            if end_mm is None or count is None:
                raise AxiscalError("a plan needs --end-mm and --targets (or --step-cycle with --period-mm)")
            for flag, value in (("--period-mm", period_mm), ("--periods", periods), ("--steps-per-period", steps_per_period)):
                if value is not None:
                    raise AxiscalError(f"{flag} goes with --step-cycle (a plan without it ignores it)")
            plan = plan_test(start_mm * MM, end_mm * MM, count, runs=5 if runs is None else runs,
                             overrun_m=(5.0 if overrun_mm is None else overrun_mm) * MM, seed=seed, cycle=cycle)
        write_plan(plan, output, gcode_path=gcode_path, dialect=dialect, axis=axis, dwell_s=dwell_s, feed_mm_per_min=feed_mm_min,
                   on_the_fly=on_the_fly)
    if not output:
        click.echo(cycle_csv(plan), nl=False)
    click.echo(f"axiscal: note: {plan.description}", err=True)
