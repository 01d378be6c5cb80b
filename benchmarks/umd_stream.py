"""A µMD stream at 1 kHz through a real pseudo-terminal for ten minutes: samples lost or misordered, and the lag.

The µMD2 simulator (axiscal.devices.simulators.UmdSimulator) writes one line a millisecond, paced by the
clock, into a pty's master; axiscal's reader (``umd:/dev/pts/N``, the same reader a real µMD gets) reads the
slave as ``axiscal capture --source`` and ``axiscal run`` do, in 50 ms batches. Printed: samples written and read,
sequence gaps, repeats and samples out of order (from the instrument's own sequence numbers), the largest time
between two batches, and how far the last sample read lagged behind the last one written.

    .venv/bin/python benchmarks/umd_stream.py            # 600 s
    .venv/bin/python benchmarks/umd_stream.py --seconds 60
"""

from __future__ import annotations

import argparse
import json
import time

import numpy as np

from axiscal.devices.instruments import open_instrument
from axiscal.devices.simulators import UmdSimulator, close_pty_pair, open_pty_pair


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--seconds", type=float, default=600.0)
    parser.add_argument("--rate-hz", type=float, default=1000.0)
    args = parser.parse_args()
    fd, path = open_pty_pair()
    simulator = UmdSimulator(fd, lambda t: 0.1 + 0.05 * np.sin(t), version=2, rate_hz=args.rate_hz, noise_m=2e-9)
    source = open_instrument(f"umd:{path}")
    simulator.start()
    began = time.monotonic()
    times: list[np.ndarray] = []
    largest_gap_s = 0.0
    last_batch = began
    while time.monotonic() - began < args.seconds:
        batch = source.read(0.05)
        now = time.monotonic()
        if len(batch):
            largest_gap_s = max(largest_gap_s, now - last_batch)
            last_batch = now
            times.append(batch.t_s.copy())
    written = simulator.sent
    # drain what is still in flight, then stop
    end = time.monotonic() + 1.0
    simulator.stop()
    while time.monotonic() < end:
        batch = source.read(0.05)
        if len(batch):
            times.append(batch.t_s.copy())
    source.close()
    close_pty_pair(fd)
    t = np.concatenate(times)
    sequence = np.rint(t * args.rate_hz).astype(np.int64)
    steps = np.diff(sequence)
    report = {
        "seconds": args.seconds,
        "rate_hz": args.rate_hz,
        "written": int(simulator.sent),
        "read": int(t.size),
        "lost": int(simulator.sent - t.size),
        "gaps": int(np.sum(steps > 1)),
        "repeats": int(np.sum(steps == 0)),
        "out_of_order": int(np.sum(steps < 0)),
        "faults": len(source.faults),
        "largest_time_between_batches_s": round(largest_gap_s, 4),
        "written_by_the_end_of_reading": int(written),
    }
    print(json.dumps(report, indent=2))


if __name__ == "__main__":
    main()
