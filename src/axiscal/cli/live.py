"""``axiscal live``: run the real-time pipeline from a source, record it, and serve the dashboard (docs/live.md).

Thin: the options go to :class:`axiscal.live.session.LiveSession`; this module only handles the
terminal (progress line, Ctrl-C, SIGTERM).
"""

from __future__ import annotations

import signal
import sys
import threading

import click

from axiscal.cli.common import FINITE, flags_named
from axiscal.errors import AxiscalError
from axiscal.cli.choices import PATHS

__all__ = ["live"]


class _OneLineCommand(click.Command):
    """A command whose usage errors (bad option, bad value) are one ``axiscal: error:`` line, exit 2."""

    def parse_args(self, ctx: click.Context, args: list[str]) -> list[str]:
        try:
            return super().parse_args(ctx, args)
        except click.UsageError as exc:
            raise AxiscalError(f"live: {exc.format_message()}") from None


@click.command("live", cls=_OneLineCommand)
@click.option("--machine", type=str, default=None, help="Machine TOML with [axes.<L>.sensors] (default: the built-in virtual module).")
@click.option("--source", "source_spec", default="sim", show_default=True, help="sim | replay:FILE | rtx:FILE:UNIT:CHANNEL | tcp:HOST:PORT | serial:DEVICE[:BAUD].")
@click.option("--rate", "rate_hz", type=FINITE, default=1000.0, show_default=True, help="Frames per second of the sim source (Hz).")
@click.option("--path", "motion", type=click.Choice(PATHS), default="diagonal", show_default=True, help="Motion of the sim source.")
@click.option("--seed", type=int, default=0, show_default=True, help="Seed of the virtual module.")
@click.option("--load-kg", type=FINITE, default=0.0, show_default=True, help="Mass on the Z slide of the virtual module (kg).")
@click.option("--no-pace", is_flag=True, help="Replay a file as fast as possible instead of at its t_s pace.")
@click.option("--record", "record_path", type=str, default=None, help="Write every frame and result to this new CSV, with a .json sidecar (docs/live.md).")
@click.option("--force", is_flag=True, help="Replace an existing --record file (never a file the run reads).")
@click.option("--duration", "duration_s", type=FINITE, default=None, help="Stop cleanly after this many seconds.")
@click.option("--port", type=int, default=8765, show_default=True, help="Dashboard port (0: any free port).")
@click.option("--bind", default="127.0.0.1", show_default=True, help="Address the dashboard listens on; 0.0.0.0 exposes it to the network (docs/live.md).")
@click.option("--allow-host", "allowed_hosts", multiple=True, help="A further Host name the dashboard answers (repeatable); default: loopback names only.")
@click.option("--no-server", is_flag=True, help="Run without the dashboard.")
@click.option("--update-hz", type=FINITE, default=10.0, show_default=True, help="Dashboard refreshes per second.")
def live(
    machine: str | None,
    source_spec: str,
    rate_hz: float,
    motion: str,
    seed: int,
    load_kg: float,
    no_pace: bool,
    record_path: str | None,
    force: bool,
    duration_s: float | None,
    port: int,
    bind: str,
    allowed_hosts: tuple[str, ...],
    no_server: bool,
    update_hz: float,
) -> None:
    """Stream frames through the measurement chain live: spatial error of the functional point, recorded and shown.

    Opens a dashboard on http://127.0.0.1:PORT/ unless --no-server. Ends after --duration, when a
    replay is finished (with --no-server), or on Ctrl-C.
    """
    from axiscal.live.session import LiveSession

    with flags_named(_FLAGS):
        session = LiveSession(
            machine=machine,
            source=source_spec,
            rate_hz=rate_hz,
            path=motion,
            seed=seed,
            load_kg=load_kg,
            pace=not no_pace,
            record=record_path,
            server=not no_server,
            port=port,
            update_hz=update_hz,
            duration_s=duration_s,
            force=force,
            bind=bind,
            allowed_hosts=allowed_hosts,
            realtime=True,
        )
    stop = threading.Event()
    previous_term = signal.getsignal(signal.SIGTERM) if threading.current_thread() is threading.main_thread() else None
    try:
        if session.url is not None:
            click.echo(f"dashboard: {session.url}", err=True)
        if session.priority is not None:
            click.echo(session.priority.text, err=True)
        if previous_term is not None:
            signal.signal(signal.SIGTERM, lambda *_: stop.set())
        on_terminal = sys.stderr.isatty()

        def progress(summary) -> None:
            text = summary.progress_text(session.state.measure_rate())
            click.echo(("\r" + text) if on_terminal else text, err=True, nl=not on_terminal)

        with flags_named(_FLAGS):
            summary = session.run(stop=stop, duration_s=duration_s, progress=progress, progress_interval_s=0.5 if on_terminal else 1.0)
        if on_terminal:
            click.echo("", err=True)
        click.echo(summary.progress_text(summary.mean_rate_hz, label="done"))
    finally:
        if previous_term is not None:
            signal.signal(signal.SIGTERM, previous_term)
        session.close()


#: the library's arguments and phrases in messages -> what to type on the command line
_FLAGS = {
    "rate_hz": "--rate", "duration_s": "--duration", "port": "--port", "update_hz": "--update-hz", "load_kg": "--load-kg",
    "seed": "--seed", "record": "--record", "force=True": "--force", "overwrite=True": "--force",
    "choose another port or host": "choose another --port or --bind", "a source replay:FILE": "--source replay:FILE",
}
