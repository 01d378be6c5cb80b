"""``axiscal run`` and ``axiscal cycle``: the positioning test driven on a controller, read by an instrument."""

from __future__ import annotations

import math

import click

from axiscal.cli.common import echo_json, finite, flags_named
from axiscal.errors import AxiscalError
from axiscal.units import MM, UM

__all__ = ["run_command", "cycle_command", "instrument_options"]

_FLAGS = {"stability_m": "--stability-um", "window_s": "--window-s", "offset_m": "--offset-mm", "dwell_s": "--dwell-s",
          "feed_m_per_s": "--feed-mm-min", "axis": "--axis", "wavelength_m": "--wavelength-nm", "rate_hz": "--rate-hz",
          "channel": "--channel", "optics_multiplier": "--optics-multiplier", "counts_per_mm": "--counts-per-mm",
          "unit": "--unit", "umd_version": "--umd-version", "resume=True": "--resume", "tolerance_e_um": "--tolerance-e-um",
          "tolerance_m": "--tolerance-mm", "seed": "--seed"}

# the flags' bounds, in their own units (the library's are the same in SI)
_FEED = finite(0.0, 100_000.0, min_open=True)
_DWELL = finite(0.0, 3600.0, min_open=True)
_WINDOW = finite(0.0, 3600.0, min_open=True)
_STABILITY = finite(0.0, 1000.0, min_open=True)
_OFFSET = finite(-100_000.0, 100_000.0)
_TOLERANCE = finite(0.0, 100.0, min_open=True)
_SEED = click.IntRange(0, 2**63 - 1)


def instrument_options(function):
    """The instrument flags shared by ``run``, ``cycle`` (and the device sources of ``capture``)."""
    for option in reversed((
        click.option("--wavelength-nm", type=finite(100.0, 20_000.0), default=632.991372, show_default=True,
                     help="µMD: the laser's vacuum wavelength."),
        click.option("--optics-multiplier", type=click.Choice(["1", "2", "4"]), default="1", show_default=True,
                     help="µMD: 1 linear retroreflector, 2 plane mirror, 4 high-resolution plane mirror."),
        click.option("--channel", default=None, help="µMD and Attocube: 1|2|3 [1]; TouchDRO: X|Y|Z|W [X]."),
        click.option("--rate-hz", type=finite(0.0, 1e6, min_open=True), default=None, help="µMD: sample rate when the stream does not say it (code 8)."),
        click.option("--umd-version", type=click.Choice(["1", "2"]), default=None,
                     help="µMD: 1 (firmware up to v60) or 2 (2.x) [told by the stream's firmware code]."),
        click.option("--material-temperature-code", type=click.Choice(["4"]), default=None,
                     help="µMD: the LowSpeed code that carries a material temperature (4)."),
        click.option("--unit", type=click.Choice(["mm", "in"]), default="mm", show_default=True, help="Sylvac: the display unit."),
        click.option("--counts-per-mm", type=finite(0.0, 1e6, min_open=True), default=None, help="TouchDRO: the scale's counts per millimetre."),
    )):
        function = option(function)
    return function


def _options(wavelength_nm, optics_multiplier, channel, rate_hz, umd_version, material_temperature_code, unit, counts_per_mm):
    from axiscal.devices.instruments import InstrumentOptions

    with flags_named(_FLAGS):
        return InstrumentOptions(wavelength_m=float(wavelength_nm) * 1e-9, optics_multiplier=int(optics_multiplier),
                                 channel=channel, rate_hz=rate_hz, umd_version=None if umd_version is None else int(umd_version),
                                 material_temperature_code=None if material_temperature_code is None else int(material_temperature_code),
                                 unit=unit, counts_per_mm=counts_per_mm)


class _Plain:
    """What stands in for the Rich line when stderr is not a terminal: one plain line per step taken."""

    is_started = False

    def stop(self) -> None:
        pass


def _progress_line(console):
    """One Rich line on a terminal (step k of n, target, reading, still or moving, time left); a line per step in a log."""
    import time

    from rich.live import Live
    from rich.text import Text

    began = time.monotonic()
    if not console.is_terminal:
        shown = [-1]

        def log(p) -> None:
            if p.taken != shown[0] and p.taken:
                shown[0] = p.taken
                click.echo(f"axiscal: run {p.taken} of {p.total} taken ({time.monotonic() - began:.0f} s)", err=True)

        return _Plain(), log

    live = Live(Text("connecting"), console=console, refresh_per_second=8, transient=False)

    def show(p) -> None:
        if not live.is_started:
            live.start()
        target = "done" if p.step is None else f"step {p.step}: target {p.target_m / MM:.3f} mm"
        reading = "-" if math.isnan(p.reading_m) else f"{p.reading_m / MM:.4f} mm"
        state = "[green]still[/]" if p.still else "[yellow]moving / settling[/]"
        left = ""
        if p.taken:
            per = (time.monotonic() - began) / p.taken
            left = f"  about {per * (p.total - p.taken):.0f} s left"
        live.update(Text.from_markup(f"run {p.taken} of {p.total}  {target}  reading {reading}  {state}{left}"))

    return live, show


@click.command("run")
@click.argument("plan_csv", type=click.Path(dir_okay=False))
@click.option("--controller", "controller_spec", required=True,
              help="linuxcnc:HOST[:PORT] | grbl:PORT[@BAUD] | grbl:tcp:HOST:PORT | marlin:PORT[@BAUD] | klipper:SOCKET | moonraker:URL | sim")
@click.option("--source", "source_spec", required=True,
              help="umd:PORT[@BAUD] | sylvac:PORT | mahr:PORT[@BAUD] | touchdro:PORT[@BAUD] | attocube:HOST[:PORT] | sim[:KIND]")
@click.option("-o", "--output", type=click.Path(dir_okay=False), help="The positioning run CSV to write (not needed with --dry-run).")
@click.option("--axis", default="X", show_default=True, help="The axis driven (absolute moves of this axis only).")
@click.option("--feed-mm-min", type=_FEED, default=1000.0, show_default=True, help="Feed of every move.")
@click.option("--dwell-s", type=_DWELL, default=1.0, show_default=True, help="Dwell after the controller reports the move done.")
@click.option("--window-s", type=_WINDOW, default=0.5, show_default=True, help="The value is the mean over the last window of the dwell.")
@click.option("--stability-um", type=_STABILITY, default=None, help="Peak to peak allowed over the window [1.0; a gauge: two counts].")
@click.option("--offset-mm", type=_OFFSET, default=0.0, show_default=True, help="The reading at the datum, when it was not zeroed there.")
@click.option("--tolerance-mm", type=_TOLERANCE, default=0.5, show_default=True,
              help="How far from its target a reading may be: one farther off stops the run (the wrong unit, scale or offset).")
@click.option("--ini", type=click.Path(dir_okay=False), default=None, help="LinuxCNC: the machine's INI file (its soft limits).")
@click.option("--resume", is_flag=True, help="Continue OUTPUT.partial: drive to where the first missing step's approach begins, go on.")
@click.option("--dry-run", is_flag=True, help="Print the moves and check them against the soft limits; move nothing.")
@click.option("--on-the-fly", "on_the_fly", is_flag=True,
              help="Drive each pass through the targets without stopping; record the reading and the controller's position;"
                   " each target's reading where the axis passes it (OUTPUT.recording.csv holds both streams).")
@click.option("--seed", type=_SEED, default=0, show_default=True, help="Noise seed of a simulated instrument.")
@click.option("--json", "as_json", is_flag=True, help="Print the steps taken as JSON.")
@instrument_options
def run_command(plan_csv, controller_spec, source_spec, output, axis, feed_mm_min, dwell_s, window_s, stability_um, offset_mm,
                tolerance_mm, ini, resume, dry_run, on_the_fly, seed, as_json, **instrument):
    """Drive PLAN_CSV's steps on a controller and read the instrument at every target: the run `capture` writes.

    Each step is an absolute move of --axis; once the controller reports it done the reading is taken
    as the mean over the last --window-s of --dwell-s (sliding on until it holds within --stability-um);
    a reading farther than --tolerance-mm from its target stops the run, as `capture` refuses a stop elsewhere.
    The axis must be homed (run never homes). Ctrl-C stops the machine and keeps OUTPUT.partial.
    """
    from axiscal.capture.connected import dry_run as plan_dry_run
    from axiscal.capture.connected import open_run_devices, run_to_file
    from axiscal.capture.drive import DriveSettings
    from axiscal.capture.run import CaptureSettings
    from axiscal.devices.instruments import default_stability_m

    options = _options(**instrument)
    with flags_named(_FLAGS):
        drive = DriveSettings(axis=axis, feed_m_per_s=feed_mm_min * MM / 60.0, dwell_s=float(dwell_s))
    if output is None and not (dry_run and not resume):
        raise AxiscalError("give -o/--output: the run CSV to write (only a --dry-run without --resume does without)")
    if dry_run:
        from axiscal.capture.connected import sim_machine
        from axiscal.devices.controller import move_words
        from axiscal.devices.controllers import open_controller

        controller = open_controller(controller_spec, ini=ini, sim=lambda: sim_machine(axis=axis).controller())
        try:
            resume_from = 0
            if resume:
                from axiscal.capture.files import _read_partial, partial_path
                from axiscal.capture.steps import plan_steps

                taken, _ = _read_partial(partial_path(output), plan_steps(plan_csv))
                resume_from = taken[-1].index + 1 if taken else 0
            result = plan_dry_run(plan_csv, controller, axis=drive.axis, resume_from=resume_from)
        finally:
            controller.close()
        if as_json:
            echo_json({"moves": [{"step": s, "position_mm": p / MM, "reading": r} for s, p, r in result.moves],
                       "limits_mm": None if result.limits is None else [v / MM for v in result.limits]})
        else:
            for step, position, reading in result.moves:
                click.echo(f"step {step}: G1 {move_words(drive.axis, position, drive.feed_m_per_s)}" + ("  (reading)" if reading else ""))
        limits = "not told by the controller" if result.limits is None else \
            f"{result.limits[0] / MM:g} .. {result.limits[1] / MM:g} mm"
        click.echo(f"axiscal: note: {len(result.moves)} moves within the soft limits ({limits}); nothing moved", err=True)
        return
    from rich.console import Console

    if on_the_fly and resume:
        raise AxiscalError("--on-the-fly drives whole passes: it has nothing to --resume (run it again)")
    with flags_named(_FLAGS):
        controller, source = open_run_devices(controller_spec, source_spec, options=options, ini=ini, seed=seed)
    if on_the_fly:
        from axiscal.capture.fly_drive import fly_plan
        from axiscal.capture.recording import environment_columns

        try:
            with flags_named(_FLAGS):
                flown = fly_plan(plan_csv, controller, source, output, drive=drive, offset_m=offset_mm * MM,
                                 environment=environment_columns(tuple(source.channels)),
                                 progress=lambda done, total: click.echo(f"axiscal: pass {done} of {total} driven", err=True))
        finally:
            source.close()
            controller.close()
        if as_json:
            from axiscal.capture.fly_drive import FLY_AGREEMENT_M, FLY_SPEED_LIMIT_M_S

            echo_json({"run_csv": str(flown.run_csv), "sidecar": str(flown.sidecar), "recording_csv": str(flown.recording_csv),
                       **flown.result.payload(), "agreement_um": FLY_AGREEMENT_M / UM,
                       "agreement_up_to_mm_min": FLY_SPEED_LIMIT_M_S / MM * 60, "warning": flown.warning})
        click.echo(f"axiscal: note: {len(flown.result.capture.readings)} targets read on the fly (the streams' delay"
                   f" {flown.result.delay_s * 1e3:.3f} ms, estimated), written to {flown.run_csv}", err=True)
        click.echo(f"axiscal: note: {flown.agreement}", err=True)
        if flown.warning is not None:
            click.echo(f"axiscal: warning: {flown.warning}", err=True)
        return
    live = None
    try:
        with flags_named(_FLAGS):
            settings = CaptureSettings(stability_m=default_stability_m(source, None if stability_um is None else stability_um * UM),
                                       window_s=window_s, offset_m=offset_mm * MM, tolerance_m=tolerance_mm * MM)
        console = Console(stderr=True)
        live, show = _progress_line(console)
        notes: list[str] = []
        with flags_named(_FLAGS):
            files = run_to_file(plan_csv, controller, source, output, drive=drive, settings=settings, resume=resume,
                                progress=show, on_fault=notes.append)
    finally:
        if live is not None and live.is_started:
            live.stop()
        source.close()
        controller.close()
    for note in notes:
        click.echo(f"axiscal: note: {note}", err=True)
    result = files.capture
    if as_json:
        echo_json({"run_csv": str(files.run_csv), "sidecar": str(files.sidecar), "source": result.source,
                   "controller": controller.description, "steps": len(result.readings),
                   "readings": [{"step": int(result.steps.step[r.index]), "target_mm": result.steps.target_m[r.index] / MM,
                                 "run": int(result.steps.run[r.index]), "direction": str(result.steps.direction[r.index]),
                                 "deviation_um": r.deviation_m / UM, "window_std_um": r.window_std_m / UM}
                                for r in result.readings]})
    click.echo(f"axiscal: note: {len(result.readings)} steps driven on {controller.description}, read by {result.source},"
               f" written to {files.run_csv}", err=True)


@click.command("cycle")
@click.argument("plan_csv", type=click.Path(dir_okay=False))
@click.option("--controller", "controller_spec", required=True, help="As `axiscal run` takes it.")
@click.option("--source", "source_spec", required=True, help="As `axiscal run` takes it.")
@click.option("--format", "fmt", type=click.Choice(["linuxcnc"]), default="linuxcnc", show_default=True,
              help="The controller's compensation file.")
@click.option("-o", "--output", "output_dir", required=True, type=click.Path(file_okay=False), help="The cycle's folder.")
@click.option("--restart-command", default=None,
              help="A command that restarts the controller with the compensation loaded and homes it (else the cycle says what to do and waits).")
@click.option("--axis", default="X", show_default=True)
@click.option("--feed-mm-min", type=_FEED, default=1000.0, show_default=True)
@click.option("--dwell-s", type=_DWELL, default=1.0, show_default=True)
@click.option("--window-s", type=_WINDOW, default=0.5, show_default=True)
@click.option("--stability-um", type=_STABILITY, default=None)
@click.option("--offset-mm", type=_OFFSET, default=0.0, show_default=True)
@click.option("--ini", type=click.Path(dir_okay=False), default=None, help="LinuxCNC: the machine's INI file.")
@click.option("--tolerance-e-um", type=finite(0.0, 1e6, min_open=True), default=None, help="ISO 230-2's E tolerance both reports hold the runs against [none: not assessed].")
@click.option("--seed", type=_SEED, default=0, show_default=True)
@click.option("--json", "as_json", is_flag=True, help="Print both verdicts and E, as found and as left, as JSON.")
@instrument_options
def cycle_command(plan_csv, controller_spec, source_spec, fmt, output_dir, restart_command, axis, feed_mm_min, dwell_s, window_s,
                  stability_um, offset_mm, ini, tolerance_e_um, seed, as_json, **instrument):
    """The closed cycle on a controller: as found -> compensation -> (restart with it) -> as left -> compared report.

    OUTPUT/as-found/{campaign,report}, OUTPUT/as-left/{campaign,report} (compared with the as-found
    results) and OUTPUT/cycle.json. Between the two runs the controller must load the compensation file:
    --restart-command does it, else the cycle prints exactly what to do and waits for Enter.
    """
    from axiscal.report.cycle import CycleSettings, closed_cycle
    from axiscal.capture.drive import DriveSettings
    from axiscal.capture.run import CaptureSettings

    options = _options(**instrument)
    with flags_named(_FLAGS):
        drive = DriveSettings(axis=axis, feed_m_per_s=feed_mm_min * MM / 60.0, dwell_s=float(dwell_s))
        settings = CaptureSettings(stability_m=1e-6 if stability_um is None else stability_um * UM, window_s=window_s,
                                   offset_m=offset_mm * MM)

    def wait_for_user(message: str) -> None:
        click.echo(message, err=True)
        click.prompt("press Enter once it is done", default="", show_default=False, err=True)

    with flags_named(_FLAGS):
        result = closed_cycle(plan_csv, controller_spec, source_spec, output_dir,
                              CycleSettings(fmt=fmt, restart_command=restart_command, ini=ini, seed=seed,
                                            stability_given=stability_um is not None, tolerance_e_um=tolerance_e_um),
                              drive=drive, settings=settings, options=options, ask=wait_for_user,
                              note=lambda text: click.echo(f"axiscal: note: {text}", err=True))
    if as_json:
        echo_json(result.summary)
    click.echo(f"axiscal: note: as found E {result.summary['as_found']['E_um']:.2f} um -> as left"
               f" {result.summary['as_left']['E_um']:.2f} um; reports in {result.folder}", err=True)
