"""The workbench: how fast its page loads, and whether its live trace keeps every sample of a 1 kHz laser.

    .venv/bin/python benchmarks/workbench.py [--loads 5] [--machines 20] [--seconds 10]

1. Page load: a history of ``--machines`` machines with five visits each (SQLite); headless
   Chromium (Debian's, driven by Playwright) opens the page ``--loads`` times, each in a fresh
   context (nothing cached). Printed per load and as the median: the browser's load event (HTML,
   script and style), and the time until the machines table is filled from the history (the page
   is usable).
2. Live trace: the virtual machine runs a plan in real time (the laser at 1000 samples/s) and the
   page's stream (``/ws``, 20 messages a second) is read for ``--seconds`` by a WebSocket client
   (the Python ``websockets`` package). Printed: messages per second, samples received per second,
   samples received against those the laser gave by the last message, any gap in the sample
   indexes (a dropped sample), and the largest message.
"""

from __future__ import annotations

import argparse
import json
import statistics
import tempfile
import time
from pathlib import Path

from axiscal.history import Drift, add_results, drifting_results, write_results
from axiscal.workbench import SIM_RATE_HZ, serve_workbench

VISIT = {"title": "Benchmark visit", "date": "2026-11-26", "operator": "bench", "machine": "VMC bench",
         "instrument": "Laser", "A_um": 45, "E_um": 40, "R_um": 5, "B_um": 6, "tests": ["positioning-X"]}
PLAN = {"start_mm": 0, "end_mm": 150, "targets": 5, "runs": 2, "overrun_mm": 5, "dwell_s": 1, "dialect": "linuxcnc"}


def page_loads(url: str, loads: int) -> None:
    from playwright.sync_api import sync_playwright

    with sync_playwright() as playwright:
        browser = playwright.chromium.launch(executable_path="/usr/bin/chromium", args=["--no-sandbox"])
        load_ms, usable_ms = [], []
        for k in range(loads):
            context = browser.new_context(viewport={"width": 1366, "height": 768})
            page = context.new_page()
            began = time.perf_counter()
            page.goto(url, wait_until="load")
            loaded = time.perf_counter()
            page.wait_for_selector("#machines tbody tr")
            usable = time.perf_counter()
            rows = page.locator("#machines tbody tr").count()
            load_ms.append((loaded - began) * 1e3)
            usable_ms.append((usable - began) * 1e3)
            print(f"  load {k + 1}: load event {load_ms[-1]:.0f} ms, machines table ({rows} rows) {usable_ms[-1]:.0f} ms")
            context.close()
        browser.close()
    print(f"page load: median load event {statistics.median(load_ms):.0f} ms, median usable (table filled)"
          f" {statistics.median(usable_ms):.0f} ms over {loads} loads")


def live_trace(server, seconds: float) -> None:
    from websockets.sync.client import connect

    bench = server.bench
    bench.new_visit(VISIT)
    bench.make_plan(PLAN)
    bench.connect({"instrument": "sim", "controller": "sim"})
    bench.start_run("as-found")
    run = bench.run
    url = server.server.url.replace("http://", "ws://") + "ws"
    received, gaps, messages, largest = 0, 0, 0, 0
    with connect(url, max_size=None, open_timeout=10) as socket:
        began = time.perf_counter()
        while time.perf_counter() - began < seconds:
            text = socket.recv(timeout=5)
            message = json.loads(text)
            messages += 1
            largest = max(largest, len(text))
            trace = message["trace"]
            if trace["from"] != received:
                gaps += 1
            received = trace["from"] + len(trace["t_s"])
        elapsed = time.perf_counter() - began
    given = run.samples_since(0)[2]
    run.abort()
    run.wait(10)
    print(f"live trace: {messages / elapsed:.1f} messages/s, {received / elapsed:.0f} samples/s received"
          f" (laser {SIM_RATE_HZ:g} samples/s); {received} samples received by the last message,"
          f" {given} given by the laser when the client stopped reading; {gaps} gaps; largest message {largest} bytes")


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--loads", type=int, default=5)
    parser.add_argument("--machines", type=int, default=20)
    parser.add_argument("--seconds", type=float, default=10.0)
    args = parser.parse_args()
    with tempfile.TemporaryDirectory(prefix="axiscal-bench-") as folder:
        tmp = Path(folder)
        db = str(tmp / "history.sqlite")
        for m in range(args.machines):
            payloads = drifting_results({"positioning.X.E": Drift(10.0 + m, 3.0, 0.5, 40.0)}, machine=f"Machine {m + 1:02d}",
                                        campaigns=5, seed=m)
            add_results(write_results(tmp / f"m{m}", payloads), url=db)
        server = serve_workbench(tmp / "data", db=db, port=0)
        try:
            page_loads(server.url, args.loads)
            live_trace(server, args.seconds)
        finally:
            server.stop()


if __name__ == "__main__":
    main()
