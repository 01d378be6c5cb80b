"""``axiscal straightness``: straightness of a profile about a least-squares, end-point or minimum-zone line."""

from __future__ import annotations

from pathlib import Path

import click
import numpy as np

from axiscal.cli.common import echo_json, ensure_parent, pyplot
from axiscal.errors import AxiscalError
from axiscal.io.tabular import read_csv
from axiscal.straightness.reference import REFERENCES, ReferenceLine, reference_line
from axiscal.units import UM

__all__ = ["read_profile", "plot_straightness", "straightness_command", "register"]


def read_profile(path: str | Path) -> tuple[np.ndarray, np.ndarray]:
    """A profile file (columns ``position_mm, deviation_um``) as positions and deviations in metres."""
    table = read_csv(path, min_rows=2)
    table.require("position_mm", "deviation_um")
    return table.numeric("position_mm") * 1e-3, table.numeric("deviation_um") * UM


def plot_straightness(path: str | Path, position_m: np.ndarray, deviation_m: np.ndarray, line: ReferenceLine) -> None:
    """Profile with its reference line and zone (top) and the residuals about the line (bottom), in mm and um."""
    plt = pyplot()
    residual = line.residuals(position_m, deviation_m)
    order = np.argsort(position_m, kind="stable")
    x = position_m[order]
    fit = line.slope * x + line.intercept_m
    fig, (top, bottom) = plt.subplots(2, 1, figsize=(7, 6), sharex=True, height_ratios=(3, 2))
    top.plot(x * 1e3, deviation_m[order] / UM, "o-", ms=3, label="profile")
    top.plot(x * 1e3, fit / UM, "-", label=f"{line.reference} line")
    for bound in (residual.min(), residual.max()):
        top.plot(x * 1e3, (fit + bound) / UM, "--", color="gray", lw=0.8)
    top.set_ylabel("deviation / um")
    top.set_title(f"straightness {line.straightness_m / UM:.4f} um ({line.reference})")
    top.legend(fontsize=8)
    bottom.plot(x * 1e3, residual[order] / UM, "o-", ms=3)
    for bound in (residual.min(), residual.max()):
        bottom.axhline(bound / UM, ls="--", color="gray", lw=0.8)
    bottom.set_ylabel("about the line / um")
    bottom.set_xlabel("position / mm")
    fig.tight_layout()
    fig.savefig(ensure_parent(path), dpi=120)
    plt.close(fig)


@click.command("straightness")
@click.argument("profile", type=click.Path(dir_okay=False))
@click.option(
    "--reference",
    type=click.Choice(REFERENCES),
    default="least-squares",
    show_default=True,
    help="Reference straight line (ISO 230-1).",
)
@click.option("--json", "as_json", is_flag=True, help="Print JSON: straightness_um, slope_urad, intercept_um, reference.")
@click.option("--plot", "plot_path", type=click.Path(dir_okay=False), help="Write a plot of the profile and its zone.")
def straightness_command(profile: str, reference: str, as_json: bool, plot_path: str | None) -> None:
    """Straightness of PROFILE (CSV with position_mm, deviation_um): the zone's width about a reference line."""
    position, deviation = read_profile(profile)
    try:
        line = reference_line(position, deviation, reference=reference)
    except AxiscalError as exc:
        raise exc.located(path=profile) from None
    if plot_path:
        plot_straightness(plot_path, position, deviation, line)
    result = {
        "straightness_um": line.straightness_m / UM,
        "slope_urad": line.slope * 1e6,
        "intercept_um": line.intercept_m / UM,
        "reference": line.reference,
    }
    if as_json:
        echo_json(result)
        return
    click.echo(f"straightness  {result['straightness_um']:.4f} um  ({reference} reference line)")
    click.echo(f"slope         {result['slope_urad']:.4f} urad")
    click.echo(f"intercept     {result['intercept_um']:.4f} um at position 0")


def register(group: click.Group) -> None:
    group.add_command(straightness_command)
