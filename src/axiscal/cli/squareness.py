"""``axiscal squareness``, ``axiscal optics pentaprism``, and the commands ``axiscal cmm`` takes as ``compensate`` and ``gauge-blocks``.

Squareness from two straightness runs (paper 002), the pentaprism's sensitivity to its set-up
(paper 002 Fig. 5) and the squareness compensation of a CMM (paper 004 eq 6). Values are typed in
the units their flags name; the computing is done in SI by :mod:`axiscal.squareness.evaluation`,
:mod:`axiscal.squareness.pentaprism` and :mod:`axiscal.squareness.cmm`.
"""

from __future__ import annotations

import math

import click

from axiscal.cli.common import FINITE, echo_json
from axiscal.errors import AxiscalError
from axiscal.cli.choices import BK7_INDEX, PAPER_004_SQUARENESS_ARCMIN, SQUARENESS_REFERENCES
from axiscal.units import ARCMIN, ARCSEC, MM

__all__ = [
    "squareness_command",
    "optics_group",
    "pentaprism_command",
    "compensate_command",
    "gauge_blocks_command",
]


@click.command("squareness")
@click.option("--first", "first_csv", required=True, type=click.Path(dir_okay=False),
              help="Run of the plane's first axis: position_mm, deviation_um (deviation along the second axis).")
@click.option("--second", "second_csv", required=True, type=click.Path(dir_okay=False),
              help="Run of the plane's second axis: position_mm, deviation_um (deviation along the first axis).")
@click.option("--plane", default="XY", show_default=True, help="XY (EC0Y), XZ (EB0Z) or YZ (EA0Z).")
@click.option("--prism-deviation-arcsec", type=FINITE, default=0.0, show_default=True,
              help="D: the prism turns the beam by 90 deg + D (paper 002 eq 13); subtracted per eq 21. "
              "Sign for a beam arriving against the first axis and leaving along the second; "
              "give -D if one of the two runs the other way (docs/squareness.md).")
@click.option("--reference", default="least-squares", show_default=True, help="least-squares or end-points line per run.")
@click.option("--convention", default="included-angle", show_default=True,
              help="Sign of squareness_arcsec: included-angle (included angle - 90 deg - D, paper 002 eq 21) "
              "or iso (the ISO 230-1 term's right-hand-rule sign).")
@click.option("--json", "as_json", is_flag=True, help="Print one JSON object.")
@click.option("--plot", "plot_path", type=click.Path(dir_okay=False), help="Write both runs and their lines to this image.")
def squareness_command(first_csv, second_csv, plane, prism_deviation_arcsec, reference, convention, as_json, plot_path):
    """Squareness of two axes from two straightness runs (paper 002 eqs 1 and 21)."""
    from axiscal.squareness.evaluation import squareness_from_files

    if reference not in SQUARENESS_REFERENCES:
        raise AxiscalError(f"--reference must be least-squares or end-points, not '{reference}'")
    if not math.isfinite(prism_deviation_arcsec):
        raise AxiscalError("--prism-deviation-arcsec must be a finite number")
    run = squareness_from_files(
        first_csv,
        second_csv,
        plane=plane,
        prism_deviation_rad=prism_deviation_arcsec * ARCSEC,
        reference=reference,
        convention=convention,
    )
    if plot_path:
        from axiscal.squareness.plot import plot_squareness

        plot_squareness(plot_path, run.result, ((run.first.position_m, run.first.deviation_m),
                                                (run.second.position_m, run.second.deviation_m)))
    if as_json:
        echo_json(run.payload())
    else:
        click.echo(run.report())


@click.group("optics")
def optics_group() -> None:
    """Ray-vector tracing through prisms (paper 002 section 3)."""


@optics_group.command("pentaprism")
@click.option("--index", type=FINITE, default=BK7_INDEX, show_default=True, help="Refractive index of the glass.")
@click.option("--range-arcmin", type=FINITE, default=10.0, show_default=True, help="Sweep rotations from -R to +R.")
@click.option("--steps", type=int, default=21, show_default=True, help="Number of rotation angles in the sweep.")
@click.option("--json", "as_json", is_flag=True, help="Print one JSON object.")
@click.option("--plot", "plot_path", type=click.Path(dir_okay=False),
              help="Write Fig. 5 (rotation about X, Y, Z; translation) to this image.")
def pentaprism_command(index, range_arcmin, steps, as_json, plot_path):
    """Deviation of the pentaprism against its rotation about X, Y, Z and its translation (Fig. 5)."""
    from axiscal.squareness.pentaprism import pentaprism_study

    if not (math.isfinite(range_arcmin) and 0 < range_arcmin <= 600):
        raise AxiscalError(f"--range-arcmin must be in (0, 600], got {range_arcmin}")
    if not 2 <= steps <= 2001:
        raise AxiscalError(f"--steps must be 2 to 2001, got {steps}")
    study = pentaprism_study(index=index, range_rad=range_arcmin * ARCMIN, steps=steps, plot_path=plot_path)
    if as_json:
        echo_json(study.payload())
    else:
        click.echo(study.report())


def _squareness_arcmin(ctx: click.Context, param: click.Parameter, text: str):
    """``"8.05,27.1,-16.6"`` (a_xy, a_xz, a_yz in arc minutes) -> CmmSquareness, naming the flag when refused."""
    from axiscal.squareness.cmm import CmmSquareness

    try:
        values = [float(p) for p in text.split(",")]
    except ValueError:
        values = []
    if len(values) != 3 or not all(math.isfinite(v) for v in values):
        raise AxiscalError(f"--squareness-arcmin needs three numbers a_xy,a_xz,a_yz (e.g. 8.05,27.1,-16.6), got '{text}'")
    try:
        return CmmSquareness.checked(*(v * ARCMIN for v in values))
    except AxiscalError as exc:
        raise AxiscalError(f"--squareness-arcmin {exc.message}") from None


_SQUARENESS_HELP = (
    "a_xy,a_xz,a_yz in arc minutes: each the included angle of the two axes minus 90 deg "
    "(paper 004's signs; as ISO terms EC0Y = a_xy, EB0Z = -a_xz, EA0Z = a_yz)."
)


@click.command("compensate")
@click.argument("points_csv", type=click.Path(dir_okay=False))
@click.option("--squareness-arcmin", "values", required=True, callback=_squareness_arcmin, help=_SQUARENESS_HELP)
@click.option("-o", "--output", "output", type=click.Path(dir_okay=False),
              help="Write the CSV (and its JSON sidecar) here (default: stdout).")
@click.option("--inverse", is_flag=True, help="Go the other way: from true coordinates to the readings the CMM shows.")
def compensate_command(points_csv, values, output, inverse):
    """Correct CMM readings by eq (6): x' = x - y a_xy - z a_xz, y' = y - z a_yz (POINTS_CSV: x_mm, y_mm, z_mm)."""
    from axiscal.squareness.cmm import compensate_file

    result = compensate_file(points_csv, values, inverse=inverse, output=output)
    if output is None:
        click.echo(result.csv_text, nl=False)


@click.command("gauge-blocks")
@click.option("--squareness-arcmin", "values", default=",".join(f"{v:g}" for v in PAPER_004_SQUARENESS_ARCMIN),
              show_default=True, callback=_squareness_arcmin, help=_SQUARENESS_HELP)
@click.option("--end-offset-mm", type=FINITE, default=1.0, show_default=True,
              help="Sideways distance, in each of the two across directions, between the two probed end points.")
@click.option("--json", "as_json", is_flag=True, help="Print one JSON object.")
def gauge_blocks_command(values, end_offset_mm, as_json):
    """Simulate paper 004's gauge block check (0.992 mm along X, 1.000 mm along Y) before and after eq (6)."""
    from axiscal.squareness.cmm import gauge_block_study

    if not (math.isfinite(end_offset_mm) and abs(end_offset_mm) <= 100):
        raise AxiscalError(f"--end-offset-mm must be within +-100, got {end_offset_mm}")
    study = gauge_block_study(values, end_offset_m=end_offset_mm * MM)
    if as_json:
        echo_json(study.payload())
    else:
        click.echo(study.report())
