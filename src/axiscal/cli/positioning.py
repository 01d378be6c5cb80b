"""``axiscal positioning``: ISO 230-2 / VDI 3441 evaluation of a bidirectional positioning test."""

from __future__ import annotations

import click
import numpy as np

from axiscal.cli.common import echo_json
from axiscal.errors import AxiscalError
from axiscal.materials import STEEL_EXPANSION_PER_K
from axiscal.positioning.evaluation import (
    STANDARDS,
    Iso230Result,
    Vdi3441Result,
    iso230_2,
    iso_edition,
    vdi3441,
)
from axiscal.positioning.reader import read_positioning_run
from axiscal.uncertainty import budget_report, positioning_uncertainty, uncertainty_payload
from axiscal.units import MM, UM

__all__ = ["evaluate_file", "payload", "report", "positioning_command", "register"]


def evaluate_file(path: str, standard: str, *, wavelength_nm: float | None = None, expansion_per_k: float = STEEL_EXPANSION_PER_K):
    """Read a run file and evaluate it to ``standard``; return (RunFile, result)."""
    data = read_positioning_run(path, wavelength_nm=wavelength_nm, expansion_per_k=expansion_per_k)
    if standard == "vdi3441":
        return data, vdi3441(data.run)
    return data, iso230_2(data.run, edition=iso_edition(standard))


def _per_target(result: Iso230Result | Vdi3441Result) -> dict[str, np.ndarray]:
    st = result.stats
    out = {
        "target_mm": st.targets / MM,
        "mean_up_um": st.mean_up / UM,
        "mean_down_um": st.mean_down / UM,
        "s_up_um": st.s_up / UM,
        "s_down_um": st.s_down / UM,
        "mean_um": st.mean / UM,
        "B_um": st.reversal / UM,
    }
    if isinstance(result, Iso230Result):
        out.update(
            R_up_um=result.repeatability_up / UM,
            R_down_um=result.repeatability_down / UM,
            R_um=result.repeatability / UM,
        )
    else:
        out.update(U_um=result.reversal_span / UM, s_mean_um=result.s_mean / UM, Ps_um=result.scatter / UM)
    return out


def payload(data, result: Iso230Result | Vdi3441Result) -> dict:
    """The JSON object of ``axiscal positioning --json``: figures in um under the standard's symbols."""
    body: dict = {"standard": result.standard, "unit": "um"}
    if isinstance(result, Iso230Result):
        body["coverage_factor"] = result.coverage
    body.update({name: value / UM for name, value in result.figures().items()})
    body.update(
        runs=data.run.runs,
        target_count=int(data.run.targets.size),
        compensated=data.compensated,
        warnings=list(result.warnings),
        targets=_per_target(result),
    )
    return body


def _cell(value: float, width: int = 9) -> str:
    return f"{'n/a':>{width}}" if not np.isfinite(value) else f"{value:>{width}.3f}"


def report(data, result: Iso230Result | Vdi3441Result) -> str:
    """The readable table of ``axiscal positioning``."""
    runs = f"{data.run.runs} run{'s' if data.run.runs != 1 else ''} each way"
    lines = [f"{data.run.source}: {result.standard}, {data.run.targets.size} targets, {runs}"]
    if data.compensated:
        lines.append("raw laser readings compensated for air index and material temperature")
    lines.append("")
    per = _per_target(result)
    names = list(per)
    lines.append("  ".join(f"{n:>9}" if len(n) <= 9 else n for n in names))
    for i in range(data.run.targets.size):
        lines.append("  ".join(_cell(per[n][i], max(9, len(n))) for n in names))
    lines.append("")
    lines.append("axis figures (um):")
    for name, value in result.figures().items():
        lines.append(f"  {name:<8} {_cell(value / UM)}")
    return "\n".join(lines)


@click.command("positioning")
@click.argument("run_csv", type=click.Path(dir_okay=False))
@click.option("--standard", type=click.Choice(STANDARDS), default="iso230-2:2014", show_default=True,
              help="Evaluation standard; jis-b6192 evaluates with the ISO 230-2:1988 (3 s) formulas.")
@click.option("--json", "as_json", is_flag=True, help="Print one JSON object (figures in um, per-target arrays).")
@click.option("--plot", "plot_path", type=click.Path(dir_okay=False), help="Write the positioning plot to this file.")
@click.option("--wavelength-nm", type=float, default=None, help="Vacuum wavelength for raw laser readings [632.991].")
@click.option("--expansion-per-k", type=float, default=STEEL_EXPANSION_PER_K, show_default=True,
              help="Material expansion coefficient for material_temperature_c normalisation to 20 degC.")
@click.option("--uncertainty", "budget_path", type=click.Path(dir_okay=False),
              help="Uncertainty budget (TOML): add U (k = 2) of E, R, B, A, M and the budget table.")
@click.option("--monte-carlo", type=click.IntRange(min=1), default=None,
              help="Also propagate the budget by Monte Carlo with this many draws (95 % coverage intervals).")
def positioning_command(run_csv, standard, as_json, plot_path, wavelength_nm, expansion_per_k, budget_path, monte_carlo):
    """Evaluate a bidirectional positioning test (RUN_CSV: target_mm, run, direction, deviation_um or actual_mm)."""
    data, result = evaluate_file(run_csv, standard, wavelength_nm=wavelength_nm, expansion_per_k=expansion_per_k)
    ctx = click.get_current_context()
    if monte_carlo and not budget_path:
        raise AxiscalError("--monte-carlo propagates a budget: give it with --uncertainty BUDGET.toml")
    if budget_path and not isinstance(result, Iso230Result):
        raise AxiscalError("--uncertainty gives U of the ISO 230-2 figures; use an iso230-2 --standard")
    for name in ("wavelength_nm", "expansion_per_k"):
        if not data.compensated and ctx.get_parameter_source(name) == click.core.ParameterSource.COMMANDLINE:
            raise AxiscalError(
                f"--{name.replace('_', '-')} applies to raw laser readings (actual_<unit> with the environment"
                " columns); this file holds none",
                path=data.run.source,
            )
    for warning in result.warnings:
        click.echo(f"axiscal: warning: {data.run.source}: {warning}", err=True)
    if plot_path:
        from axiscal.positioning.plot import plot_positioning

        plot_positioning(data.run, result, plot_path, compensated=data.compensated)
    unc = positioning_uncertainty(budget_path, data.run, monte_carlo=monte_carlo or 0) if budget_path else None
    if as_json:
        body = payload(data, result)
        if unc is not None:
            body["uncertainty"] = uncertainty_payload(unc)
        echo_json(body)
    else:
        click.echo(report(data, result) + ("\n\n" + budget_report(unc) if unc is not None else ""))


def register(group: click.Group) -> None:
    group.add_command(positioning_command)
