"""``axiscal capture`` and ``axiscal simulate capture``: the readings of a positioning test taken at each stop, from a recording or a live stream."""

from __future__ import annotations

import math

import click

from axiscal.cli.choices import CONTROLLERS, DIALECT_NAMES, READING_UNITS
from axiscal.cli.common import FINITE, echo_json, flags_named
from axiscal.errors import AxiscalError
from axiscal.units import MM, UM

__all__ = ["capture_command", "simulate_capture_command"]

_FLAGS = {"stability_m": "--stability-um", "window_s": "--window-s", "tolerance_m": "--tolerance-mm", "offset_m": "--offset-mm",
          "unit": "--unit", "channel": "--channel", "resume=True": "--resume"}


def _progress_line(console):
    """A callback drawing one Rich line: step k of n, the target, the reading and whether it holds still."""
    from rich.live import Live
    from rich.text import Text

    live = Live(Text("waiting for the first reading"), console=console, refresh_per_second=8, transient=False)

    def show(p) -> None:
        if not live.is_started:
            live.start()
        target = "done" if p.step is None else f"step {p.step}: target {p.target_m / MM:.3f} mm"
        reading = "-" if math.isnan(p.reading_m) else f"{p.reading_m / MM:.4f} mm"
        state = "[green]still[/]" if p.still else "[yellow]moving[/]"
        live.update(Text.from_markup(f"capture {p.taken} of {p.total}  {target}  reading {reading}  {state}"
                                     f"  ({p.samples} samples)"))

    return live, show


def _dashboard(steps, source, port: int):
    """The live page of a capture, served on 127.0.0.1 (its address on stderr)."""
    from axiscal.capture.board import CaptureBoard
    from axiscal.live.server import LiveServer, create_board_app

    board = CaptureBoard(steps, getattr(getattr(source, "status", None), "description", ""))
    server = LiveServer(create_board_app(board.snapshot, page="capture.html"), port=port).start()
    click.echo(f"axiscal: capture page on {server.url}", err=True)
    return server, board


@click.command("capture")
@click.argument("plan_csv", type=click.Path(dir_okay=False))
@click.option("--from", "recording", type=click.Path(dir_okay=False), help="A recording: an .rtx capture or a CSV with time_s and the reading.")
@click.option("--source", "source_spec", help="A live source: sim | tcp:HOST:PORT | serial:DEVICE[:BAUD].")
@click.option("-o", "--output", required=True, type=click.Path(dir_okay=False), help="The positioning run CSV to write.")
@click.option("--unit", type=click.Choice(READING_UNITS), default=None, help="Unit of the readings (a column name ending in _mm ... says it; an .rtx file needs it).")
@click.option("--channel", default=None, help="The column or channel holding the laser reading [the only length column; reading_mm for a source].")
@click.option("--stability-um", type=FINITE, default=1.0, show_default=True, help="Peak to peak of the reading over the window for a stop.")
@click.option("--window-s", type=FINITE, default=0.5, show_default=True, help="How long the reading must hold still; the value is the mean over the stop's last window.")
@click.option("--tolerance-mm", type=FINITE, default=0.5, show_default=True, help="How far from the plan's target a stop may be.")
@click.option("--offset-mm", type=FINITE, default=0.0, show_default=True, help="The reading at the datum, when the laser was not zeroed there.")
@click.option("--resume", is_flag=True, help="Continue the partial capture OUTPUT.partial with this recording or stream.")
@click.option("--rate-hz", type=FINITE, default=1000.0, show_default=True, help="Sample rate of the sim source.")
@click.option("--seed", type=int, default=0, show_default=True, help="Noise seed of the sim source.")
@click.option("--timeout-s", type=FINITE, default=None, help="Stop reading a live source after this many seconds.")
@click.option("--dashboard", is_flag=True, help="With --source: show the plan, the target awaited and the stops taken on a live page.")
@click.option("--port", type=int, default=8765, show_default=True, help="Port of the --dashboard page on 127.0.0.1 (0: any free port).")
@click.option("--json", "as_json", is_flag=True, help="Print the stops taken as JSON.")
def capture_command(plan_csv, recording, source_spec, output, unit, channel, stability_um, window_s, tolerance_mm, offset_mm,
                    resume, rate_hz, seed, timeout_s, dashboard, port, as_json):
    """Capture a positioning run: walk PLAN_CSV's steps through a recording (--from) or a live stream (--source).

    Each step with a target needs one stop: the reading comes within --tolerance-mm of the target and
    holds within --stability-um for --window-s; its value is the mean of the stop's last window. The run
    (target_mm, run, direction, deviation_um and the air sensors) is what `axiscal positioning` reads.
    """
    from axiscal.capture.files import capture_to_file, partial_path
    from axiscal.capture.run import CaptureSettings
    from axiscal.capture.sources import open_capture_source
    from axiscal.capture.steps import plan_steps

    if (recording is None) == (source_spec is None):
        raise AxiscalError("give one of --from RECORDING or --source SPEC")
    if dashboard and source_spec is None:
        raise AxiscalError("--dashboard shows a live capture: it goes with --source")
    with flags_named(_FLAGS):
        settings = CaptureSettings(stability_m=stability_um * UM, window_s=window_s, tolerance_m=tolerance_mm * MM,
                                   offset_m=offset_mm * MM)
    live = server = None
    options = {}
    if source_spec is not None:
        from rich.console import Console

        steps = plan_steps(plan_csv)
        source = open_capture_source(source_spec, steps=steps, channel=channel, rate_hz=rate_hz, seed=seed)
        console = Console(stderr=True)
        live, show = _progress_line(console)
        options = {"progress": show, "timeout_s": timeout_s}
        if dashboard:
            server, board = _dashboard(steps, source, port)
            options = {"progress": lambda p: (show(p), board.progress(p)), "on_stop": board.stop, "timeout_s": timeout_s}
    else:
        source = recording
    try:
        with flags_named(_FLAGS):
            files = capture_to_file(plan_csv, source, output, resume=resume, settings=settings, unit=unit, channel=channel,
                                    **options)
    except (KeyboardInterrupt, click.exceptions.Abort):
        partial = partial_path(output)
        if partial.exists():
            raise click.ClickException(f"capture interrupted: the stops taken so far are in {partial}; run the same "
                                       "command with --resume to continue it") from None
        raise click.ClickException("capture interrupted before its first stop: nothing was written") from None
    finally:
        if live is not None and live.is_started:
            live.stop()
        if source_spec is not None:
            source.close()
        if server is not None:
            server.stop()
    result = files.capture
    if as_json:
        echo_json({
            "run_csv": str(files.run_csv), "sidecar": str(files.sidecar), "source": result.source,
            "stops": len(result.readings), "environment": list(result.environment), "settings": result.settings.as_dict(),
            "readings": [{"step": int(result.steps.step[r.index]), "target_mm": result.steps.target_m[r.index] / MM,
                          "run": int(result.steps.run[r.index]), "direction": str(result.steps.direction[r.index]),
                          "deviation_um": r.deviation_m / UM, "start_s": r.start_s, "window_std_um": r.window_std_m / UM}
                         for r in result.readings],
        })
    click.echo(f"axiscal: note: {len(result.readings)} stops captured from {result.source} into {files.run_csv}", err=True)


@click.command("capture")
@click.argument("program", type=click.Path(dir_okay=False))
@click.option("--machine", required=True, type=click.Path(dir_okay=False), help="The machine model (machine.toml) whose axis runs the program.")
@click.option("--axis", required=True, help="The axis the laser reads (X, Y or Z).")
@click.option("-o", "--output", required=True, type=click.Path(dir_okay=False), help="The recording CSV to write (what capture --from reads).")
@click.option("--dialect", type=click.Choice(DIALECT_NAMES), default=None, help="The program's dialect [heidenhain for .h, sinumerik for .mpf, else linuxcnc].")
@click.option("--compensation", type=click.Path(dir_okay=False), default=None, help="A compensation file loaded into the virtual controller.")
@click.option("--controller", type=click.Choice(CONTROLLERS), default=None, help="Whose compensation file it is.")
@click.option("--comp-type", type=click.Choice(["0", "1"]), default="1", show_default=True, help="LinuxCNC COMP_FILE_TYPE of the file.")
@click.option("--reference-position-mm", type=FINITE, default=0.0, show_default=True, help="FANUC: machine position of the reference position.")
@click.option("--rate-hz", type=FINITE, default=1000.0, show_default=True, help="Samples per second of the laser.")
@click.option("--seed", type=int, default=0, show_default=True, help="Seed of the laser's noise.")
def simulate_capture_command(program, machine, axis, output, dialect, compensation, controller, comp_type, reference_position_mm,
                             rate_hz, seed):
    """Run PROGRAM on the virtual machine and record what a laser on --axis reads over time.

    Moves are trapezoidal at the programmed feed, each stop rings and creeps, dwells are held; the axis
    carries the model's positioning error and a reversal; the reading is raw (vacuum wavelength) with
    the air sensors recorded beside it. With --compensation the virtual controller applies that file.
    """
    from axiscal.capture.virtual import simulate_capture

    with flags_named({"reference_position_m": "--reference-position-mm", "rate_hz": "--rate-hz"}):
        simulated = simulate_capture(program, machine, output, axis=axis.upper(), dialect=dialect, compensation=compensation,
                                     controller=controller, comp_type=int(comp_type),
                                     reference_position_m=reference_position_mm * MM, rate_hz=rate_hz, seed=seed)
    click.echo(f"axiscal: note: {simulated.recording.time_s.size} samples over {simulated.settings['duration_s']:.1f} s,"
               f" {len(simulated.dwells)} dwells, written to {output}", err=True)
