"""``axiscal workbench``: the local web page that runs a whole visit (docs/workbench.md).

Thin: the options go to :func:`axiscal.workbench.serve_workbench`; this module only prints the
address and waits for Ctrl-C or SIGTERM.
"""

from __future__ import annotations

import signal
import threading

import click

from axiscal.cli.common import flags_named

__all__ = ["workbench"]


@click.command("workbench")
@click.option("--db", default=None, help="History database URL or SQLite file [default: $AXISCAL_DB, else the user's SQLite file].")
@click.option("--data", "data", default="axiscal-data", show_default=True, help="Folder of the visits: every file the page writes or serves lies in it.")
@click.option("--port", type=click.IntRange(0, 65535), default=8770, show_default=True, help="Port of the page (0: any free port).")
@click.option("--host", default="127.0.0.1", show_default=True,
              help="Address to listen on; any other than loopback asks for the printed token (docs/workbench.md).")
def workbench(db: str | None, data: str, port: int, host: str) -> None:
    """Open the workbench: machines and their history, a new visit, plan, connect, run, results, compensate, finish."""
    with flags_named({"port": "--port", "host": "--host", "data": "--data", "db": "--db", "choose another port or host": "choose another --port or --host"}):
        from axiscal.workbench import serve_workbench

        server = serve_workbench(data, db=db, port=port, host=host)
    stop = threading.Event()
    main_thread = threading.current_thread() is threading.main_thread()
    previous = signal.getsignal(signal.SIGTERM) if main_thread else None
    try:
        if previous is not None:
            signal.signal(signal.SIGTERM, lambda *_: stop.set())
        click.echo(f"workbench: {server.url}", err=True)
        try:
            while not stop.wait(0.5):
                pass
        except KeyboardInterrupt:
            pass
    finally:
        if previous is not None:
            signal.signal(signal.SIGTERM, previous)
        server.stop()
