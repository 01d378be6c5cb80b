"""``axiscal positioning``: ISO 230-2 / VDI 3441 evaluation of a bidirectional positioning test."""

from __future__ import annotations

import click

from axiscal.cli.common import FINITE, echo_json, flags_named, given_options
from axiscal.errors import AxiscalError
from axiscal.materials import STEEL_EXPANSION_PER_K
from axiscal.cli.choices import STANDARDS

__all__ = ["positioning_command"]


@click.command("positioning")
@click.argument("run_csv", type=click.Path(dir_okay=False))
@click.option("--standard", type=click.Choice(STANDARDS), default="iso230-2:2014", show_default=True,
              help="Evaluation standard; jis-b6192 evaluates with the ISO 230-2:1988 (3 s) formulas.")
@click.option("--json", "as_json", is_flag=True, help="Print one JSON object (figures in um, arcsec for a rotary axis; per-target arrays).")
@click.option("--plot", "plot_path", type=click.Path(dir_okay=False), help="Write the positioning plot to this file.")
@click.option("--wavelength-nm", type=FINITE, default=None, help="Vacuum wavelength for raw laser readings [632.991].")
@click.option("--expansion-per-k", type=FINITE, default=STEEL_EXPANSION_PER_K, show_default=True,
              help="Material expansion coefficient for material_temperature_c normalisation to 20 degC.")
@click.option("--uncertainty", "budget_path", type=click.Path(dir_okay=False),
              help="Uncertainty budget (TOML): add U (k = 2) of E, R, B, A, M and the budget table.")
@click.option("--monte-carlo", type=click.IntRange(min=1), default=None,
              help="Also propagate the budget by Monte Carlo with this many draws (95 % coverage intervals).")
def positioning_command(run_csv, standard, as_json, plot_path, wavelength_nm, expansion_per_k, budget_path, monte_carlo):
    """Evaluate a positioning test (RUN_CSV: target_mm, run, direction, deviation_um or actual_mm; target_deg and
    deviation_arcsec for a rotary axis; one direction or both)."""
    from axiscal.positioning.report import evaluate_positioning_file
    from axiscal.uncertainty.positioning import evaluate_positioning_with_uncertainty

    raw_options = given_options(wavelength_nm=wavelength_nm, expansion_per_k=expansion_per_k)
    if monte_carlo and not budget_path:
        raise AxiscalError("--monte-carlo propagates a budget: give it with --uncertainty BUDGET.toml")
    with flags_named({"wavelength_nm": "--wavelength-nm", "expansion_per_k": "--expansion-per-k"}):
        if budget_path:
            evaluation = evaluate_positioning_with_uncertainty(
                run_csv, budget_path, standard=standard, monte_carlo=monte_carlo or 0, **raw_options
            )
        else:
            evaluation = evaluate_positioning_file(run_csv, standard=standard, **raw_options)
    for warning in evaluation.warnings:
        click.echo(f"axiscal: warning: {evaluation.run.source}: {warning}", err=True)
    if plot_path:
        evaluation.plot(plot_path)
    if as_json:
        echo_json(evaluation.to_dict())
    else:
        click.echo(evaluation.report())
