"""``axiscal thermal etve`` and ``axiscal thermal drift``: the thermal tests of ISO 230-3."""

from __future__ import annotations

import math

import click

from axiscal.cli.common import FINITE, echo_json
from axiscal.errors import AxiscalError

__all__ = ["thermal_group", "thermal_etve_command", "thermal_drift_command"]


@click.group("thermal")
def thermal_group() -> None:
    """Thermal tests (ISO 230-3): environmental temperature variation error and thermal drift."""


@thermal_group.command("etve")
@click.argument("run", type=click.Path(dir_okay=False))
@click.option("--max-lag-h", type=FINITE, help="Largest lag of the correlations, hours (default a quarter of the test).")
@click.option("--json", "as_json", is_flag=True, help="Print JSON: etve_um per direction, temperature_range_c, correlations.")
@click.option("--plot", "plot_path", type=click.Path(dir_okay=False), help="Write the drift plot with the temperatures.")
def thermal_etve_command(run: str, max_lag_h: float | None, as_json: bool, plot_path: str | None) -> None:
    """ETVE of RUN (CSV: time_s or time_h, x_um/y_um/z_um[, a_urad, b_urad], temperature_<place>_c)."""
    from axiscal.thermal.files import evaluate_etve

    if max_lag_h is not None and not (math.isfinite(max_lag_h) and max_lag_h >= 0):
        raise AxiscalError(f"--max-lag-h must be a number of hours, zero or more, got {max_lag_h:g}")
    result = evaluate_etve(run, max_lag_s=None if max_lag_h is None else max_lag_h * 3600.0)
    if plot_path:
        from axiscal.thermal.plot import plot_etve

        plot_etve(plot_path, result)
    if as_json:
        echo_json(result.payload())
    else:
        click.echo(result.report())


@thermal_group.command("drift")
@click.argument("run", type=click.Path(dir_okay=False))
@click.option("--json", "as_json", is_flag=True,
              help="Print JSON: drift_max_um, drift_end_um, drift_heating_end_um, time_constant_h per direction ...")
@click.option("--plot", "plot_path", type=click.Path(dir_okay=False), help="Write the drift plot with the temperatures.")
def thermal_drift_command(run: str, as_json: bool, plot_path: str | None) -> None:
    """Thermal drift of RUN (CSV as for etve, with running = 1 while heating, 0 while cooling)."""
    from axiscal.thermal.files import evaluate_drift

    result = evaluate_drift(run)
    if plot_path:
        from axiscal.thermal.plot import plot_drift

        plot_drift(plot_path, result)
    if as_json:
        echo_json(result.payload())
    else:
        click.echo(result.report())
