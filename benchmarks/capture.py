"""Capture speed: a 10^6-sample recording captured from a file, and a 10 kHz TCP stream captured live.

    .venv/bin/python benchmarks/capture.py [--repeats 5] [--live-seconds 20]

1. ``capture --from``: a plan run on the virtual machine and recorded at 50 kHz for about 20 s
   (10^6 samples), written as a CSV (time_s, reading_mm and the three air sensors) and as an
   ``.rtx`` capture (the reading alone). Each is captured ``--repeats`` times in this process
   (reading the file, finding the stops, matching the plan, writing the run) and once more as a
   whole ``axiscal capture`` process; the median of each is printed beside ``pandas.read_csv`` of
   the same CSV (the floor any CSV capture stands on).
2. live: a sender process plays a 10 kHz recording of the plan over the TCP line protocol on
   127.0.0.1, each sample sent once its time stamp has passed; ``capture`` reads it through
   :class:`axiscal.live.sources.TcpSource`. Printed: samples sent, samples the capture read, any
   lost (a gap in the time stamps), the stops taken, and how far behind the stream the capture was
   when the last stop was taken.
"""

from __future__ import annotations

import argparse
import socket
import statistics
import subprocess
import sys
import tempfile
import time
from pathlib import Path

import numpy as np
import pandas as pd

from axiscal.capture import capture, capture_to_file, plan_steps, simulate_motions
from axiscal.capture.sources import plan_motions
from axiscal.capture.virtual import write_recording
from axiscal.io.importers.rtx import write_rtx
from axiscal.live.sources import TcpSource
from axiscal.model.machine import load_machine
from axiscal.positioning.plan import plan_test, write_plan
from axiscal.report.demo import builtin_example
from axiscal.units import MM

PLAN = dict(start_m=0.0, end_m=0.16, count=5, runs=1, seed=4)


def recording(rate_hz: float):
    plan = plan_test(PLAN["start_m"], PLAN["end_m"], PLAN["count"], runs=PLAN["runs"], seed=PLAN["seed"])
    machine = load_machine(builtin_example() / "machine.toml")
    simulated = simulate_motions(plan_motions(plan_steps(plan), dwell_s=0.8), machine, axis="X", rate_hz=rate_hz, seed=1)
    return plan, simulated


def median_time(call, repeats: int) -> float:
    times = []
    for _ in range(repeats):
        t0 = time.perf_counter()
        call()
        times.append(time.perf_counter() - t0)
    return statistics.median(times)


def offline(repeats: int) -> None:
    plan, simulated = recording(50_000.0)
    n = simulated.recording.time_s.size
    with tempfile.TemporaryDirectory() as folder:
        folder = Path(folder)
        write_plan(plan, folder / "plan.csv")
        write_recording(simulated, folder / "rec.csv")
        write_rtx(folder / "rec.rtx", simulated.recording.reading_m / MM, sample_rate_hz=50_000.0, unit="mm")
        print(f"recording: {n} samples over {simulated.recording.time_s[-1]:.1f} s at 50 kHz, {plan.readings} stops")
        pandas_s = median_time(lambda: pd.read_csv(folder / "rec.csv"), repeats)
        csv_s = median_time(lambda: capture_to_file(folder / "plan.csv", folder / "rec.csv", folder / "run.csv"), repeats)
        rtx_s = median_time(lambda: capture_to_file(folder / "plan.csv", folder / "rec.rtx", folder / "run_rtx.csv", unit="mm"),
                            repeats)
        t0 = time.perf_counter()
        subprocess.run([sys.executable, "-m", "axiscal.cli.main", "capture", str(folder / "plan.csv"), "--from",
                        str(folder / "rec.csv"), "-o", str(folder / "cli.csv")], check=True, capture_output=True)
        cli_s = time.perf_counter() - t0
        print(f"capture from the CSV  (in process, median of {repeats}): {csv_s:.3f} s"
              f"   [pandas.read_csv of the same file: {pandas_s:.3f} s]")
        print(f"capture from the .rtx (in process, median of {repeats}): {rtx_s:.3f} s")
        print(f"axiscal capture --from the CSV (whole process, once, imports included): {cli_s:.3f} s")


def sender(rate: float) -> None:
    """Child process: listen on a free loopback port, print it, send the recording's samples on time."""
    from axiscal.live.protocol import encode_lines, header_line

    _, simulated = recording(rate)
    rec = simulated.recording
    names = ("reading_mm", "air_temperature_c", "pressure_pa", "humidity_pct")
    values = np.column_stack([rec.reading_m / MM] + [rec.channels[c] for c in names[1:]])
    lines = encode_lines(rec.time_s, values).splitlines(keepends=True)
    listener = socket.create_server(("127.0.0.1", 0))
    listener.settimeout(30.0)
    print(listener.getsockname()[1], flush=True)
    connection, _ = listener.accept()
    connection.sendall(header_line(names))
    start = time.monotonic()
    sent = 0
    try:
        while sent < len(lines):
            due = int((time.monotonic() - start) * rate) + 1
            if due > sent:
                connection.sendall(b"".join(lines[sent:due]))
                sent = min(due, len(lines))
            time.sleep(0.002)
    except (BrokenPipeError, ConnectionResetError):
        pass  # the capture took its last stop and hung up
    connection.close()
    print(len(lines), flush=True)


def live(rate: float) -> None:
    plan, simulated = recording(rate)
    child = subprocess.Popen([sys.executable, __file__, "--sender", str(rate)], stdout=subprocess.PIPE, text=True)
    port = int(child.stdout.readline())
    source = TcpSource("127.0.0.1", port, ("reading_mm", "air_temperature_c", "pressure_pa", "humidity_pct"))
    times: list[np.ndarray] = []
    last = {}

    def progress(p):
        last["samples"] = p.samples

    original = source.read
    arrival = {}

    def read(timeout_s):
        batch = original(timeout_s)
        if len(batch):
            times.append(batch.t_s[~batch.malformed])
            arrival.setdefault("first", time.monotonic() - float(batch.t_s[0]))
            arrival["lag"] = time.monotonic() - arrival["first"] - float(batch.t_s[-1])
        return batch

    source.read = read
    t0 = time.monotonic()
    result = capture(plan, source, progress=progress)
    behind = (time.monotonic() - t0) - float(result.readings[-1].start_s)
    source.close()
    sent = int(child.stdout.readline() or 0)
    child.wait(timeout=30)
    t = np.concatenate(times) if times else np.empty(0)
    gaps = int(np.sum(np.abs(np.diff(t) - 1.0 / rate) > 0.5 / rate)) if t.size > 1 else 0
    print(f"live tcp at {rate:g} Hz: {simulated.recording.time_s.size} samples in the recording, {t.size} read by the"
          f" time the last stop was taken ({sent} sent in all), {gaps} gaps in the time stamps, {len(result.readings)} of"
          f" {plan.readings} stops taken; the capture ended {behind:.2f} s after the last stop began; the last batch"
          f" was read {arrival.get('lag', float('nan')) * 1e3:.1f} ms behind the stream")


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--repeats", type=int, default=5)
    parser.add_argument("--live-rate", type=float, default=10_000.0)
    parser.add_argument("--sender", type=float, default=None, help=argparse.SUPPRESS)
    parser.add_argument("--no-live", action="store_true")
    args = parser.parse_args()
    if args.sender is not None:
        sender(args.sender)
        return
    offline(args.repeats)
    if not args.no_live:
        live(args.live_rate)


if __name__ == "__main__":
    main()
