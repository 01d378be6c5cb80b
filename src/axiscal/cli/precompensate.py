"""``axiscal precompensate``: a part program rewritten so that the tool lands on the nominal path."""

from __future__ import annotations

import math
from contextlib import contextmanager

import click

from axiscal.cli.common import FINITE, echo_json, flags_named
from axiscal.errors import AxiscalError
from axiscal.cli.choices import DIALECT_NAMES
from axiscal.units import MM, UM

__all__ = ["precompensate_command"]

_WORD_DIALECTS = tuple(name for name in DIALECT_NAMES if name != "heidenhain")


def _vector_mm(flag: str):
    def parse(ctx: click.Context, param: click.Parameter, text: str | None):
        if text is None:
            return None
        try:
            values = [float(p) for p in text.split(",")]
        except ValueError:
            values = []
        if len(values) != 3 or not all(math.isfinite(v) for v in values):
            raise AxiscalError(f"{flag} needs three numbers X,Y,Z in mm (e.g. 0,0,-150), got '{text}'")
        return tuple(v * MM for v in values)
    return parse


@contextmanager
def _progress(program: str):
    """A Rich progress bar on stderr (lines, MB/s, time left) when stderr is a terminal; None otherwise."""
    import sys

    if not sys.stderr.isatty():
        yield None
        return
    import os

    from rich.console import Console
    from rich.progress import BarColumn, Progress, TextColumn, TimeRemainingColumn, TransferSpeedColumn

    total = None
    if program != "-":
        try:
            total = os.path.getsize(program)
        except OSError:
            total = None
    columns = (TextColumn("{task.fields[lines]:,} lines"), BarColumn(), TransferSpeedColumn(), TimeRemainingColumn())
    with Progress(*columns, console=Console(stderr=True), transient=True) as bar:
        task = bar.add_task("precompensate", total=total, lines=0)

        def update(done: int, lines: int) -> None:
            bar.update(task, completed=done, lines=lines)

        yield update


@click.command("precompensate")
@click.argument("program", type=click.Path(dir_okay=False, allow_dash=True))
@click.option("--machine", required=True, type=click.Path(dir_okay=False), help="The machine model (TOML).")
@click.option("--dialect", required=True, type=click.Choice(_WORD_DIALECTS), help="The control's G-code dialect.")
@click.option("-o", "--output", required=True, type=click.Path(dir_okay=False, allow_dash=True),
              help="The pre-compensated program ('-': standard output; PROGRAM '-' reads standard input).")
@click.option("--max-segment-mm", type=FINITE, default=2.0, show_default=True,
              help="The error is checked along every move at least every half of this; arcs are linearised into chords no longer.")
@click.option("--tolerance-um", type=FINITE, default=0.5, show_default=True,
              help="Largest distance of the tool from the nominal path along the rewritten program.")
@click.option("--tool-mm", callback=_vector_mm("--tool-mm"), help="Functional point X,Y,Z in the last carriage's frame [the machine's tool_mm].")
@click.option("--work-offset-mm", callback=_vector_mm("--work-offset-mm"),
              help="Axis position minus program coordinate X,Y,Z of the work offset (G54) the program runs in [none].")
@click.option("--json", "as_json", is_flag=True, help="Print the summary as one JSON object on stdout.")
def precompensate_command(program, machine, dialect, output, max_segment_mm, tolerance_um, tool_mm, work_offset_mm, as_json):
    """Rewrite a part program through the machine model: every point commanded where the tool lands on it."""
    import sys

    from axiscal.precompensation.streaming import precompensate_file

    if as_json and output == "-":
        raise AxiscalError("--json prints the summary on standard output, where -o - writes the program: use one of them")
    offset = None if work_offset_mm is None else dict(zip("XYZ", work_offset_mm))
    source = sys.stdin.buffer if program == "-" else program
    target = sys.stdout.buffer if output == "-" else output
    with _progress(program) as progress, \
            flags_named({"tolerance_m": "--tolerance-um", "max_segment_m": "--max-segment-mm", "tool_m": "--tool-mm"}):
        result = precompensate_file(source, machine, target, dialect=dialect, max_segment_m=max_segment_mm * MM,
                                    tolerance_m=tolerance_um * UM, tool_m=tool_mm, work_offset_m=offset, progress=progress)
    if output == "-":
        sys.stdout.flush()
    summary = {
        "program": program, "output": output, "machine": result.machine, "dialect": result.dialect,
        "lines_in": result.lines_in, "lines_out": result.lines_out, "moves": result.moves, "rewritten": result.rewritten,
        "largest_correction_um": result.largest_correction_m / UM, "largest_residual_um": result.largest_residual_m / UM,
        "tolerance_um": result.tolerance_m / UM, "max_segment_mm": result.max_segment_m / MM,
    }
    if as_json:
        echo_json(summary)
    click.echo(
        f"axiscal: {program}: {result.lines_in} lines in, {result.lines_out} out ({result.rewritten} of {result.moves}"
        f" moves rewritten); largest correction {summary['largest_correction_um']:.3f} um, largest predicted"
        f" residual along the path {summary['largest_residual_um']:.3f} um; written to {output}",
        err=True,
    )
