"""``axiscal live``: run the real-time pipeline from a source, record it, and serve the dashboard (docs/live.md)."""

from __future__ import annotations

import signal
import sys
import threading
import time
from datetime import datetime, timezone
from pathlib import Path

import click

from axiscal.cli.common import ensure_parent
from axiscal.errors import AxiscalError
from axiscal.live.pipeline import Pipeline, RunSummary
from axiscal.live.recorder import Recorder
from axiscal.live.sources import open_source, parse_source
from axiscal.live.state import LiveState, result_columns
from axiscal.measurement.faults import fault_legend
from axiscal.measurement.virtual import PATHS

__all__ = ["live", "register"]


def _progress_text(summary: RunSummary, rate_hz: float) -> str:
    record = f"  recorded {summary.frames_acknowledged}/{summary.frames_written}" if summary.frames_written or summary.frames_acknowledged else ""
    delay = f"  delay p99 {summary.latency_p99_ms:.2f} ms" if summary.latency_p99_ms == summary.latency_p99_ms else ""
    return (
        f"live {summary.elapsed_s:6.1f} s  frames {summary.frames}  rate {rate_hz:.0f} Hz  faults {summary.faults}"
        f"{record}{delay}  source {summary.source_state}"
    )


def _build_system(machine: str | None, source_kind: str, seed: int, load_kg: float):
    """The measurement system and, for the sim source, a maker of the virtual module (built once)."""
    from axiscal.measurement.virtual import VirtualModule

    built: list[VirtualModule] = []

    def module() -> VirtualModule:
        if not built:
            built.append(VirtualModule(seed=seed, load_kg=load_kg))
        return built[0]

    if machine is None:
        return module().measurement_system(), module
    from axiscal.measurement.pipeline import MeasurementSystem

    system = MeasurementSystem.from_toml(machine)
    if source_kind == "sim":
        simulated = set(module().measurement_system().channels)
        unknown = [name for name in system.channels if name not in simulated]
        if unknown:
            raise AxiscalError(
                f"the sim source cannot feed channel(s) {', '.join(unknown)}: it emits the virtual module's channels; "
                "use --source replay:FILE or tcp:HOST:PORT with this machine",
                path=machine,
            )
    return system, module


class _OneLineCommand(click.Command):
    """A command whose usage errors (bad option, bad value) are one ``axiscal: error:`` line, exit 2."""

    def parse_args(self, ctx: click.Context, args: list[str]) -> list[str]:
        try:
            return super().parse_args(ctx, args)
        except click.UsageError as exc:
            raise AxiscalError(f"live: {exc.format_message()}") from None


@click.command("live", cls=_OneLineCommand)
@click.option("--machine", type=str, default=None, help="Machine TOML with [axes.<L>.sensors] (default: the built-in virtual module).")
@click.option("--source", "source_spec", default="sim", show_default=True, help="sim | replay:FILE | tcp:HOST:PORT | serial:DEVICE[:BAUD].")
@click.option("--rate", "rate_hz", type=float, default=1000.0, show_default=True, help="Frames per second of the sim source (Hz).")
@click.option("--path", "motion", type=click.Choice(PATHS), default="diagonal", show_default=True, help="Motion of the sim source.")
@click.option("--seed", type=int, default=0, show_default=True, help="Seed of the virtual module.")
@click.option("--load-kg", type=float, default=0.0, show_default=True, help="Mass on the Z slide of the virtual module (kg).")
@click.option("--no-pace", is_flag=True, help="Replay a file as fast as possible instead of at its t_s pace.")
@click.option("--record", "record_path", type=str, default=None, help="Append every frame and result to this CSV (docs/live.md).")
@click.option("--duration", "duration_s", type=float, default=None, help="Stop cleanly after this many seconds.")
@click.option("--port", type=int, default=8765, show_default=True, help="Dashboard port on 127.0.0.1 (0: any free port).")
@click.option("--no-server", is_flag=True, help="Run without the dashboard.")
@click.option("--update-hz", type=float, default=10.0, show_default=True, help="Dashboard refreshes per second.")
def live(
    machine: str | None,
    source_spec: str,
    rate_hz: float,
    motion: str,
    seed: int,
    load_kg: float,
    no_pace: bool,
    record_path: str | None,
    duration_s: float | None,
    port: int,
    no_server: bool,
    update_hz: float,
) -> None:
    """Stream frames through the measurement chain live: spatial error of the functional point, recorded and shown.

    Opens a dashboard on http://127.0.0.1:PORT/ unless --no-server. Ends after --duration, when a
    replay is finished (with --no-server), or on Ctrl-C.
    """
    if not (rate_hz > 0 and rate_hz < float("inf")):
        raise AxiscalError(f"--rate must be a positive number of frames per second, got {rate_hz:g}")
    if duration_s is not None and not duration_s > 0:
        raise AxiscalError(f"--duration must be positive seconds, got {duration_s:g}")
    if not 0 <= port <= 65535:
        raise AxiscalError(f"--port must be 0-65535, got {port}")
    if not update_hz > 0:
        raise AxiscalError(f"--update-hz must be positive, got {update_hz:g}")
    if load_kg < 0:
        raise AxiscalError(f"--load-kg must not be negative, got {load_kg:g}")
    kind, argument = parse_source(source_spec)
    if kind == "replay" and record_path is not None and Path(record_path).resolve() == Path(argument).resolve():
        raise AxiscalError("--record names the file being replayed; record to another file", path=record_path)
    system, module = _build_system(machine, kind, seed, load_kg)
    source = open_source(source_spec, system.channels, virtual_module=module, rate_hz=rate_hz, path=motion, pace=not no_pace)
    state = LiveState(system)
    recorder = None
    server = None
    stop = threading.Event()
    previous_term = signal.getsignal(signal.SIGTERM) if threading.current_thread() is threading.main_thread() else None
    try:
        if record_path is not None:
            bits = ", ".join(f"{value} {text}" for value, text in fault_legend().items())
            try:
                record_file = ensure_parent(record_path)
            except OSError as exc:
                raise AxiscalError(f"cannot create the record's folder ({exc.strerror or exc})", path=record_path) from None
            recorder = Recorder(
                record_file,
                system.channels,
                result_columns(tuple(system.axes)),
                comments=(
                    f"source: {source.status.description}",
                    f"machine: {machine or f'built-in virtual module (seed {seed}, load {load_kg:g} kg)'}",
                    f"started: {datetime.now(timezone.utc).isoformat(timespec='seconds')}",
                    f"fault bits: {bits}",
                ),
            )
        pipeline = Pipeline(system, source, recorder=recorder, state=state)
        if not no_server:
            from axiscal.live.server import LiveServer, create_app

            server = LiveServer(create_app(state, update_hz=update_hz, title=f"axiscal live: {source.status.description}"), port=port).start()
            click.echo(f"dashboard: {server.url}", err=True)
        if previous_term is not None:
            signal.signal(signal.SIGTERM, lambda *_: stop.set())
        on_terminal = sys.stderr.isatty()

        def progress(summary: RunSummary) -> None:
            text = _progress_text(summary, state.measure_rate())
            click.echo(("\r" + text) if on_terminal else text, err=True, nl=not on_terminal)

        start = time.monotonic()
        try:
            summary = pipeline.run(stop=stop, duration_s=duration_s, progress=progress, progress_interval_s=0.5 if on_terminal else 1.0)
            if server is not None and not stop.is_set():
                remaining = None if duration_s is None else duration_s - (time.monotonic() - start)
                while not stop.is_set() and (remaining is None or remaining > 0):
                    stop.wait(0.2 if remaining is None else min(0.2, remaining))
                    remaining = None if duration_s is None else duration_s - (time.monotonic() - start)
        except KeyboardInterrupt:
            summary = pipeline.summary(time.monotonic() - start)
        if recorder is not None:
            recorder.close()
            summary = pipeline.summary(summary.elapsed_s)
        if on_terminal:
            click.echo("", err=True)
        click.echo(_progress_text(summary, summary.frames / summary.elapsed_s if summary.elapsed_s > 0 else 0.0).replace("live", "done", 1))
    finally:
        if previous_term is not None:
            signal.signal(signal.SIGTERM, previous_term)
        if server is not None:
            server.stop()
        if recorder is not None:
            recorder.close()
        source.close()


def register(group: click.Group) -> None:
    group.add_command(live)
