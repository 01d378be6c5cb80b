"""``axiscal identify``: a machine's error tables from artefacts (ball plate, step gauge, ballbar network, multilateration, R-test)."""

from __future__ import annotations

import click

from axiscal.cli.common import echo_json, flags_named
from axiscal.cli.choices import MODEL_KINDS

__all__ = ["identify_command"]


@click.command("identify")
@click.argument("machine_path", metavar="MACHINE.toml", type=click.Path(dir_okay=False))
@click.argument("artefacts", metavar="ARTEFACT.toml...", nargs=-1, required=True, type=click.Path(dir_okay=False))
@click.option("--model", default="poly:3", show_default=True,
              help=f"Error functions: poly:N (Legendre polynomials up to degree N) or spline:K (K intervals); kinds {', '.join(MODEL_KINDS)}.")
@click.option("--fix", "fix", multiple=True, metavar="TERM",
              help="Keep a term at the machine file's value: EBX:2, EBX, EC0Y, EX0C, an axis letter, squareness or location (repeatable).")
@click.option("-o", "--output", required=True, type=click.Path(file_okay=False), help="Output machine folder (created).")
@click.option("--json", "as_json", is_flag=True, help="Print the summary as one JSON object.")
def identify_command(machine_path, artefacts, model, fix, output, as_json):
    """Identify the error tables of MACHINE.toml from artefact measurements.

    Writes OUT_DIR/machine.toml with one error table per axis (read by volumetric, compensate and a
    campaign as they are), identify.json (every term with its standard uncertainty, the covariance,
    the residuals, the combinations the data cannot separate) and identify.html.
    """
    from axiscal.identification.solve import identify_files

    with flags_named({"fix": "--fix"}):
        result, text = identify_files(machine_path, artefacts, output, model=model, fix=fix)
    if as_json:
        echo_json(result.summary())
    else:
        click.echo(text, nl=False)
