"""``axiscal plan``: uneven ISO 230-2 targets and the test cycle as CSV and G-code."""

from __future__ import annotations

import click

from axiscal.cli.common import FINITE, flags_named
from axiscal.cli.choices import CYCLES, DIALECT_NAMES
from axiscal.units import MM

__all__ = ["plan_command"]


@click.command("plan")
@click.option("--start-mm", type=FINITE, required=True, help="First target position.")
@click.option("--end-mm", type=FINITE, required=True, help="Last target position.")
@click.option("--targets", "count", type=int, required=True, help="Number of targets (ISO 230-2: >= 5 per metre, >= 5).")
@click.option("--runs", type=int, default=5, show_default=True, help="Runs in each direction.")
@click.option("--overrun-mm", type=FINITE, default=5.0, show_default=True, help="Travel beyond a target before approaching it.")
@click.option("--seed", type=int, default=None, help="Seed of the random target offsets (same seed, same targets) [a fresh one, shown in the note and recorded in the sidecar and the G-code].")
@click.option("--cycle", type=click.Choice(CYCLES), default="linear", show_default=True, help="Test cycle.")
@click.option("--gcode", "gcode_path", type=click.Path(dir_okay=False), help="Also write the cycle as a G-code program.")
@click.option("--dialect", type=click.Choice(DIALECT_NAMES), default="linuxcnc", show_default=True,
              help="The control's G-code dialect: its dwell word and unit, units, comments, start and end.")
@click.option("--axis", default="X", show_default=True, help="Axis letter in the G-code program.")
@click.option("--dwell-s", type=FINITE, default=2.0, show_default=True, help="Dwell at each target in the G-code, seconds (written in the dialect's own word and unit).")
@click.option("--feed-mm-min", type=FINITE, default=2000.0, show_default=True, help="Feed of the G-code moves.")
@click.option("-o", "--output", type=click.Path(dir_okay=False),
              help="Write the cycle CSV (and its JSON sidecar) here instead of stdout.")
def plan_command(start_mm, end_mm, count, runs, overrun_mm, seed, cycle, gcode_path, dialect, axis, dwell_s, feed_mm_min, output):
    """Plan an ISO 230-2 positioning test: uneven targets and the test cycle (CSV to fill in; G-code with --gcode)."""
    from axiscal.positioning.plan import cycle_csv, plan_test, write_plan

    with flags_named({"start_m": "--start-mm", "end_m": "--end-mm", "overrun_m": "--overrun-mm", "dwell_s": "--dwell-s",
                      "feed_mm_per_min": "--feed-mm-min"}):
        plan = plan_test(start_mm * MM, end_mm * MM, count, runs=runs, overrun_m=overrun_mm * MM, seed=seed, cycle=cycle)
        write_plan(plan, output, gcode_path=gcode_path, dialect=dialect, axis=axis, dwell_s=dwell_s, feed_mm_per_min=feed_mm_min)
    if not output:
        click.echo(cycle_csv(plan), nl=False)
    click.echo(f"axiscal: note: {plan.description}", err=True)
