"""``axiscal capture`` and ``axiscal simulate capture``: the readings of a positioning test taken at each stop, from a recording or a live stream."""

from __future__ import annotations

import math

import click

from axiscal.cli.choices import CONTROLLERS, DIALECT_NAMES, READING_UNITS
from axiscal.cli.common import FINITE, echo_json, finite, flags_named
from axiscal.errors import AxiscalError
from axiscal.units import MM, UM

__all__ = ["capture_command", "simulate_capture_command"]

_FLAGS = {"stability_m": "--stability-um", "window_s": "--window-s", "tolerance_m": "--tolerance-mm", "offset_m": "--offset-mm",
          "unit": "--unit", "channel": "--channel", "resume=True": "--resume"}


def _mm(value_m: float, decimals: int) -> str:
    """A position in mm: fixed decimals, exponent form where that would be a long number (a huge --offset-mm)."""
    value = value_m / MM
    return f"{value:.{decimals}f}" if abs(value) < 1e6 else f"{value:.{decimals}e}"


def _progress_line(console):
    """A callback drawing one Rich line: step k of n, the target, the reading and whether it holds still."""
    from rich.live import Live
    from rich.text import Text

    if not console.is_terminal:  # a log: a plain line per stop taken
        from axiscal.cli.run import _Plain

        shown = [0]

        def log(p) -> None:
            if p.taken != shown[0]:
                shown[0] = p.taken
                click.echo(f"axiscal: capture {p.taken} of {p.total} taken", err=True)

        return _Plain(), log

    live = Live(Text("waiting for the first reading"), console=console, refresh_per_second=8, transient=False)

    def show(p) -> None:
        if not live.is_started:
            live.start()
        target = "done" if p.step is None else f"step {p.step}: target {_mm(p.target_m, 3)} mm"
        reading = "-" if math.isnan(p.reading_m) else f"{_mm(p.reading_m, 4)} mm"
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
@click.option("--source", "source_spec", help="A live source: sim | tcp:HOST:PORT | serial:DEVICE[:BAUD] | an instrument: umd:PORT | sylvac:PORT | mahr:PORT | touchdro:PORT | attocube:HOST | sim:KIND (docs/devices.md).")
@click.option("-o", "--output", required=True, type=click.Path(dir_okay=False), help="The positioning run CSV to write.")
@click.option("--unit", type=click.Choice(READING_UNITS), default=None, help="Unit of the readings (a column name ending in _mm ... says it; an .rtx file needs it).")
@click.option("--channel", default=None, help="The column or channel holding the laser reading [the only length column; reading_mm for a source].")
@click.option("--stability-um", type=finite(0.0, 1000.0, min_open=True), default=None, help="Peak to peak of the reading over the window for a stop [1.0; a gauge: two counts of its resolution].")
@click.option("--window-s", type=finite(0.0, 3600.0, min_open=True), default=0.5, show_default=True, help="How long the reading must hold still; the value is the mean over the stop's last window.")
@click.option("--tolerance-mm", type=finite(0.0, 100.0, min_open=True), default=0.5, show_default=True, help="How far from the plan's target a stop may be.")
@click.option("--offset-mm", type=finite(-100_000.0, 100_000.0), default=0.0, show_default=True, help="The reading at the datum, when the laser was not zeroed there.")
@click.option("--resume", is_flag=True, help="Continue the partial capture OUTPUT.partial with this recording or stream.")
@click.option("--rate-hz", type=FINITE, default=1000.0, show_default=True, help="Sample rate of the sim source.")
@click.option("--seed", type=click.IntRange(0, 2**63 - 1), default=0, show_default=True, help="Noise seed of the sim source.")
@click.option("--timeout-s", type=FINITE, default=None, help="Stop reading a live source after this many seconds.")
@click.option("--dashboard", is_flag=True, help="With --source: show the plan, the target awaited and the stops taken on a live page.")
@click.option("--port", type=int, default=8765, show_default=True, help="Port of the --dashboard page on 127.0.0.1 (0: any free port).")
@click.option("--json", "as_json", is_flag=True, help="Print the stops taken as JSON.")
@click.option("--wavelength-nm", type=finite(100.0, 20_000.0), default=632.991372, show_default=True, help="µMD: the laser's vacuum wavelength.")
@click.option("--optics-multiplier", type=click.Choice(["1", "2", "4"]), default="1", show_default=True,
              help="µMD: 1 linear retroreflector, 2 plane mirror, 4 high-resolution plane mirror.")
@click.option("--umd-version", type=click.Choice(["1", "2"]), default=None, help="µMD: 1 or 2 [told by the stream's firmware code].")
@click.option("--material-temperature-code", type=click.Choice(["4"]), default=None,
              help="µMD: the LowSpeed code that carries a material temperature (4).")
@click.option("--counts-per-mm", type=finite(0.0, 1e6, min_open=True), default=None, help="TouchDRO: the scale's counts per millimetre.")
def capture_command(plan_csv, recording, source_spec, output, unit, channel, stability_um, window_s, tolerance_mm, offset_mm,
                    resume, rate_hz, seed, timeout_s, dashboard, port, as_json, wavelength_nm, optics_multiplier, umd_version,
                    material_temperature_code, counts_per_mm):
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
    from axiscal.devices.instruments import InstrumentOptions, default_stability_m, is_instrument_spec

    device = source_spec is not None and is_instrument_spec(source_spec)
    with flags_named(_FLAGS):
        settings = CaptureSettings(stability_m=1e-6 if stability_um is None else stability_um * UM, window_s=window_s,
                                   tolerance_m=tolerance_mm * MM, offset_m=offset_mm * MM)
    live = server = None
    options = {}
    if source_spec is not None:
        from rich.console import Console

        steps = plan_steps(plan_csv)
        instrument = None
        if device:  # --channel, --unit and --rate-hz speak to the instrument; its reading is reading_mm
            with flags_named(_FLAGS | {"counts_per_mm": "--counts-per-mm", "umd_version": "--umd-version", "rate_hz": "--rate-hz"}):
                instrument = InstrumentOptions(
                    wavelength_m=float(wavelength_nm) * 1e-9, optics_multiplier=int(optics_multiplier), channel=channel,
                    rate_hz=rate_hz if rate_hz != 1000.0 else None, umd_version=None if umd_version is None else int(umd_version),
                    material_temperature_code=None if material_temperature_code is None else int(material_temperature_code),
                    unit=unit if unit in ("mm", "in") else "mm", counts_per_mm=counts_per_mm)
            channel, unit = None, None
        with flags_named(_FLAGS | {"counts_per_mm": "--counts-per-mm", "umd_version": "--umd-version", "rate_hz": "--rate-hz"}):
            source = open_capture_source(source_spec, steps=steps, channel=channel, rate_hz=rate_hz, seed=seed, instrument=instrument)
        if device and stability_um is None:
            settings = CaptureSettings(stability_m=default_stability_m(source, None), window_s=settings.window_s,
                                       tolerance_m=settings.tolerance_m, offset_m=settings.offset_m)
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
    faults = getattr(source, "faults", ()) if source_spec is not None else ()
    if faults:
        click.echo(f"axiscal: note: {len(faults)} fault(s) of the instrument outside every stop's window (the capture went on);"
                   f" the first: {faults[0].message} at {faults[0].time_s:.3f} s", err=True)
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
@click.option("--continuous", is_flag=True, help="Blend moves in one direction (path mode): the axis passes the targets without stopping.")
@click.option("--position-delay-ms", type=FINITE, default=None, help="Also record the controller's position stream (position_mm), stamped this late.")
@click.option("--periodic-um", type=FINITE, default=0.0, show_default=True, help="Amplitude of a periodic screw error of the axis.")
@click.option("--pitch-mm", type=FINITE, default=5.0, show_default=True, help="Its period (the screw's pitch).")
def simulate_capture_command(program, machine, axis, output, dialect, compensation, controller, comp_type, reference_position_mm,
                             rate_hz, seed, continuous, position_delay_ms, periodic_um, pitch_mm):
    """Run PROGRAM on the virtual machine and record what a laser on --axis reads over time.

    Moves are trapezoidal at the programmed feed, each stop rings and creeps, dwells are held; the axis
    carries the model's positioning error and a reversal; the reading is raw (vacuum wavelength) with
    the air sensors recorded beside it. With --compensation the virtual controller applies that file;
    with --continuous it blends moves (the axis passes targets without stopping); with
    --position-delay-ms it records its own position stream beside the reading, for axiscal on-the-fly.
    """
    from axiscal.capture.virtual import VirtualAxis, simulate_capture

    with flags_named({"reference_position_m": "--reference-position-mm", "rate_hz": "--rate-hz",
                      "position_delay_s": "--position-delay-ms", "periodic_m": "--periodic-um", "pitch_m": "--pitch-mm"}):
        spec = VirtualAxis(periodic_m=periodic_um * UM, pitch_m=pitch_mm * MM)
        simulated = simulate_capture(program, machine, output, axis=axis.upper(), dialect=dialect, compensation=compensation,
                                     controller=controller, comp_type=int(comp_type),
                                     reference_position_m=reference_position_mm * MM, rate_hz=rate_hz, seed=seed,
                                     continuous=continuous, spec=spec,
                                     position_delay_s=None if position_delay_ms is None else position_delay_ms * 1e-3)
    click.echo(f"axiscal: note: {simulated.recording.time_s.size} samples over {simulated.settings['duration_s']:.1f} s,"
               f" {len(simulated.dwells)} dwells, written to {output}", err=True)
