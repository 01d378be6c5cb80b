"""Memory of ``axiscal live`` while a TCP sender floods it with a line that never ends.

    .venv/bin/python benchmarks/live_flood.py [--megabytes 200]

A sender on 127.0.0.1 sends a few good frames, then MEGABYTES of digits without a line end, then a
line end and good frames again. ``axiscal live --source tcp:... --no-server`` runs in a child
process until the sender is done; the script prints the child's peak resident memory (ru_maxrss),
the frames recorded and how many of them are malformed (the flood must be exactly one).
"""

from __future__ import annotations

import argparse
import resource
import socket
import subprocess
import sys
import tempfile
import threading
import time
from pathlib import Path

import numpy as np
import pandas as pd

from axiscal.live.protocol import encode_lines
from axiscal.measurement.virtual import VirtualModule


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--megabytes", type=int, default=200)
    args = parser.parse_args()
    system = VirtualModule(seed=0).measurement_system()
    frames, _ = VirtualModule(seed=0).frames(np.arange(200) / 1000.0)
    values = np.column_stack([frames[name] for name in system.channels])
    before, after = encode_lines(frames["t_s"][:100], values[:100]), encode_lines(frames["t_s"][100:], values[100:])
    listener = socket.create_server(("127.0.0.1", 0))
    port = listener.getsockname()[1]

    def send() -> None:
        connection, _ = listener.accept()
        with connection:
            connection.sendall(before)
            chunk = b"7" * (1 << 20)
            for _ in range(args.megabytes):
                connection.sendall(chunk)
            connection.sendall(b"\n" + after)
            time.sleep(1.0)

    sender = threading.Thread(target=send, daemon=True)
    sender.start()
    with tempfile.TemporaryDirectory() as folder:
        record = Path(folder) / "flood.csv"
        child = subprocess.Popen(
            [sys.executable, "-m", "axiscal.cli.main", "live", "--no-server", "--source", f"tcp:127.0.0.1:{port}", "--record", str(record)],
            stdout=subprocess.DEVNULL,
            stderr=subprocess.DEVNULL,
        )
        sender.join(timeout=600)
        deadline = time.monotonic() + 10.0
        while time.monotonic() < deadline and (not record.exists() or len(pd.read_csv(record)) < 201):
            time.sleep(0.1)
        child.terminate()
        child.wait(timeout=30)
        table = pd.read_csv(record)
    peak_mib = resource.getrusage(resource.RUSAGE_CHILDREN).ru_maxrss / 1024
    malformed = int(((table["fault"] & 256) != 0).sum())
    print(f"sent {args.megabytes} MiB without a line end: peak RSS {peak_mib:.0f} MiB, frames {len(table)}, malformed {malformed}")


if __name__ == "__main__":
    main()
